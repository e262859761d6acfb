//! Propagation: the truncated exponential series of a mode set, summed per substep
//! ([`taylor`]) or cached as grid propagators ([`Stepping`]) once the mode set has lasted.

use super::energy::GAUSS;
use super::modes::{ModeOps, Model, SparseRows};
use super::{LEAD_TERMS, TAYLOR_TERMS};
use nalgebra::{DMatrix, DVector};

/// What the grid substeps of one long-lived mode set reuse: the propagator over one grid
/// interval, and every scanned function (events, then storey drifts) as Taylor rows so its
/// coefficients are one product with y.
pub(super) struct Stepping {
    /// exp(A h) (its Taylor polynomial, exact to round-off as above), dim × dim.
    pub(super) phi: DMatrix<f64>,
    /// The input, viscous and friction work over one grid interval as quadratic forms of
    /// its starting state, h Σ_g w_g exp(A x_g h)ᵀ Q_p exp(A x_g h) for each power
    /// p(y) = yᵀ Q_p y: the same 6-point Gauss–Legendre rule as [`Model::integrate_powers`],
    /// summed once per mode set instead of once per substep. `None` when energies are off.
    /// The plastic work's form is formed only when a storey yields (`work[3]` empty
    /// otherwise).
    pub(super) work: Option<[DMatrix<f64>; 4]>,
    /// Column f·K + k: the k-th Taylor row r Aᵏ/k! of scanned function f, so that its
    /// coefficient on τᵏ over a substep from y is that column · y.
    pub(super) rows: DMatrix<f64>,
    /// Column f: Σ_{k≥1} |r Aᵏ/k!| hᵏ componentwise, so that |g(τ) − g(0)| ≤ Σ_j |y_j|·tail_j
    /// for τ ≤ h (every term is nonnegative and grows with τ).
    pub(super) tails: DMatrix<f64>,
    /// Column f: Σ_{k≥LEAD_TERMS} |r Aᵏ/k!| hᵏ componentwise, the part of the tail past the
    /// leading coefficients, which the second test forms exactly.
    pub(super) tails_far: DMatrix<f64>,
    /// Column f: Σ_{k≥LEAD_TERMS} k |r Aᵏ/k!| hᵏ⁻¹ componentwise, the same bound on the
    /// rate g′(τ) past its leading terms: where the leading part of g′ keeps one sign by
    /// more than Σ|y_j|·rate_tail_j, g is monotone on the substep (a drift's peak there is
    /// at an end).
    pub(super) rate_tails_far: DMatrix<f64>,
    /// Column o: Σ_{k≥1} |r_o Aᵏ/k!| hᵏ componentwise for observed function o
    /// ([`ModeOps::obs_rows`]), so that |g_o(τ)| ≤ |g_o(0)| + Σ_j |y_j|·tail_j on a
    /// substep no longer than h: where that stays within the function's sampled peak, no
    /// output step inside the substep can raise it.
    pub(super) obs_tails: DMatrix<f64>,
    /// exp(A Δt) over one output step, when a grid substep holds several
    /// ([`ModeOps::out_steps`] ≥ 2): the states at the output steps inside it, one product
    /// each.
    pub(super) phi_out: Option<DMatrix<f64>>,
}

impl Model<'_> {
    /// The grid propagators of a mode set.
    pub(super) fn stepping(&self, ops: &ModeOps) -> Stepping {
        let dim = self.lay.dim;
        let nf = self.plan.floors;
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
                let i = f - ops.events.len();
                let mut d = DVector::zeros(dim);
                d[i] = 1.0;
                if i > 0 {
                    d[i - 1] = -1.0;
                }
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

/// Column `j` of a column-major matrix, as a slice.
#[inline]
pub(super) fn col(m: &DMatrix<f64>, j: usize) -> &[f64] {
    let r = m.nrows();
    &m.as_slice()[j * r..(j + 1) * r]
}

/// Σ a_i b_i over slices of equal length, in four interleaved partial sums (the step
/// loop's scalar products: no views, no shape checks, vectorisable).
#[inline]
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut s = [0.0f64; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        s[0] += x[0] * y[0];
        s[1] += x[1] * y[1];
        s[2] += x[2] * y[2];
        s[3] += x[3] * y[3];
    }
    let mut t = (s[0] + s[1]) + (s[2] + s[3]);
    for (x, y) in ra.iter().zip(rb) {
        t += x * y;
    }
    t
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

/// out = M x for a column-major M: the columns scaled and summed in order, over plain
/// slices so the compiler vectorises the inner loop (the step loop's products with the
/// propagators are small and dynamic-sized, where a generic product pays for its
/// strides).
#[inline]
pub(super) fn mat_vec(m: &DMatrix<f64>, x: &[f64], out: &mut [f64]) {
    let r = m.nrows();
    let out = &mut out[..r];
    let mut cols = m.as_slice().chunks_exact(r).zip(x);
    if let Some((c0, &x0)) = cols.next() {
        for (o, a) in out.iter_mut().zip(c0) {
            *o = a * x0;
        }
    } else {
        out.fill(0.0);
    }
    for (c, &xj) in cols {
        for (o, a) in out.iter_mut().zip(c) {
            *o += a * xj;
        }
    }
}

/// yᵀ Q y, with `scratch` for Q y.
#[inline]
pub(super) fn quadratic(q: &DMatrix<f64>, y: &DVector<f64>, scratch: &mut DVector<f64>) -> f64 {
    mat_vec(q, y.as_slice(), scratch.as_mut_slice());
    y.dot(scratch)
}

/// The Taylor coefficients p_k = Aᵏ y / k! of exp(Aτ) y.
pub(super) fn taylor(a: &SparseRows, y: &DVector<f64>, p: &mut [DVector<f64>]) {
    p[0].copy_from(y);
    for k in 1..p.len() {
        let (lo, hi) = p.split_at_mut(k);
        a.mul_into(1.0 / k as f64, lo[k - 1].as_slice(), hi[0].as_mut_slice());
    }
}
