//! What a box-QP solve reports: where each variable sits ([`Bound`]), the work done
//! ([`BoxQpStats`]) and the failures ([`BoxQpError`]).

use thiserror::Error;

/// Where a variable sits after a solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Bound {
    /// Strictly inside or, at a tie, on the box but not held there: the damper sticks
    /// (`w_i = 0` to round-off).
    #[default]
    Free,
    /// Held at `lo_i` (`w_i ≤ 0`). Fixed variables (`lo_i = hi_i`) report `Lower`.
    Lower,
    /// Held at `hi_i` (`w_i ≥ 0`).
    Upper,
}

/// Work done by one [`BoxQp::solve`](crate::friction::BoxQp::solve) call.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BoxQpStats {
    /// Active-set iterations: each one is a solve of the free-set linear system (one forward and
    /// one backward triangular solve). A warm start with an unchanged pattern takes 1.
    pub iterations: u32,
    /// Changes to the free-set Cholesky factor: full factorisations plus incremental
    /// insertions and deletions of one variable (each O(k²)). 0 when the pattern is unchanged.
    pub factorizations: u32,
    /// The answer came from the fast path: the previous working set was still optimal and its
    /// free block's inverse was cached (one product with `W_FF⁻¹`, one with `W`).
    pub fast: bool,
}

/// Errors of [`BoxQp`](crate::friction::BoxQp).
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum BoxQpError {
    /// A slice has the wrong length.
    #[error("{what} has length {got}, expected {expected}")]
    DimensionMismatch {
        /// Which argument.
        what: &'static str,
        /// Length required by the problem size.
        expected: usize,
        /// Length given.
        got: usize,
    },
    /// `W` is not symmetric to within `1e-8·sqrt(W_ii W_jj)`.
    #[error("W is not symmetric: W[{row},{col}] = {upper} but W[{col},{row}] = {lower}")]
    NotSymmetric {
        /// Row of the first offending entry (above the diagonal).
        row: usize,
        /// Column of the first offending entry.
        col: usize,
        /// `W[row, col]`.
        upper: f64,
        /// `W[col, row]`.
        lower: f64,
    },
    /// A Cholesky pivot was not above `4 m ε W_ii`: `W` is not (numerically) positive definite.
    #[error("W is not positive definite: Cholesky pivot {pivot:e} for variable {index}")]
    NotPositiveDefinite {
        /// Variable whose pivot failed.
        index: usize,
        /// The pivot `W_ii − Σ L_ip²`.
        pivot: f64,
    },
    /// Bounds that admit no value: `lo > hi`, a NaN, `lo = +∞` or `hi = −∞`.
    #[error("invalid bounds for variable {index}: lo = {lo}, hi = {hi}")]
    BadBounds {
        /// Variable index.
        index: usize,
        /// Its lower bound.
        lo: f64,
        /// Its upper bound.
        hi: f64,
    },
    /// A NaN or infinity in the input (`W`, `b`) or, after overflow, in the solution.
    #[error("{what}[{index}] = {value} is not finite")]
    NonFinite {
        /// `"W"`, `"b"` or `"solution"`.
        what: &'static str,
        /// Flat index of the entry (column-major for `W`).
        index: usize,
        /// The value found.
        value: f64,
    },
    /// The active-set iteration hit its cap (`10·m + 50`). The warm start is reset.
    #[error("box QP did not terminate within {iterations} iterations")]
    IterationLimit {
        /// Iterations performed.
        iterations: u32,
    },
}
