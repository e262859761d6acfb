//! Contract: on a convex quadratic in scaled variables with its minimum on a bound and a
//! linear constraint active, the trust-region refiner (whose quadratic model is then
//! exact) reaches the analytic constrained minimum, and every refiner returns a feasible
//! point no worse than its start within its evaluation budget. A refiner's state saved as
//! JSON mid-way and restored continues to the same answer.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use nalgebra::DMatrix;
use slipload_opt::DesignSpace;
use slipload_opt::model::config::{RefineConfig, RefineMethod};
use slipload_opt::phases::refine::{Evaluations, Point, refine};

/// f = (z₀ − 1.2)² + 2u² + v² + ½uv, u = z₁ − 0.3, v = z₂ − 0.6.
fn f(z: &[f64]) -> f64 {
    let (u, v) = (z[1] - 0.3, z[2] - 0.6);
    (z[0] - 1.2).powi(2) + 2.0 * u * u + v * v + 0.5 * u * v
}

/// [0, 1]³ with z₁ + z₂ ≤ 0.6.
fn space() -> DesignSpace {
    DesignSpace {
        dampers: vec![0, 1, 2],
        offset: vec![0.0; 3],
        basis: DMatrix::identity(3, 3),
        a: DMatrix::from_row_slice(1, 3, &[0.0, 1.0, 1.0]),
        b: vec![0.6],
        names: vec!["a".into(), "b".into(), "c".into()],
        shape: None,
        profile: vec![1.0; 3],
    }
}

fn run(method: RefineMethod) -> (Point, usize, Point) {
    let sp = space();
    let cfg = RefineConfig::default();
    let known: Vec<Point> = [
        [0.5, 0.1, 0.1],
        [0.2, 0.2, 0.3],
        [0.9, 0.4, 0.1],
        [0.1, 0.05, 0.5],
    ]
    .iter()
    .map(|z| Point {
        z: z.to_vec(),
        f: f(z),
        limits: None,
    })
    .collect();
    let start = known[0].clone();
    let oracle = |zs: &[Vec<f64>]| Ok(zs.iter().map(|z| f(z)).collect());
    let mut ev = Evaluations::new(Box::new(oracle), known);
    let best = refine(method, &sp, &start, &mut ev, &cfg, 60).unwrap().best;
    assert!(sp.is_feasible(&best.z), "{method:?}: {:?}", best.z);
    (best, ev.count(), start)
}

#[test]
fn trust_region_finds_the_constrained_minimum() {
    // minimum: z₀ = 1 (bound); on z₁ + z₂ = 0.6, 2.5u² + 0.45u + 0.09 is least at
    // u = −0.09, so z = (1, 0.21, 0.39) and f = 0.04 + 0.06975
    let f_star = 0.04 + 0.06975;
    let (best, evals, _) = run(RefineMethod::TrustRegion);
    // clarabel answers to ~1e-8 and its answer is clamped: f within 1e-6 of the minimum
    assert!(
        best.f - f_star < 1e-6,
        "f = {} vs {f_star} after {evals} evaluations",
        best.f
    );
    assert!(
        (best.z[0] - 1.0).abs() < 1e-4 && (best.z[1] - 0.21).abs() < 1e-3,
        "{:?}",
        best.z
    );
    assert!(evals <= 60);
}

#[test]
fn every_refiner_improves_within_its_budget() {
    for m in [
        RefineMethod::TrustRegion,
        RefineMethod::NelderMead,
        RefineMethod::Random,
    ] {
        let (best, evals, start) = run(m);
        assert!(best.f < start.f, "{m:?}");
        assert!(evals <= 60 + 3 * 3, "{m:?} used {evals}");
    }
}

#[test]
fn a_saved_refiner_state_continues_to_the_same_answer() {
    use slipload_opt::phases::refine::{Refiner, TrustRegion};
    let sp = space();
    let cfg = RefineConfig::default();
    let start = Point {
        z: vec![0.5, 0.1, 0.1],
        f: f(&[0.5, 0.1, 0.1]),
        limits: None,
    };
    let oracle = |zs: &[Vec<f64>]| Ok(zs.iter().map(|z| f(z)).collect());
    // uninterrupted
    let mut ev = Evaluations::new(Box::new(oracle), vec![start.clone()]);
    let mut a = TrustRegion::new(&cfg, 60);
    a.init(&sp, &start, &mut ev).unwrap();
    let mut states = Vec::new();
    while ev.count() < 60 && !a.terminate() {
        a.next_iter(&sp, &mut ev).unwrap();
        states.push(serde_json::to_string(&a).unwrap());
    }
    // stopped after 3 iterations, saved as JSON, restored and continued with the same cache
    let mut ev2 = Evaluations::new(Box::new(oracle), vec![start.clone()]);
    let mut b = TrustRegion::new(&cfg, 60);
    b.init(&sp, &start, &mut ev2).unwrap();
    for _ in 0..3 {
        b.next_iter(&sp, &mut ev2).unwrap();
    }
    let mut c: TrustRegion = serde_json::from_str(&serde_json::to_string(&b).unwrap()).unwrap();
    assert_eq!(serde_json::to_string(&c).unwrap(), states[2]);
    while ev2.count() < 60 && !c.terminate() {
        c.next_iter(&sp, &mut ev2).unwrap();
    }
    assert_eq!(c, a);
}

/// Issue 40: the refiners give the same optimum when the objective is multiplied by a
/// positive constant (a term weighted 1e-7 instead of 1): their tests are relative to
/// the objective's scale, and the trust region's model is solved at unit scale.
#[test]
fn every_refiner_is_blind_to_the_objective_scale() {
    let sp = space();
    let cfg = RefineConfig::default();
    let starts = [
        [0.5, 0.1, 0.1],
        [0.2, 0.2, 0.3],
        [0.9, 0.4, 0.1],
        [0.1, 0.05, 0.5],
    ];
    for method in [
        RefineMethod::TrustRegion,
        RefineMethod::NelderMead,
        RefineMethod::Random,
    ] {
        let at = |scale: f64| {
            let g = move |z: &[f64]| scale * f(z);
            let known: Vec<Point> = starts
                .iter()
                .map(|z| Point {
                    z: z.to_vec(),
                    f: g(z),
                    limits: None,
                })
                .collect();
            let start = known[0].clone();
            let oracle = move |zs: &[Vec<f64>]| Ok(zs.iter().map(|z| g(z)).collect());
            let mut ev = Evaluations::new(Box::new(oracle), known);
            refine(method, &sp, &start, &mut ev, &cfg, 60).unwrap().best
        };
        let (one, tiny) = (at(1.0), at(1e-7));
        // the same path up to the round-off of scaling: the same optimum to well within
        // the refiner's tolerance (1e-3 of the range)
        for (a, b) in one.z.iter().zip(&tiny.z) {
            assert!(
                (a - b).abs() < 1e-6,
                "{method:?}: {:?} vs {:?}",
                one.z,
                tiny.z
            );
        }
        assert!(
            (tiny.f / 1e-7 - one.f).abs() <= 1e-9 * one.f.abs().max(1e-3),
            "{method:?}: {} vs {}",
            tiny.f / 1e-7,
            one.f
        );
    }
}
