//! The step loop's small products, over plain slices or a sparse matrix by rows: a
//! column as a slice, dot products in four interleaved sums, M x and yᵀQy for a
//! column-major M, a contact's row on y ([`row_dot`]), and A by its nonzeros
//! ([`SparseRows`]).

use nalgebra::{DMatrix, DVector};

/// A square matrix by rows, nonzeros only (compressed sparse rows).
pub(super) struct SparseRows {
    /// Row i's entries are `start[i]..start[i + 1]` of `col` and `val`.
    start: Vec<usize>,
    col: Vec<usize>,
    val: Vec<f64>,
}

impl SparseRows {
    /// Stored entries.
    pub(super) fn nnz(&self) -> usize {
        self.val.len()
    }

    pub(super) fn of(m: &DMatrix<f64>) -> SparseRows {
        let mut start = vec![0];
        let (mut col, mut val) = (Vec::new(), Vec::new());
        for i in 0..m.nrows() {
            for j in 0..m.ncols() {
                if m[(i, j)] != 0.0 {
                    col.push(j);
                    val.push(m[(i, j)]);
                }
            }
            start.push(col.len());
        }
        // held as counted (`bytes`): no spare capacity
        col.shrink_to_fit();
        val.shrink_to_fit();
        start.shrink_to_fit();
        SparseRows { start, col, val }
    }

    /// Heap bytes held.
    pub(super) fn bytes(&self) -> usize {
        (self.start.capacity() + self.col.capacity()) * size_of::<usize>()
            + self.val.capacity() * size_of::<f64>()
    }

    /// out = scale · (M x), each row summed in column order.
    #[inline]
    pub(super) fn mul_into(&self, scale: f64, x: &[f64], out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            let (a, b) = (self.start[i], self.start[i + 1]);
            let mut s = 0.0;
            for (j, v) in self.col[a..b].iter().zip(&self.val[a..b]) {
                s += v * x[*j];
            }
            *o = scale * s;
        }
    }

    /// out = scale · (rᵀ M) (a row vector times the matrix), as a column.
    pub(super) fn row_mul_into(&self, scale: f64, r: &[f64], out: &mut [f64]) {
        out.fill(0.0);
        for (i, ri) in r.iter().enumerate() {
            if *ri == 0.0 {
                continue;
            }
            for k in self.start[i]..self.start[i + 1] {
                out[self.col[k]] += ri * self.val[k];
            }
        }
        for o in out.iter_mut() {
            *o *= scale;
        }
    }
}

/// Contact `r`'s row on y, stored as column `r` of `m` (a `ModeOps` row set), times `y`,
/// summed in order without allocating.
#[inline]
pub(super) fn row_dot(m: &DMatrix<f64>, r: usize, y: &DVector<f64>) -> f64 {
    let mut s = 0.0;
    let rows = m.nrows();
    for (mj, yj) in m.as_slice()[r * rows..(r + 1) * rows]
        .iter()
        .zip(y.as_slice())
    {
        s += mj * yj;
    }
    s
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
