//! `slipload merge`: joins the journals of sweep shards into the files one run writes.

use slipload_figures::StudyFigures;
use slipload_opt::pipeline::{SweepRun, merge_shards};
use slipload_opt::store::folder::FolderRequest;
use std::path::PathBuf;

/// Arguments of `slipload merge`.
#[derive(Debug, clap::Args)]
pub struct MergeArgs {
    /// Shard output folders
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// Where the merged files go
    #[arg(long)]
    pub out: PathBuf,
}

/// Runs `slipload merge`.
pub fn run(args: MergeArgs) -> anyhow::Result<()> {
    let dirs: Vec<&std::path::Path> = args.dirs.iter().map(PathBuf::as_path).collect();
    let folder = FolderRequest {
        path: &args.out,
        option: "--out",
        fresh: false,
    };
    let run = merge_shards(&dirs, folder, &StudyFigures)?;
    eprintln!(
        "merged {} folders, {} tasks: wrote {}/{{{}}}",
        dirs.len(),
        run.report.manifest.tasks(),
        args.out.display(),
        SweepRun::MERGE_FILES.join(",")
    );
    // the figures a single sweep draws, from the same manifest and rows
    if run.figures.is_some() {
        eprintln!(
            "figures (SVG, PNG, CSV): {}/{{{}}}",
            args.out.display(),
            run.drawn.join(",")
        );
    }
    Ok(())
}
