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
//! **Counted.** Every evaluation goes through [`Evaluations`] and no batch is larger than
//! the budget left, so the refiner never exceeds it. It stops when the radius falls below
//! the tolerance ([`StopReason::Tolerance`]), the budget is spent
//! ([`StopReason::Budget`]), or no model can be built (too few finite points,
//! [`StopReason::NoProgress`]).

use super::evaluations::{Evaluations, Point, Refiner, StopReason, clamp01, dist_inf, trust_step};
use crate::base::error::OptError;
use crate::base::qp;
use crate::model::config::RefineConfig;
use crate::model::space::DesignSpace;
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

/// Most evaluations of one profile's line search.
pub const LINE_EVALUATIONS: usize = 6;

/// Ratio between neighbouring points of a line search (1.4: a bracket of ±40 %).
const LINE_FACTOR: f64 = 1.4;

/// The model's first radius as a fraction of the study's `initial_radius` (on the
/// ten-storey check example from a uniform start: 0.006344 after 46 evaluations with a
/// third, 0.006356 with the whole radius, whose first ±450 kN probes of single floors
/// cost up to 50 % more than the centre).
const MODEL_RADIUS_FRACTION: f64 = 1.0 / 3.0;

/// Largest trust radius, scaled variables.
const MAX_RADIUS: f64 = 0.5;

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
}

impl ModelSearch {
    /// A refiner with the study's settings and `budget` (counted over the whole
    /// [`Evaluations`]).
    pub fn new(cfg: &RefineConfig, budget: usize) -> Self {
        ModelSearch {
            centre: Point {
                z: Vec::new(),
                f: f64::INFINITY,
            },
            radius: cfg.initial_radius,
            tolerance: cfg.tolerance,
            budget,
            points: Vec::new(),
            hessian: Vec::new(),
            stop: None,
        }
    }

    fn room(&self, ev: &Evaluations<'_>) -> usize {
        self.budget.saturating_sub(ev.count())
    }

    /// Objective values of `zs`, the ones the budget has no room for left out (`None`);
    /// a point off the space's constraints is +∞ without a simulation.
    fn values(
        &self,
        space: &DesignSpace,
        ev: &mut Evaluations<'_>,
        zs: &[Vec<f64>],
    ) -> Result<Vec<Option<f64>>, OptError> {
        let mut room = self.room(ev);
        let mut ask: Vec<Vec<f64>> = Vec::new();
        let mut out = vec![None; zs.len()];
        for (i, z) in zs.iter().enumerate() {
            if !space.is_feasible(z) {
                out[i] = Some(f64::INFINITY);
            } else if let Some(f) = ev.cached(z) {
                out[i] = Some(f);
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
                out[i] = ev.cached(z);
            }
        }
        Ok(out)
    }

    /// The scaled point of slip loads `loads`, clamped into the box (least squares on the
    /// space's basis: exact for a free space).
    fn z_of(space: &DesignSpace, loads: &[f64]) -> Option<Vec<f64>> {
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
        // (log α, value) of every point tried
        let mut tried: Vec<(f64, f64)> = Vec::new();
        let probe = |me: &mut Self,
                     ev: &mut Evaluations<'_>,
                     tried: &mut Vec<(f64, f64)>,
                     la: f64|
         -> Result<Option<f64>, OptError> {
            if let Some(&(_, f)) = tried.iter().find(|(l, _)| (l - la).abs() < 1e-12) {
                return Ok(Some(f));
            }
            if ev.count() - start >= LINE_EVALUATIONS {
                return Ok(None);
            }
            let Some(z) = at(la.exp()) else {
                return Ok(None);
            };
            let Some(f) = me.values(space, ev, std::slice::from_ref(&z))?[0] else {
                return Ok(None);
            };
            tried.push((la, f));
            if f < me.centre.f {
                me.centre = Point { z, f };
            }
            Ok(Some(f))
        };
        let step = LINE_FACTOR.ln();
        let l0 = alpha0.ln();
        for la in [l0 - step, l0, l0 + step] {
            if probe(self, ev, &mut tried, la)?.is_none() {
                return Ok(());
            }
        }
        // move the bracket outward until its middle point is the best
        loop {
            tried.sort_by(|a, b| a.0.total_cmp(&b.0));
            let best = (0..tried.len())
                .min_by(|&a, &b| tried[a].1.total_cmp(&tried[b].1))
                .expect("three points tried");
            if best > 0 && best + 1 < tried.len() {
                let (a, b, c) = (tried[best - 1], tried[best], tried[best + 1]);
                if let Some(v) = parabola_vertex(a, b, c) {
                    probe(self, ev, &mut tried, v)?;
                }
                return Ok(());
            }
            let next = if best == 0 {
                tried[0].0 - 2.0 * step
            } else {
                tried[tried.len() - 1].0 + 2.0 * step
            };
            // past the box the clamped points repeat: nothing more to learn
            let (edge, beyond) = (at(tried[best].0.exp()), at(next.exp()));
            if edge == beyond || probe(self, ev, &mut tried, next)?.is_none() {
                return Ok(());
            }
        }
    }

    /// Evaluates the first interpolation set: the centre and c ± Δeᵢ (c − Δ and c − 2Δ,
    /// or c + Δ and c + 2Δ, where the box has room on one side only).
    fn first_set(&mut self, space: &DesignSpace, ev: &mut Evaluations<'_>) -> Result<(), OptError> {
        let d = space.dim();
        let c = self.centre.z.clone();
        let delta = self.radius;
        // one point per coordinate first, then the second: with a budget for d of them
        // only, the model is linear
        let (mut zs, mut second) = (Vec::with_capacity(2 * d), Vec::with_capacity(d));
        for i in 0..d {
            let (a, b) = if c[i] + delta <= 1.0 && c[i] - delta >= 0.0 {
                (delta, -delta)
            } else if c[i] + delta > 1.0 {
                (-delta, -2.0 * delta)
            } else {
                (delta, 2.0 * delta)
            };
            for (s, list) in [(a, &mut zs), (b, &mut second)] {
                let mut z = c.clone();
                z[i] = (z[i] + s).clamp(0.0, 1.0);
                if z != c {
                    list.push(z);
                }
            }
        }
        zs.extend(second);
        let values = self.values(space, ev, &zs)?;
        self.points = vec![self.centre.clone()];
        for (z, f) in zs.into_iter().zip(values) {
            if let Some(f) = f {
                self.admit(Point { z, f });
            }
        }
        Ok(())
    }

    /// Takes a new point: a better one becomes the centre; a finite one joins the set
    /// (the set's farthest point from the centre leaves when it holds 2d + 1).
    fn admit(&mut self, p: Point) {
        if p.f < self.centre.f {
            self.centre = p.clone();
        }
        if !p.f.is_finite() || self.points.iter().any(|q| q.z == p.z) {
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

    /// The least-change model at the centre in s = (z − c)/Δ: gradient, Hessian (in s),
    /// and the value scale it was fitted at. `None` when the set does not determine a
    /// gradient (fewer than d + 1 points) or the solve fails.
    fn model(&self, d: usize) -> Option<(DVector<f64>, DMatrix<f64>, f64)> {
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
        let scale = match self
            .points
            .iter()
            .map(|p| (p.f - c.f).abs())
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
            rhs[k] = (self.points[k].f - c.f) / scale - 0.5 * s[k].dot(&(&h0 / scale * &s[k]));
        }
        let x = w.svd(true, true).solve(&rhs, 1e-12).ok()?;
        let g = DVector::from_iterator(d, (0..d).map(|i| x[m + 1 + i]));
        let mut h = &h0 / scale;
        for k in 0..m {
            h += &s[k] * s[k].transpose() * x[k];
        }
        if g.iter().chain(h.iter()).any(|v| !v.is_finite()) {
            return None;
        }
        Some((g, h, scale))
    }

    /// One model step (see the module doc).
    fn model_step(
        &mut self,
        space: &DesignSpace,
        ev: &mut Evaluations<'_>,
    ) -> Result<(), OptError> {
        let d = space.dim();
        let delta = self.radius;
        let Some((g, h, scale)) = self.model(d) else {
            self.stop = Some(StopReason::NoProgress);
            return Ok(());
        };
        // the least-change memory, back in z
        self.hessian = (&h * (scale / (delta * delta))).as_slice().to_vec();
        // (nalgebra is column-major; H is symmetric, so rows = columns)
        let c = self.centre.clone();
        let hp = qp::clip_to_psd(&h, 0.0);
        let step = trust_step(space, &c.z, delta, &hp, g.as_slice());
        let trial = step.and_then(|s| {
            let sv = DVector::from_column_slice(&s);
            let pred = -(g.dot(&sv) + 0.5 * sv.dot(&(&h * &sv))) * scale;
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
            // the model predicts no decrease: improve its geometry if far points made
            // it, else the region is too large
            if far > 2.0 * delta {
                return self.geometry_step(space, ev);
            }
            self.shrink();
            return Ok(());
        };
        let Some(f) = self.values(space, ev, std::slice::from_ref(&z))?[0] else {
            self.stop = Some(StopReason::Budget);
            return Ok(());
        };
        let rho = (c.f - f) / pred;
        self.admit(Point { z, f });
        if rho >= 0.7 && len >= 0.9 * delta {
            self.radius = (2.0 * delta).min(MAX_RADIUS);
        } else if rho < 0.1 || rho.is_nan() {
            if far > 2.0 * delta {
                return self.geometry_step(space, ev);
            }
            self.shrink();
        }
        Ok(())
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
        match self.values(space, ev, std::slice::from_ref(&z))?[0] {
            Some(f) => self.admit(Point { z, f }),
            None => self.stop = Some(StopReason::Budget),
        }
        Ok(())
    }

    fn shrink(&mut self) {
        self.radius *= 0.5;
        if self.radius < self.tolerance {
            self.stop = Some(StopReason::Tolerance);
        }
    }
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
        let total: f64 = own.iter().sum();
        self.line_search(space, ev, &own, 1.0)?;
        let profile = &space.profile;
        let cos = {
            let (a, b) = (
                DVector::from_column_slice(&own),
                DVector::from_column_slice(profile),
            );
            a.dot(&b) / (a.norm() * b.norm())
        };
        // (a start without slip load has no direction: cos is NaN)
        if cos.is_nan() || cos <= 0.999 {
            let upper = space.slip_loads(&vec![1.0; space.dim()]);
            let full = profile
                .iter()
                .zip(&upper)
                .filter(|(p, _)| **p > 0.0)
                .map(|(p, u)| u / p)
                .fold(f64::INFINITY, f64::min);
            let alpha0 = if total > 0.0 {
                total / profile.iter().sum::<f64>()
            } else {
                0.5 * full
            };
            self.line_search(space, ev, profile, alpha0)?;
        }
        if self.room(ev) == 0 {
            self.stop = Some(StopReason::Budget);
            return Ok(());
        }
        // the profile searches placed the overall scale; one floor against the others is
        // the valley's steep side, so the model starts at a third of the initial radius
        self.radius *= MODEL_RADIUS_FRACTION;
        self.first_set(space, ev)
    }

    fn next_iter(&mut self, space: &DesignSpace, ev: &mut Evaluations<'_>) -> Result<(), OptError> {
        if self.room(ev) == 0 {
            self.stop = Some(StopReason::Budget);
            return Ok(());
        }
        self.model_step(space, ev)
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
