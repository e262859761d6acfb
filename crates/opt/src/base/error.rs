//! Errors of the optimisation crate: typed, carrying the values that explain them.

use std::path::PathBuf;

/// Everything that can go wrong while loading a study, sweeping or refining.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OptError {
    /// A file could not be read or written.
    #[error("cannot access {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// An output file could not be written ([`crate::base::output::write_atomic`]).
    #[error("writing {path}: {source}")]
    Write {
        /// The file (the target, when the path given is a symbolic link).
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A study file does not parse or does not fit the schema (unknown field, wrong type).
    #[error("{path}: {source}")]
    Json {
        /// The file.
        path: PathBuf,
        /// serde_json's message, with line and column.
        source: serde_json::Error,
    },
    /// A study value is out of range or inconsistent.
    #[error("{path}: field `{field}`: {message}")]
    Invalid {
        /// The study file.
        path: PathBuf,
        /// The field, as a JSON path (`space.free.upper_kn[2]`).
        field: String,
        /// What was expected and what was found.
        message: String,
    },
    /// The journal in the output folder belongs to another study, or is corrupt.
    #[error("journal {path}, line {line}: {message}")]
    Journal {
        /// The journal file.
        path: PathBuf,
        /// Line number, from 1.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// Shard selection is invalid.
    #[error("shard: {0}")]
    Shard(String),
    /// A convex subproblem was not solved.
    #[error("trust-region subproblem not solved: {0}")]
    Subproblem(String),
    /// A simulation failed.
    #[error("design {design}, record {record}: {source}")]
    Simulation {
        /// Design label.
        design: String,
        /// Record name.
        record: String,
        /// The cause (boxed: a simulation error is large).
        source: Box<slipload_sim::SimError>,
    },
    /// A response or an objective came out NaN or infinite.
    #[error(
        "design {design}, record {record}: {quantity} is not finite: the response overflowed; check the record's units and the building's values"
    )]
    NonFinite {
        /// Design label.
        design: String,
        /// Record name (or the records an objective pools).
        record: String,
        /// Which value, with its value.
        quantity: String,
    },
    /// A study or a command asks for more work or memory than any real study needs.
    #[error(
        "{what}: {estimate} exceeds the limit of {limit} that no real study needs; {}",
        slipload_sim::limits::OVERRIDE_HINT
    )]
    TooLarge {
        /// What was estimated.
        what: String,
        /// The estimate, for people.
        estimate: String,
        /// The limit, for people.
        limit: String,
    },
    /// A study would hold more memory than the process's address-space limit leaves
    /// (`ulimit -v`): refused before its first run, not met by an allocation abort. The
    /// message names what was estimated, the estimate, the limit and what needs less.
    #[error("{0}")]
    AddressSpace(String),
    /// An output path is not a regular file (a FIFO, a device, a folder, a dangling link).
    #[error(
        "{path} is {kind}: refusing to replace it with an output file; give the path of a regular file"
    )]
    NotRegular {
        /// The path given.
        path: PathBuf,
        /// What it is.
        kind: String,
    },
    /// An output path is a symbolic link: slipload never writes through one.
    #[error(
        "{path} is a symbolic link (to {target}): refusing to write through it; remove the link or give the path of a regular file"
    )]
    Symlink {
        /// The path given.
        path: PathBuf,
        /// Where the link points, as written in the link.
        target: PathBuf,
    },
    /// Another command holds the output folder's lock ([`crate::store::folder`]).
    #[error(
        "{dir} is in use by another slipload command (it holds the folder's lock {dir}/.slipload.lock): one folder takes one writer at a time; wait for that run to finish, or choose another --out"
    )]
    FolderBusy {
        /// The folder.
        dir: PathBuf,
    },
    /// An output folder holds files under the names slipload writes that slipload did not
    /// write there ([`crate::store::folder::StudyFolder`]): never overwritten or removed.
    #[error(
        "{dir} holds {names} that slipload did not write there: a study command never overwrites a file it did not write; move {them} elsewhere, or choose another --out"
    )]
    NotWritten {
        /// The folder.
        dir: PathBuf,
        /// The files, named as a list (`designs.csv, rank.md`).
        names: String,
        /// `it` or `them`.
        them: &'static str,
    },
    /// A figure could not be drawn or written (the figure writer's own error, whose
    /// message is shown as it is).
    #[error(transparent)]
    Figure(Box<dyn std::error::Error + Send + Sync + 'static>),
    /// A step of a study run failed: what was being done (`sweeping STUDY into DIR`),
    /// then the cause.
    #[error("{context}")]
    Context {
        /// What was being done.
        context: String,
        /// The cause.
        source: Box<OptError>,
    },
    /// A command's argument is out of range.
    #[error("{0}")]
    Argument(String),
    /// A record could not be read or scaled.
    #[error(transparent)]
    Motion(#[from] slipload_motion::MotionError),
    /// The building could not be loaded.
    #[error(transparent)]
    Sim(Box<slipload_sim::SimError>),
    /// A response the objective needs is missing (e.g. drift ratios without storey heights).
    #[error("{0}")]
    Missing(String),
    /// A refiner asked for more evaluations than its budget has left: the refiners'
    /// executor (`phases::refine::run`) stops it there, so this never reaches a user.
    #[error("the refinement's budget of {budget} evaluations is spent")]
    BudgetSpent {
        /// The budget, evaluations.
        budget: usize,
    },
}

impl From<slipload_sim::SimError> for OptError {
    fn from(e: slipload_sim::SimError) -> Self {
        OptError::Sim(Box::new(e))
    }
}

impl OptError {
    /// This error as the cause of a failed step (`sweeping STUDY into DIR`).
    pub fn context(self, context: impl Into<String>) -> Self {
        OptError::Context {
            context: context.into(),
            source: Box::new(self),
        }
    }

    /// An [`OptError::Invalid`].
    pub fn invalid(
        path: impl Into<PathBuf>,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        OptError::Invalid {
            path: path.into(),
            field: field.into(),
            message: message.into(),
        }
    }
}
