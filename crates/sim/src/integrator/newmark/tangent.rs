//! The tangent of the `newmark` step with respect to the dampers' slip loads: forward
//! sensitivities of the discrete method (docs/MODEL.md § Sensitivities).
//!
//! Damper q's bounds are ∓F_q. The step is affine in the state and the friction forces,
//! and the forces solve the box QP F = argmin ½FᵀWF − Fᵀw_free over F⁻ ≤ F ≤ F⁺: a
//! projection, continuous and piecewise affine in w_free and the bounds. On the pattern the
//! QP ends on, a force held at a bound moves with it (∂F_c/∂F_q = ∓1 for damper q's own
//! contact, 0 for a storey's plastic element, whose bounds are its yield forces), and the
//! free (stuck) forces keep their slip rates zero: W_FF ∂F_F = ∂w_free,F − W_FA ∂F_A. A
//! contact whose bounds coincide (a damper at zero slip load) slides with the sign of its
//! slip rate, and its force moves with the bound on that side (the one-sided derivative
//! at F = 0). Every other part of the step (predictors, the linear operator, the free slip
//! rates, the elastic–perfectly plastic updates) is linear, so the tangent of the state,
//! one column per damper, is stepped by the same operators as the state itself.
//!
//! A peak's derivative is that of the response at the step where the peak was last
//! raised (the same strict comparison as [`Peaks`]); the residual drift's is the last
//! step's. The run starts from rest, which the slip loads do not change.

use super::link::{EppPred, Link};
use super::operators::{Operators, StepConstants};
use crate::friction::box_qp::Bound;
use crate::integrator::state::EppState;
use crate::plan::{ContactRole, Plan};
use crate::response::{Peaks, Sensitivity};
use nalgebra::DMatrix;

/// The tangent state of a run, one column per damper.
pub(super) struct Tangent {
    n: usize,
    nf: usize,
    nc: usize,
    p: usize,
    alpha: f64,
    /// Damper index of each contact (`None`: a storey's plastic element).
    param: Vec<Option<usize>>,
    /// Bounds of each contact coincide (a damper at zero slip load).
    fixed: Vec<bool>,
    /// The floor of each damper.
    floors: Vec<usize>,
    /// ∂u, ∂v, ∂a, column j at `j * n`.
    du: Vec<f64>,
    dv: Vec<f64>,
    da: Vec<f64>,
    /// ∂ũ, ∂ṽ, ∂a_free, and the weighted predictors (2n per column).
    dut: Vec<f64>,
    dvt: Vec<f64>,
    daf: Vec<f64>,
    dz: Vec<f64>,
    /// Per contact and column (`c * p + j`): the EPP element's state and predictors, the
    /// free slip rate, the forces of the step and of the step before.
    depp: Vec<EppState>,
    dpred: Vec<EppPred>,
    dwfree: Vec<f64>,
    df: Vec<f64>,
    df_old: Vec<f64>,
    /// The free set of the last factorisation of W_FF, and the factor.
    free: Vec<bool>,
    chol: Option<nalgebra::Cholesky<f64, nalgebra::Dyn>>,
    /// Peak tangents, `k * p + j` for storey or floor k.
    peak_drift: Vec<f64>,
    peak_displacement: Vec<f64>,
    peak_acceleration: Vec<f64>,
    peak_base_shear: Vec<f64>,
}

impl Tangent {
    /// The zero tangent of a run from rest of `plan`.
    pub(super) fn new(plan: &Plan, ops: &Operators) -> Tangent {
        let (n, nf, nc) = (ops.n, plan.floors, plan.contacts.len());
        let mut floors = Vec::new();
        let param: Vec<Option<usize>> = plan
            .contacts
            .iter()
            .map(|c| match c.role {
                ContactRole::Damper => {
                    floors.push(c.floor);
                    Some(floors.len() - 1)
                }
                ContactRole::Storey => None,
            })
            .collect();
        let p = floors.len();
        Tangent {
            n,
            nf,
            nc,
            p,
            alpha: ops.alpha,
            param,
            fixed: plan.contacts.iter().map(|c| c.lower == c.upper).collect(),
            floors,
            du: vec![0.0; n * p],
            dv: vec![0.0; n * p],
            da: vec![0.0; n * p],
            dut: vec![0.0; n * p],
            dvt: vec![0.0; n * p],
            daf: vec![0.0; n * p],
            dz: vec![0.0; 2 * n],
            depp: vec![EppState::default(); nc * p],
            dpred: vec![EppPred::default(); nc * p],
            dwfree: vec![0.0; nc * p],
            df: vec![0.0; nc * p],
            df_old: vec![0.0; nc * p],
            free: Vec::new(),
            chol: None,
            peak_drift: vec![0.0; nf * p],
            peak_displacement: vec![0.0; nf * p],
            peak_acceleration: vec![0.0; nf * p],
            peak_base_shear: vec![0.0; p],
        }
    }

    /// One step of the tangent, after the state's: `status` of each contact at the
    /// solution of the step's QP and `rate` its slip rate (the sign a contact with
    /// coincident bounds slides with).
    pub(super) fn step(
        &mut self,
        ops: &Operators,
        links: &[Link],
        k: &StepConstants,
        status: impl Fn(usize) -> Bound,
        rate: &[f64],
    ) {
        let (n, nc, p, alpha) = (self.n, self.nc, self.p, self.alpha);
        if p == 0 {
            return;
        }
        for idx in 0..n * p {
            let (u, v, a) = (self.du[idx], self.dv[idx], self.da[idx]);
            self.dut[idx] = u + k.dt * v + k.c_u * a;
            self.dvt[idx] = v + k.c_v * a;
        }
        let q = ops.q.as_slice();
        let g = ops.g.as_slice();
        for j in 0..p {
            let col = j * n..(j + 1) * n;
            for i in 0..n {
                let (c, x) = (col.start + i, 1.0 + alpha);
                self.dz[i] = x * self.dut[c] - alpha * self.du[c];
                self.dz[n + i] = x * self.dvt[c] - alpha * self.dv[c];
            }
            let daf = &mut self.daf[col.clone()];
            daf.fill(0.0);
            for (m, &zm) in self.dz.iter().enumerate() {
                if zm != 0.0 {
                    for (d, qv) in daf.iter_mut().zip(&q[m * n..(m + 1) * n]) {
                        *d += qv * zm;
                    }
                }
            }
            if alpha != 0.0 {
                let w = alpha / (1.0 + alpha);
                for c in 0..nc {
                    let f = self.df_old[c * p + j];
                    if f != 0.0 {
                        for (d, gv) in daf.iter_mut().zip(&g[c * n..(c + 1) * n]) {
                            *d += w * f * gv;
                        }
                    }
                }
            }
            for (c, l) in links.iter().enumerate() {
                let (w, pred) = l.free_slip_rate(
                    k,
                    self.depp[c * p + j],
                    (
                        &self.du[col.clone()],
                        &self.dut[col.clone()],
                        &self.dvt[col.clone()],
                    ),
                    &self.daf[col.clone()],
                );
                self.dwfree[c * p + j] = w;
                self.dpred[c * p + j] = pred;
            }
        }
        self.forces(ops, &status, rate);
        let wm = ops.w.as_slice();
        for j in 0..p {
            let col = j * n..(j + 1) * n;
            for c in 0..nc {
                let f = self.df[c * p + j];
                if f != 0.0 {
                    for (d, gv) in self.daf[col.clone()].iter_mut().zip(&g[c * n..(c + 1) * n]) {
                        *d -= f * gv;
                    }
                }
            }
            for i in col.clone() {
                let a = self.daf[i];
                self.da[i] = a;
                self.du[i] = self.dut[i] + k.bdt2 * a;
                self.dv[i] = self.dvt[i] + k.gdt * a;
            }
            for (c, l) in links.iter().enumerate() {
                if !l.epp {
                    continue;
                }
                let mut wf = 0.0;
                for m in 0..nc {
                    wf += wm[c * nc + m] * self.df[m * p + j];
                }
                let dw = self.dwfree[c * p + j] - wf;
                let pred = self.dpred[c * p + j];
                let (uf, vf) = (self.du[col.start + l.floor], self.dv[col.start + l.floor]);
                self.depp[c * p + j] = if l.algebraic {
                    l.algebraic_update(k, (pred.base, dw), uf, vf).0
                } else {
                    Link::epp_update(k, pred, vf, dw)
                };
            }
        }
        std::mem::swap(&mut self.df, &mut self.df_old);
    }

    /// The forces' tangent of the step into `df` (see the module doc).
    fn forces(&mut self, ops: &Operators, status: &impl Fn(usize) -> Bound, rate: &[f64]) {
        let (nc, p) = (self.nc, self.p);
        let mut free = vec![false; nc];
        for c in 0..nc {
            let side = match status(c) {
                Bound::Free => {
                    free[c] = true;
                    0.0
                }
                _ if self.fixed[c] => rate[c].signum() * f64::from(rate[c] != 0.0),
                Bound::Lower => -1.0,
                Bound::Upper => 1.0,
            };
            let row = &mut self.df[c * p..(c + 1) * p];
            row.fill(0.0);
            if let Some(q) = self.param[c] {
                row[q] = side;
            }
        }
        let idx: Vec<usize> = (0..nc).filter(|&c| free[c]).collect();
        if idx.is_empty() {
            return;
        }
        if free != self.free {
            let wff = DMatrix::from_fn(idx.len(), idx.len(), |a, b| ops.w[(idx[a], idx[b])]);
            self.chol = wff.cholesky();
            self.free = free;
        }
        let mut rhs = DMatrix::from_fn(idx.len(), p, |a, j| {
            let c = idx[a];
            let mut r = self.dwfree[c * p + j];
            for m in 0..nc {
                if !self.free[m] {
                    r -= ops.w[(c, m)] * self.df[m * p + j];
                }
            }
            r
        });
        // (W_FF is positive definite wherever the QP's solution is unique; a singular one
        // leaves the stuck forces' tangent at zero)
        if let Some(ch) = &self.chol {
            ch.solve_mut(&mut rhs);
            for (a, &c) in idx.iter().enumerate() {
                for j in 0..p {
                    self.df[c * p + j] = rhs[(a, j)];
                }
            }
        }
    }

    /// Before `peaks` observe the step's floors: the tangent of every peak this step
    /// raises (displacements `u`, relative accelerations `a`, ground acceleration `ag`;
    /// `shear` the signed base shear and `mr` the floors' M r).
    pub(super) fn observe(
        &mut self,
        peaks: &Peaks,
        (u, a, ag): (&[f64], &[f64], f64),
        shear: f64,
        mr: &[f64],
    ) {
        let (n, p) = (self.n, self.p);
        for i in 0..self.nf {
            let below = if i > 0 { u[i - 1] } else { 0.0 };
            let d = u[i] - below;
            if d.abs() > peaks.drift[i] {
                for j in 0..p {
                    let db = if i > 0 { self.du[j * n + i - 1] } else { 0.0 };
                    self.peak_drift[i * p + j] = d.signum() * (self.du[j * n + i] - db);
                }
            }
            if u[i].abs() > peaks.displacement[i] {
                for j in 0..p {
                    self.peak_displacement[i * p + j] = u[i].signum() * self.du[j * n + i];
                }
            }
            let acc = a[i] + ag;
            if acc.abs() > peaks.abs_acceleration[i] {
                for j in 0..p {
                    self.peak_acceleration[i * p + j] = acc.signum() * self.da[j * n + i];
                }
            }
        }
        if shear.abs() > peaks.base_shear {
            for j in 0..p {
                let col = &self.da[j * n..(j + 1) * n];
                let d: f64 = mr.iter().zip(col).map(|(m, a)| m * a).sum();
                self.peak_base_shear[j] = shear.signum() * d;
            }
        }
    }

    /// The run's sensitivities, from its last displacements `u`.
    pub(super) fn finish(self, u: &[f64]) -> Sensitivity {
        let (n, nf, p) = (self.n, self.nf, self.p);
        let rows = |v: &[f64]| -> Vec<Vec<f64>> {
            (0..nf).map(|k| v[k * p..(k + 1) * p].to_vec()).collect()
        };
        let residual = (0..nf)
            .map(|i| {
                let d = u[i] - if i > 0 { u[i - 1] } else { 0.0 };
                (0..p)
                    .map(|j| {
                        let db = if i > 0 { self.du[j * n + i - 1] } else { 0.0 };
                        d.signum() * (self.du[j * n + i] - db)
                    })
                    .collect()
            })
            .collect();
        Sensitivity {
            dampers: self.floors.clone(),
            peak_drift: rows(&self.peak_drift),
            residual_drift: residual,
            peak_displacement: rows(&self.peak_displacement),
            peak_abs_acceleration: rows(&self.peak_acceleration),
            peak_base_shear: self.peak_base_shear,
        }
    }
}
