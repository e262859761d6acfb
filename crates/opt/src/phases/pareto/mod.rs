//! Pareto fronts of slip-load designs: the trade-off between two to four objectives
//! (drift against floor acceleration, base shear, damper size…) that a study names in
//! its `objectives` list (docs/MODEL.md § Trade-offs).
//!
//! - [`front`]: non-dominated sorting, crowding distance, exact hypervolume, the knee;
//! - [`vector`]: the objective vector of one design (what each objective measures is
//!   [`crate::model::objectives`]);
//! - [`mod@search`]: the search of the front from the sweep's designs, journalled;
//! - [`candidates`]: the file's and the refinement's designs, which join the search's as
//!   candidates for the front;
//! - [`report`]: the certified front (its designs at the check fidelity) and its files,
//!   `pareto.csv`, `pareto.json` and the design table `pareto-table.{csv,md,json}`.
//!
//! [`evaluate_objectives`] and [`hypervolume`] are the entry points for other front ends
//! (a Python binding comparing searches at equal numbers of simulations).

pub mod candidates;
pub mod front;
pub mod report;
pub mod search;
pub mod surrogate;
pub mod vector;

pub use front::{crowding_distance, dominates, first_front, hypervolume, knee, nondominated_ranks};
pub use report::{Certified, ParetoReport, certify};
pub use search::{Evaluated, Search, search};

use crate::base::error::OptError;
use crate::eval::evaluate::{run_designs, suite_ranges};
use crate::eval::progress::Progress;
use crate::model::fidelity::Fidelity;
use crate::model::study::Study;

/// The objective vectors of `designs` (slip loads, N per dissipator of the study's
/// space) under `study`'s objectives, at the sweep fidelity: one simulation per design
/// and record (plus the bare frame's, when an objective needs it), run in parallel and
/// reduced in order (the same bits whatever the thread count); `progress` sees one
/// [`crate::eval::progress::Phase::Pareto`] phase and a tick per simulation. A design that
/// collapses on a record gets +∞ in every objective. Refused for a study without
/// `objectives`, or a design of the wrong length.
pub fn evaluate_objectives(
    study: &Study,
    designs: &[Vec<f64>],
    progress: &dyn Progress,
) -> Result<Vec<Vec<f64>>, OptError> {
    if study.objectives.is_empty() {
        return Err(OptError::invalid(
            &study.path,
            "objectives",
            "the study names no objectives of a front (give 2 to 4 in `objectives`)",
        ));
    }
    let m = study.space.dampers.len();
    if let Some((i, d)) = designs.iter().enumerate().find(|(_, d)| d.len() != m) {
        return Err(OptError::Missing(format!(
            "design {i} has {} slip loads; the study's space has {m} dissipators",
            d.len()
        )));
    }
    if let Some((i, v)) = designs.iter().enumerate().find_map(|(i, d)| {
        d.iter()
            .find(|v| !(v.is_finite() && **v >= 0.0))
            .map(|v| (i, v))
    }) {
        return Err(OptError::Missing(format!(
            "design {i} has slip load {v}: slip loads are finite and ≥ 0 N"
        )));
    }
    let nr = study.runs();
    let needs_bare = study.objectives.iter().any(|o| o.needs_bare());
    let mut all: Vec<Vec<f64>> = Vec::new();
    if needs_bare {
        all.push(vec![0.0; m]);
    }
    all.extend(designs.iter().cloned());
    let fid = Fidelity::sweep(study);
    progress.start(crate::eval::progress::Phase::Pareto, all.len() * nr);
    let mut runs = run_designs(study, &all, &fid, &|| progress.tick())?;
    progress.finish(crate::eval::progress::Phase::Pareto);
    let bare = needs_bare.then(|| runs.remove(0));
    let ranges = suite_ranges(study);
    designs
        .iter()
        .zip(&runs)
        .map(|(d, r)| vector::objective_vector(study, d, r, bare.as_deref(), &ranges))
        .collect()
}
