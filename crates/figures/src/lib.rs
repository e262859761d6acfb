//! The figures slipload draws, shared by every front (the `slipload` program and the
//! Python package), so that each writes the same files byte for byte.
//!
//! Public API:
//! - [`plot`]: one look for every plot — a [`plot::Figure`] described as data (panels,
//!   series, heat maps) and saved as `NAME.svg` + `NAME.png` ([`plot::Figure::save`]),
//!   with a `<metadata>` element read back by [`plot::meta::FigureMeta::from_svg`]; the
//!   axis ([`plot::axis`]) and style ([`plot::style`]) helpers; the SVG → PNG step
//!   ([`plot::raster`]).
//! - [`study::write`]: the study figures of `optimize`, `sweep` and `merge` (SVG, PNG and
//!   the CSV of their data) from a [`slipload_opt::phases::figures::FigureData`], returning the
//!   names written; [`study::map_csv`], [`study::convergence_csv`],
//!   [`study::drift_profiles_csv`], [`study::scatter_csv`] give the CSV texts alone.
//! - [`StudyFigures`]: the figure writer every front hands to the study commands of
//!   [`slipload_opt::pipeline`] (it implements [`slipload_opt::pipeline::FigureWriter`]):
//!   the study figures and, for a study with `objectives`, the front.
//! - [`plan::write_plan`]: the figures of a study in plan (`plan-view`,
//!   `line-drift-profiles`).
//! - [`pareto::write_front`]: the front figure of a study with `objectives`
//!   (`pareto-front.{svg,png,csv}`), [`pareto::front_csv`] its CSV text alone.
//! - [`check_fonts`]: whether the PNG text font can be found, checked before any work so
//!   that a missing font costs nothing and leaves no files ([`FontError`]).
//! - [`FigureError`]: every failure, typed; messages name the file and what was
//!   expected.
//!
//! The dependency arrows: `slipload` (CLI) → `slipload-figures` → `slipload-opt` →
//! `slipload-sim` → `slipload-motion`.

mod error;
pub mod names;
pub mod pareto;
pub mod plan;
pub mod plot;
pub mod study;

pub use error::{FigureError, FontError};
pub use plot::raster::check_fonts;

/// The figure writer of the study commands: [`study::write`] for the study figures,
/// [`pareto::write_front`] for a front, [`check_fonts`] before any work. Its errors reach
/// the caller as [`slipload_opt::OptError::Figure`] holding the [`FigureError`] (or the
/// [`FontError`]), whose message is shown as it is.
#[derive(Debug, Clone, Copy, Default)]
pub struct StudyFigures;

impl slipload_opt::pipeline::FigureWriter for StudyFigures {
    fn check(&self) -> Result<(), slipload_opt::OptError> {
        check_fonts().map_err(|e| slipload_opt::OptError::Figure(Box::new(e)))
    }

    fn study(
        &self,
        data: &slipload_opt::phases::figures::FigureData,
        dir: &std::path::Path,
    ) -> Result<Vec<String>, slipload_opt::OptError> {
        study::write(data, dir).map_err(|e| slipload_opt::OptError::Figure(Box::new(e)))
    }

    fn front(
        &self,
        report: &slipload_opt::phases::pareto::ParetoReport,
        dir: &std::path::Path,
    ) -> Result<Vec<String>, slipload_opt::OptError> {
        pareto::write_front(report, dir).map_err(|e| slipload_opt::OptError::Figure(Box::new(e)))
    }

    fn plan(
        &self,
        data: &slipload_opt::plan::PlanFigureData,
        dir: &std::path::Path,
    ) -> Result<Vec<String>, slipload_opt::OptError> {
        plan::write_plan(data, dir).map_err(|e| slipload_opt::OptError::Figure(Box::new(e)))
    }
}
