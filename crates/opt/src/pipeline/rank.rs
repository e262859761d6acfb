//! [`rank_study`] and [`family_study`]: candidate designs ranked over every suite, and
//! a study's optimum over a family of buildings and hazard levels, each with its files.

use crate::base::error::OptError;
use crate::eval::progress::{Phase, Progress, phase};
use crate::model::config::RefineMethod;
use crate::model::study::Study;
use crate::phases::family::{FamilyReport, check_scales, family};
use crate::phases::rank::{Ranking, load_designs, rank};
use crate::store::folder::{FolderRequest, StudyFolder};
use std::path::Path;

/// `slipload rank`: ranks the candidate designs of the file `designs` (as `optimize`
/// writes `candidates.json`) over every suite of `study` with a seeded bootstrap of
/// `bootstrap` resamples ([`crate::phases::rank::rank`]), reporting to `progress`, and
/// writes `rank.csv`, `rank.md` and `rank.json` into the folder of `request`.
pub fn rank_study(
    study: &Study,
    designs: &Path,
    bootstrap: usize,
    seed: u64,
    request: FolderRequest<'_>,
    progress: &dyn Progress,
) -> Result<Ranking, OptError> {
    StudyFolder::check_path(request.option, request.path)?;
    let designs = load_designs(study, designs)?;
    let (folder, discarded) = StudyFolder::open(request)?;
    if let Some(d) = &discarded {
        progress.discarded(folder.dir(), d);
    }
    let work = (designs.len() + 1) * study.runs();
    let ranking = phase(progress, Phase::Rank, work, |tick| {
        rank(study, &designs, bootstrap, seed, tick)
    })?;
    ranking.write_files(&folder)?;
    Ok(ranking)
}

/// `slipload table`: sweeps and refines `study` at every period scale × intensity scale
/// with `refine` (default: the study's refiner; [`crate::phases::family::family`]; not
/// journalled), reporting to `progress` (the work is not known ahead), and writes
/// `family.csv` and `family.md` into the folder of `request`.
pub fn family_study(
    study: &Study,
    period_scales: &[f64],
    intensity_scales: &[f64],
    refine: Option<RefineMethod>,
    request: FolderRequest<'_>,
    progress: &dyn Progress,
) -> Result<FamilyReport, OptError> {
    StudyFolder::check_path(request.option, request.path)?;
    check_scales(study, period_scales, intensity_scales)?;
    let method = refine.unwrap_or(study.config.refine.method);
    let method = study.check_refiner(method)?;
    let (folder, discarded) = StudyFolder::open(request)?;
    if let Some(d) = &discarded {
        progress.discarded(folder.dir(), d);
    }
    let cells = phase(progress, Phase::Family, 0, |tick| {
        family(study, period_scales, intensity_scales, method, tick)
    })?;
    let report = FamilyReport {
        study: study.name.clone(),
        objective: study.objective.label(),
        damper_floors: study.space.dampers.iter().map(|f| f + 1).collect(),
        cells,
    };
    report.write_files(&folder)?;
    Ok(report)
}
