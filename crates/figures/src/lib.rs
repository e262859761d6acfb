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
//!   the CSV of their data) from a [`slipload_opt::pipeline::FigureData`], returning the
//!   names written; [`study::map_csv`], [`study::convergence_csv`],
//!   [`study::drift_profiles_csv`], [`study::scatter_csv`] give the CSV texts alone.
//! - [`write_optimized`]: every figure of an `optimize` run from its report — the study
//!   figures and, for a study with `objectives`, the front — the one call each front makes.
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
pub mod pareto;
pub mod plot;
pub mod study;

pub use error::{FigureError, FontError};
pub use plot::raster::check_fonts;

/// Every figure `optimize` draws from its report, into `dir`: the study figures
/// ([`study::write`]) and, when the study names `objectives`, the front
/// ([`pareto::write_front`]). Returns the names written.
pub fn write_optimized(
    report: &slipload_opt::pipeline::StudyReport,
    dir: &std::path::Path,
) -> Result<Vec<String>, FigureError> {
    let mut written = study::write(&report.figures, dir)?;
    if let Some(p) = &report.pareto {
        written.extend(pareto::write_front(p, dir)?);
    }
    Ok(written)
}
