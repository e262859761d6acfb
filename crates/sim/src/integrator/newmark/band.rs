//! Symmetric band matrices ([`Band`]) and their banded LDLᵀ factorisation ([`Ldl`]): the
//! linear algebra of `newmark`'s banded step, O(N p²) to factorise and O(N p) to solve,
//! with the shear building's tridiagonal case (p = 1) written out.

use nalgebra::DMatrix;

/// A symmetric band matrix: row i holds A(i, i − d) at `a[i·(p+1) + d]`, d = 0..=p
/// (entries before the first column are zero).
#[derive(Debug, Clone)]
pub(super) struct Band {
    n: usize,
    p: usize,
    pub(super) a: Vec<f64>,
}

impl Band {
    pub(super) fn of(m: &DMatrix<f64>, p: usize) -> Band {
        let n = m.nrows();
        let w = p + 1;
        let mut a = vec![0.0; n * w];
        for i in 0..n {
            for d in 0..=p.min(i) {
                a[i * w + d] = m[(i, i - d)];
            }
        }
        Band { n, p, a }
    }

    /// y −= A x.
    #[inline]
    pub(super) fn mul_sub(&self, x: &[f64], y: &mut [f64]) {
        let w = self.p + 1;
        for i in 0..self.n {
            let row = &self.a[i * w..(i + 1) * w];
            let xi = x[i];
            let mut s = row[0] * xi;
            for d in 1..=self.p.min(i) {
                s += row[d] * x[i - d];
                y[i - d] -= row[d] * xi;
            }
            y[i] -= s;
        }
    }

    /// xᵀ A x.
    #[inline]
    pub(super) fn quad(&self, x: &[f64]) -> f64 {
        let w = self.p + 1;
        let mut total = 0.0;
        for i in 0..self.n {
            let row = &self.a[i * w..(i + 1) * w];
            let mut s = 0.5 * row[0] * x[i];
            for d in 1..=self.p.min(i) {
                s += row[d] * x[i - d];
            }
            total += 2.0 * s * x[i];
        }
        total
    }
}

/// A banded LDLᵀ factorisation: unit lower L in the [`Band`] layout (its diagonal unused)
/// and 1/D.
#[derive(Debug, Clone)]
pub(super) struct Ldl {
    n: usize,
    p: usize,
    l: Vec<f64>,
    d: Vec<f64>,
    dinv: Vec<f64>,
}

impl Ldl {
    pub(super) fn new(n: usize, p: usize) -> Ldl {
        Ldl {
            n,
            p,
            l: vec![0.0; n * (p + 1)],
            d: vec![0.0; n],
            dinv: vec![0.0; n],
        }
    }

    /// Factorises `a` (same size and bandwidth). `false` when a pivot is not above
    /// 4 n ε A(i, i) (not numerically positive definite), or not finite.
    pub(super) fn factor(&mut self, a: &Band) -> bool {
        self.factor_from(a, 0)
    }

    /// Factorises rows `start..` of `a`, whose rows before `start` are those of the matrix
    /// factorised last (row i of L and D depends only on rows ≤ i of A: the same bits as
    /// a factorisation from the first row).
    pub(super) fn factor_from(&mut self, a: &Band, start: usize) -> bool {
        let (n, p) = (self.n, self.p);
        let w = p + 1;
        if p == 1 {
            // the generic recurrence below for one band, without its inner loops
            let floor = 4.0 * n as f64 * f64::EPSILON;
            for i in start..n {
                let aii = a.a[2 * i];
                let mut s = aii;
                if i > 0 {
                    let l = a.a[2 * i + 1] * self.dinv[i - 1];
                    self.l[2 * i + 1] = l;
                    s -= l * l * self.d[i - 1];
                }
                if !(s.is_finite() && s > floor * aii) {
                    return false;
                }
                self.d[i] = s;
                self.dinv[i] = 1.0 / s;
            }
            return true;
        }
        for i in start..n {
            let j0 = i.saturating_sub(p);
            for j in j0..i {
                let mut s = a.a[i * w + (i - j)];
                for k in j0.max(j.saturating_sub(p))..j {
                    s -= self.l[i * w + (i - k)] * self.d[k] * self.l[j * w + (j - k)];
                }
                self.l[i * w + (i - j)] = s * self.dinv[j];
            }
            let aii = a.a[i * w];
            let mut s = aii;
            for k in j0..i {
                let lik = self.l[i * w + (i - k)];
                s -= lik * lik * self.d[k];
            }
            if !(s.is_finite() && s > 4.0 * n as f64 * f64::EPSILON * aii) {
                return false;
            }
            self.d[i] = s;
            self.dinv[i] = 1.0 / s;
        }
        true
    }

    /// Solves A x = b in place.
    #[inline]
    pub(super) fn solve(&self, x: &mut [f64]) {
        self.solve_with(x, |x, i| x[i]);
    }

    /// Solves A x = b with b(i) = `rhs(x, i)`, read as x[i] is first written (so that a
    /// right-hand side formed from other vectors needs no pass of its own).
    #[inline]
    pub(super) fn solve_with(&self, x: &mut [f64], rhs: impl Fn(&[f64], usize) -> f64) {
        let (n, p) = (self.n, self.p);
        let w = p + 1;
        if p == 1 {
            // the shear building's tridiagonal system: the running value stays in a
            // register along the chain of rows
            let (l, dinv) = (&self.l[..2 * n], &self.dinv[..n]);
            let x = &mut x[..n];
            let mut prev = rhs(x, 0);
            x[0] = prev;
            for i in 1..n {
                prev = rhs(x, i) - l[2 * i + 1] * prev;
                x[i] = prev;
            }
            let mut next = x[n - 1] * dinv[n - 1];
            x[n - 1] = next;
            for i in (0..n - 1).rev() {
                next = x[i] * dinv[i] - l[2 * i + 3] * next;
                x[i] = next;
            }
            return;
        }
        for i in 0..n {
            let mut s = rhs(x, i);
            for d in 1..=p.min(i) {
                s -= self.l[i * w + d] * x[i - d];
            }
            x[i] = s;
        }
        for i in (0..n).rev() {
            let mut s = x[i] * self.dinv[i];
            for d in 1..=p.min(n - 1 - i) {
                s -= self.l[(i + d) * w + d] * x[i + d];
            }
            x[i] = s;
        }
    }
}

/// r = load·mr − K zu − C zv for tridiagonal K and C (the shear building's), each row in
/// registers (its diagonal term, then the band below and the band above subtracted, in
/// that order), with no row waiting on another's store.
#[inline]
// The indexed loop: as an iterator (enumerate, skip, take) the 50-storey step measured
// 7 % slower.
#[allow(clippy::needless_range_loop)]
pub(super) fn tri_rhs(
    load: f64,
    mr: &[f64],
    k: &Band,
    zu: &[f64],
    c: &Band,
    zv: &[f64],
    r: &mut [f64],
) {
    let n = r.len();
    let (mr, zu, zv) = (&mr[..n], &zu[..n], &zv[..n]);
    let (ka, ca) = (&k.a[..2 * n], &c.a[..2 * n]);
    let row = |i: usize| load * mr[i] - (ka[2 * i] * zu[i] + ca[2 * i] * zv[i]);
    let below = |i: usize| ka[2 * i + 1] * zu[i - 1] + ca[2 * i + 1] * zv[i - 1];
    let above = |i: usize| ka[2 * i + 3] * zu[i + 1] + ca[2 * i + 3] * zv[i + 1];
    if n == 1 {
        r[0] = row(0);
        return;
    }
    r[0] = row(0) - above(0);
    for i in 1..n - 1 {
        r[i] = (row(i) - below(i)) - above(i);
    }
    r[n - 1] = row(n - 1) - below(n - 1);
}
