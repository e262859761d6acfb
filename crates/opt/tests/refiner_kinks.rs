//! The `model` refiner on an objective with kinks, as the slip-load objectives have them
//! (a peak over storeys and records, the worst of the property cases): a separable
//! V-shaped valley, f(z) = 1 + Σ wᵢ |zᵢ − zᵢ*| + ‖z − z*‖², whose minimum f* = 1 at z* is
//! a kink in every variable. An interpolation model through points on both sides of a
//! kink sees a slope near zero and curvature where there is none, so its steps fail;
//! single-variable moves toward z* gain until they step over it, and so does the design
//! that takes every gaining move together (the poll's candidates).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;

use slipload_opt::model::config::{RefineConfig, RefineMethod};
use slipload_opt::phases::refine::{Evaluations, Point, refine};

/// The minimum: slip loads falling with height, off the storey-shear-like profile of
/// [`common::free_space`], so the profile searches do not find it.
fn minimum(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| 0.7 - 0.4 * (i as f64 / (n - 1) as f64).powi(2))
        .collect()
}

/// Weights from 1 to 3: some floors matter more than others.
fn f(z: &[f64]) -> f64 {
    let n = z.len();
    let star = minimum(n);
    let mut v = 1.0;
    for (i, (z, s)) in z.iter().zip(&star).enumerate() {
        let w = 1.0 + 2.0 * i as f64 / (n - 1) as f64;
        v += w * (z - s).abs() + (z - s).powi(2);
    }
    v
}

fn run(n: usize, budget: usize) -> (Point, usize) {
    let sp = common::free_space(n);
    let z0 = vec![0.5; n];
    let start = Point::new(z0.clone(), f(&z0));
    let oracle = |zs: &[Vec<f64>]| Ok(zs.iter().map(|z| f(z)).collect());
    let mut ev = Evaluations::new(Box::new(oracle), vec![start.clone()]);
    let cfg = RefineConfig::default();
    let r = refine(RefineMethod::Model, &sp, &start, &mut ev, &cfg, budget).unwrap();
    (r.best, ev.count())
}

#[test]
fn ten_variables_on_a_kinked_valley_reach_its_floor() {
    let start = f(&[0.5; 10]);
    for budget in [60, 100, 150] {
        let (best, evals) = run(10, budget);
        println!(
            "budget {budget}: {:.4} (start {start:.4}, {evals} evaluations)",
            best.f
        );
        assert!(evals <= budget);
    }
    // within 2 % of the minimum at 150 evaluations (measured 1.011); the refiner before
    // its polls stopped on its tolerance at 1.051 after 119 evaluations, its model steps
    // failing at the kinks (1.143 at 60, 1.074 at 100; now 1.066 and 1.049)
    let (best, _) = run(10, 150);
    assert!(best.f < 1.02, "{} vs the minimum 1", best.f);
}
