//! Contract: a frame that collapses (bare or designed) is said in words. Objectives,
//! their terms and reductions read "collapsed" ("bare frame collapsed" when only the
//! reference does) in designs.csv, the design table (CSV, Markdown, JSON), rankings and
//! the family table — never NaN, null, inf or "100 % lower"; a run that stopped on the
//! collapse limit reports no residual drift; a family cell that cannot be built names
//! its scales.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::RecordMetrics;
use slipload_opt::Study;
use slipload_opt::model::config::RefineMethod;
use slipload_opt::phases::family;
use slipload_opt::phases::rank::{Ranking, SuiteRanking};
use slipload_opt::phases::sweep::Manifest;
use slipload_opt::phases::table::DesignTable;
use std::path::Path;

/// A yielding three-storey frame whose collapse limit is the drift ratio `limit`; one
/// suite of three 4-s records at 0.5 g; a uniform profile swept on a 3-level grid.
fn study(limit: f64) -> Study {
    let text = format!(
        r#"{{ "name": "collapsing", "building": {{
              "floor_masses": ["300 t", "300 t", "250 t"],
              "storey_stiffness": ["300 MN/m", "250 MN/m", "180 MN/m"],
              "storey_heights": [3.5, 3.5, 3.5],
              "damping": {{ "modal": {{ "ratio": 0.02 }} }},
              "dissipators": [
                {{ "floor": 1, "brace_stiffness": "300 MN/m", "mass": 0, "slip_load": "600 kN" }},
                {{ "floor": 2, "brace_stiffness": "250 MN/m", "mass": 0, "slip_load": "500 kN" }} ],
              "storey_yield": [
                {{ "storey": 1, "yield_drift": "17.5 mm", "post_yield_ratio": 0.02 }},
                {{ "storey": 2, "yield_drift": "17.5 mm", "post_yield_ratio": 0.02 }},
                {{ "storey": 3, "yield_drift": "17.5 mm", "post_yield_ratio": 0.02 }} ] }},
            "collapse_drift_ratio": {limit},
            "suites": [ {{ "name": "design", "synthetic": {{ "count": 3, "seed": 5, "pga_g": 0.5, "duration_s": 4 }} }} ],
            "space": {{ "profile": {{ "shape": "uniform", "scale_kn": [0, 2000] }} }},
            "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
            "fidelity": {{ "method": "newmark", "check_method": "newmark" }},
            "sweep": {{ "sampler": "grid", "levels": 3 }} }}"#
    );
    Study::from_json(
        &text,
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("inline.json"),
    )
    .unwrap()
}

/// Responses of one record: drift ratio 1 % / 1.2 %, residual 0.1 %; stopped at 4.5 s
/// on storey 2 when `collapse`.
fn metrics(collapse: bool) -> RecordMetrics {
    let mut v = serde_json::json!({
        "drift_ratio": [0.01, 0.012, 0.011], "residual_drift_ratio": [0.0, 0.001, 0.0],
        "peak_floor_acceleration": 3.0, "peak_base_shear": 1e6, "peak_displacement": 0.05,
        "stroke": [0.01, 0.01, 0.0], "energy_input": 1e6, "energy_friction": 6e5,
        "strain_energy_area": 10.0
    });
    if collapse {
        v["collapse"] = serde_json::json!([2, 4.5]);
    }
    serde_json::from_value(v).unwrap()
}

/// No number stands for a collapse (JSON's `null` is checked field by field: an
/// optional statistic with nothing to average, as the friction share of runs that never
/// dissipated, is absent there by design).
fn assert_no_number_for_collapse(what: &str, text: &str) {
    for bad in ["inf", "NaN", "100.0 %"] {
        assert!(!text.contains(bad), "{what} shows {bad:?}:\n{text}");
    }
}

/// Rows of the manifest's tasks: design d collapses on record 0 when `falls(d)`.
fn rows(m: &Manifest, falls: impl Fn(usize) -> bool) -> Vec<RecordMetrics> {
    (0..m.tasks())
        .map(|k| {
            let (d, r) = m.task(k);
            metrics(falls(d) && r == 0)
        })
        .collect()
}

#[test]
fn designs_csv_says_collapsed_for_a_design_and_for_the_bare_frame() {
    let m = Manifest::of(&study(0.05));
    // design 2 collapses on record 0: its objective, terms and reduction are words
    let csv = m.designs_csv(&rows(&m, |d| d == 2)).unwrap();
    assert_no_number_for_collapse("designs.csv", &csv);
    let line = csv.lines().nth(3).unwrap();
    assert!(line.ends_with(",collapsed,collapsed,collapsed,5"), "{line}");
    // only the bare frame collapses: the others' reduction says its reference fell
    let csv = m.designs_csv(&rows(&m, |d| d == 0)).unwrap();
    assert_no_number_for_collapse("designs.csv", &csv);
    let bare = csv.lines().nth(1).unwrap();
    assert!(bare.contains(",collapsed,collapsed,collapsed,"), "{bare}");
    let file = csv.lines().nth(2).unwrap();
    assert!(file.contains(",bare frame collapsed,"), "{file}");
    // responses.csv: no residual drift for the run that stopped
    let all: Vec<Option<RecordMetrics>> = rows(&m, |d| d == 0).into_iter().map(Some).collect();
    let resp = m.responses_csv(&all);
    let stopped = resp.lines().nth(1).unwrap();
    assert!(
        stopped.contains(",0.01,0.012,0.011,,,,3,"),
        "no residual drift after a collapse: {stopped}"
    );
    let ran = resp.lines().nth(2).unwrap();
    assert!(ran.contains(",0.01,0.012,0.011,0,0.001,0,3,"), "{ran}");
}

#[test]
fn a_design_table_of_a_collapsing_frame_says_so() {
    // a drift limit of 0.1 %: every run stops on it
    let s = study(0.001);
    let designs = vec![
        ("dampers".to_string(), vec![600e3, 500e3]),
        ("bare".to_string(), vec![0.0, 0.0]),
    ];
    let table = DesignTable::build(&s, &designs, &|| {}).unwrap();
    for (what, text) in [
        ("design-table.csv", table.to_csv()),
        ("design-table.md", table.to_markdown()),
        ("design-table.json", table.to_json()),
    ] {
        assert_no_number_for_collapse(what, &text);
        assert!(text.contains("collapsed"), "{what}:\n{text}");
    }
    let json: serde_json::Value = serde_json::from_str(&table.to_json()).unwrap();
    let row = &json["rows"][0];
    assert_eq!(row["objective"], "collapsed");
    assert_eq!(row["objective_reduction"], "collapsed");
    assert_eq!(row["residual_drift_ratio_mean"], "collapsed");
    assert_eq!(row["objective_at_125pct"], "collapsed");
    assert_eq!(row["by_suite"][0]["residual_drift_ratio_mean"], "collapsed");
    assert!(row["objective_at_75pct"].is_string() && row["peak_drift_reduction"].is_string());
    // and it reads back
    let back: DesignTable = serde_json::from_str(&table.to_json()).unwrap();
    assert_eq!(back.rows[0].objective, f64::INFINITY);
}

#[test]
fn a_ranking_says_collapsed() {
    let r = Ranking {
        study: "s".into(),
        objective: "mean peak_drift_ratio".into(),
        designs: vec!["a".into(), "b".into()],
        bootstrap: 1,
        suites: vec![SuiteRanking {
            suite: "design".into(),
            objective: vec![0.01, f64::INFINITY],
            rank: vec![1, 2],
            rank_kept: vec![1.0, 1.0],
            order_kept: 1.0,
        }],
    };
    let json = serde_json::to_string(&r).unwrap();
    assert!(json.contains(r#""objective":[0.01,"collapsed"]"#), "{json}");
    for (what, text) in [
        ("rank.csv", r.to_csv()),
        ("rank.md", r.to_markdown()),
        ("rank.json", json),
    ] {
        assert_no_number_for_collapse(what, &text);
        assert!(text.contains("collapsed"), "{what}:\n{text}");
    }
}

#[test]
fn a_family_cell_that_cannot_be_built_names_its_scales() {
    let s = study(0.001);
    let e = family::family(&s, &[1.0], &[1.5], RefineMethod::Random, &|| {}).unwrap_err();
    let mut chain = e.to_string();
    let mut src = std::error::Error::source(&e);
    while let Some(x) = src {
        chain.push_str(&format!(": {x}"));
        src = x.source();
    }
    assert!(
        chain.contains("period scale 1, intensity scale 1.5") && chain.contains("collapses"),
        "{chain}"
    );
}
