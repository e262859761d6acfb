//! Contract of the `sqp` refiner (`phases::refine::Sqp`) on the analytic narrow valley of
//! `tests/common/valley.rs` with its exact gradient, in 10 and 40 variables: from a
//! neutral start it reaches the valley's floor in fewer evaluations than the `model`
//! refiner needs; on the maximum of two valleys (the worst of two property cases, whose
//! optimum is the kink where they tie) it reaches the tie; a limit is kept to; it never
//! makes more evaluations than its budget; the same start gives the same bits; the
//! first-order post-check says a reached minimum is stationary, and its screened form
//! simulates only the moves the derivatives flag and judges them by their values.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;

use common::valley::Valley;
use slipload_opt::model::config::{RefineConfig, RefineMethod};
use slipload_opt::phases::refine::{
    Evaluations, Gradient, LimitValues, Point, STATIONARY_GAIN, StopReason, first_order_check,
    refine, screened_check,
};

/// A point of `cases` (value and gradient of each piece; the objective is their largest)
/// and `ratios` (value and gradient of each limit ratio; the point passes when all ≤ 1).
fn point(
    z: &[f64],
    cases: Vec<(f64, Vec<f64>)>,
    ratios: Vec<(f64, Vec<f64>)>,
) -> (f64, Option<LimitValues>) {
    let objective = cases.iter().map(|c| c.0).fold(f64::NEG_INFINITY, f64::max);
    let passes = ratios.iter().all(|r| r.0 <= 1.0);
    let _ = z;
    (
        if passes { objective } else { f64::INFINITY },
        Some(LimitValues {
            objective,
            ratios: ratios.iter().map(|r| r.0).collect(),
            gradient: Some(Gradient {
                cases: cases.iter().map(|c| c.0).collect(),
                case_grads: cases.into_iter().map(|c| c.1).collect(),
                ratio_grads: ratios.into_iter().map(|r| r.1).collect(),
            }),
        }),
    )
}

/// A design's value and limit values with derivatives, as the refinement's oracle gives.
type Value<'a> = dyn Fn(&[f64]) -> (f64, Option<LimitValues>) + 'a;

/// Runs `method` from the neutral start (every variable 0.5) on `value` with `budget`
/// evaluations: the best point, the evaluations made, why it stopped, the log.
fn run(
    method: RefineMethod,
    n: usize,
    budget: usize,
    value: &Value<'_>,
) -> (Point, usize, StopReason, Vec<Point>) {
    let sp = common::free_space(n);
    let cfg = RefineConfig::default();
    let z0 = vec![0.5; n];
    let (f, limits) = value(&z0);
    // the sweep's point carries no derivatives: the refiner evaluates it again
    let start = Point {
        z: z0,
        f,
        limits: limits.map(|l| LimitValues::new(l.objective, l.ratios)),
    };
    let oracle = |zs: &[Vec<f64>]| Ok(zs.iter().map(|z| value(z)).collect());
    let mut ev = Evaluations::with_limits(Box::new(oracle), vec![start.clone()]);
    let r = refine(method, &sp, &start, &mut ev, &cfg, budget).unwrap();
    assert!(sp.is_feasible(&r.best.z));
    (r.best, ev.count(), r.stop, ev.log.clone())
}

fn valley_value(v: &Valley) -> impl Fn(&[f64]) -> (f64, Option<LimitValues>) + '_ {
    move |z: &[f64]| point(z, vec![(v.f(z), v.gradient(z))], Vec::new())
}

#[test]
fn ten_variables_reach_the_valley_floor_in_fewer_evaluations_than_the_model_refiner() {
    let v = Valley::new(10);
    let value = valley_value(&v);
    let (sqp, evals, _, _) = run(RefineMethod::Sqp, 10, 20, &value);
    let (model, _, _, _) = run(RefineMethod::Model, 10, 20, &value);
    println!(
        "10 variables, 20 evaluations: sqp {:.5}, model {:.5}",
        sqp.f, model.f
    );
    assert!(evals <= 20);
    // the target, within 1 % of the minimum 1, at a third of the model's 60
    assert!(sqp.f < 1.01, "sqp {}", sqp.f);
    assert!(sqp.f < model.f, "sqp {} vs model {}", sqp.f, model.f);
}

#[test]
fn forty_variables_reach_the_valley_floor() {
    let v = Valley::new(40);
    let value = valley_value(&v);
    let (sqp, evals, _, _) = run(RefineMethod::Sqp, 40, 60, &value);
    let (model, _, _, _) = run(RefineMethod::Model, 40, 60, &value);
    println!(
        "40 variables, 60 evaluations: sqp {:.5}, model {:.5}",
        sqp.f, model.f
    );
    assert!(evals <= 60);
    // within 2 % at forty variables (the model refiner needs 240 evaluations for it)
    assert!(sqp.f < 1.02, "sqp {}", sqp.f);
    assert!(sqp.f < model.f);
}

/// The worst of two cases whose valleys are shifted ±δ along the floor: each is the
/// valley plus a linear tilt ±0.2 along the profile direction, so their maximum is the
/// valley plus 0.2 |q₀ᵀu| — a kink through the minimum, which stays z* with f* = 1, where
/// the cases tie. A refiner that models the maximum as one smooth function zigzags
/// across the kink; the minimax step stands on it.
#[test]
fn the_worst_of_two_cases_is_minimised_at_their_tie() {
    let n = 10;
    let v = Valley::new(n);
    let q0: Vec<f64> = vec![1.0 / (n as f64).sqrt(); n];
    let value = |z: &[f64]| {
        let (f, g) = (v.f(z), v.gradient(z));
        let tilt: f64 = z
            .iter()
            .zip(&v.star)
            .zip(&q0)
            .map(|((a, b), q)| (a - b) * q)
            .sum();
        let case = |s: f64| {
            (
                f + s * 0.2 * tilt,
                g.iter()
                    .zip(&q0)
                    .map(|(g, q)| g + s * 0.2 * q)
                    .collect::<Vec<_>>(),
            )
        };
        point(z, vec![case(1.0), case(-1.0)], Vec::new())
    };
    let (sqp, _, _, _) = run(RefineMethod::Sqp, n, 24, &value);
    println!("kink: sqp {:.5}", sqp.f);
    assert!(sqp.f < 1.01, "sqp {}", sqp.f);
}

/// A limit that binds: the valley's minimum misses it (ratio 1.2 there), so the best
/// design lies on the limit; the refiner keeps every accepted design within it and ends
/// within 1 % of the constrained minimum found by a long run.
#[test]
fn a_binding_limit_is_kept_to() {
    let n = 10;
    let v = Valley::new(n);
    // ratio = 1.2 − 4 (mean(z) − mean(z*)): meets the limit at mean(z) ≥ mean(z*) + 0.05
    // (the start, 0.06 above, meets it)
    let m_star: f64 = v.star.iter().sum::<f64>() / n as f64;
    let value = |z: &[f64]| {
        let mean: f64 = z.iter().sum::<f64>() / n as f64;
        let r = 1.2 - 4.0 * (mean - m_star);
        point(
            z,
            vec![(v.f(z), v.gradient(z))],
            vec![(r, vec![-4.0 / n as f64; n])],
        )
    };
    let (long, _, _, _) = run(RefineMethod::Sqp, n, 200, &value);
    let (sqp, _, _, log) = run(RefineMethod::Sqp, n, 24, &value);
    println!("limit: sqp {:.5}, long run {:.5}", sqp.f, long.f);
    assert!(
        sqp.f.is_finite() && sqp.f < long.f * 1.01,
        "{} vs {}",
        sqp.f,
        long.f
    );
    let mean: f64 = sqp.z.iter().sum::<f64>() / n as f64;
    assert!(
        1.2 - 4.0 * (mean - m_star) <= 1.0,
        "the best design meets the limit"
    );
    assert!(log.iter().any(|p| p.f.is_finite()));
}

#[test]
fn the_budget_is_never_exceeded_and_the_same_start_gives_the_same_bits() {
    let v = Valley::new(10);
    let value = valley_value(&v);
    for budget in [1, 2, 5, 11, 19, 23] {
        let (_, evals, stop, _) = run(RefineMethod::Sqp, 10, budget, &value);
        assert!(
            evals <= budget,
            "{evals} evaluations for a budget of {budget}"
        );
        if evals < budget {
            assert_ne!(stop, StopReason::Budget, "stopped early");
        }
    }
    let (a, _, _, la) = run(RefineMethod::Sqp, 10, 30, &value);
    let (b, _, _, lb) = run(RefineMethod::Sqp, 10, 30, &value);
    assert_eq!(a.f.to_bits(), b.f.to_bits());
    assert_eq!(la, lb);
}

/// The first-order post-check: stationary at the valley's minimum (the gradient is zero
/// there), not at the start, whose best move it names.
#[test]
fn the_first_order_check_tells_a_minimum_from_a_start() {
    let n = 10;
    let v = Valley::new(n);
    let value = valley_value(&v);
    let sp = common::free_space(n);
    let at = |z: Vec<f64>| {
        let (f, limits) = value(&z);
        Point { z, f, limits }
    };
    let s = first_order_check(&sp, &at(v.star.clone()), 0.01).unwrap();
    assert!(s.stationary && s.polls == 0, "{s:?}");
    let s = first_order_check(&sp, &at(vec![0.5; n]), 0.01).unwrap();
    assert!(!s.stationary && s.best_gain > 1e-3, "{s:?}");
}

/// The screened post-check on f = 1 + Σ(zᵢ − cᵢ)²: at z = c + h e₀ the first-order gain of
/// the move −s on variable 0 is 2hs, what the move gains is 2hs − s²; with 2hs above the
/// threshold and 2hs − s² below it the derivatives flag the move and its simulation
/// clears it (the move, which gains a little, is the better design all the same). Only
/// flagged moves are simulated (one here), and with h larger the
/// simulated gain passes the threshold: the design is not stationary and the move, now
/// an evaluated point, is the best one known.
#[test]
fn the_screened_check_simulates_the_flagged_moves_alone_and_judges_by_their_values() {
    let n = 10;
    let c = vec![0.5; n];
    let bowl = |z: &[f64]| -> (f64, Option<LimitValues>) {
        let f = 1.0 + z.iter().zip(&c).map(|(a, b)| (a - b).powi(2)).sum::<f64>();
        let g = z.iter().zip(&c).map(|(a, b)| 2.0 * (a - b)).collect();
        point(z, vec![(f, g)], Vec::new())
    };
    let sp = common::free_space(n);
    let s = 0.03;
    // 2hs = 1.5 × threshold (flagged), s² = 9e-4 > 0.5 × threshold × f (cleared)
    let check = |h: f64| {
        let mut z = c.clone();
        z[0] += h;
        let (f, limits) = bowl(&z);
        let at = Point { z, f, limits };
        let oracle = |zs: &[Vec<f64>]| Ok(zs.iter().map(|z| bowl(z)).collect());
        let mut ev = Evaluations::with_limits(Box::new(oracle), vec![at.clone()]);
        let out = screened_check(&sp, &at, &mut ev, s).unwrap().unwrap();
        (out, ev.count(), ev.best().unwrap(), at)
    };
    let h = 1.5 * STATIONARY_GAIN / (2.0 * s);
    let (out, count, best, at) = check(h);
    assert_eq!(out.screened, 2 * n + 2, "{out:?}");
    assert_eq!((out.moves, count, out.polls), (1, 1, 1), "{out:?}");
    assert_eq!(out.best_move, "floor1 -", "{out:?}");
    let first = 2.0 * h * s / at.f;
    assert!(first > STATIONARY_GAIN, "first-order gain {first}");
    assert!(out.stationary && out.best_gain < STATIONARY_GAIN, "{out:?}");
    assert!(
        (out.best_gain - (2.0 * h * s - s * s) / at.f).abs() < 1e-12,
        "{out:?}"
    );
    // a move that gains, if less than the threshold, is still the better design
    assert!(
        best.f < at.f && (best.z[0] - (at.z[0] - s)).abs() < 1e-15,
        "{best:?}"
    );
    // a larger offset: the simulated gain passes the threshold, the move is the best point
    let h = 3.0 * STATIONARY_GAIN / (2.0 * s);
    let (out, count, best, at) = check(h);
    // (the profile move −, half as steep here, is flagged too)
    assert_eq!(
        (out.moves, count, out.best_move.as_str()),
        (2, 2, "floor1 -"),
        "{out:?}"
    );
    assert!(
        !out.stationary && out.best_gain > STATIONARY_GAIN,
        "{out:?}"
    );
    assert!(
        best.f < at.f && (best.z[0] - (at.z[0] - s)).abs() < 1e-15,
        "{best:?}"
    );
    // at the minimum nothing is flagged and nothing simulated: the first-order answer
    let (f, limits) = bowl(&c);
    let at = Point {
        z: c.clone(),
        f,
        limits,
    };
    let oracle = |zs: &[Vec<f64>]| Ok(zs.iter().map(|z| bowl(z)).collect());
    let mut ev = Evaluations::with_limits(Box::new(oracle), vec![at.clone()]);
    let out = screened_check(&sp, &at, &mut ev, s).unwrap().unwrap();
    assert!(
        out.stationary && out.polls == 0 && ev.count() == 0,
        "{out:?}"
    );
}
