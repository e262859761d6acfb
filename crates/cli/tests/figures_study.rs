//! Contract: `optimize` and `sweep` write the study figures' data beside them (the
//! drift profiles' legend off the curves, outside the axes), and the
//! data is the study's own: the drift profiles are the design table's per-storey mean
//! and 84th percentile (optimize) or the statistics of responses.csv (sweep); the
//! per-record scatter holds one point per record whose means are the table's; the
//! convergence path counts simulations from the end of the sweep in steps of the suite
//! size and ends at the reported optimum; one line per refiner journal in the folder;
//! the objective map (opt-in) covers GRID × GRID points over the study's bounds.
//! A bad `--map-floors` fails before any simulation.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch, slipload_in};
use slipload_figures::plot::meta;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// 2 synthetic records of 3 s on the benchmark building, 6 Halton designs, a short
/// trust-region refinement.
fn tiny_study(dir: &Path) -> PathBuf {
    let building = root().join("configs/benchmark-3story.json");
    let text = format!(
        r#"{{
  "name": "tiny",
  "building": {building:?},
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": 2, "seed": 3, "pga_g": 0.4, "duration_s": 3 }} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 1500, 1000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "sweep": {{ "sampler": "halton", "points": 6, "seed": 5 }},
  "refine": {{ "method": "trust-region", "starts": 1, "max_evaluations": 8, "finalists": 1 }}
}}"#
    );
    let p = dir.join("study.json");
    std::fs::write(&p, text).unwrap();
    p
}

fn run(dir: &Path, args: &[&str]) -> String {
    let out = slipload_in(dir, args);
    assert!(
        out.status.success(),
        "slipload {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// A CSV as (header, rows of fields); no quoted fields in these files.
fn csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let head = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (head, rows)
}

/// The figure's metadata, read back from the SVG written; the PNG is there and not empty.
fn figure(dir: &Path, stem: &str) -> meta::PanelMeta {
    let svg = std::fs::read_to_string(dir.join(format!("{stem}.svg"))).unwrap();
    assert!(
        std::fs::metadata(dir.join(format!("{stem}.png")))
            .unwrap()
            .len()
            > 1000
    );
    let m = meta::FigureMeta::from_svg(&svg).unwrap();
    assert_eq!(m.panels.len(), 1, "{stem}");
    m.panels.into_iter().next().unwrap()
}

/// Every value lies within the axis as drawn, and the drawn series' range matches.
/// The legend covers no curve: its box lies outside the plotting area.
fn legend_clear_of_the_curves(p: &meta::PanelMeta, what: &str) {
    let [l, t, r, b] = p.legend.unwrap_or_else(|| panic!("{what}: a legend"));
    let [pl, pt, pr, pb] = p.plot_area.unwrap();
    let overlaps = l < pr && r > pl && t < pb && b > pt;
    assert!(
        !overlaps,
        "{what}: legend {:?} over the plotting area {:?}",
        [l, t, r, b],
        [pl, pt, pr, pb]
    );
}

fn within(axis: &meta::AxisMeta, values: &[f64], what: &str) {
    let (lo, hi) = values
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
    assert!(
        axis.min <= lo && hi <= axis.max,
        "{what}: [{lo}, {hi}] outside the axis [{}, {}]",
        axis.min,
        axis.max
    );
}

fn num(s: &str) -> f64 {
    s.parse().unwrap()
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// Relative closeness for the same statistic computed twice from the same per-record
/// values (possibly in another summation order): a few ulps.
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs())
}

#[test]
fn optimize_figure_data_is_the_studys_own() {
    let dir = scratch("fig-study", "optimize");
    let study = tiny_study(&dir);
    let out = dir.join("o");
    run(
        &dir,
        &[
            "optimize",
            s(&study),
            "--out",
            s(&out),
            "--quiet",
            "--map",
            "--map-floors",
            "1,3",
            "--map-grid",
            "3",
        ],
    );
    let table = json(&out.join("design-table.json"));
    let manifest = json(&out.join("manifest.json"));
    let optimum = json(&out.join("optimum.json"));
    let nr = manifest["records"].as_array().unwrap().len();
    let sweep_tasks = manifest["designs"].as_array().unwrap().len() * nr;

    // drift profiles: one row per design and storey, the design table's statistics,
    // best objective first
    let (head, rows) = csv(&out.join("drift-profiles.csv"));
    assert_eq!(
        head,
        ["design", "storey", "drift_ratio_mean", "drift_ratio_p84"]
    );
    let trows = table["rows"].as_array().unwrap();
    assert_eq!(rows.len(), trows.len() * 3);
    let mut by_design: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for r in &rows {
        by_design
            .entry(r[0].clone())
            .or_default()
            .push((num(&r[2]), num(&r[3])));
    }
    for t in trows {
        let name = t["design"].as_str().unwrap();
        let got = &by_design[name];
        let (mean, p84) = (
            floats(&t["drift_ratio_mean"]),
            floats(&t["drift_ratio_p84"]),
        );
        for i in 0..3 {
            assert!(
                close(got[i].0, mean[i]) && close(got[i].1, p84[i]),
                "{name} storey {}",
                i + 1
            );
        }
    }
    let order: Vec<&str> = rows.iter().step_by(3).map(|r| r[0].as_str()).collect();
    let objective_of = |n: &str| {
        trows.iter().find(|t| t["design"] == n).unwrap()["objective"]
            .as_f64()
            .unwrap()
    };
    assert!(
        order
            .windows(2)
            .all(|w| objective_of(w[0]) <= objective_of(w[1])),
        "ranked: {order:?}"
    );

    // per-record scatter: one point per record; its means are the table's
    let (head, rows) = csv(&out.join("records-scatter.csv"));
    assert_eq!(
        head,
        [
            "record",
            "bare_peak_drift_ratio",
            "optimum_peak_drift_ratio",
            "suite"
        ]
    );
    assert_eq!(rows.len(), nr);
    assert!(
        rows.iter().all(|r| r[3] == "syn"),
        "every row names its suite"
    );
    let mean = |k: usize| rows.iter().map(|r| num(&r[k])).sum::<f64>() / nr as f64;
    let row = |n: &str| trows.iter().find(|t| t["design"] == n).unwrap();
    assert!(close(
        mean(1),
        row("bare")["peak_drift_ratio_mean"].as_f64().unwrap()
    ));
    assert!(close(
        mean(2),
        row("optimum")["peak_drift_ratio_mean"].as_f64().unwrap()
    ));

    // convergence: from the end of the sweep, one suite per evaluation, best so far
    // non-increasing, ending at the reported optimum
    let (head, rows) = csv(&out.join("convergence.csv"));
    assert_eq!(head, ["refiner", "simulations", "objective", "best_so_far"]);
    assert!(rows.iter().all(|r| r[0] == "trust-region"));
    let sims: Vec<usize> = rows.iter().map(|r| r[1].parse().unwrap()).collect();
    assert_eq!(sims[0], sweep_tasks);
    assert!(sims.windows(2).all(|w| w[1] == w[0] + nr), "{sims:?}");
    assert_eq!(
        rows.len() - 1,
        optimum["refine_evaluations"].as_u64().unwrap() as usize
    );
    let best: Vec<f64> = rows.iter().map(|r| num(&r[3])).collect();
    assert!(best.windows(2).all(|w| w[1] <= w[0]));
    assert_eq!(
        *best.last().unwrap(),
        optimum["objective_value"].as_f64().unwrap()
    );

    // objective map: 3 × 3 over floors 1 and 3's bounds (0–2000 and 0–1000 kN)
    let (head, rows) = csv(&out.join("objective-map.csv"));
    assert_eq!(head, ["slip_load_kN_1", "slip_load_kN_3", "objective"]);
    assert_eq!(rows.len(), 9);
    let a: Vec<f64> = rows.iter().step_by(3).map(|r| num(&r[0])).collect();
    let b: Vec<f64> = rows[..3].iter().map(|r| num(&r[1])).collect();
    assert_eq!(a, [0.0, 1000.0, 2000.0]);
    assert_eq!(b, [0.0, 500.0, 1000.0]);
    assert!(
        rows.iter()
            .all(|r| num(&r[2]).is_finite() && num(&r[2]) > 0.0)
    );

    // the figures, read back: series counts and ranges against the CSVs
    let (_, prof) = csv(&out.join("drift-profiles.csv"));
    let p = figure(&out, "drift-profiles");
    assert_eq!(p.series.len(), 2 * trows.len(), "mean and p84 per design");
    let pct: Vec<f64> = prof
        .iter()
        .flat_map(|r| [100.0 * num(&r[2]), 100.0 * num(&r[3])])
        .collect();
    within(&p.x, &pct, "drift profiles");
    within(&p.y, &[1.0, 3.0], "storeys");
    // The storey axis is labelled at the storeys only: 1, 2, 3, no 1.5 or 2.5.
    assert_eq!(p.y.ticks, [1.0, 2.0, 3.0], "storey ticks");
    legend_clear_of_the_curves(&p, "drift profiles (optimize)");
    let (_, sc) = csv(&out.join("records-scatter.csv"));
    let p = figure(&out, "records-scatter");
    assert_eq!(p.series.len(), 2, "records and the 1:1 line");
    assert_eq!(p.series[0].points, nr);
    within(
        &p.x,
        &sc.iter().map(|r| 100.0 * num(&r[1])).collect::<Vec<_>>(),
        "scatter x",
    );
    within(
        &p.y,
        &sc.iter().map(|r| 100.0 * num(&r[2])).collect::<Vec<_>>(),
        "scatter y",
    );
    let p = figure(&out, "convergence");
    assert_eq!(p.series.len(), 1);
    within(
        &p.x,
        &sims.iter().map(|&v| v as f64).collect::<Vec<_>>(),
        "convergence x",
    );
    within(&p.y, &best, "convergence y");
    let (_, map) = csv(&out.join("objective-map.csv"));
    let p = figure(&out, "objective-map");
    let h = p.heatmap.unwrap();
    assert_eq!((h.nx, h.ny), (3, 3));
    let z: Vec<f64> = map.iter().map(|r| num(&r[2])).collect();
    let (zlo, zhi) = z
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
    assert_eq!(h.z, [Some(zlo), Some(zhi)]);
    within(&p.x, &[0.0, 2000.0], "map x");
    within(&p.y, &[0.0, 1000.0], "map y");

    // a second refiner into the same folder: one line per refiner
    run(
        &dir,
        &[
            "optimize",
            s(&study),
            "--out",
            s(&out),
            "--quiet",
            "--refine",
            "random",
        ],
    );
    let (_, rows) = csv(&out.join("convergence.csv"));
    let mut refiners: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    refiners.dedup();
    assert_eq!(refiners, ["random", "trust-region"]);
    assert_eq!(figure(&out, "convergence").series.len(), 2);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sweep_figure_data_comes_from_its_responses() {
    let dir = scratch("fig-study", "sweep");
    let study = tiny_study(&dir);
    let out = dir.join("s");
    let o = slipload_in(&dir, &["sweep", s(&study), "--out", s(&out), "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (rhead, responses) = csv(&out.join("responses.csv"));
    let col = |name: &str| rhead.iter().position(|h| h == name).unwrap();
    let drift_cols = [
        col("drift_ratio_1"),
        col("drift_ratio_2"),
        col("drift_ratio_3"),
    ];
    let label = col("label");
    let per_design =
        |l: &str| -> Vec<&Vec<String>> { responses.iter().filter(|r| r[label] == l).collect() };
    // profiles: three best sampled designs, the file design and the bare frame
    let (_, rows) = csv(&out.join("drift-profiles.csv"));
    assert_eq!(rows.len(), 5 * 3);
    for r in &rows {
        let recs = per_design(&r[0]);
        let storey: usize = r[1].parse().unwrap();
        let vals: Vec<f64> = recs
            .iter()
            .map(|x| num(&x[drift_cols[storey - 1]]))
            .collect();
        let mean = vals.iter().sum::<f64>() / vals.len() as f64;
        assert!(close(num(&r[2]), mean), "{} storey {storey}", r[0]);
        let (lo, hi) = vals
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
        assert!(
            (lo..=hi).contains(&num(&r[3])),
            "p84 within the records' range"
        );
    }
    // scatter: the bare frame's per-record peak drift ratios
    let (head, rows) = csv(&out.join("records-scatter.csv"));
    assert_eq!(head[1], "bare_peak_drift_ratio");
    let bare = per_design("bare");
    assert_eq!(rows.len(), bare.len());
    for (r, b) in rows.iter().zip(&bare) {
        let peak = drift_cols.iter().map(|&c| num(&b[c])).fold(0.0, f64::max);
        assert_eq!(num(&r[1]), peak);
    }
    let p = figure(&out, "drift-profiles");
    assert_eq!(p.series.len(), 2 * 5);
    legend_clear_of_the_curves(&p, "drift profiles (sweep)");
    assert!(
        !p.y.ticks.is_empty() && p.y.ticks.iter().all(|t| t.fract() == 0.0),
        "storey ticks {:?}",
        p.y.ticks
    );
    assert_eq!(figure(&out, "records-scatter").series[0].points, bare.len());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_map_floors_fail_before_any_simulation() {
    let dir = scratch("fig-study", "bad");
    let study = tiny_study(&dir);
    let out = dir.join("o");
    let o = slipload_in(
        &dir,
        &[
            "optimize",
            s(&study),
            "--out",
            s(&out),
            "--map",
            "--map-floors",
            "1,4",
        ],
    );
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("floor 4 has no dissipator"), "{err}");
    assert!(!out.exists(), "nothing simulated, nothing written");
    let _ = std::fs::remove_dir_all(&dir);
}
