//! The dense kernels of the box-QP solver: dot products in four partial sums, `y += a x`,
//! and the in-place Cholesky factorisation and solve of a leading block (row-major), with
//! the pivot floor below which a pivot is round-off.

/// `aᵀb` over the shorter length, with four partial sums so that it vectorises.
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for l in 0..4 {
            acc[l] += x[l] * y[l];
        }
    }
    (acc[0] + acc[2]) + (acc[1] + acc[3]) + tail
}

/// `y += a x`.
pub(super) fn axpy(a: f64, x: &[f64], y: &mut [f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

/// Smallest acceptable Cholesky pivot for a variable with diagonal `w_ii` in an m×m problem:
/// below this the pivot is indistinguishable from round-off.
pub(super) fn pivot_floor(m: usize, w_ii: f64) -> f64 {
    4.0 * m as f64 * f64::EPSILON * w_ii
}

/// In-place Cholesky factorisation `A = L Lᵀ` of the leading `k×k` block of `a` (row-major,
/// leading dimension `ld`, lower triangle read and overwritten). On a pivot not above
/// `floor(q)` returns `Err((q, pivot))`.
pub(super) fn cholesky_in_place(
    a: &mut [f64],
    k: usize,
    ld: usize,
    floor: impl Fn(usize) -> f64,
) -> Result<(), (usize, f64)> {
    for j in 0..k {
        let rj = j * ld;
        let s = a[rj + j] - dot(&a[rj..rj + j], &a[rj..rj + j]);
        if s.is_nan() || s <= floor(j) {
            return Err((j, s));
        }
        let d = s.sqrt();
        a[rj + j] = d;
        for i in j + 1..k {
            let ri = i * ld;
            let s = a[ri + j] - dot(&a[ri..ri + j], &a[rj..rj + j]);
            a[ri + j] = s / d;
        }
    }
    Ok(())
}

/// Solves `L Lᵀ x = y` in place for the leading `k×k` factor `l` (row-major, leading
/// dimension `ld`).
pub(super) fn cholesky_solve(l: &[f64], k: usize, ld: usize, y: &mut [f64]) {
    for q in 0..k {
        let rq = q * ld;
        let s = y[q] - dot(&l[rq..rq + q], &y[..q]);
        y[q] = s / l[rq + q];
    }
    for q in (0..k).rev() {
        let rq = q * ld;
        let xq = y[q] / l[rq + q];
        y[q] = xq;
        axpy(-xq, &l[rq..rq + q], &mut y[..q]);
    }
}
