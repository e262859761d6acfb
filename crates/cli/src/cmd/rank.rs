//! `slipload rank`: candidate designs over every suite of a study, with their objective,
//! rank and how stable the ranking is under a bootstrap over the records.

use super::study_args::{PhaseBars, load_study};
use slipload_opt::phases::rank::Ranking;
use slipload_opt::pipeline::rank_study;
use slipload_opt::store::folder::FolderRequest;
use std::path::PathBuf;

/// Arguments of `slipload rank`.
#[derive(Debug, clap::Args)]
pub struct RankArgs {
    /// Study file
    pub study: PathBuf,
    /// Candidates: a JSON array of {"name", "slip_loads_kn": [...]} (optimize writes
    /// candidates.json: optimum, uniform, storey-shear, file, bare)
    #[arg(long)]
    pub designs: PathBuf,
    /// Output folder (rank.csv, rank.md, rank.json)
    #[arg(long, default_value = "out/rank")]
    pub out: PathBuf,
    /// Bootstrap resamples of the records (1 to 1000000)
    #[arg(long, default_value_t = 200,
          value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub bootstrap: u32,
    /// Bootstrap seed
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    #[command(flatten)]
    pub threads: crate::args::ThreadsArg,
}

/// Runs `slipload rank`.
pub fn run(args: RankArgs) -> anyhow::Result<()> {
    let study = load_study(Some(&args.study))?;
    let folder = FolderRequest {
        path: &args.out,
        option: "--out",
        fresh: false,
    };
    let r = rank_study(
        &study,
        &args.designs,
        args.bootstrap as usize,
        args.seed,
        folder,
        &PhaseBars::default(),
    )?;
    out!("{}", r.to_markdown());
    outln!(
        "wrote {}/{{{}}}",
        args.out.display(),
        Ranking::FILES.join(",")
    );
    Ok(())
}
