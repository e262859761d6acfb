//! Refiners: from a good sweep point to a better one with few design evaluations
//! (each evaluation is one simulation per record of the study).
//!
//! All refiners work in the scaled variables z ∈ [0, 1]^d of the [`DesignSpace`] and call
//! the objective through [`Evaluations`], which remembers every point evaluated (sweep
//! points included) and counts the new ones, so the refiners can be compared by the
//! number of evaluations they need.
//!
//! [`DesignSpace`]: crate::DesignSpace

mod evaluations;
mod model;
mod nelder_mead;
mod random;
mod sqp;
mod trust_region;

pub use evaluations::{
    Evaluations, Gradient, Hook, LimitOracle, LimitValues, Oracle, Point, Refiner, STATIONARY_GAIN,
    StopReason,
};
pub use model::{LINE_EVALUATIONS, ModelSearch};
pub use nelder_mead::NelderMead;
pub use random::RandomSearch;
pub use sqp::Sqp;
pub use trust_region::TrustRegion;

use crate::base::error::OptError;
use crate::model::config::{RefineConfig, RefineMethod};
use crate::model::space::DesignSpace;
use rayon::prelude::*;

/// A refiner's answer and why it stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct Refined {
    /// The best point of the refiner's state.
    pub best: Point,
    /// Why it stopped: its own test, or the budget.
    pub stop: StopReason,
}

/// Drives a refiner: `init`, then `next_iter` while the budget of new evaluations
/// (counted over the whole [`Evaluations`]) lasts and `terminate` is false.
pub fn run(
    refiner: &mut dyn Refiner,
    space: &DesignSpace,
    start: &Point,
    ev: &mut Evaluations<'_>,
    budget: usize,
) -> Result<Refined, OptError> {
    // the executor owns the budget: no batch of any refiner passes it
    let before = ev.count();
    ev.set_limit(Some(budget));
    let mut initialised = false;
    let mut steps = || -> Result<(), OptError> {
        refiner.init(space, start, ev)?;
        initialised = true;
        while ev.count() < budget && !refiner.terminate() {
            refiner.next_iter(space, ev)?;
        }
        Ok(())
    };
    let outcome = steps();
    ev.set_limit(None);
    let spent = match outcome {
        Ok(()) => false,
        Err(OptError::BudgetSpent { .. }) => true,
        Err(e) => return Err(e),
    };
    let stop = if !spent && refiner.terminate() {
        refiner.stop_reason()
    } else {
        StopReason::Budget
    };
    let best = if initialised {
        refiner.best().clone()
    } else {
        // stopped inside its first batch: the best of the start and what it evaluated
        let mut best = start.clone();
        for p in &ev.log[before.min(ev.log.len())..] {
            if p.f < best.f {
                best = p.clone();
            }
        }
        best
    };
    Ok(Refined { best, stop })
}

/// Runs `method` from `start` until `budget` new evaluations have been made in total
/// (counting those before the call) or the method's own test stops it.
pub fn refine(
    method: RefineMethod,
    space: &DesignSpace,
    start: &Point,
    ev: &mut Evaluations<'_>,
    cfg: &RefineConfig,
    budget: usize,
) -> Result<Refined, OptError> {
    let mut r: Box<dyn Refiner> = match method {
        // (`auto` is resolved where the study is known; without one it is `model`, which
        // reads no derivatives)
        RefineMethod::Model | RefineMethod::Auto => Box::new(ModelSearch::new(cfg, budget)),
        RefineMethod::Sqp => Box::new(Sqp::new(cfg, budget)),
        RefineMethod::TrustRegion => Box::new(TrustRegion::new(cfg, budget)),
        RefineMethod::NelderMead => Box::new(NelderMead::new(cfg)),
        RefineMethod::Random => Box::new(RandomSearch::new(cfg)),
    };
    run(r.as_mut(), space, start, ev, budget)
}

/// Runs `method` from each of `starts`, each with `cfg.max_evaluations` evaluations;
/// `evaluations` makes the evaluations of a refinement (the points known before it, the
/// journal). Returns the evaluations of all starts (in the order of the starts) and why
/// each start stopped.
///
/// With `cfg.parallel_starts` the starts run side by side, each on evaluations of its own
/// (the known points and its own), so its path does not depend on the other starts or
/// on the threads; their evaluations join in the order of the starts. Otherwise they run
/// one after the other on one set of evaluations: a later start sees the earlier ones'
/// points and takes what they left of the budget.
pub fn refine_starts<'a, E>(
    method: RefineMethod,
    space: &DesignSpace,
    starts: &[&Point],
    evaluations: E,
    cfg: &RefineConfig,
) -> Result<(Evaluations<'a>, Vec<StopReason>), OptError>
where
    E: Fn() -> Evaluations<'a> + Sync,
{
    let mut ev = evaluations();
    let mut stops = Vec::with_capacity(starts.len());
    if cfg.parallel_starts && starts.len() > 1 {
        // (why it stopped, its evaluations, how many of them the journal gave)
        type Start = (StopReason, Vec<Point>, usize);
        let runs: Vec<Result<Start, OptError>> = starts
            .par_iter()
            .map(|start| {
                let mut own = evaluations();
                let r = refine(method, space, start, &mut own, cfg, cfg.max_evaluations)?;
                Ok((r.stop, std::mem::take(&mut own.log), own.replayed))
            })
            .collect();
        for run in runs {
            let (stop, log, replayed) = run?;
            stops.push(stop);
            ev.absorb(log, replayed);
        }
    } else {
        let mut budget = 0;
        for start in starts {
            budget += cfg.max_evaluations;
            stops.push(refine(method, space, start, &mut ev, cfg, budget)?.stop);
        }
    }
    Ok((ev, stops))
}

/// The post-check of a refined design: every single-variable move ±h and the profile move
/// (every slip load × (1 ± h)), evaluated in one batch.
#[derive(Debug, Clone, PartialEq)]
pub struct Stationarity {
    /// The move, scaled variables (and relative, for the profile move).
    pub step: f64,
    /// Moves evaluated (those inside the space).
    pub moves: usize,
    /// The largest relative decrease of the objective among them (≤ 0: none improves).
    pub best_gain: f64,
    /// What the best move was: `floor N +`, `floor N -`, `profile +`, `profile -`.
    pub best_move: String,
    /// Whether no move gains more than [`STATIONARY_GAIN`].
    pub stationary: bool,
    /// Polls made: the first, and each one more the budget had room for after a poll
    /// whose best move gained (that move taken); 0 for the first-order check of the
    /// `sqp` refiner, which evaluates no move.
    pub polls: usize,
    /// Moves the `sqp` refiner's derivatives judged before any was simulated (0 for the
    /// polls, which simulate every move): with a poll, `moves` are those they flagged.
    pub screened: usize,
}

/// The first-order post-check of the `sqp` refiner's design (no simulation): the moves
/// of [`post_check`], each judged by the linearisation its derivatives give — the
/// objective max_k(f_k + g_kᵀm), a move whose linearised limit ratios pass 1 left out.
/// The objective is a maximum of pieces (cases, storeys, records, time steps), each
/// convex near its kinks, so a linearised gain bounds what the move gains to first order.
/// `None` when `at` carries no derivatives or no move fits in the space.
pub fn first_order_check(space: &DesignSpace, at: &Point, step: f64) -> Option<Stationarity> {
    first_order(space, at, step).map(|(s, _)| s)
}

/// Each move of the post-checks (its name and point) with its first-order gain.
type Judged = Vec<((String, Vec<f64>), Option<f64>)>;

/// [`first_order_check`], with the moves and their first-order gains.
fn first_order(space: &DesignSpace, at: &Point, step: f64) -> Option<(Stationarity, Judged)> {
    let moves = stationarity_moves(space, &at.z, step);
    let gains = first_order_gains(at, &moves)?;
    let (k, gain) = gains
        .iter()
        .enumerate()
        .filter_map(|(k, g)| g.map(|g| (k, g)))
        .fold(None, |best: Option<(usize, f64)>, (k, g)| {
            if best.is_none_or(|(_, b)| g > b) {
                Some((k, g))
            } else {
                best
            }
        })?;
    let s = Stationarity {
        step,
        moves: moves.len(),
        best_gain: gain,
        best_move: moves[k].0.clone(),
        stationary: gain <= STATIONARY_GAIN,
        polls: 0,
        screened: moves.len(),
    };
    Some((s, moves.into_iter().zip(gains).collect()))
}

/// The post-check of the `sqp` refiner's design: [`first_order_check`] screens the moves,
/// and those whose first-order gain passes [`STATIONARY_GAIN`] are simulated in one batch
/// (their evaluations join `ev`, so a move that gains becomes the refinement's best
/// point). A first-order gain is a bound only near a kink of the maximum it reads, and a
/// linearised limit can pass where the simulated one does not, so a flagged move is
/// judged by what it gives. With no move flagged the first-order check is the answer.
pub fn screened_check(
    space: &DesignSpace,
    at: &Point,
    ev: &mut Evaluations<'_>,
    step: f64,
) -> Result<Option<Stationarity>, OptError> {
    let Some((first, judged)) = first_order(space, at, step) else {
        return Ok(None);
    };
    if first.stationary {
        return Ok(Some(first));
    }
    let flagged: Vec<(String, Vec<f64>)> = judged
        .into_iter()
        .filter(|(_, g)| g.is_some_and(|g| g > STATIONARY_GAIN))
        .map(|(m, _)| m)
        .collect();
    // (the first-order check flagged at least one move)
    Ok(Some(Stationarity {
        screened: first.moves,
        ..simulated(at, &flagged, ev, step)?
    }))
}

/// Simulates `moves` (not empty) around `at` in one batch: the poll's [`Stationarity`].
fn simulated(
    at: &Point,
    moves: &[(String, Vec<f64>)],
    ev: &mut Evaluations<'_>,
    step: f64,
) -> Result<Stationarity, OptError> {
    let zs: Vec<Vec<f64>> = moves.iter().map(|(_, z)| z.clone()).collect();
    let values = ev.eval(&zs)?;
    let scale = at.f.abs().max(f64::MIN_POSITIVE);
    let (k, gain) = values
        .iter()
        .map(|f| (at.f - f) / scale)
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .expect("at least one move");
    Ok(Stationarity {
        step,
        moves: moves.len(),
        best_gain: gain,
        best_move: moves[k].0.clone(),
        stationary: gain <= STATIONARY_GAIN,
        polls: 1,
        screened: 0,
    })
}

/// The first-order gain of each move (see [`first_order_check`]): `None` for a move whose
/// linearised limit ratios do not all pass; `None` in all when `at` carries no
/// derivatives or is not finite.
fn first_order_gains(at: &Point, moves: &[(String, Vec<f64>)]) -> Option<Vec<Option<f64>>> {
    let l = at.limits.as_ref()?;
    let g = l.gradient.as_ref()?;
    if !at.f.is_finite() {
        return None;
    }
    let dot = |a: &[f64], m: &[f64]| -> f64 {
        a.iter()
            .zip(m.iter().zip(&at.z))
            .map(|(a, (z, c))| a * (z - c))
            .sum()
    };
    let scale = at.f.abs().max(f64::MIN_POSITIVE);
    Some(
        moves
            .iter()
            .map(|(_, z)| {
                let passes = l
                    .ratios
                    .iter()
                    .zip(&g.ratio_grads)
                    .all(|(r, a)| r + dot(a, z) <= 1.0);
                passes.then(|| {
                    let f = g
                        .cases
                        .iter()
                        .zip(&g.case_grads)
                        .map(|(f, a)| f + dot(a, z))
                        .fold(f64::NEG_INFINITY, f64::max);
                    (at.f - f) / scale
                })
            })
            .collect(),
    )
}

/// Polls the moves of [`Stationarity`] around `at` (their evaluations join `ev`, so a
/// better move becomes the refinement's best point). `None` when `at` is not finite or
/// no move fits in the space.
pub fn post_check(
    space: &DesignSpace,
    at: &Point,
    ev: &mut Evaluations<'_>,
    step: f64,
) -> Result<Option<Stationarity>, OptError> {
    if !at.f.is_finite() {
        return Ok(None);
    }
    let moves = stationarity_moves(space, &at.z, step);
    if moves.is_empty() {
        return Ok(None);
    }
    simulated(at, &moves, ev, step).map(Some)
}

/// The moves of the post-checks around `z`: every single-variable move ±`step` that stays
/// in the space, and the profile moves (every slip load × (1 ± `step`)), each named.
fn stationarity_moves(space: &DesignSpace, z: &[f64], step: f64) -> Vec<(String, Vec<f64>)> {
    let mut moves: Vec<(String, Vec<f64>)> = Vec::new();
    for i in 0..space.dim() {
        for (sign, name) in [(1.0, "+"), (-1.0, "-")] {
            let mut m = z.to_vec();
            m[i] = (m[i] + sign * step).clamp(0.0, 1.0);
            if m != z && space.is_feasible(&m) {
                moves.push((format!("{} {name}", space.names[i]), m));
            }
        }
    }
    let loads = space.slip_loads(z);
    for (factor, name) in [(1.0 + step, "profile +"), (1.0 - step, "profile -")] {
        let scaled: Vec<f64> = loads.iter().map(|v| v * factor).collect();
        if let Some(m) = space.point_of(&scaled)
            && m != z
        {
            moves.push((name.to_string(), m));
        }
    }
    moves
}
