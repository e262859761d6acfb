//! `slipload merge`: joins the journals of sweep shards into the files one run writes.

use slipload_opt::pipeline::{SweepRun, merge_shards};
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
    super::output_folder("--out", &args.out)?;
    let dirs: Vec<&std::path::Path> = args.dirs.iter().map(PathBuf::as_path).collect();
    // a folder named twice, or the output among the shards, is refused
    slipload_opt::sweep::check_merge_folders(&dirs, &args.out)?;
    // the figures are drawn at the end: a missing font is refused before the run
    slipload_figures::check_fonts()?;
    // one folder, one writer: refused at once if another command holds it
    let _lock = slipload_opt::folder_lock::FolderLock::acquire(&args.out)?;
    let run = merge_shards(&dirs, &args.out)?;
    eprintln!(
        "merged {} folders, {} tasks: wrote {}/{{{}}}",
        dirs.len(),
        run.report.manifest.tasks(),
        args.out.display(),
        SweepRun::MERGE_FILES.join(",")
    );
    // the figures a single sweep draws, from the same manifest and rows
    if let Some(figures) = &run.figures {
        let written = slipload_figures::study::write(figures, &args.out)?;
        eprintln!(
            "figures (SVG, PNG, CSV): {}/{{{}}}",
            args.out.display(),
            written.join(",")
        );
    }
    Ok(())
}
