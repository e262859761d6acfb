//! [`sweep_study`] and [`merge_shards`]: a study's sweep, whole or one shard of it, and
//! the join of shard folders into the files one run writes, with the figure data of a
//! complete sweep.

use super::figures::FigureData;
use super::progress::{Phase, Progress, phase};
use crate::error::OptError;
use crate::folder_lock::FolderLock;
use crate::shard::Shard;
use crate::study::Study;
use crate::sweep::{self, Manifest, SweepReport};
use std::path::Path;

/// What a sweep (or a merge of its shards) did and found.
#[derive(Debug, Clone)]
pub struct SweepRun {
    /// The sweep's manifest, what ran, what was reused, the rows when complete.
    pub report: SweepReport,
    /// The figure data, when the sweep is complete (a whole run, or a merge).
    pub figures: Option<FigureData>,
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

    fn complete(report: SweepReport) -> Result<SweepRun, OptError> {
        let figures = match &report.rows {
            Some(rows) => Some(FigureData::of_sweep(&report.manifest, rows)?),
            None => None,
        };
        Ok(SweepRun { report, figures })
    }
}

/// Sweeps `study` (the slice `shard` owns) into `out`, continuing its journal with
/// `resume` ([`crate::sweep::run`]); reports the sweep phase to `progress`.
pub fn sweep_study(
    study: &Study,
    out: &Path,
    shard: Shard,
    resume: bool,
    progress: &dyn Progress,
) -> Result<SweepRun, OptError> {
    let _lock = FolderLock::acquire(out)?;
    let manifest = Manifest::of(study);
    let mine = (0..manifest.tasks()).filter(|&k| shard.owns(k)).count();
    let report = phase(progress, Phase::Sweep, mine, |tick| {
        sweep::run(study, out, shard, resume, tick)
            .map_err(|e| e.context(format!("sweeping {} into {}", study.name, out.display())))
    })?;
    SweepRun::complete(report)
}

/// Joins the shard folders `dirs` into `out` ([`crate::sweep::merge`]): the bytes one run
/// writes, and the same figure data.
pub fn merge_shards(dirs: &[&Path], out: &Path) -> Result<SweepRun, OptError> {
    sweep::check_merge_folders(dirs, out)?;
    let _lock = FolderLock::acquire(out)?;
    let (manifest, rows) = sweep::merge(dirs, out)
        .map_err(|e| e.context(format!("merging into {}", out.display())))?;
    SweepRun::complete(SweepReport {
        shard_tasks: manifest.tasks(),
        resumed: manifest.tasks(),
        ran: 0,
        distrusted: 0,
        manifest,
        rows: Some(rows),
    })
}
