//! Reading a record file, choosing the reader by extension.
//!
//! Contract ([`read_record`]): a file whose extension is `at2` in any case is read by
//! [`crate::parse_at2`] (the unit its title states, else g) or, with units given, by
//! [`crate::parse_at2_in`] (a note on the record when they override the title's);
//! anything else by [`crate::parse_text`] (the unit its column header states, else
//! m/s²; units given that contradict the header are refused). The record is named by
//! the path as given. Bytes that are not
//! UTF-8 (e.g. Latin-1 station names in a header) are replaced, not rejected. A path that
//! is not a regular file (a folder, a FIFO, a device) is refused by kind, and a file
//! larger than [`crate::limits::MAX_RECORD_BYTES`] by size, before anything is read.

use crate::{MotionError, Record, Units};
use std::path::Path;

/// The formats [`read_record`] knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RecordFormat {
    /// PEER NGA `.AT2` (values in g).
    At2,
    /// Text/CSV, one or two columns.
    Text,
}

impl RecordFormat {
    /// The format of `path`, by its extension (`.at2`, any case → AT2; else text).
    pub fn of_path(path: &Path) -> RecordFormat {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("at2") => RecordFormat::At2,
            _ => RecordFormat::Text,
        }
    }
}

/// Reads the record in `path`. `units` replaces the unit the file states and the format's
/// default (AT2: g; text: m/s²); for a text file they must agree with a unit its column
/// header states. `dt_s` (s) is the time step of a one-column text file; for an AT2 file or a
/// time column it must agree with the file's step (to 0.1 %) or
/// [`MotionError::DtMismatch`] results.
pub fn read_record(
    path: &Path,
    units: Option<Units>,
    dt_s: Option<f64>,
) -> Result<Record, MotionError> {
    let bytes = crate::limits::read_input_file(path, "record", crate::limits::MAX_RECORD_BYTES)?;
    let text = String::from_utf8_lossy(&bytes);
    let name = path.display().to_string();
    match RecordFormat::of_path(path) {
        RecordFormat::At2 => {
            let record = match units {
                Some(u) => crate::parse_at2_in(&text, &name, u)?,
                None => crate::parse_at2(&text, &name)?,
            };
            if let Some(given) = dt_s {
                let found = record.dt();
                if !crate::number::within(given, found, 1e-3) {
                    return Err(MotionError::DtMismatch {
                        file: name,
                        given_s: given,
                        found_s: found,
                    });
                }
            }
            Ok(record)
        }
        RecordFormat::Text => crate::parse_text(&text, &name, units, dt_s),
    }
}
