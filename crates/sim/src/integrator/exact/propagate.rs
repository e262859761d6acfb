//! Propagation: the truncated exponential series of a mode set, summed per substep
//! ([`taylor`]) or cached as grid propagators ([`Stepping`]) once the mode set has lasted.

use super::gauss::GAUSS;
use super::kernels::{SparseRows, col, dot};
use super::model::{ModeOps, Model, Stepping};
use super::params::{LEAD_TERMS, TAYLOR_TERMS};
use nalgebra::{DMatrix, DVector};

impl Model<'_> {
    /// The grid propagators of a mode set.
    pub(super) fn stepping(&self, ops: &ModeOps) -> Stepping {
        let dim = self.lay.dim;
        let nf = self.plan.drifts.len();
        let h = ops.h;
        // exp(A τ) = Σ_k (Aᵏ/k!) τᵏ, the powers formed once for every τ.
        let mut powers = Vec::with_capacity(TAYLOR_TERMS);
        powers.push(DMatrix::identity(dim, dim));
        for k in 1..TAYLOR_TERMS {
            // Aᵏ/k! column by column, with A's nonzeros only.
            let prev: &DMatrix<f64> = &powers[k - 1];
            let mut next = DMatrix::zeros(dim, dim);
            for c in 0..dim {
                ops.a_rows.mul_into(
                    1.0 / k as f64,
                    prev.column(c).as_slice(),
                    next.column_mut(c).as_mut_slice(),
                );
            }
            powers.push(next);
        }
        let expm = |tau: f64| {
            let mut phi = powers[TAYLOR_TERMS - 1].clone();
            for pk in powers[..TAYLOR_TERMS - 1].iter().rev() {
                phi *= tau;
                phi += pk;
            }
            phi
        };
        let phi = expm(h);
        let phi_out = (ops.out_steps >= 2).then(|| expm(self.plan.method.dt));
        let work = self.plan.outputs.energies.then(|| {
            let forms = self.power_forms(ops);
            let forms = &forms[..if self.storeys { 4 } else { 3 }];
            let mut work = [(); 4].map(|_| DMatrix::zeros(dim, dim));
            if !self.storeys {
                work[3] = DMatrix::zeros(0, 0);
            }
            for (x, w) in GAUSS {
                let phi_g = expm(x * h);
                for (wp, q) in work.iter_mut().zip(forms) {
                    let qphi = q * &phi_g;
                    wp.gemm_tr(w * h, &phi_g, &qphi, 1.0);
                }
            }
            work
        });
        let nfun = ops.events.len() + nf;
        let mut rows = DMatrix::zeros(dim, nfun * TAYLOR_TERMS);
        let mut tails = DMatrix::zeros(dim, nfun);
        let mut tails_far = DMatrix::zeros(dim, nfun);
        let mut rate_tails_far = DMatrix::zeros(dim, nfun);
        let mut next_r = DVector::zeros(dim);
        for f in 0..nfun {
            let mut r = if f < ops.events.len() {
                ops.events[f].row.clone()
            } else {
                let (top, bottom) = &self.plan.drifts[f - ops.events.len()];
                let mut d = DVector::zeros(dim);
                top.add(d.as_mut_slice(), 1.0);
                bottom.add(d.as_mut_slice(), -1.0);
                d
            };
            let mut hk = 1.0;
            let mut hk1 = 1.0;
            for k in 0..TAYLOR_TERMS {
                if k > 0 {
                    // r Aᵏ/k! = (r Aᵏ⁻¹/(k−1)!) A / k, with A's nonzeros only
                    ops.a_rows
                        .row_mul_into(1.0 / k as f64, r.as_slice(), next_r.as_mut_slice());
                    std::mem::swap(&mut r, &mut next_r);
                    if k > 1 {
                        hk1 *= h;
                    }
                    hk *= h;
                    for j in 0..dim {
                        tails[(j, f)] += r[j].abs() * hk;
                        if k >= LEAD_TERMS {
                            tails_far[(j, f)] += r[j].abs() * hk;
                            rate_tails_far[(j, f)] += k as f64 * r[j].abs() * hk1;
                        }
                    }
                }
                rows.set_column(f * TAYLOR_TERMS + k, &r);
            }
        }
        let nobs = ops.obs_rows.ncols();
        let mut obs_tails = DMatrix::zeros(dim, nobs);
        for o in 0..nobs {
            let mut r = ops.obs_rows.column(o).into_owned();
            let mut hk = 1.0;
            for k in 1..TAYLOR_TERMS {
                ops.a_rows
                    .row_mul_into(1.0 / k as f64, r.as_slice(), next_r.as_mut_slice());
                std::mem::swap(&mut r, &mut next_r);
                hk *= h;
                for j in 0..dim {
                    obs_tails[(j, o)] += r[j].abs() * hk;
                }
            }
        }
        Stepping {
            phi,
            obs_tails,
            phi_out,
            work,
            rows,
            tails,
            tails_far,
            rate_tails_far,
        }
    }
}

/// The leading Taylor coefficients c_k, 1 ≤ k < [`LEAD_TERMS`], of scanned function `f`
/// from `y` (c_k = its Taylor row · y).
#[inline]
pub(super) fn lead_coefs(st: &Stepping, f: usize, y: &DVector<f64>) -> [f64; LEAD_TERMS - 1] {
    std::array::from_fn(|i| dot(col(&st.rows, f * TAYLOR_TERMS + i + 1), y.as_slice()))
}

/// The leading terms c_k lenᵏ of [`lead_coefs`], each the largest |c_k τᵏ| on [0, len]:
/// so g(0) + Σ min(0, ·) bounds g(0) + Σ c_k τᵏ from below there, |g(0)| + Σ |·| from
/// above.
#[inline]
pub(super) fn lead_terms(c: &[f64; LEAD_TERMS - 1], len: f64) -> [f64; LEAD_TERMS - 1] {
    let mut lk = 1.0;
    std::array::from_fn(|i| {
        lk *= len;
        c[i] * lk
    })
}

/// Whether Σ_{1≤k<L} k c_k τᵏ⁻¹ (the leading part of g′) keeps one sign on [0, len] by a
/// margin above `rest` (a bound on the other terms of g′ there): then g is monotone on
/// [0, len]. The leading part is the quadratic c₁ + 2c₂τ + 3c₃τ², whose extremes on the
/// interval are at its ends or its vertex.
#[inline]
pub(super) fn monotone(c: &[f64; LEAD_TERMS - 1], len: f64, rest: f64) -> bool {
    let [c1, c2, c3] = *c;
    let q = |t: f64| c1 + t * (2.0 * c2 + t * 3.0 * c3);
    let (a, b) = (q(0.0), q(len));
    let (mut lo, mut hi) = (a.min(b), a.max(b));
    if c3 != 0.0 {
        let tv = -c2 / (3.0 * c3);
        if tv > 0.0 && tv < len {
            let v = q(tv);
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    lo > rest || hi < -rest
}

/// The Taylor coefficients p_k = Aᵏ y / k! of exp(Aτ) y.
pub(super) fn taylor(a: &SparseRows, y: &DVector<f64>, p: &mut [DVector<f64>]) {
    p[0].copy_from(y);
    for k in 1..p.len() {
        let (lo, hi) = p.split_at_mut(k);
        a.mul_into(1.0 / k as f64, lo[k - 1].as_slice(), hi[0].as_mut_slice());
    }
}
