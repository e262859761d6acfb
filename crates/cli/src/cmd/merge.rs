//! `slipload merge`: joins the journals of sweep shards into the files one run writes.

use crate::study_figures::sweep_figures;
use anyhow::Context;
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
    let (manifest, rows) = slipload_opt::sweep::merge(&dirs, &args.out)
        .with_context(|| format!("merging into {}", args.out.display()))?;
    eprintln!(
        "merged {} folders, {} tasks: wrote {}/{{manifest.json,responses.csv,designs.csv,journal.jsonl}}",
        dirs.len(),
        rows.len(),
        args.out.display()
    );
    // the figures a single sweep draws, from the same manifest and rows
    let written = sweep_figures(&manifest, &rows)?.write(&args.out)?;
    eprintln!(
        "figures (SVG, PNG, CSV): {}/{{{}}}",
        args.out.display(),
        written.join(",")
    );
    Ok(())
}
