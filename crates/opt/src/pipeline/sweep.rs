//! [`sweep_study`] and [`merge_shards`]: a study's sweep, whole or one shard of it, and
//! the join of shard folders into the files one run writes, each with the figures of a
//! complete sweep.

use super::figures::FigureWriter;
use crate::base::error::OptError;
use crate::base::shard::Shard;
use crate::eval::progress::{Phase, Progress, phase};
use crate::model::study::Study;
use crate::phases::figures::FigureData;
use crate::phases::sweep::{self, Manifest, SweepReport, check_merge_folders};
use crate::store::folder::{Discarded, FolderRequest, StudyFolder};
use std::path::Path;

/// What a sweep (or a merge of its shards) did and found.
#[derive(Debug, Clone)]
pub struct SweepRun {
    /// The sweep's manifest, what ran, what was reused, the rows when complete.
    pub report: SweepReport,
    /// The figure data, when the sweep is complete (a whole run, or a merge).
    pub figures: Option<FigureData>,
    /// The figures drawn (their names), when the sweep is complete.
    pub drawn: Vec<String>,
    /// What `fresh` removed and kept, when it was asked for.
    pub discarded: Option<Discarded>,
}

impl SweepRun {
    /// The files a complete sweep writes, in the order a summary names them.
    pub const FILES: [&str; 3] = ["manifest.json", "responses.csv", "designs.csv"];
    /// The files a merge writes: the sweep's and the merged journal.
    pub const MERGE_FILES: [&str; 4] = [
        "manifest.json",
        "responses.csv",
        "designs.csv",
        "journal.jsonl",
    ];

    fn complete(
        report: SweepReport,
        folder: &StudyFolder,
        figures: &dyn FigureWriter,
        discarded: Option<Discarded>,
    ) -> Result<SweepRun, OptError> {
        let data = match &report.rows {
            Some(rows) => Some(FigureData::of_sweep(&report.manifest, rows)?),
            None => None,
        };
        let drawn = match &data {
            Some(d) => {
                folder.claim_figures(&d.suite_stems())?;
                figures.study(d, folder.dir())?
            }
            None => Vec::new(),
        };
        Ok(SweepRun {
            report,
            figures: data,
            drawn,
            discarded,
        })
    }
}

/// `slipload sweep`: sweeps `study` (the slice `shard` owns) into the folder of `request`,
/// continuing its journal with `resume` ([`crate::phases::sweep::run`]), reporting the
/// sweep phase to `progress`; a complete sweep's figures are drawn by `figures`.
pub fn sweep_study(
    study: &Study,
    shard: Shard,
    resume: bool,
    request: FolderRequest<'_>,
    progress: &dyn Progress,
    figures: &dyn FigureWriter,
) -> Result<SweepRun, OptError> {
    StudyFolder::check_path(request.option, request.path)?;
    figures.check()?;
    let (folder, discarded) = StudyFolder::open(request)?;
    if let Some(d) = &discarded {
        progress.discarded(folder.dir(), d);
    }
    let manifest = Manifest::of(study);
    let mine = (0..manifest.tasks()).filter(|&k| shard.owns(k)).count();
    let report = phase(progress, Phase::Sweep, mine, |tick| {
        sweep::run(study, &folder, shard, resume, tick).map_err(|e| {
            e.context(format!(
                "sweeping {} into {}",
                study.name,
                folder.dir().display()
            ))
        })
    })?;
    SweepRun::complete(report, &folder, figures, discarded)
}

/// `slipload merge`: joins the shard folders `dirs` into the folder of `request`
/// ([`crate::phases::sweep::merge`]): the bytes one run writes, and the same figures.
pub fn merge_shards(
    dirs: &[&Path],
    request: FolderRequest<'_>,
    figures: &dyn FigureWriter,
) -> Result<SweepRun, OptError> {
    StudyFolder::check_path(request.option, request.path)?;
    // a folder named twice, or the output among the shards, is refused
    check_merge_folders(dirs, request.path)?;
    figures.check()?;
    let (folder, discarded) = StudyFolder::open(request)?;
    let (manifest, rows) = sweep::merge(dirs, &folder)
        .map_err(|e| e.context(format!("merging into {}", folder.dir().display())))?;
    SweepRun::complete(
        SweepReport {
            shard_tasks: manifest.tasks(),
            resumed: manifest.tasks(),
            ran: 0,
            distrusted: 0,
            manifest,
            rows: Some(rows),
        },
        &folder,
        figures,
        discarded,
    )
}
