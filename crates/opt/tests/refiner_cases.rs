//! The `model` refiner on the worst of three property cases, as a study that checks its
//! dampers at their property bounds reads its objective: f(z) = maxⱼ q(λⱼ z) with
//! λ = 1, 0.85, 1.15 (nominal, lower and upper slip loads) and q a smooth narrow valley
//! (neighbouring variables coupled, as neighbouring storeys are). Each case is smooth;
//! their largest has its minimum on a kink, where the lower- and the upper-bound cases
//! are equal. With each case's value beside the objective the refiner models the cases
//! one by one (the minimax step); without them, it models their largest.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;

use slipload_opt::model::config::{RefineConfig, RefineMethod};
use slipload_opt::phases::refine::{Evaluations, LimitValues, Point, refine};

const FACTORS: [f64; 3] = [1.0, 0.85, 1.15];

/// The valley's floor: falling with height, off the profile of [`common::free_space`].
fn floor(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| 0.6 - 0.3 * (i as f64 / (n - 1) as f64).powi(2))
        .collect()
}

/// q(x) = 1 + (x − m)ᵀA(x − m), A = I + 20 DᵀD (D the neighbour differences): a
/// neighbour pair out of step costs 20 times a floor off its place.
fn q(x: &[f64]) -> f64 {
    let m = floor(x.len());
    let e: Vec<f64> = x.iter().zip(&m).map(|(x, m)| x - m).collect();
    1.0 + e.iter().map(|v| v * v).sum::<f64>()
        + 20.0 * e.windows(2).map(|w| (w[0] - w[1]).powi(2)).sum::<f64>()
}

/// The minimum of the worst case, in closed form. q is convex, so along any ray the
/// nominal case lies below the larger of the bound cases, and the minimum of
/// max(q(0.85z), q(1.15z)) minimises μ q(0.85z) + (1 − μ) q(1.15z) where the two are
/// equal: that is z = c·m with c = Σwλ / Σwλ², where q(λcm) = 1 + (λc − 1)² mᵀAm is
/// equal for λ = 0.85 and 1.15 at c = 1 (μ = 0.575). So z* = m and
/// f* = 1 + 0.15² mᵀAm = q(0.85 m).
fn minimum(n: usize) -> f64 {
    q(&floor(n).iter().map(|v| 0.85 * v).collect::<Vec<_>>())
}

fn cases(z: &[f64]) -> Vec<f64> {
    FACTORS
        .iter()
        .map(|l| q(&z.iter().map(|v| l * v).collect::<Vec<_>>()))
        .collect()
}

fn worst(z: &[f64]) -> f64 {
    cases(z).into_iter().fold(f64::NEG_INFINITY, f64::max)
}

/// The best value at `budget` evaluations from the middle of the box, with each case's
/// value given to the refiner or not.
fn run(n: usize, budget: usize, with_cases: bool) -> (f64, usize) {
    let sp = common::free_space(n);
    let z0 = vec![0.5; n];
    let values = |z: &[f64]| LimitValues {
        objective: worst(z),
        ratios: Vec::new(),
        cases: if with_cases { cases(z) } else { Vec::new() },
    };
    let start = Point {
        z: z0.clone(),
        f: worst(&z0),
        limits: Some(values(&z0)),
    };
    let oracle = move |zs: &[Vec<f64>]| {
        Ok(zs
            .iter()
            .map(|z| (worst(z), Some(values(z))))
            .collect::<Vec<_>>())
    };
    let mut ev = Evaluations::with_limits(Box::new(oracle), vec![start.clone()]);
    let cfg = RefineConfig::default();
    let r = refine(RefineMethod::Model, &sp, &start, &mut ev, &cfg, budget).unwrap();
    (r.best.f, ev.count())
}

#[test]
fn the_worst_of_three_cases_is_minimised_case_by_case() {
    let n = 10;
    let best = minimum(n);
    let gap = |f: f64| 100.0 * (f / best - 1.0);
    let mut at = Vec::new();
    for budget in [40, 80, 160] {
        let (with, e1) = run(n, budget, true);
        let (without, e2) = run(n, budget, false);
        println!(
            "budget {budget}: with the cases +{:.3} %, without +{:.3} % above {best:.6}",
            gap(with),
            gap(without)
        );
        assert!(e1 <= budget && e2 <= budget);
        assert!(with >= best * (1.0 - 1e-12), "{with} below the minimum {best}");
        at.push((with, without));
    }
    // measured: +10.5 / +0.91 / +0.044 % with the cases, +13.5 / +2.8 / +0.097 % without
    // (without them the refiner stops at the kink, its tolerance reached); at 160 within
    // the 0.1 % the study's post-check calls stationary
    for (with, without) in &at {
        assert!(with < without, "{with} vs {without}");
    }
    assert!(gap(at[1].0) < 2.0, "{} % at 80 evaluations", gap(at[1].0));
    assert!(gap(at[2].0) < 0.1, "{} % at 160 evaluations", gap(at[2].0));
}
