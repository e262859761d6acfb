//! `slipload table`: the optimum of a study over a family of buildings and hazard levels
//! (period scale × intensity scale), as `family.{csv,md}`.

use super::study_args::{PhaseBars, load_study};
use slipload_opt::family::FamilyReport;
use slipload_opt::pipeline::family_study;
use slipload_opt::study::RefineMethod;
use std::path::PathBuf;

/// Arguments of `slipload table`.
#[derive(Debug, clap::Args)]
pub struct TableArgs {
    /// Study file (default: the embedded benchmark study)
    pub study: Option<PathBuf>,
    /// Period scales (every period of the building × this), comma-separated
    #[arg(long, value_delimiter = ',', default_value = "0.8,1,1.25")]
    pub period_scales: Vec<f64>,
    /// Intensity scales (every record × this), comma-separated
    #[arg(long, value_delimiter = ',', default_value = "0.5,1,1.5")]
    pub intensity_scales: Vec<f64>,
    /// Refiner (default: the study's)
    #[arg(long)]
    pub refine: Option<RefineMethod>,
    /// Output folder
    #[arg(long, default_value = "out/table")]
    pub out: PathBuf,
}

/// Runs `slipload table`.
pub fn run(args: TableArgs) -> anyhow::Result<()> {
    super::output_folder("--out", &args.out)?;
    let study = load_study(args.study.as_deref())?;
    slipload_opt::family::check_scales(&study, &args.period_scales, &args.intensity_scales)?;
    let method = args.refine.unwrap_or(study.config.refine.method);
    // one folder, one writer: refused at once if another command holds it
    let _lock = slipload_opt::folder_lock::FolderLock::acquire(&args.out)?;
    let report = family_study(
        &study,
        &args.period_scales,
        &args.intensity_scales,
        method,
        &args.out,
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
