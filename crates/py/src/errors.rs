//! Library errors as Python exceptions, and panics kept out of the interpreter.
//!
//! The exception classes live in the pure-Python module `slipload._errors` (so that one
//! class can be both a `slipload.SlipLoadError` and a `ValueError`); this module raises
//! them with the message the command line prints: the error and its causes, joined by
//! `": "`, each said once.

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use slipload_motion::MotionError;
use slipload_opt::OptError;
use slipload_sim::SimError;
use std::any::Any;
use std::error::Error;
use std::panic::{AssertUnwindSafe, catch_unwind};

/// Which Python exception an error becomes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// `slipload.InputError` (a `ValueError`): a file, field or argument is wrong.
    Input,
    /// `slipload.FileError` (an `OSError`): a file or folder cannot be read or written.
    File,
    /// `slipload.SimulationError` (a `RuntimeError`): a run failed on valid input.
    Simulation,
    /// `slipload.InternalError` (a `RuntimeError`): a bug in slipload (a caught panic).
    Internal,
}

impl Kind {
    fn class(self) -> &'static str {
        match self {
            Kind::Input => "InputError",
            Kind::File => "FileError",
            Kind::Simulation => "SimulationError",
            Kind::Internal => "InternalError",
        }
    }
}

/// The message of `e` and its causes as the command line prints it.
pub fn chain_message(e: &(dyn Error + 'static)) -> String {
    let mut out = String::new();
    let mut cause: Option<&(dyn Error + 'static)> = Some(e);
    while let Some(c) = cause {
        let s = c.to_string();
        if !s.is_empty() && !out.contains(&s) {
            if !out.is_empty() {
                out.push_str(": ");
            }
            out.push_str(&s);
        }
        cause = c.source();
    }
    out
}

/// The Python exception `kind` with `message`.
pub fn raise(kind: Kind, message: impl Into<String>) -> PyErr {
    let message = message.into();
    Python::attach(|py| {
        let class = py
            .import("slipload._errors")
            .and_then(|m| m.getattr(kind.class()));
        match class {
            Ok(class) => match class.call1((message.clone(),)) {
                Ok(value) => PyErr::from_value(value),
                Err(e) => e,
            },
            // the package's Python half is missing: still an exception, never a crash
            Err(_) => PyRuntimeError::new_err(message),
        }
    })
}

fn motion_kind(e: &MotionError) -> Kind {
    match e {
        MotionError::Io { .. } | MotionError::NotAFile { .. } => Kind::File,
        _ => Kind::Input,
    }
}

fn sim_kind(e: &SimError) -> Kind {
    match e {
        SimError::Io { .. } => Kind::File,
        SimError::Motion(m) => motion_kind(m),
        SimError::NonFinite { .. }
        | SimError::Friction { .. }
        | SimError::DelaCruzNotConverged { .. }
        | SimError::ExactBudget { .. }
        | SimError::ExactMemory { .. }
        | SimError::ExactZeno { .. }
        | SimError::NonFiniteResponse { .. } => Kind::Simulation,
        _ => Kind::Input,
    }
}

fn opt_kind(e: &OptError) -> Kind {
    match e {
        OptError::Io { .. }
        | OptError::Write { .. }
        | OptError::NotRegular { .. }
        | OptError::Symlink { .. }
        | OptError::FolderBusy { .. }
        | OptError::NotWritten { .. } => Kind::File,
        OptError::Figure(f) => figure_kind(f.as_ref()),
        OptError::Simulation { .. } | OptError::NonFinite { .. } | OptError::Subproblem(_) => {
            Kind::Simulation
        }
        OptError::Context { source, .. } => opt_kind(source),
        OptError::Motion(m) => motion_kind(m),
        OptError::Sim(s) => sim_kind(s),
        _ => Kind::Input,
    }
}

/// A library error of any crate, as its Python exception.
pub trait IntoPy {
    /// The exception.
    fn into_py(self) -> PyErr;
}

impl IntoPy for MotionError {
    fn into_py(self) -> PyErr {
        raise(motion_kind(&self), chain_message(&self))
    }
}

impl IntoPy for SimError {
    fn into_py(self) -> PyErr {
        raise(sim_kind(&self), chain_message(&self))
    }
}

impl IntoPy for OptError {
    fn into_py(self) -> PyErr {
        raise(opt_kind(&self), chain_message(&self))
    }
}

/// A simulation's error, its message after `what` (the design and record that failed).
pub fn sim_error(e: &SimError, what: &str) -> PyErr {
    raise(sim_kind(e), format!("{what}: {}", chain_message(e)))
}

/// `Result<T, E>` of a library crate → `PyResult<T>`.
pub trait PyResultExt<T> {
    /// The error as its Python exception.
    fn py(self) -> PyResult<T>;
}

impl<T, E: IntoPy> PyResultExt<T> for Result<T, E> {
    fn py(self) -> PyResult<T> {
        self.map_err(IntoPy::into_py)
    }
}

/// An `InputError` with `message`.
pub fn input(message: impl Into<String>) -> PyErr {
    raise(Kind::Input, message)
}

/// The payload a cancelled run unwinds with: not a panic, a request to stop.
#[derive(Debug)]
pub struct Cancelled;

/// What a caught unwind was.
enum Unwound {
    /// The run was cancelled (Ctrl-C).
    Cancelled,
    /// A panic: a bug.
    Panic(String),
}

/// Reads a caught unwind's payload.
fn unwound(payload: Box<dyn Any + Send>) -> Unwound {
    if payload.is::<Cancelled>() {
        return Unwound::Cancelled;
    }
    let text = payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_string());
    Unwound::Panic(text)
}

/// The exception of a caught unwind: `KeyboardInterrupt` for a cancelled run,
/// `slipload.InternalError` for a panic.
pub fn unwind_error(payload: Box<dyn Any + Send>) -> PyErr {
    match unwound(payload) {
        Unwound::Cancelled => pyo3::exceptions::PyKeyboardInterrupt::new_err("interrupted"),
        Unwound::Panic(text) => raise(
            Kind::Internal,
            format!(
                "internal error in slipload (a bug; please report it with the input that caused it): {text}"
            ),
        ),
    }
}

/// Runs `body`, turning a panic into `slipload.InternalError` (the interpreter lives on).
pub fn guarded<T>(body: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    catch_unwind(AssertUnwindSafe(body)).unwrap_or_else(|payload| Err(unwind_error(payload)))
}

/// The exception kind of a figure writer's error (the library's own writer,
/// [`slipload_figures::StudyFigures`], draws every study figure): a file that cannot be
/// written or a missing font is the caller's file problem; a figure the data cannot
/// draw is a bug.
fn figure_kind(e: &(dyn std::error::Error + Send + Sync + 'static)) -> Kind {
    use slipload_figures::{FigureError, FontError};
    if e.downcast_ref::<FontError>().is_some() {
        return Kind::File;
    }
    match e.downcast_ref::<FigureError>() {
        Some(FigureError::Write(_) | FigureError::Font(_)) => Kind::File,
        _ => Kind::Internal,
    }
}
