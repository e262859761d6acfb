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

use super::link::{EppPred, GROUND, Link};
use super::operators::{Operators, StepConstants};
use crate::friction::box_qp::Bound;
use crate::integrator::state::EppState;
use crate::plan::{ContactRole, Plan};
use crate::response::{Peaks, Sensitivity};
use nalgebra::DMatrix;
use std::collections::HashMap;

/// Most stick/slip patterns whose factor is kept (past it the cache starts again).
const MAX_PATTERNS: usize = 4096;

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
    /// Every contact is an algebraic EPP element: the lane loops serve (see
    /// [`Tangent::algebraic_free_rates`]).
    lanes: bool,
    /// The floor of each damper.
    floors: Vec<usize>,
    /// ∂u, ∂v, ∂a (n × p, column j for damper j).
    du: DMatrix<f64>,
    dv: DMatrix<f64>,
    da: DMatrix<f64>,
    /// ∂ũ, ∂ṽ, ∂a_free (n × p), and the weighted predictors (2n × p).
    dut: DMatrix<f64>,
    dvt: DMatrix<f64>,
    daf: DMatrix<f64>,
    dz: DMatrix<f64>,
    /// Per contact and column (`c * p + j`): the EPP element's state and predictors.
    depp: Vec<EppState>,
    dpred: Vec<EppPred>,
    /// ∂w_free, ∂F of the step and of the step before, and W ∂F (nc × p).
    dwfree: DMatrix<f64>,
    df: DMatrix<f64>,
    df_old: DMatrix<f64>,
    wdf: DMatrix<f64>,
    /// The step's stick/slip pattern: each contact stuck, and the stuck ones.
    is_free: Vec<bool>,
    free_idx: Vec<usize>,
    /// The contact of each damper's column that slides this step (its ∂F entry ±1).
    sliding: Vec<Option<usize>>,
    /// The slot in `factors` of each pattern met, and W_FF⁻¹ (row-major) per slot, from
    /// its Cholesky factor (`None`: W_FF singular).
    patterns: HashMap<Vec<bool>, usize>,
    factors: Vec<Option<Vec<f64>>>,
    /// The pattern of the last step that had stuck forces, and its slot.
    last_pattern: Vec<bool>,
    last_slot: usize,
    /// Right-hand sides of the stuck forces and their solution, row-major (m × p).
    rhs: Vec<f64>,
    sol: Vec<f64>,
    /// Peak tangents, `k * p + j` for storey or floor k.
    peak_drift: Vec<f64>,
    peak_displacement: Vec<f64>,
    peak_acceleration: Vec<f64>,
    peak_base_shear: Vec<f64>,
}

impl Tangent {
    /// The zero tangent of a run from rest of `plan`.
    pub(super) fn new(plan: &Plan, ops: &Operators, links: &[Link]) -> Tangent {
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
            lanes: links.iter().all(|l| l.epp && l.algebraic),
            floors,
            du: DMatrix::zeros(n, p),
            dv: DMatrix::zeros(n, p),
            da: DMatrix::zeros(n, p),
            dut: DMatrix::zeros(n, p),
            dvt: DMatrix::zeros(n, p),
            daf: DMatrix::zeros(n, p),
            dz: DMatrix::zeros(2 * n, p),
            depp: vec![EppState::default(); nc * p],
            dpred: vec![EppPred::default(); nc * p],
            dwfree: DMatrix::zeros(nc, p),
            df: DMatrix::zeros(nc, p),
            df_old: DMatrix::zeros(nc, p),
            wdf: DMatrix::zeros(nc, p),
            is_free: vec![false; nc],
            free_idx: Vec::with_capacity(nc),
            sliding: vec![None; p],
            patterns: HashMap::new(),
            factors: Vec::new(),
            last_pattern: Vec::new(),
            last_slot: 0,
            rhs: Vec::new(),
            sol: Vec::new(),
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
        let (n, p, alpha) = (self.n, self.p, self.alpha);
        if p == 0 {
            return;
        }
        {
            let (du, dv, da) = (self.du.as_slice(), self.dv.as_slice(), self.da.as_slice());
            let (dut, dvt) = (self.dut.as_mut_slice(), self.dvt.as_mut_slice());
            for i in 0..n * p {
                dut[i] = du[i] + k.dt * dv[i] + k.c_u * da[i];
                dvt[i] = dv[i] + k.c_v * da[i];
            }
        }
        let x = 1.0 + alpha;
        for j in 0..p {
            for i in 0..n {
                self.dz[(i, j)] = x * self.dut[(i, j)] - alpha * self.du[(i, j)];
                self.dz[(n + i, j)] = x * self.dvt[(i, j)] - alpha * self.dv[(i, j)];
            }
        }
        // ∂a_free = Q ∂z (+ the HHT memory of the forces)
        self.daf.gemm(1.0, &ops.q, &self.dz, 0.0);
        if alpha != 0.0 {
            self.daf
                .gemm(alpha / (1.0 + alpha), &ops.g, &self.df_old, 1.0);
        }
        let lanes = self.lanes;
        if lanes {
            self.algebraic_free_rates(links, k);
        }
        for j in (0..p).filter(|_| !lanes) {
            let col = j * n..(j + 1) * n;
            for (c, l) in links.iter().enumerate() {
                let (w, pred) = l.free_slip_rate(
                    k,
                    self.depp[c * p + j],
                    (
                        &self.du.as_slice()[col.clone()],
                        &self.dut.as_slice()[col.clone()],
                        &self.dvt.as_slice()[col.clone()],
                    ),
                    &self.daf.as_slice()[col.clone()],
                );
                self.dwfree[(c, j)] = w;
                self.dpred[c * p + j] = pred;
            }
        }
        self.forces(ops, &status, rate);
        // ∂a = ∂a_free − G ∂F, then the Newmark update
        self.daf.gemm(-1.0, &ops.g, &self.df, 1.0);
        {
            let (dut, dvt, daf) = (
                self.dut.as_slice(),
                self.dvt.as_slice(),
                self.daf.as_slice(),
            );
            let (du, dv, da) = (
                self.du.as_mut_slice(),
                self.dv.as_mut_slice(),
                self.da.as_mut_slice(),
            );
            for i in 0..n * p {
                da[i] = daf[i];
                du[i] = dut[i] + k.bdt2 * daf[i];
                dv[i] = dvt[i] + k.gdt * daf[i];
            }
        }
        // a sliding EPP element's slip moves with ∂w = ∂w_free − W ∂F; a stuck one's stays
        // zero (W_FF ∂F_F + W_FA ∂F_A = ∂w_free,F)
        // (row c of W ∂F for the sliding EPP elements alone, over ∂F's nonzero rows: the
        // stuck forces and each column's sliding damper; W is symmetric, so its column c
        // is read)
        for (c, l) in links.iter().enumerate() {
            if !l.epp || self.is_free[c] {
                continue;
            }
            let wc = ops.w.column(c);
            for j in 0..p {
                let dfj = self.df.column(j);
                let mut v = 0.0;
                for &f in &self.free_idx {
                    v += wc[f] * dfj[f];
                }
                if let Some(cq) = self.sliding[j] {
                    v += wc[cq] * dfj[cq];
                }
                self.wdf[(c, j)] = v;
            }
        }
        if lanes {
            self.algebraic_updates(links);
            std::mem::swap(&mut self.df, &mut self.df_old);
            return;
        }
        for (c, l) in links.iter().enumerate() {
            if !l.epp {
                continue;
            }
            for j in 0..p {
                let dw = if self.is_free[c] {
                    0.0
                } else {
                    self.dwfree[(c, j)] - self.wdf[(c, j)]
                };
                let pred = self.dpred[c * p + j];
                let fl = l.chain_ends().0;
                let (uf, vf) = (self.du[(fl, j)], self.dv[(fl, j)]);
                self.depp[c * p + j] = if l.algebraic {
                    l.algebraic_update(k, (pred.base, dw), uf, vf).0
                } else {
                    Link::epp_update(k, pred, vf, dw)
                };
            }
        }
        std::mem::swap(&mut self.df, &mut self.df_old);
    }

    /// The free slip rates' tangent when every contact is an algebraic EPP element (a
    /// chain of massless dampers on braces without dashpots and yielding storeys: the
    /// studies' frames), all dampers' columns of a contact at once: the linear map of
    /// [`Link::free_slip_rate`]'s algebraic branch, (∂ũ_floor − ∂ũ_below + ∂u′ − ∂u_floor)
    /// k′/κ + γΔt (∂a_floor − ∂a_below), with ∂u′ the condensed DOF's tangent (`depp[..].u`)
    /// and ∂u′ − ∂u_floor kept as the step's base.
    fn algebraic_free_rates(&mut self, links: &[Link], k: &StepConstants) {
        let (n, p) = (self.n, self.p);
        let (du, dut, daf) = (self.du.as_slice(), self.dut.as_slice(), self.daf.as_slice());
        for (c, l) in links.iter().enumerate() {
            let ((f, other), kk) = (l.chain_ends(), l.k_over_kappa);
            for j in 0..p {
                let col = j * n;
                let (ub, ab) = if other == GROUND {
                    (0.0, 0.0)
                } else {
                    (dut[col + other], daf[col + other])
                };
                let base = self.depp[c * p + j].u - du[col + f];
                self.dpred[c * p + j].base = base;
                self.dwfree[(c, j)] = (dut[col + f] - ub + base) * kk + k.gdt * (daf[col + f] - ab);
            }
        }
    }

    /// The EPP elements' tangent after the step when every contact is algebraic: the
    /// linear map of [`Link::algebraic_update`], ∂u′ = ∂u_floor + base − ∂w k′⁻¹κ with
    /// ∂w = 0 for a stuck element (its slip rate stays zero) and ∂w_free − W ∂F for a
    /// sliding one.
    fn algebraic_updates(&mut self, links: &[Link]) {
        let (n, p) = (self.n, self.p);
        let du = self.du.as_slice();
        for (c, l) in links.iter().enumerate() {
            let free = self.is_free[c];
            let inv = 1.0 / l.k_over_kappa;
            for j in 0..p {
                let dw = if free {
                    0.0
                } else {
                    self.dwfree[(c, j)] - self.wdf[(c, j)]
                };
                let e = &mut self.depp[c * p + j];
                e.u = du[j * n + l.chain_ends().0] + self.dpred[c * p + j].base - dw * inv;
            }
        }
    }

    /// The forces' tangent of the step into `df` (see the module doc): a sliding
    /// damper's moves with its bound, a yielding storey's not at all, the stuck ones solve
    /// W_FF ∂F_F = ∂w_free,F − W_FA ∂F_A with W_FF's Cholesky factor, kept per stick/slip
    /// pattern (a run visits few patterns, and returns to them).
    fn forces(&mut self, ops: &Operators, status: &impl Fn(usize) -> Bound, rate: &[f64]) {
        let p = self.p;
        self.free_idx.clear();
        self.df.fill(0.0);
        self.sliding.fill(None);
        let mut any_sliding = false;
        for (c, &rate_c) in rate.iter().enumerate().take(self.nc) {
            let side = match status(c) {
                Bound::Free => {
                    self.is_free[c] = true;
                    self.free_idx.push(c);
                    continue;
                }
                _ if self.fixed[c] => rate_c.signum() * f64::from(rate_c != 0.0),
                Bound::Lower => -1.0,
                Bound::Upper => 1.0,
            };
            self.is_free[c] = false;
            if let Some(q) = self.param[c] {
                self.df[(c, q)] = side;
                if side != 0.0 {
                    any_sliding = true;
                    self.sliding[q] = Some(c);
                }
            }
        }
        let m = self.free_idx.len();
        if m == 0 {
            return;
        }
        // most steps keep the step before's pattern: it is compared before it is hashed
        if self.last_pattern != self.is_free {
            if self.patterns.len() > MAX_PATTERNS {
                self.patterns.clear();
                self.factors.clear();
            }
            let next = self.factors.len();
            let slot = *self.patterns.entry(self.is_free.clone()).or_insert(next);
            if slot == next {
                let idx = &self.free_idx;
                let wff: Vec<f64> = (0..m * m)
                    .map(|e| ops.w[(idx[e / m], idx[e % m])])
                    .collect();
                self.factors.push(inverse(&wff, m));
            }
            self.last_pattern.clone_from(&self.is_free);
            self.last_slot = slot;
        }
        // (W_FF is positive definite wherever the QP's solution is unique; a singular one
        // leaves the stuck forces' tangent at zero)
        let Some(inv) = &self.factors[self.last_slot] else {
            return;
        };
        // right-hand sides row by row (m × p); a column of ∂F_A holds at most its own
        // damper's ±1, so W_FA ∂F_A is that damper's column of W times ±1 (exactly the
        // product a full W ∂F would form)
        self.rhs.resize(m * p, 0.0);
        for (a, &c) in self.free_idx.iter().enumerate() {
            for j in 0..p {
                self.rhs[a * p + j] = self.dwfree[(c, j)];
            }
        }
        if any_sliding {
            for (q, &cq) in self.sliding.iter().enumerate() {
                let Some(cq) = cq else { continue };
                let side = self.df[(cq, q)];
                for (a, &c) in self.free_idx.iter().enumerate() {
                    self.rhs[a * p + q] -= ops.w[(c, cq)] * side;
                }
            }
        }
        // ∂F_F = W_FF⁻¹ (right-hand sides), row by row over the dampers' columns
        self.sol.clear();
        self.sol.resize(m * p, 0.0);
        for a in 0..m {
            let out = &mut self.sol[a * p..(a + 1) * p];
            for b in 0..m {
                let w = inv[a * m + b];
                for (o, r) in out.iter_mut().zip(&self.rhs[b * p..(b + 1) * p]) {
                    *o += w * r;
                }
            }
        }
        let x = &self.sol;
        for (a, &c) in self.free_idx.iter().enumerate() {
            for j in 0..p {
                self.df[(c, j)] = x[a * p + j];
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
                    let db = if i > 0 {
                        self.du.as_slice()[j * n + i - 1]
                    } else {
                        0.0
                    };
                    self.peak_drift[i * p + j] = d.signum() * (self.du.as_slice()[j * n + i] - db);
                }
            }
            if u[i].abs() > peaks.displacement[i] {
                for j in 0..p {
                    self.peak_displacement[i * p + j] =
                        u[i].signum() * self.du.as_slice()[j * n + i];
                }
            }
            let acc = a[i] + ag;
            if acc.abs() > peaks.abs_acceleration[i] {
                for j in 0..p {
                    self.peak_acceleration[i * p + j] =
                        acc.signum() * self.da.as_slice()[j * n + i];
                }
            }
        }
        if shear.abs() > peaks.base_shear {
            for j in 0..p {
                let col = &self.da.as_slice()[j * n..(j + 1) * n];
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
                        let db = if i > 0 {
                            self.du.as_slice()[j * n + i - 1]
                        } else {
                            0.0
                        };
                        d.signum() * (self.du.as_slice()[j * n + i] - db)
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

/// The inverse (row-major) of the symmetric positive definite m × m matrix `a`
/// (row-major), by its Cholesky factor; `None` when it is not positive definite.
fn inverse(a: &[f64], m: usize) -> Option<Vec<f64>> {
    let l = cholesky(a, m)?;
    let mut inv = vec![0.0; m * m];
    for e in 0..m {
        // L y = e_e, then Lᵀ x = y
        let mut y = vec![0.0; m];
        for i in 0..m {
            let mut v = if i == e { 1.0 } else { 0.0 };
            for k in 0..i {
                v -= l[i * m + k] * y[k];
            }
            y[i] = v / l[i * m + i];
        }
        for i in (0..m).rev() {
            let mut v = y[i];
            for k in i + 1..m {
                v -= l[k * m + i] * inv[k * m + e];
            }
            inv[i * m + e] = v / l[i * m + i];
        }
    }
    Some(inv)
}

/// The Cholesky factor L (row-major, lower triangle) of the symmetric m × m matrix `a`
/// (row-major); `None` when it is not positive definite.
fn cholesky(a: &[f64], m: usize) -> Option<Vec<f64>> {
    let mut l = vec![0.0; m * m];
    for i in 0..m {
        for j in 0..=i {
            let mut sum = a[i * m + j];
            for k in 0..j {
                sum -= l[i * m + k] * l[j * m + k];
            }
            if i == j {
                if sum.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                    return None;
                }
                l[i * m + i] = sum.sqrt();
            } else {
                l[i * m + j] = sum / l[j * m + j];
            }
        }
    }
    Some(l)
}
