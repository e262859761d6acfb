//! The `sqp` refiner: a trust-region SQP on the derivatives the runs carry — the refiner
//! that finds the design in ten to forty dimensions within a budget of a few dozen
//! evaluations.
//!
//! **What each evaluation tells.** Every evaluation runs its simulations with the
//! sensitivities of `newmark` (`outputs.sensitivities`), so beside its value a design
//! carries the derivatives with respect to every slip load of each property case's
//! objective and of each limit ratio ([`Gradient`], `phases::gradient`): one evaluation
//! gives what finite differences would need d + 1 for.
//!
//! **The objective as the maximum it is.** A study that reads the worst property case
//! minimises max_k f_k(z); at its optimum two cases tie (the lower-bound case drifts more
//! as the slip loads fall, the upper-bound case as they rise), which is a kink no smooth
//! model fits. The step is that of a minimax SQP (after Fletcher's SL₁QP and the
//! Han–Powell method, Nocedal & Wright 2006, § 18): minimise t + ½sᵀBs subject to
//! f_k + g_kᵀs ≤ t for every case, every limit ratio's linearisation
//! r_l + a_lᵀs ≤ max(1 − [`LIMIT_MARGIN`], r_l), the box [0, 1]^d, the space's linear
//! constraints and the trust box ‖s‖∞ ≤ Δ: a convex QP solved by clarabel, whose
//! multipliers weigh the cases and limits in the Lagrangian. B approximates the
//! Lagrangian's Hessian by damped BFGS updates (Powell 1978) from the gradients at the
//! centre and at every trial, scaled by yᵀy/sᵀy at the first update; before it, B = σI
//! with σ chosen so that the first step is a steepest-descent step to the radius.
//!
//! **First the profile.** From a start without the building's storey-shear profile's
//! shape, the refiner first searches the ray α·profile from the start's total slip load:
//! each point's derivative along the ray tells the side of the minimum, the step doubles
//! until a neighbour brackets it, and the cubic through the bracket's values and
//! derivatives places it (at most [`RAY_EVALUATIONS`] designs; consecutive points update
//! B). The steps then start at a third of the study's `initial_radius`.
//!
//! **Trust region.** The trial c + s is accepted when it meets the limits and achieves at
//! least 0.1 of the model's predicted decrease; the radius doubles (to at most 0.5) when
//! the step reached it and achieved 0.75, and halves when it achieved less than 0.25 or
//! was rejected. A trial that misses a limit is followed back along the step to where the
//! limits' ratios, linear between the centre and the trial, reach the margin (one
//! evaluation), as the `model` refiner does. Values are divided by the start's objective,
//! so the QP and B are of order one whatever the objective's units.
//!
//! **Stops.** When the model predicts no decrease the centre satisfies the first-order
//! conditions of the linearised problem — unless B was learnt across kinks (a jump of the
//! gradient reads as a large curvature), so B starts again once per centre before the
//! refiner stops ([`StopReason::Tolerance`]). When the radius falls below the tolerance
//! the refiner starts again from its centre with the first B if the centre improved since
//! the last start, at twice the longest step accepted since (at most the first radius):
//! the valley's width the last steps found, where the first radius would spend
//! evaluations halving down to it again. It stops on the tolerance if the centre did not
//! improve, and when the budget is spent ([`StopReason::Budget`]) or a design carries no derivatives
//! (a collapse: [`StopReason::NoProgress`]). Every evaluation is counted, and no batch
//! passes the budget.

use super::evaluations::{
    Evaluations, Gradient, Point, Refiner, StopReason, clamp01, dist_inf, profile_start,
};
use super::model::{LIMIT_MARGIN, ModelSearch};
use crate::base::error::OptError;
use crate::base::qp;
use crate::model::config::RefineConfig;
use crate::model::space::DesignSpace;
use nalgebra::DMatrix;
use serde::{Deserialize, Serialize};

/// Most evaluations of the search along the storey-shear profile's ray.
const RAY_EVALUATIONS: usize = 5;

/// The ray search's first step in log α (a factor 1.4), doubled until it brackets.
const RAY_STEP: f64 = 0.336_472_236_621_212_9;

/// The ray search stops at a point whose derivative along the ray is below this share of
/// the first point's.
const RAY_FLAT: f64 = 0.1;

/// The trust radius after the ray search, as a fraction of the study's
/// `initial_radius` (the `model` refiner's first radius too).
const RADIUS_AFTER_RAY: f64 = 1.0 / 3.0;

/// Largest trust radius, scaled variables.
const MAX_RADIUS: f64 = 0.5;

/// Least achieved share of the predicted decrease for a step to be taken.
const ACCEPT: f64 = 0.1;

/// A predicted decrease below this share of the objective is none: the centre is
/// stationary for the model (a tenth of the post-check's 0.1 %).
const STATIONARY_PREDICTION: f64 = 1e-4;

/// The `sqp` refiner's state (see the module doc); plain data, so a refinement can be
/// saved between iterations and continued.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sqp {
    /// Centre: the best point so far, with its derivatives.
    pub centre: Point,
    /// Trust radius Δ, scaled variables (∞-norm).
    pub radius: f64,
    /// Stop when Δ falls below this.
    pub tolerance: f64,
    /// Most new evaluations in total, counted over the whole [`Evaluations`].
    pub budget: usize,
    /// The value scale (the start's objective): the QP and B see values over it.
    pub scale: f64,
    /// B, row by row (d × d); empty until the first update.
    pub hessian: Vec<f64>,
    /// Why it stopped, once it has.
    pub stop: Option<StopReason>,
    /// B was started again at the present centre (see `next_iter`).
    #[serde(default)]
    pub reset: bool,
    /// The radius the steps start with (after the ray search).
    #[serde(default)]
    pub first_radius: f64,
    /// Starts again from a better centre (when the radius falls below the tolerance).
    #[serde(default)]
    pub restarts: usize,
    /// The centre's value at the last start (+∞: none yet).
    #[serde(default = "infinity")]
    pub restarted_at: f64,
    /// The longest step accepted since the last start (scaled variables, ∞-norm).
    #[serde(default)]
    pub longest: f64,
}

fn infinity() -> f64 {
    f64::INFINITY
}

/// One solved step: s, the model's decrease over the scale, and the multipliers of the
/// cases and of the ratios.
struct Step {
    s: Vec<f64>,
    pred: f64,
    cases: Vec<f64>,
    ratios: Vec<f64>,
}

impl Sqp {
    /// A refiner with the study's settings and `budget` (counted over the whole
    /// [`Evaluations`]).
    pub fn new(cfg: &RefineConfig, budget: usize) -> Self {
        Sqp {
            centre: Point::new(Vec::new(), f64::INFINITY),
            radius: cfg.initial_radius,
            tolerance: cfg.tolerance,
            budget,
            scale: 1.0,
            hessian: Vec::new(),
            stop: None,
            reset: false,
            first_radius: cfg.initial_radius * RADIUS_AFTER_RAY,
            restarts: 0,
            restarted_at: f64::INFINITY,
            longest: 0.0,
        }
    }

    fn room(&self, ev: &Evaluations<'_>) -> usize {
        self.budget.saturating_sub(ev.count())
    }

    /// The point `z` with its derivatives (evaluated when not known with them); `None`
    /// when the budget has no room. A point off the space's constraints is +∞.
    fn evaluate(
        &self,
        space: &DesignSpace,
        ev: &mut Evaluations<'_>,
        z: &[f64],
    ) -> Result<Option<Point>, OptError> {
        if !space.is_feasible(z) {
            return Ok(Some(Point::new(z.to_vec(), f64::INFINITY)));
        }
        if self.room(ev) == 0 && ev.point(z).is_none_or(|p| gradient(&p).is_none()) {
            return Ok(None);
        }
        ev.eval(&[z.to_vec()])?;
        Ok(ev.point(z))
    }

    fn b(&self, d: usize, g: &[f64]) -> DMatrix<f64> {
        if self.hessian.len() == d * d {
            return DMatrix::from_row_slice(d, d, &self.hessian);
        }
        // before the first update: a steepest-descent step of length Δ
        let norm = g.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        let sigma = if norm > 0.0 { norm / self.radius } else { 1.0 };
        DMatrix::identity(d, d) * sigma
    }

    /// The step of the minimax QP around the centre (see the module doc).
    fn step(
        &self,
        space: &DesignSpace,
        g: &Gradient,
        ratios: &[f64],
        b: &DMatrix<f64>,
    ) -> Option<Step> {
        let c = &self.centre.z;
        let d = c.len();
        let delta = self.radius;
        let fs = self.scale;
        let fc = g.cases.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let gs: Vec<Vec<f64>> = g
            .case_grads
            .iter()
            .map(|v| v.iter().map(|x| x / fs).collect())
            .collect();
        let mut p = DMatrix::zeros(d + 1, d + 1);
        p.view_mut((0, 0), (d, d)).copy_from(b);
        let mut q = vec![0.0; d + 1];
        q[d] = 1.0;
        let mut lo: Vec<f64> = c.iter().map(|z| (-delta).max(-z)).collect();
        let mut hi: Vec<f64> = c.iter().map(|z| delta.min(1.0 - z)).collect();
        // t (the model's maximum, relative to the centre's) is bounded by what the linear
        // pieces can reach inside the trust box
        let reach = gs
            .iter()
            .map(|v| v.iter().map(|x| x.abs()).sum::<f64>() * delta)
            .fold(0.0, f64::max);
        let spread = g.cases.iter().map(|f| (fc - f) / fs).fold(0.0, f64::max);
        let t_bound = 2.0 * (reach + spread) + 1e-9;
        lo.push(-t_bound);
        hi.push(t_bound);
        let target = 1.0 - LIMIT_MARGIN;
        let sp_rows = space.a.nrows();
        let nk = gs.len();
        let nl = ratios.len().min(g.ratio_grads.len());
        let rows = nk + nl + sp_rows;
        let mut a = DMatrix::zeros(rows, d + 1);
        let mut rhs = vec![0.0; rows];
        for (k, v) in gs.iter().enumerate() {
            for j in 0..d {
                a[(k, j)] = v[j];
            }
            a[(k, d)] = -1.0;
            rhs[k] = (fc - g.cases[k]) / fs;
        }
        for l in 0..nl {
            for j in 0..d {
                a[(nk + l, j)] = g.ratio_grads[l][j];
            }
            rhs[nk + l] = target.max(ratios[l]) - ratios[l];
        }
        for r in 0..sp_rows {
            for j in 0..d {
                a[(nk + nl + r, j)] = space.a[(r, j)];
            }
            rhs[nk + nl + r] = space.b[r] - (0..d).map(|j| space.a[(r, j)] * c[j]).sum::<f64>();
        }
        let (x, duals) = qp::solve_with_duals(&p, &q, &lo, &hi, &a, &rhs).ok()?;
        let s = x[..d].to_vec();
        let sv = nalgebra::DVector::from_column_slice(&s);
        let model_max = gs
            .iter()
            .zip(&g.cases)
            .map(|(v, f)| (f - fc) / fs + v.iter().zip(&s).map(|(a, b)| a * b).sum::<f64>())
            .fold(f64::NEG_INFINITY, f64::max);
        let pred = -(model_max + 0.5 * sv.dot(&(b * &sv)));
        Some(Step {
            s,
            pred,
            cases: duals[..nk].to_vec(),
            ratios: duals[nk..nk + nl].to_vec(),
        })
    }

    /// The gradient of the Lagrangian (over the scale) at a point's derivatives, with the
    /// step's multipliers.
    fn lagrangian(&self, g: &Gradient, step: &Step) -> Vec<f64> {
        let d = self.centre.z.len();
        let mut out = vec![0.0; d];
        for (w, v) in step.cases.iter().zip(&g.case_grads) {
            for j in 0..d {
                out[j] += w * v[j] / self.scale;
            }
        }
        for (w, v) in step.ratios.iter().zip(&g.ratio_grads) {
            for j in 0..d {
                out[j] += w * v[j];
            }
        }
        out
    }

    /// The damped BFGS update of B with the step `s` and the change `y` of the
    /// Lagrangian's gradient (Powell's damping keeps B positive definite).
    fn update(&mut self, s: &[f64], y: &[f64], b_before: &DMatrix<f64>) {
        let d = s.len();
        let sv = nalgebra::DVector::from_column_slice(s);
        let yv = nalgebra::DVector::from_column_slice(y);
        let sy = sv.dot(&yv);
        let mut b = if self.hessian.len() == d * d {
            b_before.clone()
        } else if sy > 0.0 {
            DMatrix::identity(d, d) * (yv.dot(&yv) / sy)
        } else {
            b_before.clone()
        };
        let bs = &b * &sv;
        let sbs = sv.dot(&bs);
        if !(sbs > 0.0 && sbs.is_finite()) {
            return;
        }
        let theta = if sy >= 0.2 * sbs {
            1.0
        } else {
            0.8 * sbs / (sbs - sy)
        };
        let r = &yv * theta + &bs * (1.0 - theta);
        let sr = sv.dot(&r);
        if !(sr > 0.0 && sr.is_finite()) {
            return;
        }
        b += &r * r.transpose() / sr - &bs * bs.transpose() / sbs;
        let b = (&b + b.transpose()) * 0.5;
        if b.iter().all(|v| v.is_finite()) {
            self.hessian = b.transpose().as_slice().to_vec();
        }
    }
}

/// The case of the largest objective.
fn worst_case(g: &Gradient) -> usize {
    (0..g.cases.len())
        .max_by(|&a, &b| g.cases[a].total_cmp(&g.cases[b]))
        .unwrap_or(0)
}

/// The minimiser of the cubic through (x, f, f') at both ends of [a, b] (Nocedal & Wright
/// 2006, eq. 3.59); the midpoint where the cubic has none inside.
fn cubic_minimiser((a, fa, da): (f64, f64, f64), (b, fb, db): (f64, f64, f64)) -> f64 {
    let d1 = da + db - 3.0 * (fa - fb) / (a - b);
    let disc = d1 * d1 - da * db;
    if disc < 0.0 {
        return 0.5 * (a + b);
    }
    let d2 = (b - a).signum() * disc.sqrt();
    let x = b - (b - a) * (db + d2 - d1) / (db - da + 2.0 * d2);
    if x.is_finite() && x > a && x < b {
        x
    } else {
        0.5 * (a + b)
    }
}

/// A point's derivatives, where its objective is finite.
fn gradient(p: &Point) -> Option<&Gradient> {
    p.limits
        .as_ref()
        .filter(|l| l.objective.is_finite())
        .and_then(|l| l.gradient.as_ref())
}

/// A point's limit ratios (none without limits).
fn ratios(p: &Point) -> Vec<f64> {
    p.limits
        .as_ref()
        .map_or_else(Vec::new, |l| l.ratios.clone())
}

impl Refiner for Sqp {
    fn init(
        &mut self,
        space: &DesignSpace,
        start: &Point,
        ev: &mut Evaluations<'_>,
    ) -> Result<(), OptError> {
        ev.require_gradients();
        self.centre = start.clone();
        let Some(p) = self.evaluate(space, ev, &start.z)? else {
            self.stop = Some(StopReason::Budget);
            return Ok(());
        };
        self.centre = p;
        if gradient(&self.centre).is_none() || !self.centre.f.is_finite() {
            self.stop = Some(StopReason::NoProgress);
            return Ok(());
        }
        self.scale = self.centre.objective().abs().max(f64::MIN_POSITIVE);
        self.ray(space, ev)?;
        // the ray placed the overall scale; one floor against the others is the valley's
        // steep side, so the steps start at a third of the initial radius
        self.radius = self.first_radius;
        self.restarted_at = self.centre.f;
        Ok(())
    }

    fn next_iter(&mut self, space: &DesignSpace, ev: &mut Evaluations<'_>) -> Result<(), OptError> {
        if self.room(ev) == 0 {
            self.stop = Some(StopReason::Budget);
            return Ok(());
        }
        let c = self.centre.clone();
        let Some(gc) = gradient(&c).cloned() else {
            self.stop = Some(StopReason::NoProgress);
            return Ok(());
        };
        let rc = ratios(&c);
        let d = c.z.len();
        let active: Vec<f64> = gc
            .case_grads
            .get(worst_case(&gc))
            .map_or_else(Vec::new, |v| v.iter().map(|x| x / self.scale).collect());
        let b_before = self.b(d, &active);
        let Some(step) = self.step(space, &gc, &rc, &b_before) else {
            // a QP clarabel cannot solve: a smaller region is a better-conditioned one
            self.shrink(0.5 * self.radius);
            return Ok(());
        };
        if step.pred <= STATIONARY_PREDICTION * (c.f / self.scale).abs() {
            // no decrease the model sees: with B learnt across kinks (a jump of the
            // gradient reads as a large curvature) the steps may be short for B's sake
            // alone, so B starts again once per centre; with the first B the centre is
            // stationary for the linearised problem
            if !self.hessian.is_empty() && !self.reset {
                self.hessian.clear();
                self.reset = true;
                return Ok(());
            }
            self.stop = Some(StopReason::Tolerance);
            return Ok(());
        }
        let mut z: Vec<f64> = c.z.iter().zip(&step.s).map(|(a, b)| a + b).collect();
        clamp01(&mut z);
        let len = dist_inf(&z, &c.z);
        let Some(p) = self.evaluate(space, ev, &z)? else {
            self.stop = Some(StopReason::Budget);
            return Ok(());
        };
        if let Some(gp) = gradient(&p) {
            let (lc, lp) = (self.lagrangian(&gc, &step), self.lagrangian(gp, &step));
            let y: Vec<f64> = lp.iter().zip(&lc).map(|(a, b)| a - b).collect();
            let s: Vec<f64> = z.iter().zip(&c.z).map(|(a, b)| a - b).collect();
            self.update(&s, &y, &b_before);
        }
        let rho = (c.f - p.f) / self.scale / step.pred;
        if std::env::var_os("SLIPLOAD_DEBUG_SQP").is_some() {
            eprintln!(
                "sqp: radius {:.4} len {:.4} pred {:.3e} rho {:.3} f {:.6} -> {:.6} duals {:?}",
                self.radius, len, step.pred, rho, c.f, p.f, step.cases
            );
        }
        if p.f.is_finite() && rho >= ACCEPT {
            self.centre = p;
            self.reset = false;
            self.longest = self.longest.max(len);
            if rho >= 0.75 && len >= 0.9 * self.radius {
                self.radius = (2.0 * self.radius).min(MAX_RADIUS);
            } else if rho < 0.25 {
                self.shrink(0.5 * self.radius);
            }
            return Ok(());
        }
        // a step that missed a limit: back along it to where the ratios reach the margin
        if let Some(t) = ModelSearch::back_to_limit(&c, &p)
            && self.room(ev) > 0
        {
            let mut zb: Vec<f64> = c.z.iter().zip(&z).map(|(a, b)| a + t * (b - a)).collect();
            clamp01(&mut zb);
            if let Some(pb) = self.evaluate(space, ev, &zb)?
                && pb.f < c.f
                && gradient(&pb).is_some()
            {
                self.longest = self.longest.max(dist_inf(&pb.z, &c.z));
                self.centre = pb;
                self.reset = false;
                self.shrink(0.5 * self.radius);
                return Ok(());
            }
        }
        self.shrink(0.5 * self.radius);
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

impl Sqp {
    /// The search along the storey-shear profile's ray α·profile from the start's total
    /// slip load (see the module doc): each point's derivative along the ray brackets the
    /// best α, and the cubic through the bracket's values and derivatives places it.
    /// Consecutive points update B (the curvature along the ray).
    fn ray(&mut self, space: &DesignSpace, ev: &mut Evaluations<'_>) -> Result<(), OptError> {
        let profile = &space.profile;
        let own = space.slip_loads(&self.centre.z);
        let Some(alpha0) = profile_start(space, &own) else {
            return Ok(());
        };
        let at = |la: f64| {
            ModelSearch::z_of(
                space,
                &profile.iter().map(|p| la.exp() * p).collect::<Vec<_>>(),
            )
        };
        // (log α, what the refiner minimises, its derivative along the ray, the point)
        let mut tried: Vec<(f64, f64, f64, Point)> = Vec::new();
        let mut la = alpha0.ln();
        let mut h = RAY_STEP;
        let mut d0 = f64::NAN;
        for _ in 0..RAY_EVALUATIONS {
            let Some(z) = at(la) else { break };
            let Some(p) = self.evaluate(space, ev, &z)? else {
                self.stop = Some(StopReason::Budget);
                break;
            };
            let d = gradient(&p).map_or(f64::NAN, |_| self.ray_derivative(&at, la, &p));
            if let Some((_, _, _, q)) = tried.last() {
                self.update_from(q, &p);
            }
            if d0.is_nan() {
                d0 = d;
            }
            tried.push((la, p.f, d, p.clone()));
            if p.f < self.centre.f {
                self.centre = p;
            }
            tried.sort_by(|a, b| a.0.total_cmp(&b.0));
            // the best point, and whether a neighbour brackets the minimum
            let best = (0..tried.len())
                .min_by(|&a, &b| tried[a].1.total_cmp(&tried[b].1))
                .expect("one point tried");
            let (lb, fb, db, _) = tried[best].clone();
            if fb.is_finite() && db.abs() <= RAY_FLAT * d0.abs().max(f64::MIN_POSITIVE) {
                break;
            }
            let side = if db.is_nan() { -1.0 } else { -db.signum() };
            let neighbour = if side > 0.0 {
                tried.get(best + 1)
            } else {
                best.checked_sub(1).and_then(|i| tried.get(i))
            };
            la = match neighbour {
                Some((ln, fnb, dn, _)) if fb.is_finite() => {
                    let (a, b) = if *ln < lb { (*ln, lb) } else { (lb, *ln) };
                    let v = if fnb.is_finite() && dn.is_finite() {
                        let (fa, da, fb2, db2) = if *ln < lb {
                            (*fnb, *dn, fb, db)
                        } else {
                            (fb, db, *fnb, *dn)
                        };
                        cubic_minimiser((a, fa, da), (b, fb2, db2))
                    } else {
                        0.5 * (a + b)
                    };
                    v.clamp(a + 0.1 * (b - a), b - 0.1 * (b - a))
                }
                _ => {
                    let next = lb + side * h;
                    h *= 2.0;
                    next
                }
            };
            if tried.iter().any(|t| (t.0 - la).abs() < 1e-9) || at(la) == at(lb) {
                break;
            }
        }
        Ok(())
    }

    /// φ'(log α) along the ray at `p`: the worst case's gradient times dz/d(log α).
    fn ray_derivative(&self, at: &impl Fn(f64) -> Option<Vec<f64>>, la: f64, p: &Point) -> f64 {
        let Some(g) = gradient(p) else {
            return f64::NAN;
        };
        let (Some(a), Some(b)) = (at(la + 1e-6), at(la - 1e-6)) else {
            return f64::NAN;
        };
        let worst = worst_case(g);
        g.case_grads[worst]
            .iter()
            .zip(a.iter().zip(&b))
            .map(|(gi, (x, y))| gi * (x - y) / 2e-6)
            .sum::<f64>()
            / self.scale
    }

    /// The BFGS update from two evaluated points (the worst case's gradients).
    fn update_from(&mut self, a: &Point, b: &Point) {
        let (Some(ga), Some(gb)) = (gradient(a), gradient(b)) else {
            return;
        };
        let d = a.z.len();
        let (wa, wb) = (worst_case(ga), worst_case(gb));
        let s: Vec<f64> = b.z.iter().zip(&a.z).map(|(x, y)| x - y).collect();
        let y: Vec<f64> = (0..d)
            .map(|j| (gb.case_grads[wb][j] - ga.case_grads[wa][j]) / self.scale)
            .collect();
        let g: Vec<f64> = ga.case_grads[wa].iter().map(|x| x / self.scale).collect();
        let before = self.b(d, &g);
        self.update(&s, &y, &before);
    }

    /// Sets the radius to `to`; below the tolerance the refiner starts again from its
    /// centre with B = σI, at twice the longest step accepted since the last start (at
    /// most the first radius), when the centre improved since that start (across kinks B
    /// is what the steps failed on, not the centre), and stops on the tolerance when it
    /// did not.
    fn shrink(&mut self, to: f64) {
        self.radius = to;
        if self.radius < self.tolerance {
            if self.centre.f < self.restarted_at {
                self.restarted_at = self.centre.f;
                self.restarts += 1;
                self.hessian.clear();
                self.reset = false;
                // the steps that gained since the last start say how far the valley lets
                // a step go: twice the longest, not the first radius again
                self.radius = if self.longest > 0.0 {
                    (2.0 * self.longest).clamp(2.0 * self.tolerance, self.first_radius)
                } else {
                    self.first_radius
                };
                self.longest = 0.0;
            } else {
                self.stop = Some(StopReason::Tolerance);
            }
        }
    }
}
