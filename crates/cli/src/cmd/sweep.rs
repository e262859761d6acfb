//! `slipload sweep`: a sample of designs × every record of a study, journalled in the
//! output folder (`--resume` continues it), optionally one shard of a job array.

use super::study_args::{load_study, progress};
use crate::study_figures::{RecordScatter, StudyFigures, drift_profiles};
use anyhow::Context;
use slipload_opt::Shard;
use slipload_opt::sweep;
use std::path::PathBuf;

/// Arguments of `slipload sweep`.
#[derive(Debug, clap::Args)]
pub struct SweepArgs {
    /// Study file (JSON)
    pub study: PathBuf,
    /// Output folder: manifest.json, responses.csv, designs.csv, journal.jsonl
    #[arg(long, default_value = "out/sweep")]
    pub out: PathBuf,
    /// No progress bar
    #[arg(long)]
    pub quiet: bool,
    /// Run one slice of the task list: I/N (from 0), or `auto` (job-array environment)
    #[arg(long)]
    pub shard: Option<String>,
    /// Number of shards for `--shard auto` when the scheduler does not say
    #[arg(long)]
    pub shards: Option<usize>,
    /// Continue the journal in the output folder: finished tasks are not run again (only
    /// a journal of the same study, by its fingerprint)
    #[arg(long, conflicts_with = "fresh")]
    pub resume: bool,
    /// Discard the output folder's journals (and the tables built from them) and start
    /// afresh
    #[arg(long)]
    pub fresh: bool,
}

/// Runs `slipload sweep`.
pub fn run(args: SweepArgs) -> anyhow::Result<()> {
    let study = load_study(Some(&args.study))?;
    let shard = match &args.shard {
        None => Shard::ALL,
        Some(spec) => Shard::parse(spec, args.shards, &|k| std::env::var(k).ok())?,
    };
    if args.fresh {
        let removed = slipload_opt::journal::discard_journals(&args.out)?;
        if !removed.is_empty() {
            eprintln!(
                "--fresh: removed {} from {}",
                removed.join(", "),
                args.out.display()
            );
        }
    }
    let manifest = sweep::Manifest::of(&study);
    let mine = (0..manifest.tasks()).filter(|&k| shard.owns(k)).count();
    let pb = progress(mine as u64, args.quiet, "sweep");
    let start = std::time::Instant::now();
    let report = sweep::run(&study, &args.out, shard, args.resume, &|| pb.inc(1))
        .with_context(|| format!("sweeping {} into {}", study.name, args.out.display()))?;
    pb.finish_and_clear();
    let secs = start.elapsed().as_secs_f64();
    eprintln!(
        "{}: {} designs × {} records; shard {}/{}: {} tasks ({} from the journal, {} run in {:.2} s, {:.1} tasks/s)",
        study.name,
        report.manifest.designs.len(),
        report.manifest.records.len(),
        shard.index,
        shard.count,
        report.shard_tasks,
        report.resumed,
        report.ran,
        secs,
        report.ran as f64 / secs.max(1e-9)
    );
    if let Some(rows) = &report.rows {
        eprintln!(
            "wrote {}/{{manifest.json,responses.csv,designs.csv}}",
            args.out.display()
        );
        let written = sweep_figures(&study, &report.manifest, rows)?.write(&args.out)?;
        eprintln!(
            "figures (SVG, PNG, CSV): {}/{{{}}}",
            args.out.display(),
            written.join(",")
        );
    } else {
        eprintln!(
            "shard journal in {}; join the shards with `slipload merge --out DIR SHARD_DIR...`",
            args.out.display()
        );
    }
    Ok(())
}

/// The sweep's figures (no new simulations): drift profiles of the three best designs,
/// the building file's design and the bare frame; the best design vs the bare frame per
/// record.
fn sweep_figures(
    study: &slipload_opt::Study,
    m: &sweep::Manifest,
    rows: &[slipload_opt::RecordMetrics],
) -> anyhow::Result<StudyFigures> {
    let nr = m.records.len();
    let obj = m.objectives(rows)?;
    let mut order: Vec<usize> = (0..obj.len()).collect();
    order.sort_by(|&a, &b| obj[a].0.total_cmp(&obj[b].0).then(a.cmp(&b)));
    // design 0 is the bare frame (the manifest puts it first)
    let is_file = |d: usize| m.designs[d].label == "file";
    let mut picked: Vec<usize> = order
        .iter()
        .copied()
        .filter(|&d| d != 0 && !is_file(d))
        .take(3)
        .collect();
    picked.extend(order.iter().copied().filter(|&d| is_file(d)));
    picked.push(0);
    picked.sort_by(|&a, &b| obj[a].0.total_cmp(&obj[b].0).then(a.cmp(&b)));
    let names: Vec<String> = picked.iter().map(|&d| m.designs[d].label.clone()).collect();
    let runs: Vec<&[slipload_opt::RecordMetrics]> = picked
        .iter()
        .map(|&d| &rows[d * nr..(d + 1) * nr])
        .collect();
    let best = order.iter().copied().find(|&d| d != 0);
    Ok(StudyFigures {
        map: None,
        convergence: Vec::new(),
        profiles: drift_profiles(&names, &runs),
        scatter: best.map(|d| {
            RecordScatter::new(
                &m.designs[d].label,
                study,
                &rows[..nr],
                &rows[d * nr..(d + 1) * nr],
            )
        }),
        fidelity: format!("{} (sweep fidelity)", m.method.as_str()),
    })
}
