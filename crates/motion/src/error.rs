//! The typed error of the motion crate.
//!
//! Every variant carries what is needed to fix the input: the file (or record) name, the
//! 1-based line number where it applies, and what was expected. Parsers never panic; every
//! malformed input ends here.

use std::path::PathBuf;

/// How to go beyond a size limit ([`crate::limits`]), the end of the messages that refuse
/// one.
pub(crate) const OVERRIDE_HINT: &str =
    "pass --allow-large (or set SLIPLOAD_ALLOW_LARGE=1) to run it anyway";

/// Everything that can go wrong while reading, building or processing a ground motion.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MotionError {
    /// The file could not be read.
    #[error("cannot read {path}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// A path given as an input file is a folder, a FIFO, a device or a socket.
    #[error(
        "{path}: the {what} file is {kind}, not a regular file: give the path of a {what} file"
    )]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What the file should hold ("record", "scene", …).
        what: &'static str,
        /// What the path is ("a folder", "a named pipe (FIFO)", "a character device", …).
        kind: &'static str,
    },
    /// An input file is larger than any real one ([`crate::limits`]).
    #[error(
        "{path}: the {what} file is {size}, more than any real {what} file (limit {limit}): not a {what}, or {hint}",
        hint = OVERRIDE_HINT
    )]
    FileTooLarge {
        /// The path.
        path: PathBuf,
        /// What the file should hold.
        what: &'static str,
        /// Its size, for people.
        size: String,
        /// The limit, for people.
        limit: String,
    },
    /// A count a user gave is beyond any real study's ([`crate::limits`]).
    #[error(
        "{count} {what} is more than any real study needs (limit {limit}); {hint}",
        hint = OVERRIDE_HINT
    )]
    TooMany {
        /// What is counted.
        what: String,
        /// The count asked for.
        count: f64,
        /// The limit.
        limit: f64,
    },
    /// An AT2 header announces more values than the file can hold.
    #[error(
        "{file}:{line}: the header announces NPTS = {npts} values, but a file of {file_bytes} bytes can hold at most {max_values} (each value takes at least two bytes): the header is wrong or the file is cut short"
    )]
    NptsBeyondFile {
        /// The file or record name.
        file: String,
        /// 1-based line of the header.
        line: usize,
        /// NPTS from the header.
        npts: usize,
        /// The size of the text, bytes.
        file_bytes: usize,
        /// The most values it can hold.
        max_values: usize,
    },
    /// A file's sample interval is longer than any accelerograph's.
    #[error(
        "{file}: sample interval {} s is longer than any accelerograph's (at most {max_s} s; records are sampled at 50-1000 Hz): check the units of the step (a header's, a time column's or one given)", readable(*dt_s)
    )]
    ImplausibleLongTimeStep {
        /// The file or record name.
        file: String,
        /// The sample interval, s.
        dt_s: f64,
        /// The bound, s.
        max_s: f64,
    },
    /// No line of an AT2 file holds the NPTS/DT header.
    #[error(
        "{file}: no header line with NPTS and DT (expected `NPTS= n, DT= dt SEC` or `n dt NPTS, DT`)"
    )]
    MissingHeader {
        /// The file or record name.
        file: String,
    },
    /// A line mentions NPTS but NPTS and DT could not be read from it.
    #[error("{file}:{line}: cannot read NPTS and DT from header `{text}` ({expected})")]
    MalformedHeader {
        /// The file or record name.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The header line as found (trimmed).
        text: String,
        /// What the reader expected.
        expected: &'static str,
    },
    /// The file holds fewer values than its header announces.
    #[error("{file}: truncated: header announces NPTS = {expected} values, found {found}")]
    Truncated {
        /// The file or record name.
        file: String,
        /// NPTS from the header.
        expected: usize,
        /// Values actually present.
        found: usize,
    },
    /// A token that should be a number is not one.
    #[error("{file}:{line}: `{token}` is not a number (expected {expected})")]
    NotANumber {
        /// The file or record name.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The offending text (at most 40 characters).
        token: String,
        /// What was expected there.
        expected: &'static str,
    },
    /// A number is NaN or infinite (or overflows once converted to m/s²).
    #[error("{file}:{line}: value `{token}` is not finite")]
    NonFinite {
        /// The file or record name.
        file: String,
        /// 1-based line number (0 when the value did not come from a file).
        line: usize,
        /// The offending text (at most 40 characters).
        token: String,
    },
    /// A value read from a file is beyond any physical ground acceleration
    /// ([`crate::MAX_ABS_ACCEL_G`]): wrong units, a corrupt file, or not a record.
    #[error(
        "{file}:{line}: acceleration `{token}` = {accel_g:.4e} g is beyond any physical record: the largest recorded ground accelerations are about 4-5 g and slipload refuses more than {limit_g} g (values read in {units}: wrong units?)"
    )]
    Implausible {
        /// The file or record name.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The offending text (at most 40 characters).
        token: String,
        /// The value in g.
        accel_g: f64,
        /// The bound, g.
        limit_g: f64,
        /// The units the values were read in.
        units: String,
    },
    /// A scaled record's peak ground acceleration would be beyond any physical record.
    #[error(
        "{file}: scaling gives a PGA of {pga_g:.4e} g, beyond any physical record: the largest recorded ground accelerations are about 4-5 g and slipload refuses more than {limit_g} g"
    )]
    ImplausibleScale {
        /// The record name.
        file: String,
        /// The PGA the scaling would give, g.
        pga_g: f64,
        /// The bound, g.
        limit_g: f64,
    },
    /// A file's sample interval is shorter than any accelerograph's.
    #[error(
        "{file}: sample interval {} s is shorter than any accelerograph's ({min_s} s, i.e. more than a megahertz): check the units of the step (a header's, a time column's or one given)", readable(*dt_s)
    )]
    ImplausibleTimeStep {
        /// The file or record name.
        file: String,
        /// The sample interval, s.
        dt_s: f64,
        /// The bound, s.
        min_s: f64,
    },
    /// An AT2 file holds more values than its header announces.
    #[error(
        "{file}: the header announces NPTS = {npts} values but the file holds {found}: the header or the data is wrong (refusing to guess which values are the record)"
    )]
    NptsMismatch {
        /// The file or record name.
        file: String,
        /// NPTS from the header.
        npts: usize,
        /// Values found after the header.
        found: usize,
    },
    /// A sample given to [`crate::Record::new`] is NaN or infinite.
    #[error("{file}: sample {index} is not finite ({value})")]
    NonFiniteSample {
        /// The record name.
        file: String,
        /// 0-based sample index.
        index: usize,
        /// The value.
        value: f64,
    },
    /// The time step is zero, negative or not finite.
    #[error("{file}: time step {dt_s} s must be positive and finite")]
    BadTimeStep {
        /// The file or record name.
        file: String,
        /// The time step, seconds.
        dt_s: f64,
    },
    /// The time column does not increase.
    #[error("{file}:{line}: time {time_s} s does not increase (previous {previous_s} s)")]
    TimeNotIncreasing {
        /// The file or record name.
        file: String,
        /// 1-based line number.
        line: usize,
        /// Time on this line, seconds.
        time_s: f64,
        /// Time on the previous data line, seconds.
        previous_s: f64,
    },
    /// The time column is not uniformly spaced.
    #[error("{file}:{line}: time step {found_s} s differs from the uniform step {expected_s} s")]
    NonUniformTime {
        /// The file or record name.
        file: String,
        /// 1-based line number.
        line: usize,
        /// The uniform step, (last − first)/(n − 1), seconds.
        expected_s: f64,
        /// The step ending on this line, seconds.
        found_s: f64,
    },
    /// The record holds no samples.
    #[error("{file}: empty record (no acceleration values)")]
    Empty {
        /// The file or record name.
        file: String,
    },
    /// A one-column text record (or a one-row two-column one) needs a time step.
    #[error(
        "{file}: the time step is unknown: give dt (one acceleration column) or a time column with at least two rows"
    )]
    MissingDt {
        /// The file or record name.
        file: String,
    },
    /// A given time step disagrees with the file's (AT2 header or time column).
    #[error("{file}: given dt = {given_s} s disagrees with the file's time step {found_s} s")]
    DtMismatch {
        /// The file or record name.
        file: String,
        /// The time step given by the caller, seconds.
        given_s: f64,
        /// The file's time step, seconds.
        found_s: f64,
    },
    /// A text record's line has the wrong number of columns.
    #[error("{file}:{line}: {found} columns, expected {expected}")]
    ColumnCount {
        /// The file or record name.
        file: String,
        /// 1-based line number.
        line: usize,
        /// Columns of the first data line (1 or 2).
        expected: usize,
        /// Columns on this line.
        found: usize,
    },
    /// A file's column header states a unit other than the one given to read it in.
    #[error(
        "{file}:{line}: the header `{header}` says the values are in {stated}, but units {given} were given: drop the units or make them agree with the header"
    )]
    UnitsContradictHeader {
        /// The file or record name.
        file: String,
        /// 1-based line of the header.
        line: usize,
        /// The header line (at most 40 characters).
        header: String,
        /// The unit the header states.
        stated: crate::Units,
        /// The unit given.
        given: crate::Units,
    },
    /// A file's header names an acceleration unit slipload does not convert.
    #[error(
        "{file}:{line}: the header `{header}` names the unit `{unit}`, which slipload does not convert (it reads g, m/s2 and cm/s2): convert the values and their header to one of these"
    )]
    UnknownHeaderUnits {
        /// The file or record name.
        file: String,
        /// 1-based line of the header.
        line: usize,
        /// The header line (at most 40 characters).
        header: String,
        /// The unit as written (lower-cased, at most 40 characters).
        unit: String,
    },
    /// An acceleration unit that is not known.
    #[error("unknown acceleration unit `{given}` (expected g, m/s2, m/s^2, cm/s2 or gal)")]
    UnknownUnits {
        /// The text given.
        given: String,
    },
    /// An argument is outside its valid range.
    #[error("{what} = {} is invalid: {expected}", readable(*value))]
    InvalidArgument {
        /// Which argument.
        what: &'static str,
        /// Its value.
        value: f64,
        /// The valid range.
        expected: &'static str,
    },
    /// A parameter of a target spectrum is out of its range.
    #[error("{field} = {} is invalid: expected {expected}", readable(*value))]
    InvalidSpectrum {
        /// The parameter, as the study names it relative to the spectrum (`periods_s[3]`,
        /// `ag_g`).
        field: String,
        /// Its value.
        value: f64,
        /// What was expected.
        expected: String,
    },
    /// A period range reaches outside the periods a target spectrum is defined over.
    #[error(
        "the period range [{}, {}] s leaves the target spectrum, defined from {} to {} s: it is not extrapolated; give a target that covers the range (or a shorter range)",
        readable(range_s[0]), readable(range_s[1]), readable(span_s[0]), readable(span_s[1])
    )]
    OutsideSpectrum {
        /// The range, s.
        range_s: [f64; 2],
        /// The target's span, s.
        span_s: [f64; 2],
    },
    /// Two records named as the components of one event cannot be a pair.
    #[error("record pair {pair}: {reason}")]
    PairMismatch {
        /// The pair's name.
        pair: String,
        /// Why not, with what was expected.
        reason: String,
    },
    /// A record cannot be scaled to a target because its measure is zero.
    #[error("{file}: cannot scale to a target {measure}: the record's {measure} is zero")]
    ZeroMeasure {
        /// The record name.
        file: String,
        /// The measure (e.g. "PGA").
        measure: &'static str,
    },
}

/// A number for people: as written for ordinary magnitudes, in exponent form for very
/// large or small ones (1e300, not 301 digits).
pub fn readable(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e9).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Shortens user text quoted in an error to at most 40 characters.
pub(crate) fn snippet(text: &str) -> String {
    text.chars().take(40).collect()
}
