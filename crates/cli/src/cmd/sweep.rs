//! `slipload sweep`: a sample of designs × every record of a study, journalled in the
//! output folder (`--resume` continues it), optionally one shard of a job array.

use super::study_args::{PhaseBars, load_study};
use slipload_figures::StudyFigures;
use slipload_opt::Shard;
use slipload_opt::pipeline::{SweepRun, sweep_study};
use slipload_opt::store::folder::{FolderRequest, StudyFolder};
use std::path::PathBuf;

/// Arguments of `slipload sweep`.
#[derive(Debug, clap::Args)]
pub struct SweepArgs {
    /// Study file (JSON)
    pub study: PathBuf,
    /// Output folder: manifest.json, responses.csv, designs.csv, journal.jsonl
    #[arg(long, default_value = "out/sweep")]
    pub out: PathBuf,
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
    /// Remove every file a slipload command wrote in the output folder (journals, tables,
    /// figures, rankings, report; any other file is kept and named) and start afresh
    #[arg(long)]
    pub fresh: bool,
    #[command(flatten)]
    pub threads: crate::args::ThreadsArg,
}

/// Most shards of `--shards` (job arrays of real clusters stop at tens of thousands).
const MAX_SHARDS: usize = 100_000;

/// Runs `slipload sweep`.
pub fn run(args: SweepArgs) -> anyhow::Result<()> {
    StudyFolder::check_path("--out", &args.out)?;
    if let Some(n) = args.shards {
        super::count_flag("--shards", n, MAX_SHARDS)?;
        // without `--shard auto` the count would be ignored and the whole sweep run
        if args.shard.as_deref() != Some("auto") {
            anyhow::bail!(
                "--shards {n} applies to `--shard auto` only (given: {}): give --shard auto --shards {n}, or --shard I/{n}",
                args.shard
                    .as_deref()
                    .map_or("no --shard".to_string(), |s| format!("--shard {s}"))
            );
        }
    }
    let study = load_study(Some(&args.study))?;
    let shard = match &args.shard {
        None => Shard::ALL,
        Some(spec) => Shard::parse(spec, args.shards, &|k| std::env::var(k).ok())?,
    };
    let start = std::time::Instant::now();
    let folder = FolderRequest {
        path: &args.out,
        option: "--out",
        fresh: args.fresh,
    };
    let run = sweep_study(
        &study,
        shard,
        args.resume,
        folder,
        &PhaseBars::default(),
        &StudyFigures,
    )?;
    let report = &run.report;
    let secs = start.elapsed().as_secs_f64();
    eprintln!(
        "{}: {} designs × {}; shard {}/{}: {} tasks ({} from the journal, {} run in {:.2} s, {:.1} tasks/s)",
        study.name,
        report.manifest.designs.len(),
        super::study_text::runs_text(&report.manifest),
        shard.index,
        shard.count,
        report.shard_tasks,
        report.resumed,
        report.ran,
        secs,
        report.ran as f64 / secs.max(1e-9)
    );
    if report.distrusted > 0 {
        eprintln!(
            "{} line(s) of {}/journal.jsonl failed their checksum or had none (an older slipload's): not trusted, their tasks ran again",
            report.distrusted,
            args.out.display()
        );
    }
    eprintln!(
        "sweep method {} ({})",
        report.manifest.method.as_str(),
        report.manifest.method_reason
    );
    eprintln!("memory: {}", study.memory.text());
    if run.figures.is_some() {
        eprintln!(
            "wrote {}/{{{}}}",
            args.out.display(),
            SweepRun::FILES.join(",")
        );
        eprintln!(
            "figures (SVG, PNG, CSV): {}/{{{}}}",
            args.out.display(),
            run.drawn.join(",")
        );
    } else {
        eprintln!(
            "shard journal in {}; join the shards with `slipload merge --out DIR SHARD_DIR...`",
            args.out.display()
        );
    }
    Ok(())
}
