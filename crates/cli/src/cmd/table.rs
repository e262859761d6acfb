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
    // every scaled frame must stay a building: its periods within the physical band
    let (lo, hi) = slipload_sim::building::PERIOD_BAND_S;
    let periods = study.building.modes.periods();
    let (t_long, t_short) = (periods[0], periods[periods.len() - 1]);
    for &p in &args.period_scales {
        if !(p.is_finite() && p > 0.0 && t_short * p >= lo && t_long * p <= hi) {
            anyhow::bail!(
                "--period-scales {p:e}: must be positive and keep the frame's periods ({t_short:.3} … {t_long:.3} s) within {lo:e} … {hi:e} s"
            );
        }
    }
    // every scaled record must stay a ground motion: its PGA within the study's band
    let pgas = study.records.iter().map(|r| r.pga() / slipload_motion::G);
    let (pga_lo, pga_hi) = pgas.fold((f64::INFINITY, 0.0_f64), |(lo, hi), p| {
        (lo.min(p), hi.max(p))
    });
    let (min_g, max_g) = (
        slipload_opt::study::MIN_STUDY_PGA_G,
        slipload_motion::MAX_ABS_ACCEL_G,
    );
    for &i in &args.intensity_scales {
        if !(i.is_finite() && i > 0.0 && pga_lo * i >= min_g && pga_hi * i <= max_g) {
            anyhow::bail!(
                "--intensity-scales {i:e}: must be positive and keep the records' PGA ({pga_lo:.3} … {pga_hi:.3} g) within {min_g} … {max_g} g (below, no dissipator slips; beyond, no ground has shaken)"
            );
        }
    }
    for (name, scales) in [
        ("--period-scales", &args.period_scales),
        ("--intensity-scales", &args.intensity_scales),
    ] {
        if let Some((k, v)) = scales
            .iter()
            .enumerate()
            .find(|(k, v)| scales[..*k].contains(v))
        {
            anyhow::bail!(
                "{name}: {v} is given twice (values {} and {}): each scale is one row of the table; give each once",
                scales.iter().position(|x| x == v).map_or(0, |p| p + 1),
                k + 1
            );
        }
    }
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
