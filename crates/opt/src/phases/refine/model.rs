//! The model refiner: a search along slip-load profiles, then a trust region on a
//! least-change quadratic interpolation model — the refiner for ten to forty slip loads.
//!
//! **Profiles first.** Slip-load optima lie in a narrow valley: scaling every slip load
//! by a few per cent moves the objective little, moving one floor against the others
//! moves it a lot. So the refiner first searches the two coordinates that move the
//! objective most and that an engineer knows before any study: the overall scale of the
//! start's own profile, and the scale of the storey-shear profile of the building
//! ([`DesignSpace::profile`], the shear of a triangular load pattern, the code's
//! equivalent-lateral-force shape). Each is a one-dimensional search along the ray
//! α·profile in slip loads: three points a factor 1.4 apart, moved outward until the
//! middle one is the best, then the vertex of the parabola through the best three in
//! log α (at most [`LINE_EVALUATIONS`] evaluations a ray).
//!
//! **Then every floor.** From the best point of those searches, a derivative-free trust
//! region in the scaled variables (after Powell's NEWUOA and BOBYQA, Powell 2006 and
//! 2009): the model q(s) = f_c + gᵀs + ½sᵀHs interpolates up to 2d + 1 points (the
//! centre and c ± Δeᵢ at first, Δ a third of the study's `initial_radius`) and, where those points do not determine H, takes the H
//! of least change ‖H − H_old‖_F from the previous model (the KKT system of the least
//! Frobenius norm update, solved in the coordinates s = (z − c)/Δ). So each iteration
//! costs one evaluation once the first 2d are made, and the model learns the valley's
//! curvature from every point it sees. The step minimises the model (its Hessian clipped
//! to positive semidefinite) over the box, the study's linear constraints and the trust
//! box ‖s‖∞ ≤ Δ: a convex QP solved by clarabel. A new point replaces the point of the set
//! farthest from the centre. The radius doubles after a step that achieved at least 0.7
//! of the predicted decrease at the region's edge and halves after one below 0.1 whose
//! points are all near the centre; when far points made the model poor, the farthest is
//! first replaced by a point at the radius (a geometry step). A design that fails the
//! limits or collapses (+∞) is no sample of the model: it is a rejected step.
//!
//! **Polls where the model misleads.** The first interpolation set is a poll: the 2d
//! single-floor moves ±Δ around the centre, one batch, followed by the design that takes
//! every move that gained, whole and half way. A slip-load objective has kinks (a peak
//! over storeys and records, the worst of the property cases: one floor too low drifts
//! and governs, one floor higher changes little), and there the interpolation model's
//! steps fail while single-floor moves and their combination still gain. So when the
//! last poll lowered the objective by more than [`POLL_GAIN`], faster per evaluation than
//! the model steps since, a second failed model step in a row is followed by another
//! poll at that poll's radius instead of a second shrink; such a poll also tries the step
//! of the separable quadratic through each floor's two moves (implicit filtering's
//! difference gradient at the scale Δ, Kelley 2011), whole and half way. On a smooth
//! valley the model's steps win and no second poll is made (the analytic valleys of
//! `tests/refiner_model.rs` take the same path to the bit).
//!
//! **Limits as constraints.** In a study with limits every evaluation carries, beside
//! the value the refiners minimise (+∞ for a design that misses a limit), the objective
//! itself and the ratio demand/limit of each criterion at each property case
//! ([`super::LimitValues`]). A design that misses a limit is then no lost evaluation:
//! its objective and ratios join the interpolation set. Each ratio gets a least-norm
//! quadratic model from the same interpolation system as the objective, and every ratio
//! whose linear model can reach 1 inside the trust box enters the step's QP as the row
//! r(c) + gᵀs ≤ 1 − [`LIMIT_MARGIN`] (one that cannot reach it is left out, so a study
//! whose limits are far from binding steps exactly as without them); the most binding
//! one adds its curvature times its least-squares multiplier to the model's Hessian
//! (the Lagrangian of an SQP step). The centre always meets the limits, so s = 0 is
//! feasible and every step a decrease of a passing design. A step that misses a limit is
//! followed back along itself to where the ratios, linear between the centre and the
//! trial, reach the margin (one evaluation); a decrease that passes there keeps the
//! radius, so a rough limit (a residual drift) does not shrink the region to the
//! tolerance by itself. A line search whose best
//! point has a neighbour that misses a limit at a lower objective walks to the limit
//! (the secant of log ratio in log α, up to [`LIMIT_EVALUATIONS`] more points): the
//! least dampers that meet the limits (`objective.cost`) lie where a limit binds.
//!
//! **Counted.** Every evaluation goes through [`Evaluations`] and no batch is larger than
//! the budget left, so the refiner never exceeds it. It stops when the radius falls below
//! the tolerance ([`StopReason::Tolerance`]), the budget is spent
//! ([`StopReason::Budget`]), or no model can be built (too few finite points,
//! [`StopReason::NoProgress`]).

use super::evaluations::{
    Evaluations, Point, Refiner, STATIONARY_GAIN, StopReason, clamp01, dist_inf, profile_start,
    trust_step,
};
use crate::base::error::OptError;
use crate::base::qp;
use crate::model::config::RefineConfig;
use crate::model::space::DesignSpace;
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

/// Most evaluations of one profile's line search.
pub const LINE_EVALUATIONS: usize = 6;

/// Evaluations a line search may add to walk to a limit ([`ModelSearch::walk_to_limit`]).
pub const LIMIT_EVALUATIONS: usize = 3;

/// Ratio between neighbouring points of a line search (1.4: a bracket of ±40 %).
const LINE_FACTOR: f64 = 1.4;

/// The model's first radius as a fraction of the study's `initial_radius` (on the
/// ten-storey check example from a uniform start: 0.006344 after 46 evaluations with a
/// third, 0.006356 with the whole radius, whose first ±450 kN probes of single floors
/// cost up to 50 % more than the centre).
const MODEL_RADIUS_FRACTION: f64 = 1.0 / 3.0;

/// Largest trust radius, scaled variables.
const MAX_RADIUS: f64 = 0.5;

/// Least decrease of a poll, as a fraction of the objective, for polls to go on
/// ([`ModelSearch::poll_gained`]): the post-check's threshold of a stationary design
/// ([`STATIONARY_GAIN`]).
const POLL_GAIN: f64 = STATIONARY_GAIN;

/// How far inside its limits the refiner aims a design it moves toward them: a ratio of
/// 1 − 0.1 % (the linearised limits are first-order; a step aimed at exactly 1 lands
/// outside as often as inside).
pub const LIMIT_MARGIN: f64 = 1e-3;

/// The model refiner's state (see the module doc); plain data, so a refinement can be
/// saved between iterations and continued.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelSearch {
    /// Centre: the best point so far.
    pub centre: Point,
    /// Trust radius Δ, scaled variables (∞-norm).
    pub radius: f64,
    /// Stop when Δ falls below this.
    pub tolerance: f64,
    /// Most new evaluations in total, counted over the whole [`Evaluations`].
    pub budget: usize,
    /// The interpolation set (finite values; the centre among them).
    pub points: Vec<Point>,
    /// The model's Hessian in the scaled variables z, row by row (d × d): the memory of
    /// the least-change update.
    pub hessian: Vec<f64>,
    /// Why it stopped, once it has.
    pub stop: Option<StopReason>,
    /// Model steps failed in a row since the centre last moved.
    #[serde(default)]
    pub failures: usize,
    /// The last poll that lowered the objective by more than 0.1 % of it (`POLL_GAIN`): its
    /// radius and its decrease per evaluation (`None`: it did not, or no poll yet).
    /// While polls gain faster than the model steps made since, a second failed model
    /// step in a row is followed by a poll at that radius, not by a second shrink.
    #[serde(default)]
    pub poll_gained: Option<(f64, f64)>,
    /// The decrease the model steps made since the last poll, and their evaluations.
    #[serde(default)]
    pub model_gain: (f64, usize),
    /// Polls made.
    #[serde(default)]
    pub polls: usize,
}

impl ModelSearch {
    /// A refiner with the study's settings and `budget` (counted over the whole
    /// [`Evaluations`]).
    pub fn new(cfg: &RefineConfig, budget: usize) -> Self {
        ModelSearch {
            centre: Point::new(Vec::new(), f64::INFINITY),
            radius: cfg.initial_radius,
            tolerance: cfg.tolerance,
            budget,
            points: Vec::new(),
            hessian: Vec::new(),
            stop: None,
            failures: 0,
            poll_gained: None,
            model_gain: (0.0, 0),
            polls: 0,
        }
    }

    fn room(&self, ev: &Evaluations<'_>) -> usize {
        self.budget.saturating_sub(ev.count())
    }

    /// The evaluated points of `zs` (with their limit values), the ones the budget has no
    /// room for left out (`None`); a point off the space's constraints is +∞ without a
    /// simulation.
    fn values(
        &self,
        space: &DesignSpace,
        ev: &mut Evaluations<'_>,
        zs: &[Vec<f64>],
    ) -> Result<Vec<Option<Point>>, OptError> {
        let mut room = self.room(ev);
        let mut ask: Vec<Vec<f64>> = Vec::new();
        let mut out = vec![None; zs.len()];
        for (i, z) in zs.iter().enumerate() {
            if !space.is_feasible(z) {
                out[i] = Some(Point::new(z.clone(), f64::INFINITY));
            } else if let Some(p) = ev.point(z) {
                out[i] = Some(p);
            } else if ask.contains(z) {
                // asked already in this batch: filled below
            } else if room > 0 {
                ask.push(z.clone());
                room -= 1;
            }
        }
        ev.eval(&ask)?;
        for (i, z) in zs.iter().enumerate() {
            if out[i].is_none() {
                out[i] = ev.point(z);
            }
        }
        Ok(out)
    }

    /// The scaled point of slip loads `loads`, clamped into the box (least squares on the
    /// space's basis: exact for a free space).
    pub(super) fn z_of(space: &DesignSpace, loads: &[f64]) -> Option<Vec<f64>> {
        let mut z = space.least_squares_point(loads)?;
        if z.iter().any(|v| !v.is_finite()) {
            return None;
        }
        clamp01(&mut z);
        Some(z)
    }

    /// Searches the ray α·`profile` (slip loads, N) from α₀ (see the module doc); the
    /// best point found becomes the centre when it is better.
    fn line_search(
        &mut self,
        space: &DesignSpace,
        ev: &mut Evaluations<'_>,
        profile: &[f64],
        alpha0: f64,
    ) -> Result<(), OptError> {
        if !(alpha0 > 0.0 && alpha0.is_finite()) || profile.iter().all(|v| *v <= 0.0) {
            return Ok(());
        }
        let at = |a: f64| Self::z_of(space, &profile.iter().map(|p| a * p).collect::<Vec<_>>());
        let start = ev.count();
        // every point tried, by log α
        let mut tried: Vec<Tried> = Vec::new();
        let probe = |me: &mut Self,
                     ev: &mut Evaluations<'_>,
                     tried: &mut Vec<Tried>,
                     la: f64,
                     cap: usize|
         -> Result<Option<f64>, OptError> {
            if let Some(t) = tried.iter().find(|t| (t.la - la).abs() < 1e-12) {
                return Ok(Some(t.f));
            }
            if ev.count() - start >= cap {
                return Ok(None);
            }
            let Some(z) = at(la.exp()) else {
                return Ok(None);
            };
            let Some(p) = me.values(space, ev, std::slice::from_ref(&z))?.remove(0) else {
                return Ok(None);
            };
            let f = p.f;
            tried.push(Tried {
                la,
                f,
                raw: p.objective(),
                governing: governing_ratio(&p),
            });
            if f < me.centre.f {
                me.centre = p;
            }
            Ok(Some(f))
        };
        let step = LINE_FACTOR.ln();
        let l0 = alpha0.ln();
        for la in [l0 - step, l0, l0 + step] {
            if probe(self, ev, &mut tried, la, LINE_EVALUATIONS)?.is_none() {
                return Ok(());
            }
        }
        // move the bracket outward until its middle point is the best
        loop {
            tried.sort_by(|a, b| a.la.total_cmp(&b.la));
            let best = (0..tried.len())
                .min_by(|&a, &b| tried[a].f.total_cmp(&tried[b].f))
                .expect("three points tried");
            if best > 0 && best + 1 < tried.len() {
                let (a, b, c) = (&tried[best - 1], &tried[best], &tried[best + 1]);
                // a neighbour that misses a limit with a lower objective: the best point
                // of the ray lies at the limit
                let missed = [a, c]
                    .into_iter()
                    .find(|t| t.f == f64::INFINITY && t.governing.is_some() && t.raw < b.f);
                if let (Some(m), Some(gb)) = (missed, b.governing) {
                    let (fail, pass) = ((m.la, m.governing.expect("found above")), (b.la, gb));
                    return self.walk_to_limit(ev, fail, pass, &mut tried, &probe);
                }
                // (the objective whether the limits pass or not: smooth across them)
                if let Some(v) = parabola_vertex((a.la, a.raw), (b.la, b.raw), (c.la, c.raw)) {
                    probe(self, ev, &mut tried, v, LINE_EVALUATIONS)?;
                }
                return Ok(());
            }
            let next = if best == 0 {
                tried[0].la - 2.0 * step
            } else {
                tried[tried.len() - 1].la + 2.0 * step
            };
            // past the box the clamped points repeat: nothing more to learn
            let (edge, beyond) = (at(tried[best].la.exp()), at(next.exp()));
            if edge == beyond || probe(self, ev, &mut tried, next, LINE_EVALUATIONS)?.is_none() {
                return Ok(());
            }
        }
    }

    /// Walks the ray from a point that passes the limits toward a neighbour that misses
    /// one, to where the governing ratio reaches 1 − [`LIMIT_MARGIN`]: the secant of
    /// log ratio against log α (a drift falls about as a power of the slip loads), kept a
    /// tenth of the bracket inside it, until the bracket is within 1 % in α or the
    /// ray's evaluations and [`LIMIT_EVALUATIONS`] more are spent. `fail`, `pass`:
    /// (log α, governing ratio).
    fn walk_to_limit<P>(
        &mut self,
        ev: &mut Evaluations<'_>,
        mut fail: (f64, f64),
        mut pass: (f64, f64),
        tried: &mut Vec<Tried>,
        probe: &P,
    ) -> Result<(), OptError>
    where
        P: Fn(
            &mut Self,
            &mut Evaluations<'_>,
            &mut Vec<Tried>,
            f64,
            usize,
        ) -> Result<Option<f64>, OptError>,
    {
        let target = (1.0 - LIMIT_MARGIN).ln();
        while (fail.0 - pass.0).abs() > 1.01f64.ln() {
            let t = if fail.1 > 0.0 && pass.1 > 0.0 {
                let (df, dp) = (fail.1.ln() - target, pass.1.ln() - target);
                if df > dp && dp <= 0.0 {
                    (-dp / (df - dp)).clamp(0.1, 0.9)
                } else {
                    0.5
                }
            } else {
                0.5
            };
            let la = pass.0 + t * (fail.0 - pass.0);
            if probe(self, ev, tried, la, LINE_EVALUATIONS + LIMIT_EVALUATIONS)?.is_none() {
                break;
            }
            let Some(now) = tried.iter().find(|x| (x.la - la).abs() < 1e-12) else {
                break;
            };
            match (now.f.is_finite(), now.governing) {
                (true, Some(g)) => pass = (la, g),
                (false, Some(g)) => fail = (la, g),
                _ => break,
            }
        }
        Ok(())
    }

    /// Polls the centre: evaluates c ± Δeᵢ (c − Δ and c − 2Δ, or c + Δ and c + 2Δ, where
    /// the box has room on one side only), one batch, then the designs the poll points
    /// to ([`poll_candidates`]), a second batch. The first poll makes the first
    /// interpolation set; a later one joins the set (its farthest points leave).
    fn poll(
        &mut self,
        space: &DesignSpace,
        ev: &mut Evaluations<'_>,
        first: bool,
    ) -> Result<(), OptError> {
        let d = space.dim();
        let centre = self.centre.clone();
        let c = &centre.z;
        let delta = self.radius;
        // one point per coordinate first, then the second: with a budget for d of them
        // only, the model is linear
        let (mut moves, mut second) = (Vec::with_capacity(2 * d), Vec::with_capacity(d));
        for i in 0..d {
            let (a, b) = if c[i] + delta <= 1.0 && c[i] - delta >= 0.0 {
                (delta, -delta)
            } else if c[i] + delta > 1.0 {
                (-delta, -2.0 * delta)
            } else {
                (delta, 2.0 * delta)
            };
            for (s, list) in [(a, &mut moves), (b, &mut second)] {
                let mut z = c.clone();
                z[i] = (z[i] + s).clamp(0.0, 1.0);
                if z != *c {
                    list.push((i, z));
                }
            }
        }
        moves.extend(second);
        let zs: Vec<Vec<f64>> = moves.iter().map(|(_, z)| z.clone()).collect();
        let before = ev.count();
        let values = self.values(space, ev, &zs)?;
        if first {
            self.points = vec![centre.clone()];
        }
        let mut polled = Vec::with_capacity(moves.len());
        for ((i, z), p) in moves.into_iter().zip(values) {
            if let Some(p) = p {
                polled.push((i, z[i] - c[i], p.clone()));
                self.admit(p);
            }
        }
        let candidates = poll_candidates(&centre, &polled, delta, !first);
        for p in self.values(space, ev, &candidates)?.into_iter().flatten() {
            self.admit(p);
        }
        let (gain, evals) = (centre.f - self.centre.f, ev.count() - before);
        self.poll_gained =
            (gain > POLL_GAIN * centre.f.abs() && evals > 0).then(|| (delta, gain / evals as f64));
        self.model_gain = (0.0, 0);
        self.polls += 1;
        Ok(())
    }

    /// Takes a new point: a better one becomes the centre; one with a finite objective
    /// joins the set (a design that misses a limit too: its objective and ratios are
    /// samples of the models; the set's farthest point from the centre leaves when it
    /// holds 2d + 1).
    fn admit(&mut self, p: Point) {
        if p.f < self.centre.f {
            self.centre = p.clone();
            self.failures = 0;
        }
        if !p.objective().is_finite() || self.points.iter().any(|q| q.z == p.z) {
            return;
        }
        self.points.push(p);
        let cap = 2 * self.centre.z.len() + 1;
        while self.points.len() > cap {
            let c = &self.centre.z;
            let far = (0..self.points.len())
                .filter(|&k| self.points[k].z != *c)
                .max_by(|&a, &b| {
                    dist_inf(&self.points[a].z, c).total_cmp(&dist_inf(&self.points[b].z, c))
                })
                .expect("more points than the centre");
            self.points.remove(far);
        }
    }

    /// The least-change model at the centre in s = (z − c)/Δ (gradient, Hessian in s, and
    /// the value scale it was fitted at) and, where every point of the set carries the
    /// limits' ratios, a least-norm model of each ratio. `None` when the set does not
    /// determine a gradient (fewer than d + 1 points) or the solve fails.
    fn model(&self, d: usize) -> Option<Fit> {
        let c = &self.centre;
        let delta = self.radius;
        let m = self.points.len();
        if m < d + 1 {
            return None;
        }
        let s: Vec<DVector<f64>> = self
            .points
            .iter()
            .map(|p| DVector::from_iterator(d, p.z.iter().zip(&c.z).map(|(z, c)| (z - c) / delta)))
            .collect();
        let h0 = DMatrix::from_row_slice(d, d, &self.hessian) * (delta * delta);
        let fc = c.objective();
        let scale = match self
            .points
            .iter()
            .map(|p| (p.objective() - fc).abs())
            .fold(0.0, f64::max)
        {
            v if v > 0.0 && v.is_finite() => v,
            _ => 1.0,
        };
        let n = m + d + 1;
        let mut w = DMatrix::zeros(n, n);
        let mut rhs = DVector::zeros(n);
        for k in 0..m {
            for j in 0..m {
                w[(k, j)] = 0.5 * s[k].dot(&s[j]).powi(2);
            }
            w[(k, m)] = 1.0;
            w[(m, k)] = 1.0;
            for i in 0..d {
                w[(k, m + 1 + i)] = s[k][i];
                w[(m + 1 + i, k)] = s[k][i];
            }
            rhs[k] =
                (self.points[k].objective() - fc) / scale - 0.5 * s[k].dot(&(&h0 / scale * &s[k]));
        }
        let svd = w.svd(true, true);
        // the quadratic of the multipliers x: gradient and Hessian (in s) added to `h0`
        let quadratic = |x: &DVector<f64>, h0: DMatrix<f64>| {
            let g = DVector::from_iterator(d, (0..d).map(|i| x[m + 1 + i]));
            let mut h = h0;
            for k in 0..m {
                h += &s[k] * s[k].transpose() * x[k];
            }
            (g, h)
        };
        let x = svd.solve(&rhs, 1e-12).ok()?;
        let (g, h) = quadratic(&x, &h0 / scale);
        if g.iter().chain(h.iter()).any(|v| !v.is_finite()) {
            return None;
        }
        // the limits: every ratio of every point, least-norm (no memory), same system
        let ratios = |p: &Point| p.limits.as_ref().map(|l| l.ratios.clone());
        let rc = ratios(c).filter(|r| !r.is_empty());
        let mut limits = Vec::new();
        if let Some(rc) = rc
            && self
                .points
                .iter()
                .all(|p| ratios(p).is_some_and(|r| r.len() == rc.len()))
        {
            for (j, &r0) in rc.iter().enumerate() {
                let mut rhs = DVector::zeros(n);
                for k in 0..m {
                    rhs[k] = self.points[k]
                        .limits
                        .as_ref()
                        .expect("checked above")
                        .ratios[j]
                        - r0;
                }
                let Ok(x) = svd.solve(&rhs, 1e-12) else {
                    continue;
                };
                let (gj, hj) = quadratic(&x, DMatrix::zeros(d, d));
                if r0.is_finite() && gj.iter().chain(hj.iter()).all(|v| v.is_finite()) {
                    limits.push(LimitModel {
                        at: r0,
                        g: gj,
                        h: hj,
                    });
                }
            }
        }
        Some(Fit {
            g,
            h,
            scale,
            limits,
        })
    }

    /// The linearised limits that can bind inside the trust box (a ratio whose linear
    /// model reaches 1 − [`LIMIT_MARGIN`] somewhere in it), as rows gᵀs ≤ 1 − margin − r(c),
    /// and the curvature they add to the step's model: the Hessian of the most binding
    /// one times its multiplier, estimated by least squares from g_f + λ g_r = 0 (the
    /// Lagrangian's curvature of an SQP step).
    fn binding_limits(fit: &Fit) -> (Vec<Cut>, Option<DMatrix<f64>>) {
        let target = 1.0 - LIMIT_MARGIN;
        let mut cuts = Vec::new();
        let mut most: Option<(&LimitModel, f64)> = None;
        for l in &fit.limits {
            let reach = l.at + l.g.iter().map(|v| v.abs()).sum::<f64>();
            if reach <= target {
                continue;
            }
            // (a centre past the target already, by round-off or the margin: no step may
            // raise the ratio further)
            cuts.push((l.g.as_slice().to_vec(), (target - l.at).max(0.0)));
            if most.is_none_or(|(_, r)| l.at > r) {
                most = Some((l, l.at));
            }
        }
        let curvature = most.and_then(|(l, _)| {
            let gg = l.g.dot(&l.g);
            let lambda = -fit.g.dot(&l.g) / gg;
            (gg > 0.0 && lambda > 0.0 && lambda.is_finite()).then(|| &l.h * lambda)
        });
        (cuts, curvature)
    }

    /// One model step (see the module doc).
    fn model_step(
        &mut self,
        space: &DesignSpace,
        ev: &mut Evaluations<'_>,
    ) -> Result<(), OptError> {
        let d = space.dim();
        let delta = self.radius;
        let Some(fit) = self.model(d) else {
            self.stop = Some(StopReason::NoProgress);
            return Ok(());
        };
        let (g, h, scale) = (&fit.g, &fit.h, fit.scale);
        // the least-change memory, back in z
        self.hessian = (h * (scale / (delta * delta))).as_slice().to_vec();
        // (nalgebra is column-major; H is symmetric, so rows = columns)
        let c = self.centre.clone();
        let (cuts, curvature) = Self::binding_limits(&fit);
        let hp = match curvature {
            Some(hl) => qp::clip_to_psd(&(h + hl), 0.0),
            None => qp::clip_to_psd(h, 0.0),
        };
        let step = trust_step(space, &c.z, delta, &hp, g.as_slice(), &cuts);
        let trial = step.and_then(|s| {
            let sv = DVector::from_column_slice(&s);
            let pred = -(g.dot(&sv) + 0.5 * sv.dot(&(h * &sv))) * scale;
            let mut z: Vec<f64> = c.z.iter().zip(&s).map(|(c, s)| c + delta * s).collect();
            clamp01(&mut z);
            let len = dist_inf(&z, &c.z);
            (pred > 1e-12 * c.f.abs().max(f64::MIN_POSITIVE)
                && len >= 1e-3 * delta
                && space.is_feasible(&z))
            .then_some((z, pred, len))
        });
        let far = self
            .points
            .iter()
            .map(|p| dist_inf(&p.z, &c.z))
            .fold(0.0, f64::max);
        let Some((z, pred, len)) = trial else {
            // the model predicts no decrease: poll (see `fail`), improve its geometry if
            // far points made it, else the region is too large
            if self.fail() {
                return self.poll(space, ev, false);
            }
            if far > 2.0 * delta {
                return self.geometry_step(space, ev);
            }
            self.shrink();
            return Ok(());
        };
        let Some(p) = self.values(space, ev, std::slice::from_ref(&z))?.remove(0) else {
            self.stop = Some(StopReason::Budget);
            return Ok(());
        };
        let rho = (c.f - p.f) / pred;
        let back = Self::back_to_limit(&c, &p);
        self.admit(p);
        // a step that missed a limit: back along it to where the limits' ratios, linear
        // between the centre and the trial, reach the margin; a decrease that passes
        // there keeps the radius
        if let Some(t) = back
            && self.room(ev) > 0
        {
            let mut zb: Vec<f64> = c.z.iter().zip(&z).map(|(c, z)| c + t * (z - c)).collect();
            clamp01(&mut zb);
            if space.is_feasible(&zb)
                && let Some(pb) = self.values(space, ev, std::slice::from_ref(&zb))?.remove(0)
            {
                let better = pb.f < c.f;
                self.admit(pb);
                if better {
                    return Ok(());
                }
            }
        }
        if rho >= 0.7 && len >= 0.9 * delta {
            self.radius = (2.0 * delta).min(MAX_RADIUS);
        } else if rho < 0.1 || rho.is_nan() {
            if self.centre.z == c.z && self.fail() {
                return self.poll(space, ev, false);
            }
            if far > 2.0 * delta {
                return self.geometry_step(space, ev);
            }
            self.shrink();
        }
        Ok(())
    }

    /// Where to go back along a step c → p that missed a limit (p stands: its objective
    /// is finite): the fraction t of the step at which the first ratio, linear between
    /// the centre and p, reaches 1 − [`LIMIT_MARGIN`], kept within [0.1, 0.9]. `None`
    /// when p met the limits, collapsed, or carries no ratios.
    pub(super) fn back_to_limit(c: &Point, p: &Point) -> Option<f64> {
        let (lc, lp) = (c.limits.as_ref()?, p.limits.as_ref()?);
        if p.f.is_finite() || !lp.objective.is_finite() || lc.ratios.len() != lp.ratios.len() {
            return None;
        }
        let target = 1.0 - LIMIT_MARGIN;
        let t = lc
            .ratios
            .iter()
            .zip(&lp.ratios)
            .filter(|(rc, rp)| **rp > target && rp > rc)
            .map(|(rc, rp)| (target - rc) / (rp - rc))
            .fold(f64::INFINITY, f64::min);
        t.is_finite().then(|| t.clamp(0.1, 0.9))
    }

    /// Replaces the set's farthest point by one at the radius along the coordinate the
    /// remaining points cover least (one evaluation).
    fn geometry_step(
        &mut self,
        space: &DesignSpace,
        ev: &mut Evaluations<'_>,
    ) -> Result<(), OptError> {
        let c = self.centre.z.clone();
        let d = c.len();
        let delta = self.radius;
        let far = (0..self.points.len())
            .filter(|&k| self.points[k].z != c)
            .max_by(|&a, &b| {
                dist_inf(&self.points[a].z, &c).total_cmp(&dist_inf(&self.points[b].z, &c))
            });
        if let Some(k) = far {
            self.points.remove(k);
        }
        // the coordinate whose largest displacement among the near points is least
        let cover = |i: usize| {
            self.points
                .iter()
                .map(|p| (p.z[i] - c[i]).abs())
                .fold(0.0, f64::max)
        };
        let i = (0..d)
            .min_by(|&a, &b| cover(a).total_cmp(&cover(b)))
            .unwrap_or(0);
        let mut z = c.clone();
        z[i] = if c[i] + delta <= 1.0 {
            c[i] + delta
        } else {
            c[i] - delta
        };
        clamp01(&mut z);
        match self.values(space, ev, std::slice::from_ref(&z))?.remove(0) {
            Some(p) => self.admit(p),
            None => self.stop = Some(StopReason::Budget),
        }
        Ok(())
    }

    /// Counts a failed model step; true when it is the second in a row at a centre while
    /// the last poll gained, and sets the radius back to that poll's for the next one.
    /// On a smooth objective a failed step means the region was too large (the model
    /// steps on after one shrink); on an objective with kinks (a peak over storeys and
    /// records, the worst of the property cases) the interpolation model misleads again
    /// and again where single-floor moves and their combination still gain.
    fn fail(&mut self) -> bool {
        self.failures += 1;
        let (gain, evals) = self.model_gain;
        let model_rate = if evals > 0 { gain / evals as f64 } else { 0.0 };
        match self.poll_gained {
            Some((r, rate)) if self.failures >= 2 && rate > model_rate => {
                self.radius = r;
                self.failures = 0;
                true
            }
            _ => false,
        }
    }

    fn shrink(&mut self) {
        self.radius *= 0.5;
        if self.radius < self.tolerance {
            self.stop = Some(StopReason::Tolerance);
        }
    }
}

/// A linear constraint aᵀs ≤ b of a trust step (a linearised limit).
type Cut = (Vec<f64>, f64);

/// The models of one fit ([`ModelSearch::model`]).
struct Fit {
    /// The objective's gradient in s, over `scale`.
    g: DVector<f64>,
    /// Its Hessian in s, over `scale`.
    h: DMatrix<f64>,
    /// The value scale of `g` and `h`.
    scale: f64,
    /// The limits' ratios.
    limits: Vec<LimitModel>,
}

/// The least-norm quadratic model of one limit ratio around the centre, in s.
struct LimitModel {
    /// The ratio at the centre.
    at: f64,
    /// Its gradient.
    g: DVector<f64>,
    /// Its Hessian.
    h: DMatrix<f64>,
}

/// A point of a line search.
#[derive(Debug, Clone, Copy)]
struct Tried {
    /// log α.
    la: f64,
    /// What the refiner minimises (+∞: missed a limit or collapsed).
    f: f64,
    /// The objective whether the limits pass or not ([`Point::objective`]).
    raw: f64,
    /// The largest of the limits' smooth ratios, where the point carries them.
    governing: Option<f64>,
}

/// The largest of a point's smooth limit ratios (`None`: it carries none).
fn governing_ratio(p: &Point) -> Option<f64> {
    p.limits
        .as_ref()
        .filter(|l| !l.ratios.is_empty())
        .map(|l| l.ratios.iter().copied().fold(f64::NEG_INFINITY, f64::max))
}

/// The designs a poll around `c` points to (`polled`: coordinate, move, point): the
/// step of the separable quadratic through each coordinate's two moves (its gradient
/// and curvature by differences, the curvature at least |g|/(2Δ), so no coordinate moves
/// more than 2Δ), and the design that takes every move that lowered what the refiner
/// minimises, each whole and half way. On an objective with kinks (a peak over storeys
/// and records, the worst of the property cases) one floor moved alone often climbs
/// where floors moved together descend, and the interpolation model of the whole set
/// misleads; these steps read only the poll around the present centre (implicit
/// filtering's difference gradient at the scale Δ, Kelley 2011, and a combined
/// coordinate move).
fn poll_candidates(
    c: &Point,
    polled: &[(usize, f64, Point)],
    delta: f64,
    separable: bool,
) -> Vec<Vec<f64>> {
    let d = c.z.len();
    let fc = c.objective();
    // each coordinate's moves: (offset, objective) — the objective whether the limits
    // pass or not, smooth across them
    let mut per: Vec<Vec<(f64, f64)>> = vec![Vec::new(); d];
    let mut gain = vec![(0.0, c.f); d];
    for (i, s, p) in polled {
        per[*i].push((*s, p.objective()));
        if p.f < gain[*i].1 {
            gain[*i] = (*s, p.f);
        }
    }
    let mut newton = vec![0.0; d];
    for (i, moves) in per.iter().enumerate() {
        let &[(a, fa), (b, fb)] = &moves[..] else {
            continue;
        };
        if !(fa.is_finite() && fb.is_finite() && fc.is_finite()) || a == b {
            continue;
        }
        // the parabola through (0, fc), (a, fa), (b, fb)
        let (da, db) = ((fa - fc) / a, (fb - fc) / b);
        let curvature = 2.0 * (da - db) / (a - b);
        let g = da - 0.5 * curvature * a;
        if g != 0.0 {
            newton[i] =
                (-g / curvature.max(g.abs() / (2.0 * delta))).clamp(-2.0 * delta, 2.0 * delta);
        }
    }
    let combined: Vec<f64> = gain.iter().map(|(s, _)| *s).collect();
    let mut out: Vec<Vec<f64>> = Vec::new();
    let gaining = combined.iter().filter(|s| **s != 0.0).count();
    // (one gaining move alone: the poll made it whole already, its half is new)
    for (step, useful) in [
        (&newton, separable && newton.iter().any(|s| *s != 0.0)),
        (&combined, gaining >= 1),
    ] {
        if !useful {
            continue;
        }
        for t in [1.0, 0.5] {
            let mut z: Vec<f64> = c.z.iter().zip(step).map(|(z, s)| z + t * s).collect();
            clamp01(&mut z);
            if z != c.z && !out.contains(&z) {
                out.push(z);
            }
        }
    }
    out
}

/// The vertex (in log α) of the parabola through three points of a bracket whose middle
/// point is the lowest; `None` when they are collinear.
fn parabola_vertex(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> Option<f64> {
    let (x1, f1) = a;
    let (x2, f2) = b;
    let (x3, f3) = c;
    let num = (x2 - x1).powi(2) * (f2 - f3) - (x2 - x3).powi(2) * (f2 - f1);
    let den = (x2 - x1) * (f2 - f3) - (x2 - x3) * (f2 - f1);
    if !(den.abs() > 0.0 && den.is_finite() && num.is_finite()) {
        return None;
    }
    let v = x2 - 0.5 * num / den;
    (v > x1 && v < x3).then_some(v)
}

impl Refiner for ModelSearch {
    fn init(
        &mut self,
        space: &DesignSpace,
        start: &Point,
        ev: &mut Evaluations<'_>,
    ) -> Result<(), OptError> {
        self.centre = start.clone();
        self.hessian = vec![0.0; space.dim() * space.dim()];
        // the start's own profile, then the building's storey-shear profile at the same
        // total slip load (or, from a start without slip load, at half the box)
        let own = space.slip_loads(&start.z);
        self.line_search(space, ev, &own, 1.0)?;
        if let Some(alpha0) = profile_start(space, &own) {
            let profile = space.profile.clone();
            self.line_search(space, ev, &profile, alpha0)?;
        }
        if self.room(ev) == 0 {
            self.stop = Some(StopReason::Budget);
            return Ok(());
        }
        // the profile searches placed the overall scale; one floor against the others is
        // the valley's steep side, so the model starts at a third of the initial radius
        self.radius *= MODEL_RADIUS_FRACTION;
        self.poll(space, ev, true)
    }

    fn next_iter(&mut self, space: &DesignSpace, ev: &mut Evaluations<'_>) -> Result<(), OptError> {
        if self.room(ev) == 0 {
            self.stop = Some(StopReason::Budget);
            return Ok(());
        }
        let (f, n, polls) = (self.centre.f, ev.count(), self.polls);
        self.model_step(space, ev)?;
        if self.polls == polls {
            self.model_gain.0 += f - self.centre.f;
            self.model_gain.1 += ev.count() - n;
        }
        Ok(())
    }

    fn terminate(&self) -> bool {
        self.stop.is_some()
    }

    fn best(&self) -> &Point {
        &self.centre
    }

    fn stop_reason(&self) -> StopReason {
        self.stop.unwrap_or(StopReason::Budget)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a separable quadratic f = Σ aᵢ (zᵢ − mᵢ)² with each mᵢ within 2Δ of the centre,
    /// the separable step of a poll lands on the minimum (to round-off: differences of a
    /// quadratic are exact), and the combined design takes every gaining move.
    #[test]
    fn a_polls_separable_step_lands_on_a_separable_quadratics_minimum() {
        let (a, m) = ([1.0, 4.0, 0.5], [0.42, 0.55, 0.6]);
        let f = |z: &[f64]| -> f64 { (0..3).map(|i| a[i] * (z[i] - m[i]).powi(2)).sum() };
        let (c, delta) = (vec![0.5, 0.5, 0.5], 0.05);
        let centre = Point::new(c.clone(), f(&c));
        let mut polled = Vec::new();
        for i in 0..3 {
            for s in [delta, -delta] {
                let mut z = c.clone();
                z[i] += s;
                polled.push((i, s, Point::new(z.clone(), f(&z))));
            }
        }
        let cands = poll_candidates(&centre, &polled, delta, true);
        // the separable step whole, then half way, then the combined moves
        let step = &cands[0];
        for i in 0..3 {
            assert!((step[i] - m[i]).abs() < 1e-12, "{step:?} vs {m:?}");
        }
        // floors 1 and 2 gain downward and upward by Δ; floor 3's minimum is 2Δ up
        let combined = [0.45, 0.55, 0.55];
        assert!(
            cands
                .iter()
                .any(|z| z.iter().zip(&combined).all(|(a, b)| (a - b).abs() < 1e-15))
        );
        // without the separable step (the first poll) only the combined moves
        assert_eq!(poll_candidates(&centre, &polled, delta, false).len(), 2);
    }
}
