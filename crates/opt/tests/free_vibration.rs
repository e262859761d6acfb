//! Contract (issue 45 §5): a suite's `free_vibration_s` runs each of its records followed by
//! that many seconds of ground at rest, at the same time step, so its residual drifts are
//! read after the free vibration instead of at the record's end; the longer run holds the
//! shorter one as its prefix (no peak below it), the fingerprint tells the two apart (the
//! journals of one never serve the other), and the code check names the runs whose
//! residual alone exceeds a residual limit.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::eval::evaluate::{DesignLoads, design_scene, run_design};
use slipload_opt::model::fidelity::Fidelity;
use slipload_opt::model::fingerprint::of_study;
use std::path::Path;

/// The three-storey benchmark under two 6 s synthetic records at 0.5 g, with a residual
/// limit; `rest`: the suite's extra members.
fn study(rest: &str) -> Study {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/benchmark-3story.json",
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": 2, "seed": 11, "pga_g": 0.5, "duration_s": 6.0 }}{rest},
                 "limits": {{ "criteria": [ {{ "metric": "residual_drift_ratio", "statistic": "mean", "max": 0.0001 }} ] }} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    Study::from_json(&text, &root.join("study.json")).unwrap()
}

#[test]
fn a_rest_after_the_records_extends_every_run_and_moves_where_the_residual_is_read() {
    let (plain, rested) = (study(""), study(r#", "free_vibration_s": 15"#));
    assert_eq!(rested.suites[0].free_vibration_s, 15.0);
    let fid = Fidelity::sweep(&plain);
    assert_eq!(fid, Fidelity::sweep(&rested));
    // low slip loads: the dampers slip and leave a residual
    let design: DesignLoads = vec![150e3, 120e3, 80e3].into();
    let mut moved = false;
    for run in 0..plain.records.len() {
        let (a, b) = (
            design_scene(&plain, &design, run, &fid, "a"),
            design_scene(&rested, &design, run, &fid, "b"),
        );
        assert_eq!(b.duration, a.duration + 15.0);
        assert_eq!(b.method.dt, a.method.dt);
        let ma = run_design(&plain, &design, run, &fid, "a").unwrap();
        let mb = run_design(&rested, &design, run, &fid, "b").unwrap();
        // the same record at the same step, then more: the peaks can only grow
        for (pa, pb) in ma.drift_ratio.iter().zip(&mb.drift_ratio) {
            assert!(pb >= pa, "{pb} < {pa}");
        }
        moved |= ma.residual_drift_ratio != mb.residual_drift_ratio;
    }
    assert!(moved, "the residual drifts were read at the same time");
    // the free vibration dies out: the braced frame's vibration (T ≈ 0.5 s, Rayleigh
    // damping ≈ 1.4 % there) decays as exp(−ζωt), to 1e-3 of itself after 40 s, so 40 s
    // more of rest move the residual by far less than the first 40 s did
    let (r40, r80) = (
        study(r#", "free_vibration_s": 40"#),
        study(r#", "free_vibration_s": 80"#),
    );
    for run in 0..plain.records.len() {
        let r = |s: &Study| {
            run_design(s, &design, run, &fid, "r")
                .unwrap()
                .residual_drift_ratio
                .iter()
                .fold(0.0f64, |m, v| m.max(v.abs()))
        };
        let (end, settled, later) = (r(&plain), r(&r40), r(&r80));
        assert!(
            (later - settled).abs() < 0.05 * (settled - end).abs(),
            "{end} {settled} {later}"
        );
    }
    let designs = [];
    assert_ne!(
        of_study(&plain, &designs).hash,
        of_study(&rested, &designs).hash
    );
    // a rest out of range names its field
    for bad in ["0", "-1", "601"] {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let text = format!(
            r#"{{ "building": "configs/benchmark-3story.json",
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": 2 }}, "free_vibration_s": {bad} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }} }}"#
        );
        let err = Study::from_json(&text, &root.join("study.json"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("suites[0].free_vibration_s"), "{bad}: {err}");
    }
}
