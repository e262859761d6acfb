//! What every refiner shares: the [`Refiner`] state machine, the [`Point`]s it evaluates,
//! and [`Evaluations`], which remembers every point evaluated (sweep points included) and
//! counts the new ones.

use crate::base::error::OptError;
use crate::model::space::DesignSpace;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// An argmin-style refiner: a state machine (`init`, then `next_iter` until `terminate`)
/// driven by [`super::run`]. Its state is plain data (the implementations serialise), so a
/// refinement can be inspected, saved between iterations and continued.
pub trait Refiner {
    /// Sets the state up from the start point (may evaluate points).
    fn init(
        &mut self,
        space: &DesignSpace,
        start: &Point,
        ev: &mut Evaluations<'_>,
    ) -> Result<(), OptError>;
    /// One iteration.
    fn next_iter(&mut self, space: &DesignSpace, ev: &mut Evaluations<'_>) -> Result<(), OptError>;
    /// The refiner's own stopping test (the executor also stops at the budget).
    fn terminate(&self) -> bool;
    /// The best point of the state.
    fn best(&self) -> &Point;
    /// Why `terminate` said stop (asked only when it did): by default the step fell
    /// below the tolerance.
    fn stop_reason(&self) -> StopReason {
        StopReason::Tolerance
    }
}

/// A design counts as stationary when no poll move lowers its objective by more than
/// this fraction of it (0.1 %: a tenth of the 1 % within which a study should find the
/// best design).
pub const STATIONARY_GAIN: f64 = 1e-3;

/// Why a refiner stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// The step (trust radius, simplex size) fell below the tolerance: converged.
    Tolerance,
    /// The evaluation budget was spent.
    Budget,
    /// No progress could be made: no model could be fitted (too few designs near the
    /// centre that pass and stand).
    NoProgress,
}

impl StopReason {
    /// As the summary and optimum.json say it.
    pub fn as_str(self) -> &'static str {
        match self {
            StopReason::Tolerance => "tolerance",
            StopReason::Budget => "budget",
            StopReason::NoProgress => "no_progress",
        }
    }
}

/// One evaluated design.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// Scaled variables.
    pub z: Vec<f64>,
    /// What the refiners minimise: the objective (+∞, written `"inf"`, for a design that
    /// collapses on a record or, in a study with limits, misses one).
    #[serde(with = "objective_value")]
    pub f: f64,
    /// In a study with limits: the objective and the limits' ratios, also where `f` is
    /// +∞ because a limit is missed (what the model refiner models the limits from).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limits: Option<LimitValues>,
}

impl Point {
    /// A point without limit values.
    pub fn new(z: Vec<f64>, f: f64) -> Point {
        Point { z, f, limits: None }
    }

    /// The objective the model refiner fits: the objective ignoring the limits where the
    /// point carries it, else `f`.
    pub fn objective(&self) -> f64 {
        self.limits.as_ref().map_or(self.f, |l| l.objective)
    }
}

/// A design's objective and the ratios of the study's limits, as the model refiner
/// models the limits ([`crate::model::check::DesignCheck::smooth_ratios`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LimitValues {
    /// The objective whether the limits pass or not (+∞, written `"inf"`: collapsed).
    #[serde(with = "objective_value")]
    pub objective: f64,
    /// demand / limit of each criterion at each case, in the check's order (counts of
    /// unacceptable responses left out: they are steps, not smooth functions); ≤ 1
    /// passes.
    pub ratios: Vec<f64>,
    /// Their derivatives, where the evaluation computed them (the `sqp` refiner's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gradient: Option<Gradient>,
}

impl LimitValues {
    /// The objective and the ratios, without derivatives.
    pub fn new(objective: f64, ratios: Vec<f64>) -> LimitValues {
        LimitValues {
            objective,
            ratios,
            gradient: None,
        }
    }
}

/// The derivatives of a design's objective and limit ratios with respect to the scaled
/// variables z, from the sensitivities of its runs (`phases::gradient`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Gradient {
    /// The objective of each property case the objective reads (the nominal case alone,
    /// or every case when it reads the worst: the objective is their largest), each with
    /// the design's cost.
    pub cases: Vec<f64>,
    /// ∂/∂z of each case's objective.
    pub case_grads: Vec<Vec<f64>>,
    /// ∂/∂z of each of [`LimitValues::ratios`].
    pub ratio_grads: Vec<Vec<f64>>,
}

/// An objective value in a journal: a JSON number, or `"inf"` for +∞ (a collapsed
/// design), which JSON numbers cannot hold.
mod objective_value {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        if *v == f64::INFINITY {
            s.serialize_str("inf")
        } else {
            s.serialize_f64(*v)
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Num(f64),
            Text(String),
        }
        match Raw::deserialize(d)? {
            Raw::Num(v) => Ok(v),
            Raw::Text(t) if t == "inf" => Ok(f64::INFINITY),
            Raw::Text(t) => Err(serde::de::Error::custom(format!(
                "objective {t:?}: expected a number or \"inf\""
            ))),
        }
    }
}

/// The batch objective: objective values of several scaled points.
pub type Oracle<'a> = dyn FnMut(&[Vec<f64>]) -> Result<Vec<f64>, OptError> + 'a;

/// The batch objective of a study with limits: each point's value and its limit values.
pub type LimitOracle<'a> =
    dyn FnMut(&[Vec<f64>]) -> Result<Vec<(f64, Option<LimitValues>)>, OptError> + 'a;

/// Called with each newly computed point.
pub type Hook<'a> = dyn FnMut(&Point) -> Result<(), OptError> + 'a;

/// Every evaluation so far, with a cache keyed by the exact bits of z.
pub struct Evaluations<'a> {
    oracle: Box<LimitOracle<'a>>,
    cache: HashMap<Vec<u64>, (f64, Option<LimitValues>)>,
    /// Values from an earlier, interrupted run: counted as new evaluations when asked
    /// for (so the refiners take the same path) but not computed again.
    replay: HashMap<Vec<u64>, (f64, Option<LimitValues>)>,
    /// Called with every point the oracle computed (journal append).
    hook: Option<Box<Hook<'a>>>,
    /// Evaluations taken from the replay.
    pub replayed: usize,
    /// Points known before refining (not counted).
    pub known: Vec<Point>,
    /// New evaluations, in order.
    pub log: Vec<Point>,
    /// Most new evaluations in all (set by the executor, [`super::run`]): a batch that
    /// would pass it evaluates the points that fit and answers
    /// [`OptError::BudgetSpent`].
    limit: Option<usize>,
    /// A known point without derivatives is evaluated again when asked for (set by a
    /// refiner that reads them, [`Evaluations::require_gradients`]).
    gradients: bool,
}

fn key(z: &[f64]) -> Vec<u64> {
    z.iter().map(|v| v.to_bits()).collect()
}

impl<'a> Evaluations<'a> {
    /// Starts with points already evaluated (the sweep's).
    pub fn new(mut oracle: Box<Oracle<'a>>, known: Vec<Point>) -> Self {
        Self::with_limits(
            Box::new(move |zs: &[Vec<f64>]| {
                Ok(oracle(zs)?.into_iter().map(|f| (f, None)).collect())
            }),
            known,
        )
    }

    /// Starts with points already evaluated (the sweep's), for an oracle that gives the
    /// limit values of each point beside its value.
    pub fn with_limits(oracle: Box<LimitOracle<'a>>, known: Vec<Point>) -> Self {
        let cache = known
            .iter()
            .map(|p| (key(&p.z), (p.f, p.limits.clone())))
            .collect();
        Evaluations {
            oracle,
            cache,
            replay: HashMap::new(),
            hook: None,
            replayed: 0,
            known,
            log: Vec::new(),
            limit: None,
            gradients: false,
        }
    }

    /// Points evaluated by an earlier run of the same refinement (its journal), and a
    /// hook called with every point computed from now on.
    pub fn with_journal(mut self, replay: Vec<Point>, hook: Box<Hook<'a>>) -> Self {
        self.replay = replay
            .into_iter()
            .map(|p| (key(&p.z), (p.f, p.limits)))
            .collect();
        self.hook = Some(hook);
        self
    }

    /// From now on a point known without derivatives (a sweep point) is evaluated again
    /// when asked for, by the oracle that gives them: the `sqp` refiner reads them.
    pub fn require_gradients(&mut self) {
        self.gradients = true;
    }

    /// From now on a known point serves as it is, derivatives or not (the post-check of
    /// the `sqp` refiner reads values alone); the caller's oracle stops computing them.
    pub fn release_gradients(&mut self) {
        self.gradients = false;
    }

    /// Whether `z` is known, with derivatives when they are required.
    fn knows(&self, z: &[f64]) -> bool {
        match self.cache.get(&key(z)) {
            None => false,
            Some((f, limits)) => {
                !self.gradients
                    || !f.is_finite() && limits.as_ref().is_none_or(|l| !l.objective.is_finite())
                    || limits.as_ref().is_some_and(|l| l.gradient.is_some())
            }
        }
    }

    /// Sets the most new evaluations in all (`None`: no limit).
    pub fn set_limit(&mut self, limit: Option<usize>) {
        self.limit = limit;
    }

    /// Objective at each point; only points never seen are evaluated (in one batch).
    /// Past the limit ([`Evaluations::set_limit`]) only the first points that fit are
    /// evaluated and the answer is [`OptError::BudgetSpent`].
    pub fn eval(&mut self, zs: &[Vec<f64>]) -> Result<Vec<f64>, OptError> {
        let mut fresh: Vec<Vec<f64>> = Vec::new();
        for z in zs {
            if !self.knows(z) && !fresh.contains(z) {
                fresh.push(z.clone());
            }
        }
        let over = self.limit.filter(|&l| self.log.len() + fresh.len() > l);
        if let Some(l) = over {
            fresh.truncate(l.saturating_sub(self.log.len()));
            self.compute(fresh)?;
            return Err(OptError::BudgetSpent { budget: l });
        }
        self.compute(fresh)?;
        Ok(zs
            .iter()
            .map(|z| self.cache.get(&key(z)).expect("evaluated above").0)
            .collect())
    }

    /// Evaluates `fresh` (points never seen), in one batch, taking replayed values.
    fn compute(&mut self, fresh: Vec<Vec<f64>>) -> Result<(), OptError> {
        if !fresh.is_empty() {
            let compute: Vec<Vec<f64>> = fresh
                .iter()
                .filter(|z| !self.replay.contains_key(&key(z)))
                .cloned()
                .collect();
            let mut computed = if compute.is_empty() {
                Vec::new()
            } else {
                (self.oracle)(&compute)?
            }
            .into_iter();
            for z in fresh {
                let (f, limits) = match self.replay.get(&key(&z)) {
                    Some(v) => {
                        self.replayed += 1;
                        v.clone()
                    }
                    None => {
                        let (f, limits) = computed.next().expect("one value per computed point");
                        if let Some(h) = self.hook.as_mut() {
                            h(&Point {
                                z: z.clone(),
                                f,
                                limits: limits.clone(),
                            })?;
                        }
                        (f, limits)
                    }
                };
                self.cache.insert(key(&z), (f, limits.clone()));
                self.log.push(Point { z, f, limits });
            }
        }
        Ok(())
    }

    /// Points evaluated by another [`Evaluations`] of the same objective (a start run side
    /// by side), joined in their order: counted as new evaluations and known from now on,
    /// not computed again (the journal's hook saw them where they were computed).
    /// `replayed`: how many of them that one took from the journal.
    pub fn absorb(&mut self, points: Vec<Point>, replayed: usize) {
        self.replayed += replayed;
        for p in points {
            self.cache.insert(key(&p.z), (p.f, p.limits.clone()));
            self.log.push(p);
        }
    }

    /// Objective at one point.
    pub fn eval_one(&mut self, z: &[f64]) -> Result<f64, OptError> {
        Ok(self.eval(&[z.to_vec()])?[0])
    }

    /// The objective at `z` when it is known (evaluated, or known before refining).
    pub fn cached(&self, z: &[f64]) -> Option<f64> {
        self.cache.get(&key(z)).map(|v| v.0)
    }

    /// The point at `z` with its limit values, when it is known.
    pub fn point(&self, z: &[f64]) -> Option<Point> {
        self.cache.get(&key(z)).map(|(f, limits)| Point {
            z: z.to_vec(),
            f: *f,
            limits: limits.clone(),
        })
    }

    /// Number of new evaluations.
    pub fn count(&self) -> usize {
        self.log.len()
    }

    /// Every point seen (known, then new).
    pub fn all(&self) -> impl Iterator<Item = &Point> {
        self.known.iter().chain(self.log.iter())
    }

    /// The best point seen (first of equals).
    pub fn best(&self) -> Option<Point> {
        let mut best: Option<&Point> = None;
        for p in self.all() {
            if best.is_none_or(|b| p.f < b.f) {
                best = Some(p);
            }
        }
        best.cloned()
    }
}

/// The ∞-norm distance between two scaled points.
pub(crate) fn dist_inf(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The step s = (z − c)/Δ that minimises the model gᵀs + ½sᵀHs (H positive
/// semidefinite) over the box [0, 1]^d, the space's constraints, the rows `cuts`
/// (aᵀs ≤ b, in s: the linearised limits of the model refiner) and ‖s‖∞ ≤ 1, around `c`
/// at radius `delta`: a convex QP solved by clarabel. `None` when clarabel cannot solve
/// it (a numerically hard model).
pub(crate) fn trust_step(
    space: &DesignSpace,
    c: &[f64],
    delta: f64,
    h: &nalgebra::DMatrix<f64>,
    g: &[f64],
    cuts: &[(Vec<f64>, f64)],
) -> Option<Vec<f64>> {
    let d = c.len();
    let lo: Vec<f64> = c.iter().map(|z| (-1.0f64).max(-z / delta)).collect();
    let hi: Vec<f64> = c.iter().map(|z| 1.0f64.min((1.0 - z) / delta)).collect();
    let rows = space.a.nrows();
    let a = nalgebra::DMatrix::from_fn(rows + cuts.len(), d, |i, j| {
        if i < rows {
            space.a[(i, j)] * delta
        } else {
            cuts[i - rows].0[j]
        }
    });
    let b: Vec<f64> = (0..rows)
        .map(|i| space.b[i] - (0..d).map(|j| space.a[(i, j)] * c[j]).sum::<f64>())
        .chain(cuts.iter().map(|(_, b)| *b))
        .collect();
    crate::base::qp::solve(h, g, &lo, &hi, &a, &b).ok()
}

/// z clamped into [0, 1]^d.
pub(crate) fn clamp01(z: &mut [f64]) {
    for v in z {
        *v = v.clamp(0.0, 1.0);
    }
}

/// Where a search along the building's storey-shear profile α·profile starts, for a start
/// whose slip loads are `own`: α₀ at the start's total slip load, or (a start without
/// slip load, which has no direction) half the largest α the box holds; `None` when the
/// start already has the profile's shape (cosine above 0.999) or the profile is empty.
pub(crate) fn profile_start(space: &DesignSpace, own: &[f64]) -> Option<f64> {
    let profile = &space.profile;
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let dot: f64 = own.iter().zip(profile).map(|(a, b)| a * b).sum();
    let cos = dot / (norm(own) * norm(profile));
    let psum: f64 = profile.iter().sum();
    if psum.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) || cos > 0.999 {
        return None;
    }
    let total: f64 = own.iter().sum();
    let alpha0 = if total > 0.0 {
        total / psum
    } else {
        let upper = space.slip_loads(&vec![1.0; space.dim()]);
        0.5 * profile
            .iter()
            .zip(&upper)
            .filter(|(p, _)| **p > 0.0)
            .map(|(p, u)| u / p)
            .fold(f64::INFINITY, f64::min)
    };
    (alpha0 > 0.0 && alpha0.is_finite()).then_some(alpha0)
}
