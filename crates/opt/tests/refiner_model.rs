//! Contract of the `model` refiner (`phases::refine::ModelSearch`) on narrow valleys with
//! known minima, in 10 and 40 variables: from a neutral start it reaches the valley's
//! floor, better than the quadratic-fit trust region at the same budget; it never makes
//! more evaluations than its budget; the same start gives the same bits; the stop reason
//! and the stationarity post-check say what happened.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;

use common::valley::Valley;
use slipload_opt::model::config::{RefineConfig, RefineMethod};
use slipload_opt::phases::refine::{
    Evaluations, Point, STATIONARY_GAIN, StopReason, post_check, refine, refine_starts,
};

/// Runs `method` from the neutral start (every variable 0.5) with `budget` evaluations;
/// returns the best point and the evaluations made.
fn run(method: RefineMethod, n: usize, budget: usize) -> (Point, usize, StopReason, Vec<Point>) {
    let valley = Valley::new(n);
    let sp = common::free_space(n);
    let cfg = RefineConfig::default();
    let z0 = vec![0.5; n];
    let start = Point {
        f: valley.f(&z0),
        z: z0,
        limits: None,
    };
    let oracle = |zs: &[Vec<f64>]| Ok(zs.iter().map(|z| valley.f(z)).collect());
    let mut ev = Evaluations::new(Box::new(oracle), vec![start.clone()]);
    let r = refine(method, &sp, &start, &mut ev, &cfg, budget).unwrap();
    assert!(sp.is_feasible(&r.best.z));
    (r.best, ev.count(), r.stop, ev.log.clone())
}

#[test]
fn ten_variables_from_a_neutral_start_reach_the_valley_floor() {
    let start = Valley::new(10).f(&[0.5; 10]);
    for budget in [20, 40, 60, 80] {
        let (best, evals, _, _) = run(RefineMethod::Model, 10, budget);
        let (tr, _, _, _) = run(RefineMethod::TrustRegion, 10, budget);
        println!(
            "10 variables, budget {budget}: model {:.3e}, trust-region {:.3e} (start {start:.3e}, {evals} evaluations)",
            best.f, tr.f
        );
        assert!(evals <= budget);
        assert!(best.f < tr.f, "model {} vs trust region {}", best.f, tr.f);
    }
    // the target: within 1 % of the minimum at ten variables
    let (best, _, _, _) = run(RefineMethod::Model, 10, 60);
    assert!(best.f < 1.01, "{} vs the minimum 1", best.f);
}

#[test]
fn forty_variables_from_a_neutral_start_reach_the_valley_floor() {
    let start = Valley::new(40).f(&[0.5; 40]);
    let (best, evals, _, _) = run(RefineMethod::Model, 40, 240);
    let (tr, _, _, _) = run(RefineMethod::TrustRegion, 40, 240);
    println!(
        "40 variables, budget 240: model {:.4}, trust-region {:.4} (start {start:.4})",
        best.f, tr.f
    );
    assert!(evals <= 240);
    assert!(best.f < tr.f);
    // the target: within 2 % of the minimum at forty variables (measured 1.013 at
    // 240 evaluations, 1.069 at 160)
    assert!(best.f < 1.02, "{} vs the minimum 1", best.f);
}

#[test]
fn the_budget_is_never_exceeded_and_the_stop_is_said() {
    for method in [
        RefineMethod::Model,
        RefineMethod::TrustRegion,
        RefineMethod::NelderMead,
        RefineMethod::Random,
    ] {
        for budget in [1, 2, 5, 11, 19, 23, 37] {
            let (_, evals, stop, _) = run(method, 10, budget);
            assert!(
                evals <= budget,
                "{method:?}: {evals} evaluations for a budget of {budget}"
            );
            if evals < budget {
                assert_ne!(stop, StopReason::Budget, "{method:?} stopped early");
            }
        }
    }
    // a generous budget ends on the tolerance
    let (_, evals, stop, _) = run(RefineMethod::Model, 10, 2000);
    assert_eq!(stop, StopReason::Tolerance, "after {evals} evaluations");
}

#[test]
fn the_same_start_gives_the_same_bits() {
    let (a, _, _, la) = run(RefineMethod::Model, 10, 60);
    let (b, _, _, lb) = run(RefineMethod::Model, 10, 60);
    assert_eq!(a.f.to_bits(), b.f.to_bits());
    assert_eq!(la, lb);
}

/// Starts side by side (`parallel_starts`): each start's evaluations are exactly those it
/// makes alone (the other start does not feed it), each within its own budget, on one
/// thread or two.
#[test]
fn starts_side_by_side_take_the_paths_they_take_alone() {
    let n = 10;
    let valley = Valley::new(n);
    let sp = common::free_space(n);
    let point = |z: Vec<f64>| Point::new(z.clone(), valley.f(&z));
    let starts = [point(vec![0.5; n]), point(vec![0.35; n])];
    let known: Vec<Point> = starts.to_vec();
    let evaluations = || {
        let oracle = |zs: &[Vec<f64>]| Ok(zs.iter().map(|z| valley.f(z)).collect());
        Evaluations::new(Box::new(oracle), known.clone())
    };
    let budget = 30;
    let alone: Vec<Vec<Point>> = starts
        .iter()
        .map(|s| {
            let cfg = RefineConfig {
                max_evaluations: budget,
                ..RefineConfig::default()
            };
            let mut ev = evaluations();
            refine(RefineMethod::Model, &sp, s, &mut ev, &cfg, budget).unwrap();
            ev.log
        })
        .collect();
    let refs: Vec<&Point> = starts.iter().collect();
    let cfg = RefineConfig {
        max_evaluations: budget,
        parallel_starts: true,
        ..RefineConfig::default()
    };
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let (log, stops) = pool
            .install(|| {
                refine_starts(RefineMethod::Model, &sp, &refs, evaluations, &cfg)
                    .map(|(ev, stops)| (ev.log, stops))
            })
            .unwrap();
        assert_eq!(stops, vec![StopReason::Budget; 2], "{threads} threads");
        assert_eq!(log.len(), 2 * budget);
        assert_eq!(log[..budget], alone[0][..], "{threads} threads");
        assert_eq!(log[budget..], alone[1][..], "{threads} threads");
    }
}

#[test]
fn the_post_check_finds_the_valley_floor_stationary_and_a_slope_not() {
    let n = 10;
    let valley = Valley::new(n);
    let sp = common::free_space(n);
    let oracle = |zs: &[Vec<f64>]| Ok(zs.iter().map(|z| valley.f(z)).collect());
    let at_min = Point {
        z: valley.star.clone(),
        f: valley.f(&valley.star),
        limits: None,
    };
    let mut ev = Evaluations::new(Box::new(oracle), vec![]);
    // at the minimum (f = 0) every move is worse
    let s = post_check(&sp, &at_min, &mut ev, 0.01).unwrap().unwrap();
    assert!(s.stationary && s.best_gain < 0.0, "{s:?}");
    assert_eq!(s.moves, 2 * n + 2);
    // a point off the floor on a steep side is not stationary
    let mut z = valley.star.clone();
    z[3] += 0.05;
    let off = Point::new(z.clone(), valley.f(&z));
    let s = post_check(&sp, &off, &mut ev, 0.01).unwrap().unwrap();
    assert!(
        !s.stationary && s.best_gain > 10.0 * STATIONARY_GAIN,
        "{s:?}"
    );
}

/// A study refined by the model refiner (profile searches, model steps, post-check)
/// writes the same optimum.json and refine.csv bytes on pools of one and two threads:
/// the refiner is sequential and every batch keeps its order.
#[test]
fn a_model_study_gives_the_same_bytes_on_one_and_two_threads() {
    use slipload_opt::Study;
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["suites"][0]["synthetic"]["count"] = 2.into();
    v["suites"][0]["synthetic"]["duration_s"] = 3.0.into();
    v["sweep"]["points"] = 6.into();
    v["fidelity"] = serde_json::json!({ "method": "newmark", "check_method": "newmark" });
    v["refine"] = serde_json::json!({ "method": "model", "starts": 1, "max_evaluations": 14, "finalists": 2 });
    let study = Study::from_json(&v.to_string(), &path).unwrap();
    let mut outs = Vec::new();
    for threads in [1, 2] {
        let dir = std::env::temp_dir().join(format!(
            "slipload-model-threads-{}-{threads}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let run = pool.install(|| common::optimize_fresh(&study, &dir));
        let r = &run.report.refine;
        // the budget, then the post-check's 2d + 2 moves
        assert!(r.log.len() <= 14 + 2 * 3 + 2, "{} evaluations", r.log.len());
        assert!(r.stationarity.is_some());
        outs.push((
            std::fs::read(dir.join("optimum.json")).unwrap(),
            std::fs::read(dir.join("refine.csv")).unwrap(),
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
    assert!(outs[0] == outs[1]);
}
