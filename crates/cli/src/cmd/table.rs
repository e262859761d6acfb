//! `slipload table`: the optimum of a study over a family of buildings and hazard levels
//! (period scale × intensity scale), as `family.{csv,md}`.

use super::study_args::{PhaseBars, load_study};
use slipload_opt::model::config::RefineMethod;
use slipload_opt::phases::family::FamilyReport;
use slipload_opt::pipeline::family_study;
use slipload_opt::store::folder::{FolderRequest, StudyFolder};
use std::path::PathBuf;

/// Arguments of `slipload table`.
#[derive(Debug, clap::Args)]
pub struct TableArgs {
    /// Study file (default: the embedded benchmark study)
    pub study: Option<PathBuf>,
    /// Period scales (every period of the building × this), comma-separated
    #[arg(long, value_parser = scales, default_value = "0.8,1,1.25", allow_hyphen_values = true)]
    pub period_scales: Scales,
    /// Intensity scales (every record × this), comma-separated
    #[arg(long, value_parser = scales, default_value = "0.5,1,1.5", allow_hyphen_values = true)]
    pub intensity_scales: Scales,
    /// Refiner (default: the study's)
    #[arg(long)]
    pub refine: Option<RefineMethod>,
    /// Output folder
    #[arg(long, default_value = "out/table")]
    pub out: PathBuf,
    #[command(flatten)]
    pub threads: crate::args::ThreadsArg,
}

/// A comma-separated list of scales as given: `""` is the empty list, which reaches the
/// library's check (`check_scales`) and is refused there in the words every front uses.
#[derive(Debug, Clone)]
pub struct Scales(pub Vec<f64>);

/// Parses `--period-scales` and `--intensity-scales`.
fn scales(s: &str) -> Result<Scales, String> {
    if s.trim().is_empty() {
        return Ok(Scales(Vec::new()));
    }
    s.split(',')
        .map(|v| {
            v.trim()
                .parse::<f64>()
                .map_err(|_| format!("expected numbers separated by commas, got {v:?}"))
        })
        .collect::<Result<Vec<f64>, String>>()
        .map(Scales)
}

/// Runs `slipload table`.
pub fn run(args: TableArgs) -> anyhow::Result<()> {
    StudyFolder::check_path("--out", &args.out)?;
    let study = load_study(args.study.as_deref())?;
    let folder = FolderRequest {
        path: &args.out,
        option: "--out",
        fresh: false,
    };
    let report = family_study(
        &study,
        &args.period_scales.0,
        &args.intensity_scales.0,
        args.refine,
        folder,
        &PhaseBars::default(),
    )?;
    out!("{}\n\n{}", report.study, report.to_markdown());
    outln!(
        "wrote {}/{{{}}}",
        args.out.display(),
        FamilyReport::FILES.join(",")
    );
    Ok(())
}
