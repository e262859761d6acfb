//! `slipload table`: the optimum of a study over a family of buildings and hazard levels
//! (period scale × intensity scale), as `family.{csv,md}`.

use super::study_args::{load_study, progress};
use slipload_opt::family::{family, to_csv, to_markdown};
use slipload_opt::output::write_atomic;
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
    let study = load_study(args.study.as_deref())?;
    let method = args.refine.unwrap_or(study.config.refine.method);
    let pb = progress(0, "family");
    let cells = family(
        &study,
        &args.period_scales,
        &args.intensity_scales,
        method,
        &|| pb.inc(1),
    )?;
    pb.finish_and_clear();
    let floors: Vec<usize> = study.space.dampers.iter().map(|f| f + 1).collect();
    write_atomic(
        &args.out.join("family.csv"),
        to_csv(&cells, &floors).as_bytes(),
    )?;
    let md = to_markdown(&cells, &floors, &study.objective.label());
    write_atomic(&args.out.join("family.md"), md.as_bytes())?;
    out!("{}\n\n{md}", study.name);
    outln!("wrote {}/{{family.csv,family.md}}", args.out.display());
    Ok(())
}
