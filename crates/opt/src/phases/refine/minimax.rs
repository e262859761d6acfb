//! The model refiner's step where the objective is the worst of the property cases.
//!
//! A study that checks its dampers at their property bounds and reads the worst case
//! minimises f(x) = maxⱼ fⱼ(x) over the cases j (nominal, lower, upper). Each fⱼ is as
//! smooth as the response, but their largest has a kink wherever two cases are equal,
//! and that is where such an optimum lies: slip loads too low let the lower-bound case
//! drift most, too high make the upper-bound case worst, and the design balances them.
//! A quadratic interpolated through values of the maximum across that kink is a poor
//! model on both sides of it (its steps fail where a step along the kink gains).
//!
//! So each case gets its own quadratic model qⱼ(s) = aⱼ + gⱼᵀs + ½sᵀHⱼs from the same
//! interpolation points (least change from the objective's Hessian memory, as the
//! objective's model), and the step solves the subproblem of sequential quadratic
//! programming for minimax problems (Fletcher 1987, *Practical Methods of Optimization*,
//! §14.6; Zhou and Tits 1993):
//!
//! min over (s, t) of t + ½sᵀHs  subject to  aⱼ + gⱼᵀs ≤ t for every case,
//!
//! over the box, the space's constraints, the linearised limits and the trust box: a
//! convex QP for clarabel with one variable more. H is the Hessian of the Lagrangian
//! Σ λⱼHⱼ, its multipliers λ estimated as the least-norm convex combination of the
//! gradients of the cases that can govern inside the trust box (at a minimax point that
//! combination is zero: the first-order condition 0 ∈ conv{gⱼ}). The model of the
//! objective the step is judged by is maxⱼ qⱼ(s).

use crate::base::qp;
use crate::model::space::DesignSpace;
use nalgebra::{DMatrix, DVector};

/// The model of one property case's objective around the centre, in s = (z − c)/Δ and
/// over the objective's value scale: its value relative to the centre's objective (≤ 0;
/// 0 for the case that governs there), gradient and Hessian.
pub(super) struct CaseModel {
    /// (fⱼ(c) − f(c)) / scale.
    pub at: f64,
    /// Gradient in s.
    pub g: DVector<f64>,
    /// Hessian in s.
    pub h: DMatrix<f64>,
}

impl CaseModel {
    /// The model's value at s.
    fn at_step(&self, s: &DVector<f64>) -> f64 {
        self.at + self.g.dot(s) + 0.5 * s.dot(&(&self.h * s))
    }
}

/// The model of the objective at step `s`: the largest case model (relative to the
/// centre's objective, over the value scale).
pub(super) fn model_value(cases: &[CaseModel], s: &[f64]) -> f64 {
    let s = DVector::from_column_slice(s);
    cases
        .iter()
        .map(|c| c.at_step(&s))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The cases that can govern inside the unit trust box: the governing one and every
/// case whose linear model can reach it there (aⱼ + ‖gⱼ − g_gov‖₁ ≥ 0).
fn near_active(cases: &[CaseModel]) -> Vec<usize> {
    let Some(gov) = (0..cases.len()).max_by(|&a, &b| cases[a].at.total_cmp(&cases[b].at)) else {
        return Vec::new();
    };
    (0..cases.len())
        .filter(|&j| {
            let gap: f64 = (&cases[j].g - &cases[gov].g).iter().map(|v| v.abs()).sum();
            j == gov || cases[j].at - cases[gov].at + gap >= 0.0
        })
        .collect()
}

/// The least-norm point of the convex hull of `gs`: its weights (Gilbert's algorithm,
/// a Frank–Wolfe iteration with exact line search; a fixed number of iterations, so the
/// answer is deterministic).
fn least_norm_weights(gs: &[&DVector<f64>]) -> Vec<f64> {
    let k = gs.len();
    let mut w = vec![0.0; k];
    if k == 0 {
        return w;
    }
    // start at the shortest gradient
    let first = (0..k)
        .min_by(|&a, &b| gs[a].norm_squared().total_cmp(&gs[b].norm_squared()))
        .expect("k > 0");
    w[first] = 1.0;
    let mut x = gs[first].clone();
    for _ in 0..200 {
        // the vertex that most lowers ‖x‖² along it
        let j = (0..k)
            .min_by(|&a, &b| gs[a].dot(&x).total_cmp(&gs[b].dot(&x)))
            .expect("k > 0");
        let dir = gs[j] - &x;
        let dd = dir.norm_squared();
        let slope = -x.dot(&dir);
        if dd <= 0.0 || slope <= 1e-15 * x.norm_squared() {
            break;
        }
        let t = (slope / dd).min(1.0);
        for (i, wi) in w.iter_mut().enumerate() {
            *wi *= 1.0 - t;
            if i == j {
                *wi += t;
            }
        }
        x += dir * t;
    }
    w
}

/// The Hessian of the Lagrangian Σ λⱼHⱼ over the cases that can govern inside the trust
/// box, λ their gradients' least-norm convex combination.
pub(super) fn lagrangian_hessian(cases: &[CaseModel], d: usize) -> DMatrix<f64> {
    let near = near_active(cases);
    let gs: Vec<&DVector<f64>> = near.iter().map(|&j| &cases[j].g).collect();
    let w = least_norm_weights(&gs);
    let mut h = DMatrix::zeros(d, d);
    for (&j, wj) in near.iter().zip(w) {
        if wj > 0.0 {
            h += &cases[j].h * wj;
        }
    }
    h
}

/// The minimax step (see the module doc): s = (z − c)/Δ minimising t + ½sᵀHs (H
/// positive semidefinite) subject to aⱼ + gⱼᵀs ≤ t for every case, the box [0, 1]^d,
/// the space's constraints, the rows `cuts` (aᵀs ≤ b, in s) and ‖s‖∞ ≤ 1, around `c` at
/// radius `delta`. `None` when clarabel cannot solve it.
pub(super) fn step(
    space: &DesignSpace,
    c: &[f64],
    delta: f64,
    h: &DMatrix<f64>,
    cases: &[CaseModel],
    cuts: &[(Vec<f64>, f64)],
) -> Option<Vec<f64>> {
    let d = c.len();
    let n = d + 1;
    // t lies between the lowest any case model can reach and the largest value at s = 0
    // (which is feasible): a bound that never binds
    let reach = cases
        .iter()
        .map(|m| m.at.abs() + m.g.iter().map(|v| v.abs()).sum::<f64>())
        .fold(1.0, f64::max);
    let mut lo: Vec<f64> = c.iter().map(|z| (-1.0f64).max(-z / delta)).collect();
    let mut hi: Vec<f64> = c.iter().map(|z| 1.0f64.min((1.0 - z) / delta)).collect();
    lo.push(-2.0 * reach);
    hi.push(2.0 * reach);
    let mut p = DMatrix::zeros(n, n);
    p.view_mut((0, 0), (d, d)).copy_from(h);
    let mut q = vec![0.0; n];
    q[d] = 1.0;
    let rows = space.a.nrows();
    let total = rows + cuts.len() + cases.len();
    let a = DMatrix::from_fn(total, n, |i, j| {
        if i < rows {
            if j < d { space.a[(i, j)] * delta } else { 0.0 }
        } else if i < rows + cuts.len() {
            if j < d { cuts[i - rows].0[j] } else { 0.0 }
        } else {
            let m = &cases[i - rows - cuts.len()];
            if j < d { m.g[j] } else { -1.0 }
        }
    });
    let b: Vec<f64> = (0..rows)
        .map(|i| space.b[i] - (0..d).map(|j| space.a[(i, j)] * c[j]).sum::<f64>())
        .chain(cuts.iter().map(|(_, b)| *b))
        .chain(cases.iter().map(|m| -m.at))
        .collect();
    let mut x = qp::solve(&p, &q, &lo, &hi, &a, &b).ok()?;
    x.truncate(d);
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn least_norm_weights_find_the_hulls_nearest_point() {
        // two gradients pointing apart along x, both up along y: the nearest point of
        // their segment is (0, 1), half of each
        let (a, b) = (
            DVector::from_vec(vec![2.0, 1.0]),
            DVector::from_vec(vec![-2.0, 1.0]),
        );
        let w = least_norm_weights(&[&a, &b]);
        assert!(
            (w[0] - 0.5).abs() < 1e-12 && (w[1] - 0.5).abs() < 1e-12,
            "{w:?}"
        );
        // a hull that holds the origin: the combination is zero
        let c = DVector::from_vec(vec![0.0, -1.0]);
        let w = least_norm_weights(&[&a, &b, &c]);
        let x = &a * w[0] + &b * w[1] + &c * w[2];
        assert!(x.norm() < 1e-6, "{x:?}");
    }

    /// Two cases meeting at a kink: the minimax step of
    /// f(z) = max(2(z₀ − ½) + (z₁ − ½), −2(z₀ − ½) + (z₁ − ½)) + ½‖z − ½‖² from a point
    /// on the kink moves along it (z₀ stays) and down in z₁: a step a smooth model of
    /// the maximum alone (gradient (0, 1) on average, curvature across the kink) misses.
    #[test]
    fn the_minimax_step_follows_the_kink() {
        let space = DesignSpace {
            dampers: vec![0, 1],
            offset: vec![0.0; 2],
            basis: DMatrix::from_diagonal_element(2, 2, 1.0e6),
            a: DMatrix::zeros(0, 2),
            b: vec![],
            names: vec!["floor1".into(), "floor2".into()],
            shape: None,
            profile: vec![1.0; 2],
        };
        let c = [0.5, 0.5];
        let delta = 0.1;
        let h = DMatrix::identity(2, 2) * (delta * delta);
        let case = |gx: f64| CaseModel {
            at: 0.0,
            g: DVector::from_vec(vec![gx * delta, delta]),
            h: h.clone(),
        };
        let cases = [case(2.0), case(-2.0)];
        let s = step(&space, &c, delta, &h, &cases, &[]).unwrap();
        assert!(s[0].abs() < 1e-6, "{s:?}");
        // along the kink the model is t = s₁Δ + ½s₁²Δ², least at the trust box's edge
        assert!((s[1] + 1.0).abs() < 1e-6, "{s:?}");
        assert!(model_value(&cases, &s) < -0.9 * delta);
        let hl = lagrangian_hessian(&cases, 2);
        assert!((hl[(0, 0)] - h[(0, 0)]).abs() < 1e-15);
    }
}
