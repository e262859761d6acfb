//! `slipload record spectrum … --plot DIR`: the pseudo-acceleration spectra of a suite,
//! their mean and the design target (`DIR/spectra.svg`, `.png`), with the data in
//! `DIR/spectra.csv`.

use slipload_figures::plot::{
    Figure, Legend, Panel, RGBColor, Series, strip_image_extension, style, with_suffix,
};
use slipload_motion::{DesignSpectrum, G, Spectrum};
use slipload_opt::base::output::write_atomic;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Name (stem) of the spectra figure and its data in the `--plot` folder.
pub const STEM: &str = "spectra";

/// Records are drawn thin and grey so the mean and the target stand out.
const RECORD_GREY: RGBColor = RGBColor(165, 165, 165);

/// Arithmetic mean of the pseudo-accelerations (g) at each period of the first spectrum
/// (all spectra share the periods).
pub fn mean_psa_g(spectra: &[Spectrum]) -> Vec<f64> {
    let n = spectra.len() as f64;
    (0..spectra[0].periods_s.len())
        .map(|k| spectra.iter().map(|s| s.psa_m_s2[k] / G).sum::<f64>() / n)
        .collect()
}

/// Writes `STEM.svg`, `STEM.png` and `STEM.csv` (period_s, one psa_g column per record,
/// mean_psa_g, target_psa_g when a target is given); returns STEM.
pub fn write(
    stem: &Path,
    names: &[String],
    spectra: &[Spectrum],
    damping: f64,
    target: Option<&DesignSpectrum>,
) -> anyhow::Result<PathBuf> {
    anyhow::ensure!(!spectra.is_empty(), "no spectrum to plot");
    let stem = strip_image_extension(stem);
    let periods = spectra[0].periods_s.clone();
    let mean = mean_psa_g(spectra);
    let tgt: Option<Vec<f64>> = target.map(|d| periods.iter().map(|t| d.sa_g(*t)).collect());
    let log_x = periods.len() > 1 && periods.iter().all(|t| *t > 0.0);

    let mut p = Panel::new("period T (s)", "pseudo-acceleration Sa (g)")
        .y_from_zero()
        .legend(Legend::UpperRight);
    if log_x {
        p = p.x_log();
    }
    let several = spectra.len() > 1;
    for (i, (name, s)) in names.iter().zip(spectra).enumerate() {
        let psa: Vec<f64> = s.psa_m_s2.iter().map(|a| a / G).collect();
        let mut series = Series::line(
            if several {
                format!("records ({})", spectra.len())
            } else {
                name.clone()
            },
            s.periods_s.clone(),
            psa,
        )
        .rgb(if several {
            RECORD_GREY
        } else {
            style::color(0)
        })
        .width(if several { 1 } else { style::LINE_WIDTH });
        if several && i > 0 {
            series = series.no_legend();
        }
        p.push(series);
    }
    if several {
        p.push(
            Series::line("mean", periods.clone(), mean.clone())
                .rgb(style::INK)
                .width(3),
        );
    }
    if let (Some(d), Some(t)) = (target, &tgt) {
        p.push(
            Series::line(
                format!(
                    "target (ASCE 7, S_DS {} g, S_D1 {} g)",
                    d.sds_g(),
                    d.sd1_g()
                ),
                periods.clone(),
                t.clone(),
            )
            .rgb(style::color(1))
            .dashed()
            .width(3),
        );
    }
    let title = format!(
        "Response spectra, {} % damping{}",
        damping * 100.0,
        if several {
            format!(", {} records", spectra.len())
        } else {
            String::new()
        }
    );
    let fig = Figure::new(title).panel(p);

    let mut csv = String::from("period_s");
    for n in names {
        let _ = write!(csv, ",psa_g:{}", n.replace([',', '"', '\n'], "_"));
    }
    csv.push_str(",mean_psa_g");
    if tgt.is_some() {
        csv.push_str(",target_psa_g");
    }
    csv.push('\n');
    for (k, t) in periods.iter().enumerate() {
        let _ = write!(csv, "{t}");
        for s in spectra {
            let _ = write!(csv, ",{}", s.psa_m_s2[k] / G);
        }
        let _ = write!(csv, ",{}", mean[k]);
        if let Some(v) = &tgt {
            let _ = write!(csv, ",{}", v[k]);
        }
        csv.push('\n');
    }
    fig.save(&stem)?;
    write_atomic(&with_suffix(&stem, "csv"), csv.as_bytes())?;
    Ok(stem)
}
