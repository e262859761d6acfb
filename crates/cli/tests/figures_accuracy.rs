//! Contract: `slipload accuracy … --out DIR` draws NAME-work-precision and NAME-error-vs-dt
//! (SVG + PNG, non-empty) beside NAME.csv: one panel per error measure, one series per
//! method plus one of failed runs; every series matches the CSV rows it comes from, the
//! failed runs sit above every error, and the legend of error vs Δt gives the fitted order
//! that NAME.json reports. The peak-drift panel costs each run by its peaks-only time (what
//! a sweep pays), the energy and history panels by the time with those outputs; `exact`,
//! whose error against itself is round-off, is a vertical line at its cost.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
mod figures_common;

use common::{scratch, slipload};
use figures_common::{assert_inside, assert_x, assert_y, figure};

/// The CSV prints errors, CPU times and Δt with 7 significant digits (`{:.6e}`;
/// Δt with 10): relative rounding ≤ 5e-7.
const REL: f64 = 1e-6;

struct Row {
    method: String,
    dt: f64,
    errors: Option<[f64; 3]>,
    cpu: Option<f64>,
    cpu_peaks: Option<f64>,
}

impl Row {
    /// The cost panel `k` draws (0: peak drift, peaks only; else with outputs).
    fn cost(&self, k: usize) -> Option<f64> {
        if k == 0 { self.cpu_peaks } else { self.cpu }
    }
}

fn rows(csv: &str) -> Vec<Row> {
    csv.lines()
        .skip(1)
        .map(|l| {
            let c: Vec<&str> = l.splitn(11, ',').collect();
            let num = |s: &str| s.parse::<f64>().ok();
            Row {
                method: c[1].to_string(),
                dt: num(c[3]).unwrap(),
                errors: num(c[4]).map(|a| [a, num(c[5]).unwrap(), num(c[6]).unwrap()]),
                cpu: num(c[7]),
                cpu_peaks: num(c[8]),
            }
        })
        .collect()
}

fn span(v: impl Iterator<Item = f64>) -> (f64, f64) {
    v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    })
}

/// `slipload accuracy` of the massless benchmark on 3 s of SYL090 (one timed repeat),
/// `methods` at `dts`, into `dir` as NAME.*; it must succeed.
fn accuracy(dir: &std::path::Path, methods: &str, dts: &str, name: &str) {
    let out = slipload(&[
        "accuracy",
        "configs/benchmark-3story-massless.json",
        "--record",
        "records/SYL090.AT2",
        "--duration",
        "3",
        "--methods",
        methods,
        "--dts",
        dts,
        "--repeats",
        "1",
        "--out",
        dir.to_str().unwrap(),
        "--name",
        name,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn work_precision_and_error_vs_dt_match_the_csv() {
    let dir = scratch("figacc", "m");
    accuracy(&dir, "delacruz,newmark", "T1/25,T1/50,T1/100", "m");
    let rows = rows(&std::fs::read_to_string(dir.join("m.csv")).unwrap());
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("m.json")).unwrap()).unwrap();
    let methods = ["delacruz", "newmark"];
    // This case must contain a failure for the test to check how failures are drawn:
    // delacruz is conditionally stable and T1/25 is beyond its limit on this building.
    let failed: Vec<&Row> = rows.iter().filter(|r| r.errors.is_none()).collect();
    assert_eq!(failed.len(), 1, "one failed run expected");
    assert_eq!(failed[0].method, "delacruz");

    let wp = figure(&dir.join("m-work-precision"));
    let dt = figure(&dir.join("m-error-vs-dt"));
    assert_eq!(wp.panels.len(), 3);
    assert_eq!(dt.panels.len(), 3);
    for k in 0..3 {
        let (pw, pd) = (&wp.panels[k], &dt.panels[k]);
        assert!(pw.x.log && pw.y.log && pd.x.log && pd.y.log, "log-log");
        assert_inside(pw);
        assert_inside(pd);
        assert_eq!(pw.series.len(), methods.len() + 1);
        assert_eq!(pd.series.len(), methods.len() + 1);
        let mut max_err: f64 = 0.0;
        for (i, m) in methods.iter().enumerate() {
            let ok: Vec<&Row> = rows
                .iter()
                .filter(|r| r.method == *m && r.errors.is_some())
                .collect();
            let e = span(ok.iter().map(|r| r.errors.unwrap()[k]));
            max_err = max_err.max(e.1);
            let c = span(ok.iter().map(|r| r.cost(k).unwrap()));
            let d = span(ok.iter().map(|r| r.dt));
            assert_eq!(pw.series[i].drawn, ok.len(), "{m}: a marker per Δt");
            assert_y(&pw.series[i], e, REL * e.1);
            assert_x(&pw.series[i], c, REL * c.1);
            assert_y(&pd.series[i], e, REL * e.1);
            assert_x(&pd.series[i], d, REL * d.1);
            // The fitted order in the legend is the report's.
            let order = json["records"][0]["orders"]
                .as_array()
                .unwrap()
                .iter()
                .find(|o| o["method"] == *m)
                .unwrap()[["peak_drift", "friction_energy", "roof_history"][k]]
                .as_f64()
                .unwrap();
            assert!(
                pd.series[i].name.contains(&format!("order {order:.2}")),
                "{}",
                pd.series[i].name
            );
        }
        // Failed runs: a cross at its Δt (and at the cost estimated from the nearest
        // successful Δt of the same method, ∝ 1/Δt), above every error.
        let f = &pd.series[methods.len()];
        assert_eq!((f.kind.as_str(), f.drawn), ("scatter", 1));
        assert_x(f, (failed[0].dt, failed[0].dt), REL * failed[0].dt);
        assert!(f.y[0].unwrap() > max_err && f.y[0].unwrap() <= pd.y.max);
        let near = rows
            .iter()
            .filter(|r| r.method == "delacruz" && r.errors.is_some())
            .min_by(|a, b| {
                (a.dt / failed[0].dt)
                    .ln()
                    .abs()
                    .total_cmp(&(b.dt / failed[0].dt).ln().abs())
            })
            .unwrap();
        let est = near.cost(k).unwrap() * near.dt / failed[0].dt;
        let fw = &pw.series[methods.len()];
        assert_eq!(fw.drawn, 1);
        assert_x(fw, (est, est), 2.0 * REL * est);
        assert!(fw.y[0].unwrap() > max_err);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn exact_is_a_line_at_its_cost_at_the_default_step() {
    let dir = scratch("figacc", "x");
    accuracy(&dir, "newmark,exact", "T1/100,T1/400", "x");
    let rows = rows(&std::fs::read_to_string(dir.join("x.csv")).unwrap());
    // T1/400, the finer of the two steps
    let at_default = rows
        .iter()
        .filter(|r| r.method == "exact")
        .min_by(|a, b| a.dt.total_cmp(&b.dt))
        .unwrap();
    assert!(at_default.cpu_peaks.unwrap() > 0.0);
    let wp = figure(&dir.join("x-work-precision"));
    for k in 0..3 {
        let line = &wp.panels[k].series[1];
        assert!(line.name.starts_with("exact at T1/400"), "{}", line.name);
        let c = at_default.cost(k).unwrap();
        assert_x(line, (c, c), REL * c);
        assert_eq!(line.kind, "line");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
