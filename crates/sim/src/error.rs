//! Errors of the simulation crate: typed, carrying the values that explain them.

use crate::kind::file_kind::{Expected, FileKind};
use std::path::PathBuf;

/// Everything that can go wrong while loading, compiling or running a scene.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SimError {
    /// A file could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A JSON file does not parse or does not fit the schema (unknown field, wrong type).
    #[error("{path}: {source}")]
    Json {
        /// The file (or `<inline>`).
        path: PathBuf,
        /// serde_json's message, with line and column.
        source: serde_json::Error,
    },
    /// The file is another kind of slipload input than the command reads (a study given
    /// to `simulate`, a building given to `optimize`): says which, and what to run.
    #[error(
        "{} is {}, not {}: {}",
        .path.display(),
        .found.article(),
        .expected.describe(),
        .found.advice(.path)
    )]
    WrongKind {
        /// The file.
        path: PathBuf,
        /// What it is.
        found: FileKind,
        /// What the command reads.
        expected: Expected,
    },
    /// A value is out of its valid range or inconsistent with others.
    #[error("{path}: field `{field}`: {message}")]
    Invalid {
        /// The file (or `<inline>`).
        path: PathBuf,
        /// The field, as a JSON path (`dissipators[2].brace_stiffness`).
        field: String,
        /// What was expected and what was found.
        message: String,
    },
    /// A matrix that must be symmetric positive definite is not.
    #[error("{what} is not positive definite{hint}")]
    NotPositiveDefinite {
        /// Which matrix.
        what: String,
        /// Advice, possibly empty.
        hint: String,
    },
    /// The time step is not usable.
    #[error("time step {dt} s must be positive and finite")]
    BadTimeStep {
        /// The step, seconds.
        dt: f64,
    },
    /// The scene asks for something that cannot be run (missing duration, …).
    #[error("scene: {0}")]
    Scene(String),
    /// The state became non-finite: the integration blew up.
    #[error("state became non-finite at step {step} (t = {t:.6} s); {hint}")]
    NonFinite {
        /// Step index.
        step: usize,
        /// Time, seconds.
        t: f64,
        /// Advice.
        hint: String,
    },
    /// The friction QP failed (should not happen for a valid plan).
    #[error("friction forces at t = {t:.6} s: {source}")]
    Friction {
        /// Time, seconds.
        t: f64,
        /// The solver's error.
        source: crate::friction::BoxQpError,
    },
    /// `delacruz`: a fixed-point loop did not converge within its iteration cap (or
    /// diverged), or the response blew up — the method is only conditionally stable.
    #[error(
        "delacruz: the {loop_name} loop did not converge at step {step} (t = {t:.6} s) after {iterations} iterations; the method is only conditionally stable: try dt <= {suggested_dt:.3e} s"
    )]
    DelaCruzNotConverged {
        /// Step index (1 = the first step).
        step: usize,
        /// Time at the end of the step, s.
        t: f64,
        /// `inner` (structural accelerations), `middle` (stuck friction forces), `outer`
        /// (sliding dissipator accelerations) or `response` (the state blew up).
        loop_name: &'static str,
        /// Iterations done when it gave up.
        iterations: u32,
        /// A time step for which the loops contract, s.
        suggested_dt: f64,
    },
    /// The `exact` integrator would exceed a documented work cap (very stiff or very
    /// light dissipators ringing faster than the run can resolve, or chattering).
    #[error("exact: {what} at t = {t:.6} s: {needed} exceeds the cap of {limit}; {hint}")]
    ExactBudget {
        /// What was counted (substeps, events).
        what: String,
        /// Time, seconds.
        t: f64,
        /// The count needed (or reached).
        needed: u64,
        /// The cap.
        limit: u64,
        /// Advice.
        hint: String,
    },
    /// Stick↔slip events repeat at one instant without time advancing (Zeno behaviour).
    #[error(
        "exact: {events} stick-slip events at t = {t:.12} s without time advancing (Zeno), last on floor {floor}"
    )]
    ExactZeno {
        /// Time, seconds.
        t: f64,
        /// Events at that instant.
        events: u32,
        /// Floor number (from 1) of the last event.
        floor: usize,
    },
    /// `exact` cannot hold what one run needs at once (two stick/slip mode sets' matrices
    /// and propagators, and the scratch of forming one) within its memory budget
    /// (`integrator::exact::MemoryBudget`). Refused before the first step.
    #[error(
        "exact: a run of this scene holds {} of matrices at once (two stick-slip mode sets and the scratch of forming one), more than its memory budget of {}; run newmark instead, at a small step (method.dt = {suggested_dt:.3e} s, a quarter of this scene's step: its error falls as dt²)",
        shown_bytes(.needed),
        shown_bytes(.budget)
    )]
    ExactMemory {
        /// Bytes a run holds at once, bytes.
        needed: u64,
        /// The budget, bytes.
        budget: u64,
        /// A `newmark` step for the same scene, s.
        suggested_dt: f64,
    },
    /// A run would exceed a work or memory limit no real study needs (the `limits`
    /// module, whose advice [`slipload_motion::limits::OVERRIDE_HINT`] ends the message).
    #[error(
        "{what}: {estimate} exceeds the limit of {limit} that no real study needs; {}",
        slipload_motion::limits::OVERRIDE_HINT
    )]
    TooLarge {
        /// What was estimated (steps of a run, memory of its histories).
        what: String,
        /// The estimate, for people.
        estimate: String,
        /// The limit, for people.
        limit: String,
    },
    /// A number of worker threads no run can use: none, or more than
    /// [`crate::limits::max_threads`] while the limits are in force. The message leaves the
    /// number to the front, which names its parameter (`--threads 0`, `threads=0`).
    #[error("{}", if *threads == 0 {
        "no worker thread: give at least 1 (or leave it out for one per core)".to_string()
    } else {
        format!(
            "more than {limit} worker threads ({cores} cores here) only adds overhead and takes long to start; give at most {limit}, or {}",
            slipload_motion::limits::OVERRIDE_HINT
        )
    })]
    Threads {
        /// The threads asked for.
        threads: usize,
        /// The most without the limits lifted.
        limit: usize,
        /// The cores of this machine.
        cores: usize,
    },
    /// The time step is longer than the span it must resolve (the duration, or the
    /// record's sample interval for a step-by-step method): the answer would be wrong.
    #[error("time step {dt} s is longer than {what} ({span} s): {consequence}")]
    StepTooLong {
        /// The step, s.
        dt: f64,
        /// What it exceeds.
        what: String,
        /// That span, s.
        span: f64,
        /// What would go wrong, and what to do.
        consequence: String,
    },
    /// A response came out NaN, infinite or beyond any physical magnitude.
    #[error(
        "{quantity} is not finite ({value}) under {record}: the response overflowed; check the record's units and the building's values"
    )]
    NonFiniteResponse {
        /// Which response.
        quantity: String,
        /// Its value.
        value: f64,
        /// The excitation (record name, or `no record`).
        record: String,
    },
    /// The scene has something the OpenSees script cannot write as elements OpenSees
    /// solves with `newmark`'s discrete equations ([`crate::opensees`]); the gap names
    /// the alternative.
    #[error("{scene} cannot be written as an OpenSees script: {gap}")]
    OpenSees {
        /// The scene's name.
        scene: String,
        /// What cannot be written, and what to do instead.
        gap: OpenSeesGap,
    },
    /// A ground-motion error (reading or scaling a record).
    #[error(transparent)]
    Motion(#[from] slipload_motion::MotionError),
}

/// A byte count for people, as [`slipload_motion::limits::bytes`].
fn shown_bytes(b: &u64) -> String {
    slipload_motion::limits::bytes(*b as f64)
}

impl SimError {
    /// An [`SimError::Invalid`] for `path`/`field`.
    pub(crate) fn invalid(
        path: &std::path::Path,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        SimError::Invalid {
            path: path.to_path_buf(),
            field: field.into(),
            message: message.into(),
        }
    }
}

/// What a scene has that the OpenSees script cannot express as elements OpenSees solves
/// with `newmark`'s discrete equations; each message names the alternative.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum OpenSeesGap {
    /// The scene's method is not Newmark average acceleration.
    #[error(
        "the script integrates with Newmark average acceleration (gamma = 1/2, beta = 1/4) as method newmark does, and the scene's method is {method}; give method newmark (or bilinear, which ignores dissipator masses)"
    )]
    Method {
        /// The scene's method.
        method: &'static str,
    },
    /// A dissipator with mass under `newmark`: its friction contact between two masses has
    /// no OpenSees element that steps it as `newmark` does.
    #[error(
        "the dissipator of floor {floor} has mass m' = {mass} kg; OpenSees has no friction contact between two masses that it solves as newmark does, so the script models brace + damper as one elastic-perfectly plastic spring with the mass ignored, which is method bilinear: give method bilinear (what frame programs compute), or mass 0"
    )]
    DissipatorMass {
        /// Floor number, from 1.
        floor: usize,
        /// m′, kg.
        mass: f64,
    },
    /// A massless damper whose brace has a dashpot: brace and contact are then not one
    /// elastic–perfectly plastic element, and newmark steps it on the end-of-step slip rate.
    #[error(
        "the massless dissipator of floor {floor} has a brace dashpot c' = {damping} N*s/m; brace + contact are then a Kelvin brace in series with a rigid-plastic contact, which no OpenSees material models without a penalty stiffness (and newmark steps it on the slip rate, not by the return mapping): give brace_damping 0"
    )]
    BraceDamping {
        /// Floor number, from 1.
        floor: usize,
        /// c′, N·s/m.
        damping: f64,
    },
    /// A mass matrix with off-diagonal terms: OpenSees's nodes carry lumped masses.
    #[error(
        "mass_matrix has off-diagonal terms (floors {row} and {col}: {value} kg); OpenSees nodes carry lumped masses: give floor_masses"
    )]
    MassMatrix {
        /// Row (floor number, from 1).
        row: usize,
        /// Column (floor number, from 1).
        col: usize,
        /// The term, kg.
        value: f64,
    },
    /// An initial state other than rest.
    #[error(
        "the scene starts from an initial state other than rest, which the script does not set up (the elastic-perfectly plastic elements' initial slips included); remove excitation.initial"
    )]
    InitialState,
    /// `reduce: false` keeps massless dissipators as zero-mass DOFs, which the script
    /// does not model.
    #[error(
        "the scene asks for the unreduced model (reduce: false), whose massless dissipators are zero-mass DOFs; the script writes the reduced model: set reduce to true"
    )]
    Unreduced,
}
