//! Figures of one simulation (`slipload simulate --plot DIR`): displacement histories with
//! the slip thresholds, friction hysteresis, energies, the peak drift profile, and the
//! comparison with the bare frame.
//!
//! Data beside the figures: `history.csv` (every history column, SI units; the figures
//! show mm, kN, kJ), `history-bare.csv`, `drift-profile.csv`, `response.json` (the output
//! contract), `response-bare.json`, and `scene.json`, the scene that ran
//! ([`super::scene_file`]).

use anyhow::Context;
use slipload_figures::plot::{Figure, Legend, Marker, Panel, Series, style};
use slipload_opt::base::output::write_atomic;
use slipload_sim::{History, Outcome, Scene};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A history column, or an error naming it (the figures need it).
fn column(h: &History, name: &str) -> anyhow::Result<Vec<f64>> {
    h.column(name)
        .with_context(|| format!("history has no column {name}"))
}

/// `v` with 4 significant digits, no trailing zeros.
fn sig(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let d = (3 - v.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{v:.d$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

fn scaled(v: &[f64], k: f64) -> Vec<f64> {
    v.iter().map(|x| x * k).collect()
}

/// Panels per row for `n` panels of one per storey.
fn columns_for(n: usize) -> usize {
    if n <= 3 { 1 } else { 2 }
}

/// Writes every figure of a run and the data beside them, and `scene.json` (the resolved
/// scene, `scene_json`); returns the files written. `bare` is the same scene without
/// braces (when `--compare-bare` asked for it).
pub fn write_all(
    dir: &Path,
    scene: &Scene,
    scene_json: &super::scene_file::SceneAsRun,
    out: &Outcome,
    bare: Option<&Outcome>,
) -> anyhow::Result<Vec<PathBuf>> {
    slipload_figures::check_fonts()?;
    let h = out
        .history
        .as_ref()
        .context("the run kept no histories to plot")?;
    let mut files = Vec::new();
    let kept = dir.join("scene.json");
    let mut text = serde_json::to_string_pretty(scene_json)?;
    text.push('\n');
    write_atomic(&kept, text.as_bytes())?;
    files.push(kept);
    let csv = dir.join("history.csv");
    write_atomic(&csv, h.to_csv().as_bytes())?;
    files.push(csv);
    let json = dir.join("response.json");
    write_atomic(
        &json,
        serde_json::to_string_pretty(&out.response)?.as_bytes(),
    )?;
    files.push(json);
    if let Some(b) = bare {
        let hb = b
            .history
            .as_ref()
            .context("the bare-frame run kept no histories")?;
        let csv = dir.join("history-bare.csv");
        write_atomic(&csv, hb.to_csv().as_bytes())?;
        files.push(csv);
        let json = dir.join("response-bare.json");
        write_atomic(&json, serde_json::to_string_pretty(&b.response)?.as_bytes())?;
        files.push(json);
    }
    let mut save = |fig: Figure, name: &str| -> anyhow::Result<()> {
        let (svg, png) = fig.save(&dir.join(name))?;
        files.push(svg);
        files.push(png);
        Ok(())
    };
    save(displacements(scene, h)?, "displacements")?;
    if let Some(fig) = hysteresis(scene, h)? {
        save(fig, "hysteresis")?;
    }
    if let Some(fig) = storey_hysteresis(scene, h)? {
        save(fig, "storey-hysteresis")?;
    }
    if h.columns.iter().any(|c| c == "E_input_J") {
        save(energies(scene, h, out)?, "energy")?;
    }
    let (fig, csv) = drift_profile(scene, out, bare);
    write_atomic(&dir.join("drift-profile.csv"), csv.as_bytes())?;
    save(fig, "drift-profile")?;
    if let Some(b) = bare {
        let hb = b.history.as_ref().context("bare-frame histories")?;
        save(bare_comparison(scene, h, hb)?, "bare-comparison")?;
    }
    files.push(dir.join("drift-profile.csv"));
    Ok(files)
}

/// Per storey: the storey drift xᵢ − xᵢ₋₁ and the brace elongation x′ᵢ − xᵢ₋₁ (the
/// dissipator's displacement relative to the floor its brace stands on), with the slip
/// thresholds F⁺/k′ and F⁻/k′ (±μN/k′) that the brace elongation of a massless damper
/// never leaves. On storey 1 these are the floor and dissipator displacements of the
/// paper's Figs. 6–7 (De la Cruz et al. 2007).
pub fn displacements(scene: &Scene, h: &History) -> anyhow::Result<Figure> {
    let t = column(h, "t_s")?;
    let (t0, t1) = (t[0], *t.last().expect("a history has a first row"));
    let n = scene.building.floors();
    let mut fig = Figure::new(format!("{}: storey drift and brace elongation", scene.name))
        .columns(columns_for(n));
    let mut below = vec![0.0; t.len()];
    for i in 1..=n {
        let x = column(h, &format!("x{i}_m"))?;
        let drift: Vec<f64> = x.iter().zip(&below).map(|(a, b)| 1e3 * (a - b)).collect();
        let drift_name = if i == 1 {
            "floor x1".to_string()
        } else {
            format!("drift x{i} − x{}", i - 1)
        };
        let mut p = Panel::new("time (s)", "displacement (mm)")
            .title(format!("storey {i}"))
            .legend(Legend::Right)
            .series(Series::line(drift_name, t.clone(), drift).color(0));
        if let Some(xd) = h.column(&format!("xd{i}_m")) {
            let brace: Vec<f64> = xd.iter().zip(&below).map(|(a, b)| 1e3 * (a - b)).collect();
            let name = if i == 1 {
                "dissipator x′1".to_string()
            } else {
                format!("brace x′{i} − x{}", i - 1)
            };
            p.push(Series::line(name, t.clone(), brace).color(1).width(1));
            if let Some(Some(d)) = scene.building.dissipators.get(i - 1)
                && d.upper.is_finite()
                && d.lower.is_finite()
            {
                let k = 1e3 / d.brace_stiffness;
                let name = if d.upper == -d.lower {
                    "±μN/k′"
                } else {
                    "F±/k′"
                };
                p.push(Series::hline(name, d.upper * k, t0, t1).rgb(style::INK));
                p.push(
                    Series::hline("", d.lower * k, t0, t1)
                        .rgb(style::INK)
                        .no_legend(),
                );
            }
        }
        fig = fig.panel(p);
        below = x;
    }
    Ok(fig)
}

/// Per damper: friction force Fᵢ against slip xᵢ − x′ᵢ (the paper's Fig. 10), with the
/// slip loads F⁺ and F⁻ dashed. `None` when the plan has no contact.
pub fn hysteresis(scene: &Scene, h: &History) -> anyhow::Result<Option<Figure>> {
    let n = scene.building.floors();
    let floors: Vec<usize> = (1..=n)
        .filter(|i| h.columns.iter().any(|c| *c == format!("F{i}_N")))
        .collect();
    if floors.is_empty() {
        return Ok(None);
    }
    let mut fig = Figure::new(format!("{}: friction force vs slip", scene.name))
        .columns(if floors.len() == 1 { 1 } else { 2 });
    for &i in &floors {
        let x = column(h, &format!("x{i}_m"))?;
        let xd = column(h, &format!("xd{i}_m"))?;
        let f = column(h, &format!("F{i}_N"))?;
        let slip: Vec<f64> = x.iter().zip(&xd).map(|(a, b)| 1e3 * (a - b)).collect();
        let (lo, hi) = slip
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), v| {
                (l.min(*v), u.max(*v))
            });
        // The slip loads (dashed) are named in the title; no legend covers the loop.
        let mut p = Panel::new(
            format!("slip x{i} − x′{i} (mm)"),
            format!("friction force F{i} (kN)"),
        )
        .title(format!("damper {i}"))
        .legend(Legend::None)
        .series(Series::line("friction force", slip, scaled(&f, 1e-3)).color(0));
        if let Some(Some(d)) = scene.building.dissipators.get(i - 1)
            && d.upper.is_finite()
            && d.lower.is_finite()
            && lo.is_finite()
        {
            let (name, title) = if d.upper == -d.lower {
                (
                    "±μN",
                    format!("damper {i}: μN = {} kN (dashed)", sig(d.upper * 1e-3)),
                )
            } else {
                (
                    "F⁺, F⁻",
                    format!(
                        "damper {i}: F⁻ = {} kN, F⁺ = {} kN (dashed)",
                        sig(d.lower * 1e-3),
                        sig(d.upper * 1e-3)
                    ),
                )
            };
            let m = d.upper.max(-d.lower) * 1e-3;
            p = p.title(title).y_range(-1.15 * m, 1.15 * m);
            p.push(Series::hline(name, d.upper * 1e-3, lo, hi).rgb(style::INK));
            p.push(
                Series::hline("", d.lower * 1e-3, lo, hi)
                    .rgb(style::INK)
                    .no_legend(),
            );
        }
        fig = fig.panel(p);
    }
    if floors.len() == 1 {
        fig = fig.size(style::SIZE.0, style::SIZE.1);
    }
    Ok(Some(fig))
}

/// Per yielding storey: the storey shear αk·d + Fₚ (its elastic part and its plastic
/// element's force) against the drift d, with ±Fy dashed, beside the friction force
/// against slip of the damper on the same floor (when there is one). `None` when no
/// storey yields.
pub fn storey_hysteresis(scene: &Scene, h: &History) -> anyhow::Result<Option<Figure>> {
    let yielding: Vec<(usize, slipload_sim::StoreyYield)> = scene
        .building
        .storey_yield
        .iter()
        .enumerate()
        .filter_map(|(i, y)| y.map(|y| (i + 1, y)))
        .filter(|(i, _)| h.columns.iter().any(|c| *c == format!("Fp{i}_N")))
        .collect();
    if yielding.is_empty() {
        return Ok(None);
    }
    let mut fig = Figure::new(format!(
        "{}: storey shear vs drift, beside the damper's friction force vs slip",
        scene.name
    ))
    .columns(2);
    for (i, y) in yielding {
        let drift = column(h, &format!("drift{i}_m"))?;
        let fp = column(h, &format!("Fp{i}_N"))?;
        let shear: Vec<f64> = drift
            .iter()
            .zip(&fp)
            .map(|(d, f)| 1e-3 * (y.post_yield_ratio * y.stiffness * d + f))
            .collect();
        let d_mm = scaled(&drift, 1e3);
        let (lo, hi) = d_mm
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), v| {
                (l.min(*v), u.max(*v))
            });
        let fy = y.yield_shear * 1e-3;
        let mut p = Panel::new(format!("drift {i} (mm)"), format!("storey shear {i} (kN)"))
            .title(format!(
                "storey {i}: Fy = {} kN, α = {} (dashed ±Fy)",
                sig(fy),
                sig(y.post_yield_ratio)
            ))
            .legend(Legend::None)
            .series(Series::line("storey shear", d_mm, shear).color(1));
        if lo.is_finite() {
            p.push(Series::hline("±Fy", fy, lo, hi).rgb(style::INK));
            p.push(Series::hline("", -fy, lo, hi).rgb(style::INK).no_legend());
        }
        fig = fig.panel(p);
        let damper = match (
            h.column(&format!("x{i}_m")),
            h.column(&format!("xd{i}_m")),
            h.column(&format!("F{i}_N")),
        ) {
            (Some(x), Some(xd), Some(f)) => Some((x, xd, f)),
            _ => None,
        };
        fig = fig.panel(match damper {
            Some((x, xd, f)) => {
                let slip: Vec<f64> = x.iter().zip(&xd).map(|(a, b)| 1e3 * (a - b)).collect();
                Panel::new(
                    format!("slip x{i} − x′{i} (mm)"),
                    format!("friction force F{i} (kN)"),
                )
                .title(format!("damper {i}"))
                .legend(Legend::None)
                .series(Series::line("friction force", slip, scaled(&f, 1e-3)).color(0))
            }
            None => Panel::new("-", "-").title(format!("storey {i}: no damper")),
        });
    }
    Ok(Some(fig))
}

/// Energy histories (relative formulation): friction, viscous and kinetic + strain
/// stacked, the input (plus any initial energy) as a line on top; the gap between the
/// line and the stack is the balance error.
pub fn energies(scene: &Scene, h: &History, out: &Outcome) -> anyhow::Result<Figure> {
    let t = column(h, "t_s")?;
    let kj = |name: &str| column(h, name).map(|v| scaled(&v, 1e-3));
    let (input, kinetic, strain, viscous, friction) = (
        kj("E_input_J")?,
        kj("E_kinetic_J")?,
        kj("E_strain_J")?,
        kj("E_viscous_J")?,
        kj("E_friction_J")?,
    );
    let e0 = out.diagnostics.initial_energy * 1e-3;
    let ks: Vec<f64> = kinetic.iter().zip(&strain).map(|(a, b)| a + b).collect();
    let (line_name, supplied): (&str, Vec<f64>) = if e0 > 0.0 {
        ("input + initial", input.iter().map(|v| v + e0).collect())
    } else {
        ("input", input)
    };
    let mut p = Panel::new("time (s)", "energy (kJ)")
        .y_from_zero()
        .legend(Legend::UpperLeft);
    if let Some(plastic) = h.column("E_plastic_J") {
        p = p.series(Series::area("plastic (frame)", t.clone(), scaled(&plastic, 1e-3)).color(3));
    }
    let p = p
        .series(Series::area("friction", t.clone(), friction).color(1))
        .series(Series::area("viscous", t.clone(), viscous).color(0))
        .series(Series::area("kinetic + strain", t.clone(), ks).color(2))
        .series(Series::line(line_name, t, supplied).rgb(style::INK));
    Ok(Figure::new(format!("{}: energies", scene.name)).panel(p))
}

/// Peak interstorey drift ratio per storey (peak drift in mm when the building has no
/// storey heights), with the bare frame's when given; and its CSV.
pub fn drift_profile(scene: &Scene, out: &Outcome, bare: Option<&Outcome>) -> (Figure, String) {
    let n = out.response.peak_drift.len();
    let ratio = out.response.peak_drift_ratio.is_some();
    let values = |o: &Outcome| -> Vec<f64> {
        match &o.response.peak_drift_ratio {
            Some(r) => scaled(r, 100.0),
            None => scaled(&o.response.peak_drift, 1e3),
        }
    };
    let storeys: Vec<f64> = (1..=n).map(|i| i as f64).collect();
    let label = if ratio {
        "peak interstorey drift ratio (%)"
    } else {
        "peak interstorey drift (mm)"
    };
    let mut p = Panel::new(label, "storey (-)")
        .x_from_zero()
        .y_range(0.5, n as f64 + 0.5)
        .y_integer()
        .legend(Legend::Right)
        .series(
            Series::line("with dampers", values(out), storeys.clone())
                .marker(Marker::Circle)
                .color(0),
        );
    let mut csv = String::from("storey,peak_drift_m,peak_drift_ratio");
    if bare.is_some() {
        csv.push_str(",bare_peak_drift_m,bare_peak_drift_ratio");
    }
    csv.push('\n');
    if let Some(b) = bare {
        p.push(
            Series::line("bare frame", values(b), storeys)
                .marker(Marker::Square)
                .dashed()
                .color(1),
        );
    }
    let cell = |o: &Outcome, i: usize| {
        format!(
            "{:.9e},{}",
            o.response.peak_drift[i],
            o.response
                .peak_drift_ratio
                .as_ref()
                .map_or(String::new(), |r| format!("{:.9e}", r[i]))
        )
    };
    for i in 0..n {
        let _ = write!(csv, "{},{}", i + 1, cell(out, i));
        if let Some(b) = bare {
            let _ = write!(csv, ",{}", cell(b, i));
        }
        csv.push('\n');
    }
    let fig = Figure::new(format!("{}: peak drift profile", scene.name))
        .panel(p)
        .size(760, 140 + 60 * n.clamp(3, 10) as u32);
    (fig, csv)
}

/// Floor displacements with and without dampers on one axis, one panel per floor, top
/// floor first (the paper's Fig. 13 style). The bare frame is the same scene with no
/// braces (every slip load 0: a brace without friction carries no force).
pub fn bare_comparison(scene: &Scene, h: &History, bare: &History) -> anyhow::Result<Figure> {
    let n = scene.building.floors();
    let t = column(h, "t_s")?;
    let tb = column(bare, "t_s")?;
    let mut fig =
        Figure::new(format!("{}: with and without dampers", scene.name)).columns(columns_for(n));
    for i in (1..=n).rev() {
        let x = column(h, &format!("x{i}_m"))?;
        let xb = column(bare, &format!("x{i}_m"))?;
        fig = fig.panel(
            Panel::new("time (s)", format!("floor {i} displacement (mm)"))
                .title(format!("floor {i}"))
                .legend(Legend::Right)
                .series(Series::line("bare frame", tb.clone(), scaled(&xb, 1e3)).color(1))
                .series(Series::line("with dampers", t.clone(), scaled(&x, 1e3)).color(0)),
        );
    }
    Ok(fig)
}
