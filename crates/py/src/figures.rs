//! The study figures, drawn by the same library call as the command line's
//! (`slipload_figures::study::write`), and the font check made before a study runs.

use crate::errors::{Kind, chain_message, raise};
use pyo3::prelude::*;
use slipload_figures::{FigureError, FontError};

fn figure_error(e: FigureError) -> PyErr {
    let kind = match &e {
        FigureError::Write(_) | FigureError::Font(_) => Kind::File,
        // a figure the data cannot draw is a bug, not the caller's input
        _ => Kind::Internal,
    };
    raise(kind, chain_message(&e))
}

/// Checks, before a study runs, that the figures can be rendered (the font is there), so
/// that a long run does not fail at its end.
pub fn check_fonts() -> PyResult<()> {
    slipload_figures::check_fonts().map_err(|e: FontError| raise(Kind::File, chain_message(&e)))
}

/// Draws the study figures of `data` into `out`; the names written.
pub fn write(
    data: &slipload_opt::pipeline::FigureData,
    out: &std::path::Path,
) -> PyResult<Vec<String>> {
    slipload_figures::study::write(data, out).map_err(figure_error)
}

/// Draws every figure of an `optimize` run into `out`; the names written.
pub fn write_optimized(
    report: &slipload_opt::pipeline::StudyReport,
    out: &std::path::Path,
) -> PyResult<Vec<String>> {
    slipload_figures::write_optimized(report, out).map_err(figure_error)
}
