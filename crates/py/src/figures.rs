//! The study figures are drawn by the library's own figure writer
//! ([`slipload_figures::StudyFigures`], the command line's); this module only says which
//! Python exception a figure error becomes.

use crate::errors::Kind;
use slipload_figures::{FigureError, FontError};

/// The exception kind of a figure writer's error: a file that cannot be written or a
/// missing font is the caller's file problem; a figure the data cannot draw is a bug.
pub fn figure_kind(e: &(dyn std::error::Error + Send + Sync + 'static)) -> Kind {
    if e.downcast_ref::<FontError>().is_some() {
        return Kind::File;
    }
    match e.downcast_ref::<FigureError>() {
        Some(FigureError::Write(_) | FigureError::Font(_)) => Kind::File,
        _ => Kind::Internal,
    }
}
