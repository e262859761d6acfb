//! Issue 39: a study's work estimate includes its memory. Loading a study estimates what
//! it holds at once (the records, and on every thread the larger of a sweep run and a
//! check run: `exact`'s memory budget, `MemoryBudget::for_plan`, where it runs), and a
//! study beyond the limit is refused before its first run, naming the estimate and what
//! needs less.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::base::error::OptError;
use slipload_opt::eval::evaluate::{DesignLoads, design_plan};
use slipload_opt::eval::memory::{MAX_STUDY_MEMORY_BYTES, run_bytes};
use slipload_opt::eval::probe::{EXACT_CHECK_COST, check_label};
use slipload_opt::model::fidelity::Fidelity;
use slipload_sim::bench_scenes::{ShearDamping, shear_building_damped};
use slipload_sim::integrator::exact::MemoryBudget;
use slipload_sim::scene::MethodName;
use std::path::Path;

/// A profile study of the bench's `storeys`-storey shear frame (a massless damper on every
/// floor) over one 2 s synthetic record, sweeping with `newmark`, checked with `check`.
fn tall_study(storeys: usize, check: &str) -> Study {
    let building: serde_json::Value =
        serde_json::from_str(&shear_building_damped(storeys, ShearDamping::Rayleigh)).unwrap();
    let v = serde_json::json!({
        "name": "tall",
        "building": building,
        "suites": [ { "name": "syn", "synthetic": { "count": 1, "seed": 7, "pga_g": 0.3, "duration_s": 2.0 } } ],
        "space": { "profile": { "shape": "storey_shear", "scale_kn": [100, 20000] } },
        "objective": { "terms": [ { "metric": "peak_drift_ratio", "statistic": "mean" } ] },
        "fidelity": { "method": "newmark", "check_method": check, "check_dt_factor": 0.5 },
        "sweep": { "sampler": "halton", "points": 4, "seed": 1 },
        "refine": { "method": "trust-region", "starts": 1, "max_evaluations": 4,
                    "tolerance": 0.01, "initial_radius": 0.15, "finalists": 1 }
    });
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/inline-study.json");
    Study::from_json(&v.to_string(), &path).unwrap()
}

#[test]
fn the_estimate_holds_exacts_budget_on_every_thread_and_the_records_once() {
    // 20 storeys: exact's cost on the probe is within the check's bound (at 60 it is not,
    // and the check runs newmark, named sweep method or not)
    let study = tall_study(20, "exact");
    assert_eq!(study.check_method.method, MethodName::Exact);
    let m = study.memory;
    assert_eq!(m.threads, rayon::current_num_threads().max(1));
    let plan =
        |fid: &Fidelity| design_plan(&study, &DesignLoads::file(&study), 0, fid, "t").unwrap();
    let check = plan(&Fidelity::check(&study));
    let sweep = plan(&Fidelity::sweep(&study));
    assert_eq!(m.check_run_bytes, run_bytes(&check));
    assert_eq!(m.sweep_run_bytes, run_bytes(&sweep));
    // exact's run holds its budget (at 20 storeys about 64 MiB), newmark's far less
    assert!(
        m.check_run_bytes >= MemoryBudget::for_plan(&check).bytes,
        "{m:?}"
    );
    assert!(m.check_run_bytes > 100 * m.sweep_run_bytes, "{m:?}");
    // one 2 s record at 0.01 s
    assert_eq!(m.records_bytes, (study.records[0].len() * 8) as u64);
    assert_eq!(
        m.total_bytes(),
        m.records_bytes + m.threads as u64 * m.check_run_bytes
    );
    let text = m.text();
    assert!(
        text.starts_with("about ") && text.contains("thread(s) x"),
        "{text}"
    );
    // within the limit it is accepted; below the estimate it is refused with what needs less
    m.check(&study.path, true, MAX_STUDY_MEMORY_BYTES).unwrap();
    let err = m
        .check(&study.path, true, m.total_bytes() as f64 - 1.0)
        .unwrap_err();
    assert!(matches!(err, OptError::TooLarge { .. }), "{err}");
    let msg = err.to_string();
    assert!(msg.contains(&text), "{msg}");
    assert!(msg.contains("`fidelity.check_method: newmark`"), "{msg}");
}

#[test]
fn a_newmark_check_needs_no_exact_budget() {
    let study = tall_study(60, "newmark");
    let m = study.memory;
    // both runs step by step: only the dense matrices, under 1 MiB per run at 60 storeys
    assert!(m.check_run_bytes < 1 << 20, "{m:?}");
    assert_eq!(m.check_run_bytes, m.sweep_run_bytes, "{m:?}");
    let msg = m.check(&study.path, false, 0.0).unwrap_err().to_string();
    assert!(!msg.contains("check_method"), "{msg}");
    assert!(msg.contains("fewer threads"), "{msg}");
    // named as the user gives them: the command's option, Python's argument
    assert!(
        msg.contains("`--threads N`") && msg.contains("`threads=N` in Python"),
        "{msg}"
    );
}

/// Issue 39's fidelity choice never runs what it has not bounded: where `exact` refuses the
/// check (600 storeys: two mode sets exceed its 1.5 GiB cap), the check runs `newmark` at
/// the check's step and says so, with that check's measured step-halving error; where it
/// fits, the study's `exact` check is kept and its bound is named.
#[test]
fn a_check_exact_refuses_runs_newmark_and_says_its_step_halving_error() {
    let kept = tall_study(20, "exact");
    assert_eq!(kept.check_method.method, MethodName::Exact);
    assert!(
        kept.check_method.reason.contains("within its bounds"),
        "{}",
        kept.check_method.reason
    );
    // the summary's line says the reference ran where it did
    assert_eq!(
        check_label(&kept),
        "check at reference accuracy (exact at 0.5 × dt)"
    );

    let study = tall_study(600, "exact");
    let c = &study.check_method;
    assert_eq!(c.method, MethodName::Newmark, "{}", c.reason);
    assert!(
        c.reason.starts_with("exact refused the check: "),
        "{}",
        c.reason
    );
    assert!(
        c.reason.contains("the check runs newmark at dt = "),
        "{}",
        c.reason
    );
    // the error is measured: a number, small at a quarter of newmark's default step
    let error: f64 = c
        .reason
        .rsplit(" is ")
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|e| panic!("{e}: {}", c.reason));
    assert!(error > 0.0 && error < 0.05, "{}", c.reason);
    // the check that runs is newmark's, and the memory estimate is newmark's too
    assert_eq!(Fidelity::check(&study).method, MethodName::Newmark);
    // and the summary says newmark ran, not the reference
    let label = check_label(&study);
    assert!(
        label.starts_with(
            "check at the check's step (newmark at 0.5 × dt, in place of the study's exact"
        ),
        "{label}"
    );
    assert!(!label.contains("reference"), "{label}");
    assert_eq!(study.memory.check_run_bytes, study.memory.sweep_run_bytes);
}

/// Where the sweep-method probe measured `exact` at more than `EXACT_CHECK_COST` times
/// `newmark`'s work (a 60-storey frame whose every floor slips), the check does not run
/// `exact`: it runs `newmark` at the check's step and says why, with its error — whether
/// the sweep's method was chosen by the probe or named by the study (`fidelity.method`,
/// as the shipped check example names it).
#[test]
fn a_check_exact_would_take_too_long_runs_newmark_and_says_why() {
    for named in [None, Some("newmark")] {
        a_check_exact_would_take_too_long(named);
    }
}

fn a_check_exact_would_take_too_long(method: Option<&str>) {
    let building: serde_json::Value =
        serde_json::from_str(&shear_building_damped(60, ShearDamping::Rayleigh)).unwrap();
    let mut v = serde_json::json!({
        "name": "tall",
        "building": building,
        "suites": [ { "name": "syn", "synthetic": { "count": 1, "seed": 7, "pga_g": 0.3, "duration_s": 2.0 } } ],
        "space": { "profile": { "shape": "storey_shear", "scale_kn": [100, 20000] } },
        "objective": { "terms": [ { "metric": "peak_drift_ratio", "statistic": "mean" } ] }
    });
    if let Some(m) = method {
        v["fidelity"] = serde_json::json!({ "method": m });
    }
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/inline-study.json");
    let study = Study::from_json(&v.to_string(), &path).unwrap();
    assert_eq!(study.sweep_method.method, MethodName::Newmark);
    assert_eq!(
        study.sweep_method.reason == "named by the study (fidelity.method)",
        method.is_some(),
        "{}",
        study.sweep_method.reason
    );
    let c = &study.check_method;
    assert_eq!(c.method, MethodName::Newmark, "{}", c.reason);
    assert!(c.reason.starts_with("exact costs "), "{}", c.reason);
    assert!(
        c.reason.contains(&format!("more than {EXACT_CHECK_COST}")),
        "{}",
        c.reason
    );
    assert!(c.reason.contains("step-halving error"), "{}", c.reason);
    let ratio: f64 = c.reason["exact costs ".len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(ratio > EXACT_CHECK_COST, "{}", c.reason);
}
