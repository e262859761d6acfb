//! [`rank_study`] and [`family_study`]: candidate designs ranked over every suite, and
//! a study's optimum over a family of buildings and hazard levels, each with its files.

use super::progress::{Phase, Progress, phase};
use crate::error::OptError;
use crate::family::{FamilyReport, family};
use crate::folder_lock::FolderLock;
use crate::rank::{NamedDesign, Ranking, rank};
use crate::study::{RefineMethod, Study};
use std::path::Path;

/// Ranks `designs` over every suite of `study` with a seeded bootstrap of `bootstrap`
/// resamples ([`crate::rank::rank`]), reporting to `progress`, and writes `rank.csv`,
/// `rank.md` and `rank.json` into `out`.
pub fn rank_study(
    study: &Study,
    designs: &[NamedDesign],
    bootstrap: usize,
    seed: u64,
    out: &Path,
    progress: &dyn Progress,
) -> Result<Ranking, OptError> {
    let _lock = FolderLock::acquire(out)?;
    let work = (designs.len() + 1) * study.records.len();
    let ranking = phase(progress, Phase::Rank, work, |tick| {
        rank(study, designs, bootstrap, seed, tick)
    })?;
    ranking.write_files(out)?;
    Ok(ranking)
}

/// Sweeps and refines `study` at every period scale × intensity scale with `method`
/// ([`crate::family::family`]; not journalled), reporting to `progress` (the work is not
/// known ahead), and writes `family.csv` and `family.md` into `out`.
pub fn family_study(
    study: &Study,
    period_scales: &[f64],
    intensity_scales: &[f64],
    method: RefineMethod,
    out: &Path,
    progress: &dyn Progress,
) -> Result<FamilyReport, OptError> {
    let _lock = FolderLock::acquire(out)?;
    let cells = phase(progress, Phase::Family, 0, |tick| {
        family(study, period_scales, intensity_scales, method, tick)
    })?;
    let report = FamilyReport {
        study: study.name.clone(),
        objective: study.objective.label(),
        damper_floors: study.space.dampers.iter().map(|f| f + 1).collect(),
        cells,
    };
    report.write_files(out)?;
    Ok(report)
}
