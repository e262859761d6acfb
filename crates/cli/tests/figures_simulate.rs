//! Contract: `slipload simulate … --plot DIR` writes each figure as non-empty SVG + PNG,
//! and every series the SVG holds matches the data written beside it (history.csv,
//! history-bare.csv, drift-profile.csv): series count per panel, data ranges, and the
//! axes contain the data.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
mod figures_common;

use common::{scratch, slipload};
use figures_common::{Csv, assert_inside, assert_x, assert_y, figure, range};

/// CSV cells carry 10 significant digits (`{:.9e}`): relative rounding ≤ 5e-10 of a value,
/// so 1e-9 of the largest magnitude bounds the error of a value or of a difference of two.
fn tol(v: &[f64]) -> f64 {
    let (a, b) = range(v);
    1e-9 * a.abs().max(b.abs()).max(1e-300)
}

fn mm(v: &[f64]) -> Vec<f64> {
    v.iter().map(|x| x * 1e3).collect()
}

fn diff_mm(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| 1e3 * (x - y)).collect()
}

#[test]
fn benchmark_figures_match_their_csv() {
    let dir = scratch("figsim", "bench");
    let d = dir.to_str().unwrap();
    let out = slipload(&["simulate", "--duration", "3", "--plot", d, "--compare-bare"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let h = Csv::read(&dir.join("history.csv"));
    let hb = Csv::read(&dir.join("history-bare.csv"));
    let t = h.col("t_s");
    let t_range = range(&t);
    let floors = 3;

    // Displacements: one panel per storey; drift and brace elongation as in the CSV.
    let m = figure(&dir.join("displacements"));
    assert_eq!(m.panels.len(), floors);
    let mut below = vec![0.0; t.len()];
    for (i, p) in m.panels.iter().enumerate() {
        let x = h.col(&format!("x{}_m", i + 1));
        assert_inside(p);
        // drift, brace, +threshold, −threshold (every storey of the benchmark has a damper)
        assert_eq!(p.series.len(), 4, "panel {}", p.title);
        let drift = mm(&h.col(&format!("drift{}_m", i + 1)));
        assert_y(&p.series[0], range(&drift), tol(&drift));
        assert_x(&p.series[0], t_range, tol(&t));
        let brace = diff_mm(&h.col(&format!("xd{}_m", i + 1)), &below);
        assert_y(&p.series[1], range(&brace), 2.0 * tol(&brace));
        let (up, lo) = (p.series[2].y[0].unwrap(), p.series[3].y[0].unwrap());
        assert!(
            up > 0.0 && (up + lo).abs() <= 1e-12 * up,
            "±μN/k′: {up}, {lo}"
        );
        below = x;
    }

    // Hysteresis: one panel per damper, F (kN) vs slip (mm).
    let m = figure(&dir.join("hysteresis"));
    assert_eq!(m.panels.len(), floors);
    for (i, p) in m.panels.iter().enumerate() {
        let k = i + 1;
        assert_inside(p);
        let slip = diff_mm(&h.col(&format!("x{k}_m")), &h.col(&format!("xd{k}_m")));
        let f: Vec<f64> = h.col(&format!("F{k}_N")).iter().map(|v| v * 1e-3).collect();
        // A difference of two 10-digit CSV columns: its rounding error scales with the
        // operands (floor and dissipator displacements), not with the slip itself.
        let mm = |c: Vec<f64>| -> Vec<f64> { c.iter().map(|v| v * 1e3).collect() };
        let operands = tol(&mm(h.col(&format!("x{k}_m")))) + tol(&mm(h.col(&format!("xd{k}_m"))));
        assert_x(&p.series[0], range(&slip), 2.0 * tol(&slip) + operands);
        assert_y(&p.series[0], range(&f), tol(&f));
        // The slip loads bound the force (the friction law).
        let mu_n = p.series[1].y[0].unwrap();
        assert!(range(&f).1 <= mu_n * (1.0 + 1e-9) && range(&f).0 >= -mu_n * (1.0 + 1e-9));
    }

    // Energies: three stacked bands and the input line.
    let m = figure(&dir.join("energy"));
    let p = &m.panels[0];
    assert_eq!(p.series.len(), 4);
    assert_inside(p);
    let kj = |c: &str| -> Vec<f64> { h.col(c).iter().map(|v| v * 1e-3).collect() };
    let ks: Vec<f64> = kj("E_kinetic_J")
        .iter()
        .zip(kj("E_strain_J"))
        .map(|(a, b)| a + b)
        .collect();
    for (s, v) in p
        .series
        .iter()
        .zip([kj("E_friction_J"), kj("E_viscous_J"), ks, kj("E_input_J")])
    {
        assert_y(s, range(&v), 2.0 * tol(&v));
    }
    assert_eq!(p.series.iter().filter(|s| s.kind == "area").count(), 3);
    // Zero is on the axis (the relative input energy may dip below it).
    assert!(p.y.min <= 0.0 && p.y.max > 0.0);

    // Drift profile: with dampers and bare, as in drift-profile.csv.
    let m = figure(&dir.join("drift-profile"));
    let dp = Csv::read(&dir.join("drift-profile.csv"));
    let p = &m.panels[0];
    assert_eq!(p.series.len(), 2);
    assert_inside(p);
    // The legend covers no curve: it sits outside the plotting area.
    let [l, t, r, b] = p.legend.expect("a legend");
    let [pl, pt, pr, pb] = p.plot_area.unwrap();
    assert!(
        r <= pl || l >= pr || b <= pt || t >= pb,
        "legend {:?} over the plotting area {:?}",
        [l, t, r, b],
        [pl, pt, pr, pb]
    );
    // Storeys are labelled at whole numbers only.
    let storeys: Vec<f64> = (1..=floors).map(|i| i as f64).collect();
    assert!(
        p.y.ticks.iter().all(|t| storeys.contains(t)) && !p.y.ticks.is_empty(),
        "storey ticks {:?}",
        p.y.ticks
    );
    for (s, c) in p
        .series
        .iter()
        .zip(["peak_drift_ratio", "bare_peak_drift_ratio"])
    {
        let v: Vec<f64> = dp.col(c).iter().map(|x| x * 100.0).collect();
        assert_x(s, range(&v), tol(&v));
        assert_y(s, (1.0, floors as f64), 0.0);
        assert_eq!(s.points, floors);
    }

    // With and without dampers: one panel per floor, top floor first.
    let m = figure(&dir.join("bare-comparison"));
    assert_eq!(m.panels.len(), floors);
    for (k, p) in m.panels.iter().enumerate() {
        let floor = floors - k;
        assert_inside(p);
        assert_eq!(p.series.len(), 2);
        let xb = mm(&hb.col(&format!("x{floor}_m")));
        let x = mm(&h.col(&format!("x{floor}_m")));
        assert_y(&p.series[0], range(&xb), tol(&xb));
        assert_y(&p.series[1], range(&x), tol(&x));
    }
    // The bare frame moves more than the damped one on this record (the figure's point).
    assert!(
        range(&hb.col("x3_m")).1 - range(&hb.col("x3_m")).0
            > range(&h.col("x3_m")).1 - range(&h.col("x3_m")).0
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// One storey, a harmonic force, massive dissipator: one panel each; no bare figure
/// unless asked.
#[test]
fn one_storey_figures() {
    let dir = scratch("figsim", "one");
    let d = dir.to_str().unwrap();
    let out = slipload(&[
        "simulate",
        "configs/paper-1story-harmonic.json",
        "--duration",
        "1",
        "--plot",
        d,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!dir.join("bare-comparison.svg").exists());
    assert!(!dir.join("history-bare.csv").exists());
    let h = Csv::read(&dir.join("history.csv"));
    for name in ["displacements", "hysteresis", "energy", "drift-profile"] {
        let m = figure(&dir.join(name));
        assert_eq!(m.panels.len(), 1, "{name}");
        assert_inside(&m.panels[0]);
    }
    let m = figure(&dir.join("displacements"));
    let x = mm(&h.col("x1_m"));
    assert_y(&m.panels[0].series[0], range(&x), tol(&x));
    let xd = mm(&h.col("xd1_m"));
    assert_y(&m.panels[0].series[1], range(&xd), tol(&xd));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn compare_bare_needs_plot_and_bad_folder_is_an_error() {
    let out = slipload(&["simulate", "--duration", "1", "--compare-bare"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--plot"));
    // A file where the folder should be: a clear error, no figure anywhere.
    let dir = scratch("figsim", "bad");
    let file = dir.join("not-a-folder");
    std::fs::write(&file, "x").unwrap();
    let out = slipload(&[
        "simulate",
        "--duration",
        "1",
        "--plot",
        file.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("not-a-folder"), "{err}");
    assert!(
        err.contains("existing file") && err.contains("--plot takes a folder"),
        "says what --plot takes: {err}"
    );
    assert_eq!(
        std::fs::read_to_string(&file).unwrap(),
        "x",
        "the file is untouched"
    );
    assert!(!String::from_utf8_lossy(&out.stderr).contains("panicked"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Without a font the PNG cannot be drawn: the error names the variable or the paths
/// looked at, and nothing is written.
#[test]
fn missing_font_is_a_clear_error_before_any_output() {
    let dir = scratch("figsim", "nofont");
    let plot = dir.join("figs");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_slipload"))
        .args([
            "simulate",
            "--duration",
            "1",
            "--plot",
            plot.to_str().unwrap(),
        ])
        .current_dir(common::root())
        .env("SLIPLOAD_FONT", dir.join("no-such-font.ttf"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("SLIPLOAD_FONT") && err.contains("no-such-font.ttf"),
        "{err}"
    );
    assert!(
        !plot.exists(),
        "no output folder for a run that cannot draw"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
