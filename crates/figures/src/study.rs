//! The study figures of `optimize`, `sweep` and `merge`, drawn from the figure data of
//! their reports ([`slipload_opt::phases::figures::FigureData`]), each with the CSV of its data
//! written beside it:
//! - objective map over the slip loads of two dissipators, the others at the optimum
//!   (opt-in);
//! - the refiners' convergence: best objective so far vs simulations;
//! - peak drift-ratio profiles over the storeys of the ranked designs (mean and 84th
//!   percentile over the suite), with the peak drift ratio limits the suite states as
//!   dotted vertical lines;
//! - per-record peak drift ratio of the best design vs the bare frame;
//! - each code-scaled suite's mean spectrum against its target (`code-spectra`).
//!
//! A study of several suites draws the profiles and the scatter once per suite
//! (`drift-profiles-SUITE`, `records-scatter-SUITE`); a study of one suite under the plain
//! names.

use crate::FigureError;
use slipload_opt::base::collapse::objective_text;
use slipload_opt::phases::figures::{
    Convergence, DriftLimit, DriftProfile, FigureData, ObjectiveMap, RecordScatter, SuiteFigures,
};
use slipload_sim::response::csv_field;
use std::fmt::Write as _;
use std::path::Path;

/// `slip_load_kN_A,slip_load_kN_B,objective`, one line per grid point.
pub fn map_csv(m: &ObjectiveMap) -> String {
    let [a, b] = m.floors;
    let mut s = format!("slip_load_kN_{a},slip_load_kN_{b},objective\n");
    let nb = m.loads_b_kn.len();
    for (i, x) in m.loads_a_kn.iter().enumerate() {
        for (j, y) in m.loads_b_kn.iter().enumerate() {
            // a collapsed design's objective is the word, not inf
            let _ = writeln!(
                s,
                "{x},{y},{}",
                objective_text(m.objective[i * nb + j], None)
            );
        }
    }
    s
}

/// `refiner,simulations,objective,best_so_far`.
pub fn convergence_csv(paths: &[Convergence]) -> String {
    let mut s = String::from("refiner,simulations,objective,best_so_far\n");
    for c in paths {
        for (n, f, b) in &c.points {
            let _ = writeln!(
                s,
                "{},{n},{},{}",
                csv_field(&c.refiner),
                objective_text(*f, None),
                objective_text(*b, None)
            );
        }
    }
    s
}

/// `design,storey,drift_ratio_mean,drift_ratio_p84`.
pub fn drift_profiles_csv(profiles: &[DriftProfile]) -> String {
    let mut s = String::from("design,storey,drift_ratio_mean,drift_ratio_p84\n");
    for p in profiles {
        for (i, (m, q)) in p.mean.iter().zip(&p.p84).enumerate() {
            let _ = writeln!(s, "{},{},{m},{q}", csv_field(&p.design), i + 1);
        }
    }
    s
}

/// `record,bare_peak_drift_ratio,DESIGN_peak_drift_ratio,suite`: every row names the
/// suite of its record.
pub fn scatter_csv(sc: &RecordScatter) -> String {
    let mut s = format!(
        "record,bare_peak_drift_ratio,{}_peak_drift_ratio,suite\n",
        sc.design
    );
    for (((r, b), d), suite) in sc
        .records
        .iter()
        .zip(&sc.bare)
        .zip(&sc.design_values)
        .zip(&sc.suites)
    {
        let _ = writeln!(s, "{},{b},{d},{}", csv_field(r), csv_field(suite));
    }
    s
}

/// A number as a design states it: at most `digits` decimals, no trailing zeros
/// (`2`, `0.5`, `1.25`).
pub fn trimmed(v: f64, digits: usize) -> String {
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// The legend name of a drift limit on a profile: `limit, mean: 2 %`.
pub fn limit_label(l: &DriftLimit) -> String {
    format!("limit, {}: {} %", l.applies_to, trimmed(100.0 * l.ratio, 3))
}

/// The palette colour of each design of a figure by what the design is, not where it
/// ranks: the designs the study tables name keep one colour each in every figure
/// (`optimum` blue, `file` vermillion, `uniform` green, `storey-shear` purple, `stiffness`
/// orange, `bare` black); every other design (a sweep's sample, `s0012`) takes the palette
/// colours no named design of this figure holds, in the order of the designs' names. The
/// colours depend on the set of designs only, so reordering them (another ranking) keeps
/// each design's colour.
pub fn design_colors(names: &[&str]) -> Vec<plotters::style::RGBColor> {
    use crate::plot::style::{PALETTE, color};
    const ROLES: [(&str, usize); 6] = [
        ("optimum", 0),
        ("file", 1),
        ("uniform", 2),
        ("storey-shear", 3),
        ("stiffness", 4),
        ("bare", 6),
    ];
    let role = |name: &str| ROLES.iter().find(|(r, _)| *r == name).map(|&(_, i)| i);
    let taken: Vec<usize> = names.iter().filter_map(|n| role(n)).collect();
    let free: Vec<usize> = (0..PALETTE.len()).filter(|i| !taken.contains(i)).collect();
    let mut others: Vec<&str> = names
        .iter()
        .copied()
        .filter(|n| role(n).is_none())
        .collect();
    others.sort_unstable();
    others.dedup();
    names
        .iter()
        .map(|n| match role(n) {
            Some(i) => color(i),
            None => {
                let k = others.iter().position(|o| o == n).unwrap_or(0);
                color(free.get(k % free.len().max(1)).copied().unwrap_or(k))
            }
        })
        .collect()
}

/// Writes every figure of `data` present (`NAME.svg`, `NAME.png`, in the shared plot
/// style) with its data (`NAME.csv`) into `dir` (created when missing); returns the names
/// written (stems, without extension), in the order above. Every file is written
/// atomically; the PNGs need a font ([`crate::check_fonts`]).
pub fn write(data: &FigureData, dir: &Path) -> Result<Vec<String>, FigureError> {
    use crate::plot::{Figure, HeatMap, Legend, Marker, Panel, Series, style};
    let mut names = Vec::new();
    let mut put = |stem: &str, csv: String, fig: Figure| -> Result<(), FigureError> {
        slipload_opt::base::output::write_atomic(&dir.join(format!("{stem}.csv")), csv.as_bytes())?;
        fig.save(&dir.join(stem))?;
        names.push(stem.to_string());
        Ok(())
    };
    if let Some(m) = &data.map {
        let [a, b] = m.floors;
        let nb = m.loads_b_kn.len();
        let z: Vec<Vec<f64>> = (0..nb)
            .map(|j| {
                (0..m.loads_a_kn.len())
                    .map(|i| m.objective[i * nb + j])
                    .collect()
            })
            .collect();
        let fig = Figure::new(format!("Objective map: {}", m.label)).panel(
            Panel::new(
                format!("slip load, floor {a} (kN)"),
                format!("slip load, floor {b} (kN)"),
            )
            .title("other floors at the optimum")
            // outside the axes: the heat map fills them, and the optimum may sit in any
            // corner, where a legend inside would hide its marker
            .legend(Legend::Right)
            .heatmap(HeatMap {
                x: m.loads_a_kn.clone(),
                y: m.loads_b_kn.clone(),
                z,
                label: format!("{} (-)", m.label),
                z_range: None,
            })
            .series(
                Series::scatter("optimum", vec![m.optimum_kn[0]], vec![m.optimum_kn[1]])
                    .marker(Marker::Diamond)
                    .rgb(style::INK),
            ),
        );
        put("objective-map", map_csv(m), fig)?;
    }
    if !data.convergence.is_empty() {
        let mut panel =
            Panel::new("simulations (-)", "best objective so far (-)").legend(Legend::UpperRight);
        for (k, c) in data.convergence.iter().enumerate() {
            let x = c.points.iter().map(|p| p.0 as f64).collect();
            let y = c.points.iter().map(|p| p.2).collect();
            panel = panel.series(
                Series::line(c.refiner.clone(), x, y)
                    .color(k)
                    .marker(Marker::ALL[k % Marker::ALL.len()]),
            );
        }
        let fig = Figure::new("Refiner convergence").panel(panel);
        put("convergence", convergence_csv(&data.convergence), fig)?;
    }
    for sf in &data.suites {
        let several = !sf.suffix.is_empty();
        if let Some(fig) = profiles_figure(sf, &data.fidelity, several) {
            put(
                &sf.stem("drift-profiles"),
                drift_profiles_csv(&sf.profiles),
                fig,
            )?;
        }
        if let Some(sc) = &sf.scatter {
            let fig = scatter_figure(sc, &sf.suite, &data.fidelity, several);
            put(&sf.stem("records-scatter"), scatter_csv(sc), fig)?;
        }
    }
    if !data.spectra.is_empty() {
        // the clause of the rule each suite was scaled by, each once
        let mut clauses: Vec<&str> = Vec::new();
        for (_, c) in &data.spectra {
            if !clauses.contains(&c.clause()) {
                clauses.push(c.clause());
            }
        }
        let mut panel = Panel::new("period (s)", "pseudo-spectral acceleration, 5 % (g)")
            .title(format!(
                "solid: the scaled suite's mean; dashed: the target; dotted: 90 % of it ({})",
                clauses.join("; ")
            ))
            .x_log()
            .y_from_zero()
            .legend(Legend::UpperRight);
        for (k, (name, c)) in data.spectra.iter().enumerate() {
            panel = panel
                .series(
                    Series::line(
                        format!("{name} (× {:.3})", c.factor),
                        c.periods_s.clone(),
                        c.mean_sa_g.clone(),
                    )
                    .color(k),
                )
                .series(
                    Series::line(
                        format!("{name} target ({})", c.hazard.as_str()),
                        c.periods_s.clone(),
                        c.target_sa_g.clone(),
                    )
                    .color(k)
                    .dashed(),
                )
                .series(
                    Series::line(
                        format!("{name} 90 % of target"),
                        c.periods_s.clone(),
                        c.target_sa_g.iter().map(|v| 0.9 * v).collect(),
                    )
                    .color(k)
                    .dotted(),
                );
        }
        let fig = Figure::new("Code-scaled suites against their target spectra").panel(panel);
        put("code-spectra", spectra_csv(&data.spectra), fig)?;
    }
    Ok(names)
}

/// The drift profiles of one suite's ranked designs (mean solid, 84th percentile dashed)
/// with the suite's drift limits as dotted vertical lines, in percent; `None` without a
/// profile.
fn profiles_figure(
    sf: &SuiteFigures,
    fidelity: &str,
    several: bool,
) -> Option<crate::plot::Figure> {
    use crate::plot::{Figure, Legend, Marker, Panel, Series, style};
    if sf.profiles.is_empty() {
        return None;
    }
    let storeys = sf.profiles.iter().map(|p| p.mean.len()).max().unwrap_or(1);
    let mut panel = Panel::new("peak drift ratio (%)", "storey (-)")
        .title(format!(
            "solid: mean, dashed: 84th percentile{}; {fidelity}",
            if sf.limits.is_empty() {
                ""
            } else {
                ", dotted: limit"
            }
        ))
        .x_from_zero()
        .y_range(0.5, storeys as f64 + 0.5)
        .y_integer()
        // outside the axes: the profiles span the whole height, and the bare frame's
        // reaches the right edge, so no corner inside is free
        .legend(Legend::Right);
    let names: Vec<&str> = sf.profiles.iter().map(|p| p.design.as_str()).collect();
    let colors = design_colors(&names);
    for (p, &color) in sf.profiles.iter().zip(&colors) {
        let storeys: Vec<f64> = (1..=p.mean.len()).map(|i| i as f64).collect();
        let pct = |v: &[f64]| v.iter().map(|x| 100.0 * x).collect::<Vec<_>>();
        panel = panel
            .series(
                Series::line(p.design.clone(), pct(&p.mean), storeys.clone())
                    .rgb(color)
                    .marker(Marker::Circle),
            )
            .series(
                Series::line(format!("{} p84", p.design), pct(&p.p84), storeys)
                    .rgb(color)
                    .dashed()
                    .no_legend(),
            );
    }
    // the suite's limits over the whole height, in the axis' unit (percent)
    for l in &sf.limits {
        let x = 100.0 * l.ratio;
        panel = panel.series(
            Series::line(limit_label(l), vec![x, x], vec![0.5, storeys as f64 + 0.5])
                .rgb(style::INK)
                .width(style::REF_WIDTH)
                .dotted(),
        );
    }
    let title = if several {
        format!(
            "Peak drift-ratio profiles of the ranked designs, suite {}",
            sf.suite
        )
    } else {
        "Peak drift-ratio profiles of the ranked designs".to_string()
    };
    Some(Figure::new(title).panel(panel))
}

/// One suite's best design vs the bare frame, per record, in percent, with the 1:1 line.
fn scatter_figure(
    sc: &RecordScatter,
    suite: &str,
    fidelity: &str,
    several: bool,
) -> crate::plot::Figure {
    use crate::plot::{Figure, Legend, Panel, Series, style};
    let x: Vec<f64> = sc.bare.iter().map(|v| 100.0 * v).collect();
    let y: Vec<f64> = sc.design_values.iter().map(|v| 100.0 * v).collect();
    let top = x.iter().chain(&y).copied().fold(0.0, f64::max);
    let title = if several {
        format!("Per record: {} vs bare frame, suite {suite}", sc.design)
    } else {
        format!("Per record: {} vs bare frame", sc.design)
    };
    Figure::new(title).panel(
        Panel::new(
            "bare frame: peak drift ratio (%)",
            format!("{}: peak drift ratio (%)", sc.design),
        )
        .title(fidelity.to_string())
        .x_from_zero()
        .y_from_zero()
        .legend(Legend::UpperLeft)
        .series(Series::scatter("records", x, y).color(0))
        .series(
            Series::line("1:1", vec![0.0, top], vec![0.0, top])
                .dashed()
                .rgb(style::INK),
        ),
    )
}

/// `suite,hazard,factor,period_s,mean_sa_g,target_sa_g`, one line per suite and period.
pub fn spectra_csv(spectra: &[(String, slipload_opt::model::study::CodeScaling)]) -> String {
    let mut s = String::from("suite,hazard,factor,period_s,mean_sa_g,target_sa_g\n");
    for (name, c) in spectra {
        for ((t, m), g) in c.periods_s.iter().zip(&c.mean_sa_g).zip(&c.target_sa_g) {
            let _ = writeln!(s, "{name},{},{},{t},{m},{g}", c.hazard.as_str(), c.factor);
        }
    }
    s
}
