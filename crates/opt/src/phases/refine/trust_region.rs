//! Trust region on a fitted quadratic model (derivative-free, model-based).
//!
//! Each iteration fits m(s) = f₀ + gᵀs + ½ sᵀHs by least squares to the evaluated points
//! within the trust region around the centre c (s = (z − c)/Δ, so the fit is well scaled),
//! adding stencil points c ± Δeᵢ, c ± Δ/2 eᵢ, c + Δ/2(±eᵢ ± eⱼ) when fewer than
//! 1 + d + d(d+1)/2 + 1 points are at hand. H is projected onto the PSD cone by eigenvalue
//! clipping, so the subproblem — minimise m over the box, the trust region and the
//! study's linear constraints — is a convex QP, solved by clarabel. The step is accepted
//! when it lowers the objective; the radius grows after a good prediction
//! (ρ ≥ 0.75 at the region's edge) and halves after a poor one (ρ < 0.25) or when the
//! model predicts no decrease (or the QP is not solved). Stops when Δ < tolerance or the
//! budget is spent; the model step counts in the budget like the stencil's points (the
//! executor, [`super::run`], stops a refiner at its budget).

use super::evaluations::{Evaluations, Point, Refiner, clamp01, dist_inf, trust_step};
use crate::base::error::OptError;
use crate::base::qp;
use crate::model::config::RefineConfig;
use crate::model::space::DesignSpace;
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

fn features(s: &[f64]) -> Vec<f64> {
    let d = s.len();
    let mut f = Vec::with_capacity(1 + d + d * (d + 1) / 2);
    f.push(1.0);
    f.extend_from_slice(s);
    for i in 0..d {
        for j in i..d {
            f.push(if i == j {
                0.5 * s[i] * s[i]
            } else {
                s[i] * s[j]
            });
        }
    }
    f
}

/// Candidate stencil points around `c` at radius `delta`, clamped into the box.
fn stencil(c: &[f64], delta: f64) -> Vec<Vec<f64>> {
    let d = c.len();
    let mut out = Vec::new();
    for scale in [1.0, -1.0, 0.5, -0.5] {
        for i in 0..d {
            let mut z = c.to_vec();
            z[i] += scale * delta;
            clamp01(&mut z);
            out.push(z);
        }
    }
    for (si, sj) in [(1.0, 1.0), (-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0)] {
        for i in 0..d {
            for j in i + 1..d {
                let mut z = c.to_vec();
                z[i] += 0.5 * si * delta;
                z[j] += 0.5 * sj * delta;
                clamp01(&mut z);
                out.push(z);
            }
        }
    }
    out
}

/// The trust-region refiner's state (see the module doc); serialisable, so a refinement
/// can be saved between iterations and continued.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrustRegion {
    /// Centre: the best point so far.
    pub centre: Point,
    /// Trust radius Δ, scaled variables (∞-norm).
    pub radius: f64,
    /// Stop when Δ falls below this.
    pub tolerance: f64,
    /// Most new evaluations in total (stencil points are cut to fit).
    pub budget: usize,
    /// No model can be fitted (too few feasible points near the centre).
    pub stalled: bool,
}

impl TrustRegion {
    /// A refiner with the study's settings and `budget`.
    pub fn new(cfg: &RefineConfig, budget: usize) -> Self {
        TrustRegion {
            centre: Point::new(Vec::new(), f64::INFINITY),
            radius: cfg.initial_radius,
            tolerance: cfg.tolerance,
            budget,
            stalled: false,
        }
    }
}

impl Refiner for TrustRegion {
    fn init(
        &mut self,
        _space: &DesignSpace,
        start: &Point,
        _ev: &mut Evaluations<'_>,
    ) -> Result<(), OptError> {
        self.centre = start.clone();
        Ok(())
    }

    fn next_iter(&mut self, space: &DesignSpace, ev: &mut Evaluations<'_>) -> Result<(), OptError> {
        let d = space.dim();
        let p = 1 + d + d * (d + 1) / 2;
        let c = self.centre.clone();
        let mut delta = self.radius;
        self.step(space, ev, d, p, &c, &mut delta)?;
        self.radius = delta;
        Ok(())
    }

    fn terminate(&self) -> bool {
        self.stalled || self.radius < self.tolerance
    }

    fn best(&self) -> &Point {
        &self.centre
    }
}

impl TrustRegion {
    /// One model fit, subproblem and trial point; updates the centre and `delta`.
    fn step(
        &mut self,
        space: &DesignSpace,
        ev: &mut Evaluations<'_>,
        d: usize,
        p: usize,
        c: &Point,
        delta: &mut f64,
    ) -> Result<(), OptError> {
        let near = |ev: &Evaluations<'_>, c: &Point, delta: f64| -> Vec<Point> {
            let mut v: Vec<Point> = ev
                .all()
                // A collapsed design (+∞) is no sample of a smooth model.
                .filter(|q| q.f.is_finite() && dist_inf(&q.z, &c.z) <= delta * (1.0 + 1e-12))
                .cloned()
                .collect();
            v.sort_by(|a, b| dist_inf(&a.z, &c.z).total_cmp(&dist_inf(&b.z, &c.z)));
            v.dedup_by(|a, b| a.z == b.z);
            v
        };
        let mut pts = near(ev, c, *delta);
        if pts.len() < p + 1 {
            let want = p + 1 - pts.len();
            let mut add: Vec<Vec<f64>> = Vec::new();
            for z in stencil(&c.z, *delta) {
                if add.len() == want {
                    break;
                }
                if space.is_feasible(&z) && !pts.iter().any(|q| q.z == z) && !add.contains(&z) {
                    add.push(z);
                }
            }
            let room = self.budget.saturating_sub(ev.count());
            add.truncate(room);
            if add.is_empty() && pts.len() < d + 2 {
                self.stalled = true;
                return Ok(());
            }
            ev.eval(&add)?;
            pts = near(ev, c, *delta);
        }
        // least squares fit in s = (z − c)/Δ; SVD gives the minimum-norm fit when the
        // points do not determine every coefficient
        let rows: Vec<Vec<f64>> = pts
            .iter()
            .map(|q| {
                features(
                    &q.z.iter()
                        .zip(&c.z)
                        .map(|(z, c)| (z - c) / *delta)
                        .collect::<Vec<_>>(),
                )
            })
            .collect();
        let x = DMatrix::from_fn(rows.len(), p, |i, j| rows[i][j]);
        let y = DVector::from_iterator(pts.len(), pts.iter().map(|q| q.f - c.f));
        // the model at unit scale: the QP's tolerances are absolute, so an objective
        // weighted 1e-7 would otherwise be solved to a different point
        let scale = match y.amax() {
            s if s > 0.0 && s.is_finite() => s,
            _ => 1.0,
        };
        let y = y / scale;
        let coef = x
            .svd(true, true)
            .solve(&y, 1e-10)
            .map_err(|e| OptError::Subproblem(format!("model fit: {e}")))?;
        let g: Vec<f64> = (0..d).map(|i| coef[1 + i]).collect();
        let mut h = DMatrix::zeros(d, d);
        let mut k = 1 + d;
        for i in 0..d {
            for j in i..d {
                h[(i, j)] = coef[k];
                h[(j, i)] = coef[k];
                k += 1;
            }
        }
        let h = qp::clip_to_psd(&h, 0.0);
        // a subproblem clarabel cannot solve (numerically hard model) is treated like a
        // model that predicts no decrease: shrink and refit
        let Some(s) = trust_step(space, &c.z, *delta, &h, &g, &[]) else {
            *delta *= 0.5;
            return Ok(());
        };
        let sv = DVector::from_column_slice(&s);
        let pred = -(DVector::from_column_slice(&g).dot(&sv) + 0.5 * sv.dot(&(&h * &sv))) * scale;
        let mut z: Vec<f64> = c.z.iter().zip(&s).map(|(c, s)| c + *delta * s).collect();
        clamp01(&mut z);
        let step = dist_inf(&z, &c.z);
        if pred <= 1e-12 * c.f.abs() || step < 1e-3 * *delta || !space.is_feasible(&z) {
            *delta *= 0.5;
            return Ok(());
        }
        let f = ev.eval_one(&z)?;
        let rho = (c.f - f) / pred;
        if f < c.f {
            self.centre = Point::new(z, f);
        }
        if rho >= 0.75 && step >= 0.9 * *delta {
            *delta = (2.0 * *delta).min(0.5);
        } else if rho < 0.25 {
            *delta *= 0.5;
        }
        Ok(())
    }
}
