//! Contract: a study that names no sweep method sweeps with `exact` where its counted
//! work on the probe (first record, the building file's slip loads) is at most twice
//! `newmark`'s, else with `newmark`, and says why in its manifest; a named method is
//! taken as named; a building `exact` refuses sweeps with `newmark`. Where the sweep ran
//! `exact` and the check is `exact`, the finalists' check runs nothing and reports the
//! sweep's objectives, which are then the check's.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::eval::evaluate::{run_designs, simulate_one};
use slipload_opt::model::config::RefineMethod;
use slipload_opt::model::fidelity::EXACT_SWEEP_COST;
use slipload_opt::model::fidelity::Fidelity;
use slipload_opt::phases::refinement::{OptimizeReport, optimize};
use slipload_opt::phases::sweep::Manifest;
use slipload_sim::scene::MethodName;
use std::path::Path;

fn configs() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs")
}

/// A study of a one-storey frame with one dissipator (`mass` kg, on a brace of
/// `brace_kn_m` kN/m) over three 10 s synthetic records; `method` names the sweep's, or not.
fn one_storey(mass: f64, brace_kn_m: f64, method: Option<&str>) -> Study {
    let mut v = serde_json::json!({
        "name": "one-storey",
        "building": {
            "floor_masses": ["5740.39 kg"], "storey_stiffness": ["2999.471 kN/m"],
            "storey_heights": [3.0], "damping": { "storey": ["13121.77 N*s/m"] },
            "dissipators": [ { "floor": 1, "brace_stiffness": format!("{brace_kn_m} kN/m"),
                               "mass": mass, "slip_load": "39.325 kN" } ] },
        "suites": [ { "name": "syn", "synthetic": { "count": 3, "seed": 7, "pga_g": 0.4, "duration_s": 10.0 } } ],
        "space": { "free": { "lower_kn": [0], "upper_kn": [200] } },
        "objective": { "terms": [ { "metric": "peak_drift_ratio", "statistic": "mean" } ] },
        "fidelity": { "check_method": "exact", "check_dt_factor": 0.25 },
        "sweep": { "sampler": "halton", "points": 8, "seed": 1 },
        "refine": { "method": "trust-region", "starts": 1, "max_evaluations": 6,
                    "tolerance": 0.002, "initial_radius": 0.15, "finalists": 2 }
    });
    if let Some(m) = method {
        v["fidelity"]["method"] = m.into();
    }
    Study::from_json(&v.to_string(), &configs().join("inline-study.json")).unwrap()
}

/// Each method's counted work on the study's probe.
fn probe_work(study: &Study) -> (u64, u64) {
    let work = |method| {
        let fid = Fidelity {
            method,
            dt_s: None,
            dt_factor: 1.0,
            energies: study.needs_energies(),
            dampers: false,
            sensitivities: false,
        };
        simulate_one(study, &study.file_slip_loads(), 0, &fid, "probe")
            .unwrap()
            .diagnostics
            .work
    };
    (work(MethodName::Exact), work(MethodName::Newmark))
}

/// The study's sweep, then its refinement and finalists' check.
fn swept_and_optimized(study: &Study) -> OptimizeReport {
    let m = Manifest::of(study);
    let designs: Vec<Vec<f64>> = m.designs.iter().map(|d| d.slip_loads_n.clone()).collect();
    let rows: Vec<_> = run_designs(study, &designs, &Fidelity::sweep(study), &|| {})
        .unwrap()
        .into_iter()
        .flatten()
        .collect();
    optimize(
        study,
        &m,
        &rows,
        RefineMethod::TrustRegion,
        None,
        None,
        &|| {},
    )
    .unwrap()
}

#[test]
fn a_study_sweeps_with_exact_where_it_costs_at_most_twice_newmark() {
    // A one-storey frame with a massless dissipator: exact's substeps follow the record
    // (and the frame's modes), not T1/400, so it costs about newmark's work.
    let study = one_storey(0.0, 2597.01, None);
    let (exact, newmark) = probe_work(&study);
    let ratio = exact as f64 / newmark as f64;
    assert!(ratio <= EXACT_SWEEP_COST, "work ratio {ratio}");
    assert_eq!(study.sweep_method.method, MethodName::Exact);
    let m = Manifest::of(&study);
    assert_eq!(m.method, MethodName::Exact);
    assert!(
        m.method_reason
            .contains(&format!("{ratio:.2} x newmark's work")),
        "{}",
        m.method_reason
    );
    // The check has nothing to correct: no simulations, the sweep's objectives.
    let r = swept_and_optimized(&study);
    assert!(!r.check_reran && r.ranking_held);
    assert_eq!(
        r.simulations,
        (r.log.len() - r.replayed) * study.records.len()
    );
    for f in &r.finalists {
        assert_eq!(f.f_check.to_bits(), f.f_sweep.to_bits());
    }
    // Named, newmark sweeps and the finalists are checked by exact.
    let named = one_storey(0.0, 2597.01, Some("newmark"));
    assert_eq!(named.sweep_method.method, MethodName::Newmark);
    assert_eq!(
        named.sweep_method.reason,
        "named by the study (fidelity.method)"
    );
    let r = swept_and_optimized(&named);
    assert!(r.check_reran);
    assert!(r.finalists.iter().all(|f| f.f_check != f.f_sweep));
}

#[test]
fn a_study_sweeps_with_newmark_where_exact_costs_more_or_refuses() {
    // The benchmark's 350 kg dissipators ring at ~1100 rad/s while they slide: exact's
    // work is many times newmark's.
    let path = configs().join("study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert!(
        v["fidelity"].get("method").is_none(),
        "the shipped study names no method"
    );
    v["suites"][0]["synthetic"]["count"] = 2.into();
    v["suites"][0]["synthetic"]["duration_s"] = 8.0.into();
    let study = Study::from_json(&v.to_string(), &path).unwrap();
    let (exact, newmark) = probe_work(&study);
    assert!(exact as f64 > EXACT_SWEEP_COST * newmark as f64);
    assert_eq!(study.sweep_method.method, MethodName::Newmark);
    assert!(
        study.sweep_method.reason.starts_with("chosen: exact costs"),
        "{}",
        study.sweep_method.reason
    );
    // A light dissipator on a stiff brace rings too fast for exact's budget: it refuses
    // the probe, and the sweep is newmark's.
    let light = one_storey(1e-6, 4.48e5, None);
    assert_eq!(light.sweep_method.method, MethodName::Newmark);
    assert!(
        light
            .sweep_method
            .reason
            .contains("exact refused the probe"),
        "{}",
        light.sweep_method.reason
    );
}
