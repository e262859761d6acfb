//! Contract: on a frame whose storeys yield (and carry P-Δ) a study reads the ductility,
//! the hysteretic energy and the friction share of every record, a design that collapses
//! on a record fails it (objective +∞, journalled as `"inf"`), and the design table gives
//! each design's responses per suite (intensity level) with its collapses. On an elastic
//! frame none of this appears and the ductility objective is refused by name.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
#![allow(clippy::single_range_in_vec_init)] // one suite: a slice of one range

use slipload_opt::phases::refine::Point;
use slipload_opt::phases::table::DesignTable;
use slipload_opt::{Metric, Objective, RecordMetrics, Statistic, Study, Term};
use std::path::Path;

/// A three-storey shear frame with massless dampers on floors 1–2; storeys yield at
/// 0.5 % drift (α = 2 %), P-Δ from the masses; two suites: the design level and × 1.5.
fn study(yielding: bool) -> Study {
    let frame = if yielding {
        r#", "storey_yield": [
            { "storey": 1, "yield_drift": "17.5 mm", "post_yield_ratio": 0.02 },
            { "storey": 2, "yield_drift": "17.5 mm", "post_yield_ratio": 0.02 },
            { "storey": 3, "yield_drift": "17.5 mm", "post_yield_ratio": 0.02 } ],
           "p_delta": {}"#
    } else {
        ""
    };
    let text = format!(
        r#"{{ "name": "yielding", "building": {{
              "floor_masses": ["300 t", "300 t", "250 t"],
              "storey_stiffness": ["300 MN/m", "250 MN/m", "180 MN/m"],
              "storey_heights": [3.5, 3.5, 3.5],
              "damping": {{ "modal": {{ "ratio": 0.02 }} }},
              "dissipators": [
                {{ "floor": 1, "brace_stiffness": "300 MN/m", "mass": 0, "slip_load": "600 kN" }},
                {{ "floor": 2, "brace_stiffness": "250 MN/m", "mass": 0, "slip_load": "500 kN" }} ]
              {frame} }},
            "suites": [
              {{ "name": "design", "synthetic": {{ "count": 3, "seed": 5, "pga_g": 0.5, "duration_s": 8 }} }},
              {{ "name": "mce", "synthetic": {{ "count": 3, "seed": 5, "pga_g": 0.75, "duration_s": 8 }} }} ],
            "space": {{ "profile": {{ "shape": "uniform", "scale_kn": [0, 2000] }} }},
            "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
            "fidelity": {{ "method": "newmark", "check_method": "exact" }},
            "sweep": {{ "sampler": "grid", "levels": 3 }} }}"#
    );
    Study::from_json(
        &text,
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("inline.json"),
    )
    .unwrap()
}

#[test]
fn the_design_table_gives_ductility_energy_and_collapses_per_suite() {
    let s = study(true);
    let designs = vec![
        ("dampers".to_string(), vec![600e3, 500e3]),
        ("bare".to_string(), vec![0.0, 0.0]),
    ];
    let table = DesignTable::build(&s, &designs, &|| {}).unwrap();
    for row in &table.rows {
        let by = row.by_suite.as_ref().unwrap();
        assert_eq!(
            by.iter().map(|b| b.suite.as_str()).collect::<Vec<_>>(),
            ["design", "mce"]
        );
        for b in by {
            assert_eq!(b.records, 3);
            let mu = b.peak_ductility_mean.unwrap();
            // ductility is drift over the yield drift (0.5 % of 3.5 m)
            assert!(
                (mu - b.peak_drift_ratio_mean / 0.005).abs() < 1e-9 * mu,
                "{b:?}"
            );
            assert!(b.hysteretic_energy_mean.unwrap() >= 0.0);
        }
        // more intensity, more drift
        assert!(by[1].peak_drift_ratio_mean > by[0].peak_drift_ratio_mean);
    }
    let bare = &table.rows[1].by_suite.as_ref().unwrap()[1];
    let damped = &table.rows[0].by_suite.as_ref().unwrap()[1];
    assert!(
        bare.peak_ductility_mean.unwrap() > 1.0,
        "the bare frame yields at MCE"
    );
    assert!(damped.peak_ductility_mean < bare.peak_ductility_mean);
    assert!(damped.friction_share_mean.unwrap() > 0.5, "{damped:?}");
    let md = table.to_markdown();
    assert!(
        md.contains("| design | suite | records | collapses |"),
        "{md}"
    );
    // An elastic frame has no per-suite section: its tables are as before.
    let elastic = DesignTable::build(&study(false), &designs, &|| {}).unwrap();
    assert!(elastic.rows.iter().all(|r| r.by_suite.is_none()));
    assert!(!elastic.to_markdown().contains("By suite"));
}

fn metrics(collapse: bool, ductility: Option<Vec<f64>>) -> RecordMetrics {
    let mut v = serde_json::json!({
        "drift_ratio": [0.01, 0.012], "residual_drift_ratio": [0.0, 0.001],
        "peak_floor_acceleration": 3.0, "peak_base_shear": 1e6, "peak_displacement": 0.05,
        "stroke": [0.01, 0.01], "energy_input": 1e6, "energy_friction": 6e5,
        "strain_energy_area": 10.0
    });
    if let Some(mu) = ductility {
        v["ductility"] = serde_json::json!(mu);
        v["energy_plastic"] = serde_json::json!(2e5);
    }
    if collapse {
        v["collapse"] = serde_json::json!([2, 4.5]);
    }
    serde_json::from_value(v).unwrap()
}

#[test]
fn a_design_that_collapses_on_a_record_fails_it() {
    let objective = Objective {
        terms: vec![Term {
            metric: Metric::PeakDriftRatio,
            statistic: Statistic::Mean,
            weight: 1.0,
        }],
        cost: None,
    };
    let stands = vec![metrics(false, None), metrics(false, None)];
    let f = objective.value(&stands, None, &[0..2]).unwrap();
    assert!((f - 0.012).abs() < 1e-15);
    let falls = vec![metrics(false, None), metrics(true, None)];
    assert_eq!(
        objective.value(&falls, None, &[0..2]).unwrap(),
        f64::INFINITY
    );
    // Only the suites the objective reads count.
    assert_eq!(objective.value(&falls, None, &[0..1]).unwrap(), f);
    // A failed design is journalled as "inf" and read back.
    let p = Point {
        z: vec![0.5],
        f: f64::INFINITY,
        limits: None,
    };
    let line = serde_json::to_string(&p).unwrap();
    assert_eq!(line, r#"{"z":[0.5],"f":"inf"}"#);
    assert_eq!(serde_json::from_str::<Point>(&line).unwrap(), p);
    let finite = Point {
        z: vec![0.5],
        f: 0.25,
        limits: None,
    };
    assert_eq!(
        serde_json::to_string(&finite).unwrap(),
        r#"{"z":[0.5],"f":0.25}"#
    );
    assert!(serde_json::from_str::<Point>(r#"{"z":[0.5],"f":"nan"}"#).is_err());
}

#[test]
fn ductility_energy_and_friction_share_metrics() {
    let m = metrics(false, Some(vec![1.5, 2.5]));
    assert_eq!(Metric::PeakDuctility.value(&m, None).unwrap(), 2.5);
    assert_eq!(Metric::HystereticEnergy.value(&m, None).unwrap(), 2e5);
    // 1 − E_f / (E_f + E_p) = 1 − 6/8
    assert!((Metric::FrictionShare.value(&m, None).unwrap() - 0.25).abs() < 1e-15);
    let elastic = metrics(false, None);
    let err = Metric::PeakDuctility
        .value(&elastic, None)
        .unwrap_err()
        .to_string();
    assert!(err.contains("storey_yield"), "{err}");
    assert!(Metric::HystereticEnergy.value(&elastic, None).is_err());
    assert_eq!(Metric::FrictionShare.value(&elastic, None).unwrap(), 0.0);
}
