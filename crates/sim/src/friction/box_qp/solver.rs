//! The primal active-set solver [`BoxQp`] (the method is in the `box_qp` module docs):
//! the working set, the free block's Cholesky factor kept up to date by bordering and
//! Givens rotations, the warm start and the fast path of cached free-block inverses.

use super::cholesky::{axpy, cholesky_in_place, cholesky_solve, dot, pivot_floor};
use super::outcome::{Bound, BoxQpError, BoxQpStats};

/// Marks "not in the free list" in the position table.
const NONE: usize = usize::MAX;

/// Consecutive zero-length steps after which the least-index (Bland) rule is used.
const BLAND_AFTER: u32 = 3;

/// Incremental factor updates after which the next change of the free set refactorises.
const UPDATE_LIMIT: u32 = 64;

/// Largest problem for which explicit inverses of free blocks are cached (the fast path).
const FAST_MAX: usize = 16;

/// Slots of the direct-mapped cache of free-block inverses.
const INV_SLOTS: usize = 16;

/// Marks an empty cache slot (no free set has all 64 bits).
const EMPTY: u64 = u64::MAX;

/// Solver for min ½FᵀWF − Fᵀb over lo ≤ F ≤ hi, W SPD fixed at construction.
///
/// Holds `W`, its full Cholesky factor, the Cholesky factor of the current free block
/// `W_FF` (updated incrementally), the warm-start working set and all scratch space. Clone
/// one per worker thread.
#[derive(Debug, Clone)]
pub struct BoxQp {
    m: usize,
    /// `W`, symmetrised, column-major (= row-major).
    w: Vec<f64>,
    /// `‖W‖∞` (max absolute row sum).
    w_norm: f64,
    /// `1/sqrt(W_ii)`, to rank multipliers independently of each variable's scale.
    inv_sqrt_diag: Vec<f64>,
    /// Cholesky factor of the whole of `W`, lower, row-major with leading dimension `m`.
    chol_full: Vec<f64>,
    /// Cholesky factor of `W_FF` in the order of `free`, same layout as `chol_full`.
    l: Vec<f64>,
    /// Free variables in factor order.
    free: Vec<usize>,
    /// `pos[i]`: position of `i` in `free`, or `NONE`.
    pos: Vec<usize>,
    /// `l` was computed from scratch and not updated since.
    fresh: bool,
    /// Incremental updates since the last factorisation from scratch.
    updates: u32,
    /// Warm-start state: where each variable was held at the end of the last call.
    status: Vec<Bound>,
    /// Scratch: `W_{:,B} F_B`.
    t: Vec<f64>,
    /// Scratch: right-hand side / solution of the free system, in factor order.
    rhs: Vec<f64>,
    /// Scratch: slip rates `w = b − WF`.
    slip: Vec<f64>,
    /// Scratch: variables not to be released again in this call.
    frozen: Vec<bool>,
    /// Fast path: free set (bit i = variable i free) of each cached inverse, or [`EMPTY`].
    inv_key: Vec<u64>,
    /// Fast path: the cached `W_FF⁻¹`, `k×k` row-major at the start of each `m²` slot.
    inv: Vec<f64>,
    /// Fast path: the free set tried by the previous call (an inverse is built for a free set
    /// the second time in a row it is tried, so a pattern seen once costs nothing extra).
    last_mask: u64,
    /// Fast path scratch: free variables in increasing order.
    idx: Vec<usize>,
}

impl BoxQp {
    /// Builds the solver for the m×m matrix `w` (column-major, length `m²`).
    ///
    /// `w` must be finite, symmetric to within `1e-8·sqrt(W_ii W_jj)` (it is symmetrised
    /// internally) and positive definite: every Cholesky pivot must exceed `4 m ε W_ii`.
    /// The warm start begins with all variables free.
    ///
    /// # Errors
    /// [`BoxQpError::DimensionMismatch`], [`BoxQpError::NonFinite`],
    /// [`BoxQpError::NotSymmetric`], [`BoxQpError::NotPositiveDefinite`].
    pub fn new(w: &[f64], m: usize) -> Result<BoxQp, BoxQpError> {
        let expected = m.checked_mul(m).ok_or(BoxQpError::DimensionMismatch {
            what: "W",
            expected: usize::MAX,
            got: w.len(),
        })?;
        if w.len() != expected {
            return Err(BoxQpError::DimensionMismatch {
                what: "W",
                expected,
                got: w.len(),
            });
        }
        if let Some((index, &value)) = w.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(BoxQpError::NonFinite {
                what: "W",
                index,
                value,
            });
        }
        let mut ws = w.to_vec();
        for j in 0..m {
            for i in 0..j {
                let (upper, lower) = (w[i + j * m], w[j + i * m]);
                let allowed = 1e-8 * (w[i + i * m] * w[j + j * m]).abs().sqrt();
                if (upper - lower).abs() > allowed {
                    return Err(BoxQpError::NotSymmetric {
                        row: i,
                        col: j,
                        upper,
                        lower,
                    });
                }
                let mean = 0.5 * (upper + lower);
                ws[i + j * m] = mean;
                ws[j + i * m] = mean;
            }
        }
        let w_norm = (0..m)
            .map(|i| (0..m).map(|j| ws[i + j * m].abs()).sum::<f64>())
            .fold(0.0, f64::max);
        let mut chol_full = ws.clone(); // symmetric: row-major lower triangle = column-major
        cholesky_in_place(&mut chol_full, m, m, |q| pivot_floor(m, ws[q + q * m]))
            .map_err(|(index, pivot)| BoxQpError::NotPositiveDefinite { index, pivot })?;
        let inv_sqrt_diag = (0..m).map(|i| 1.0 / ws[i * (m + 1)].sqrt()).collect();
        let mut qp = BoxQp {
            m,
            inv_sqrt_diag,
            w: ws,
            w_norm,
            chol_full,
            l: vec![0.0; expected],
            free: Vec::with_capacity(m),
            pos: vec![NONE; m],
            fresh: false,
            updates: 0,
            status: vec![Bound::Free; m],
            t: vec![0.0; m],
            rhs: vec![0.0; m],
            slip: vec![0.0; m],
            frozen: vec![false; m],
            inv_key: if m <= FAST_MAX {
                vec![EMPTY; INV_SLOTS]
            } else {
                Vec::new()
            },
            inv: if m <= FAST_MAX {
                vec![0.0; INV_SLOTS * expected]
            } else {
                Vec::new()
            },
            last_mask: EMPTY,
            idx: vec![0; m],
        };
        qp.reset();
        Ok(qp)
    }

    /// Number of variables m.
    pub fn dim(&self) -> usize {
        self.m
    }

    /// Forgets the warm start: all variables free (the next call starts from the
    /// unconstrained minimiser direction, whose factor is the precomputed full one).
    pub fn reset(&mut self) {
        self.status.fill(Bound::Free);
        self.free.clear();
        self.free.extend(0..self.m);
        for (i, p) in self.pos.iter_mut().enumerate() {
            *p = i;
        }
        self.l.copy_from_slice(&self.chol_full);
        self.fresh = true;
        self.updates = 0;
    }

    /// Status of variable `i` after the last successful solve: [`Bound::Free`] (sticks,
    /// interior) or held at [`Bound::Lower`] / [`Bound::Upper`] (slips). Before any solve, or
    /// after [`BoxQp::reset`] or an error, all are `Free`.
    ///
    /// # Panics
    /// If `i >= self.dim()`.
    pub fn status(&self, i: usize) -> Bound {
        self.status[i]
    }

    /// Solves for `f` (length m). `f` on entry is ignored except as a hint; the internal
    /// warm-start state (which bound each variable sat on last call) is used. Returns stats.
    ///
    /// Variables that were held at a bound in the previous call start at that bound (if it is
    /// finite now); the others start at `f_i` clamped into `[lo_i, hi_i]` (0 clamped if `f_i` is
    /// not finite). Any such start gives the same minimiser; a good one saves iterations.
    ///
    /// `b` must be finite; `lo_i ≤ hi_i`, `lo_i < +∞`, `hi_i > −∞` (either may be infinite
    /// outward; `lo_i = hi_i` fixes variable `i`). These checks cost O(m) per call.
    ///
    /// # Errors
    /// On [`BoxQpError::DimensionMismatch`], [`BoxQpError::NonFinite`] (in `b`) and
    /// [`BoxQpError::BadBounds`], `f` and the warm start are untouched. The errors below
    /// reset the warm start: [`BoxQpError::IterationLimit`] (`f` holds the last iterate,
    /// which is feasible); [`BoxQpError::NonFinite`] with `what = "solution"` (overflow, e.g.
    /// `W` near the smallest normal numbers; `f` is meaningless);
    /// [`BoxQpError::NotPositiveDefinite`] if round-off makes a principal submatrix of a
    /// nearly singular `W` lose definiteness (not reachable for the conditioning tested, 1e8).
    pub fn solve(
        &mut self,
        b: &[f64],
        lo: &[f64],
        hi: &[f64],
        f: &mut [f64],
    ) -> Result<BoxQpStats, BoxQpError> {
        let m = self.m;
        for (what, got) in [
            ("b", b.len()),
            ("lo", lo.len()),
            ("hi", hi.len()),
            ("f", f.len()),
        ] {
            if got != m {
                return Err(BoxQpError::DimensionMismatch {
                    what,
                    expected: m,
                    got,
                });
            }
        }
        let mut b_norm = 0.0f64;
        for i in 0..m {
            if !b[i].is_finite() {
                return Err(BoxQpError::NonFinite {
                    what: "b",
                    index: i,
                    value: b[i],
                });
            }
            b_norm = b_norm.max(b[i].abs());
            let (l, h) = (lo[i], hi[i]);
            if l.is_nan() || h.is_nan() || l > h || l == f64::INFINITY || h == f64::NEG_INFINITY {
                return Err(BoxQpError::BadBounds {
                    index: i,
                    lo: l,
                    hi: h,
                });
            }
        }
        if let Some(stats) = self.try_fast(b, b_norm, lo, hi, f) {
            return Ok(stats);
        }
        let result = self.run(b, b_norm, lo, hi, f);
        if result.is_err() {
            self.status.fill(Bound::Free);
        }
        result
    }

    /// The fast path on validated input: when the previous call's working set is still
    /// optimal — the usual case from one time step to the next — its minimiser is
    /// `F_F = W_FF⁻¹ (b_F − W_FB F_B)` with a cached inverse, and the optimality test is the
    /// same as the active-set iteration's (free values inside the box, held multipliers of the
    /// right sign beyond the same round-off threshold). Returns `None` (leaving the warm start
    /// as it was, `f` as a hint) when the working set changed or no inverse is cached yet; the
    /// active-set iteration then runs.
    fn try_fast(
        &mut self,
        b: &[f64],
        b_norm: f64,
        lo: &[f64],
        hi: &[f64],
        f: &mut [f64],
    ) -> Option<BoxQpStats> {
        let m = self.m;
        if m > FAST_MAX || m == 0 {
            return None;
        }
        let mut mask = 0u64;
        let mut k = 0;
        for i in 0..m {
            let (l, h) = (lo[i], hi[i]);
            match self.status[i] {
                Bound::Lower if l.is_finite() => f[i] = l,
                Bound::Upper if h.is_finite() && l != h => f[i] = h,
                Bound::Free if l != h => {
                    mask |= 1 << i;
                    self.idx[k] = i;
                    k += 1;
                }
                _ => return None,
            }
        }
        let slot = if m <= 4 {
            mask as usize
        } else {
            (mask.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 60) as usize
        };
        let base = slot * m * m;
        if k > 0 && self.inv_key[slot] != mask {
            if mask != self.last_mask {
                self.last_mask = mask;
                return None;
            }
            if !self.build_inverse(k, base) {
                return None;
            }
            self.inv_key[slot] = mask;
        }
        self.last_mask = mask;
        // rhs_F = b_F − W_FB F_B, then F_F = W_FF⁻¹ rhs_F.
        for q in 0..k {
            let i = self.idx[q];
            let mut r = b[i];
            for (j, &fj) in f.iter().enumerate() {
                if mask & (1 << j) == 0 {
                    r -= self.w[i + j * m] * fj;
                }
            }
            self.rhs[q] = r;
        }
        for q in 0..k {
            let i = self.idx[q];
            let x = dot(&self.inv[base + q * k..base + (q + 1) * k], &self.rhs[..k]);
            if !(x >= lo[i] && x <= hi[i]) {
                return None;
            }
            f[i] = x;
        }
        let f_norm = f.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let tol = 8.0 * (m as f64 + 1.0) * f64::EPSILON * (self.w_norm * f_norm + b_norm);
        for i in 0..m {
            let slip = b[i] - dot(&self.w[i * m..(i + 1) * m], f);
            let wrong = match self.status[i] {
                // An explicit inverse is not backward stable: on an ill-conditioned block the
                // free rows' residual can exceed round-off; the factor-based iteration decides.
                Bound::Free => slip.abs(),
                _ if lo[i] == hi[i] => continue,
                Bound::Lower => slip,
                Bound::Upper => -slip,
            };
            if wrong > tol {
                return None;
            }
        }
        Some(BoxQpStats {
            iterations: 1,
            factorizations: 0,
            fast: true,
        })
    }

    /// Writes `W_FF⁻¹` for the free variables `idx[..k]` at `inv[base..]` (k×k, row-major).
    /// `false` if the block is numerically singular (the active-set iteration then decides).
    fn build_inverse(&mut self, k: usize, base: usize) -> bool {
        let m = self.m;
        // Factor W_FF in the scratch `l`-shaped block of the slot, then solve for each column.
        let mut a = [0.0f64; FAST_MAX * FAST_MAX];
        for p in 0..k {
            for q in 0..k {
                a[p * k + q] = self.w[self.idx[p] + self.idx[q] * m];
            }
        }
        let (w, idx) = (&self.w, &self.idx);
        if cholesky_in_place(&mut a, k, k, |q| pivot_floor(m, w[idx[q] * (m + 1)])).is_err() {
            return false;
        }
        let mut col = [0.0f64; FAST_MAX];
        for q in 0..k {
            col[..k].fill(0.0);
            col[q] = 1.0;
            cholesky_solve(&a, k, k, &mut col[..k]);
            for (p, &c) in col[..k].iter().enumerate() {
                self.inv[base + p * k + q] = c;
            }
        }
        // Symmetrise: the inverse of a symmetric matrix is symmetric; round-off is not.
        for p in 0..k {
            for q in 0..p {
                let mean = 0.5 * (self.inv[base + p * k + q] + self.inv[base + q * k + p]);
                self.inv[base + p * k + q] = mean;
                self.inv[base + q * k + p] = mean;
            }
        }
        true
    }

    /// The active-set iteration on validated input.
    fn run(
        &mut self,
        b: &[f64],
        b_norm: f64,
        lo: &[f64],
        hi: &[f64],
        f: &mut [f64],
    ) -> Result<BoxQpStats, BoxQpError> {
        let m = self.m;
        let mut stats = BoxQpStats::default();

        // Feasible starting point from the warm start, and t = W_{:,B} F_B.
        self.t.fill(0.0);
        for i in 0..m {
            let (l, h) = (lo[i], hi[i]);
            self.frozen[i] = false;
            let st = if l == h {
                Bound::Lower
            } else {
                match self.status[i] {
                    Bound::Lower if l.is_finite() => Bound::Lower,
                    Bound::Upper if h.is_finite() => Bound::Upper,
                    _ => Bound::Free,
                }
            };
            self.status[i] = st;
            f[i] = match st {
                Bound::Lower => l,
                Bound::Upper => h,
                Bound::Free if f[i].is_finite() => f[i].clamp(l, h),
                Bound::Free => 0.0f64.clamp(l, h),
            };
            if st != Bound::Free && f[i] != 0.0 {
                axpy(f[i], &self.w[i * m..(i + 1) * m], &mut self.t);
            }
        }
        self.sync_factor(&mut stats)?;

        let cap = 10 * m as u32 + 50;
        let tol_factor = 8.0 * (m as f64 + 1.0) * f64::EPSILON;
        let mut bland = false;
        let mut degenerate_run = 0u32;
        let mut last_released = NONE;
        loop {
            if stats.iterations >= cap {
                return Err(BoxQpError::IterationLimit {
                    iterations: stats.iterations,
                });
            }
            stats.iterations += 1;

            // Subproblem: W_FF x_F = b_F − W_FB F_B.
            let k = self.free.len();
            for q in 0..k {
                let i = self.free[q];
                self.rhs[q] = b[i] - self.t[i];
            }
            cholesky_solve(&self.l, k, m, &mut self.rhs);

            // Ratio test: the first bound met on the way from F_F to x_F.
            let mut alpha = f64::INFINITY;
            let mut block = NONE;
            let mut block_bound = Bound::Free;
            for q in 0..k {
                let i = self.free[q];
                let (xi, fi) = (self.rhs[q], f[i]);
                let (a, bound) = if xi < lo[i] {
                    ((lo[i] - fi) / (xi - fi), Bound::Lower)
                } else if xi > hi[i] {
                    ((hi[i] - fi) / (xi - fi), Bound::Upper)
                } else {
                    continue;
                };
                let better = a < alpha || (bland && a == alpha && i < self.free[block]);
                if better {
                    alpha = a;
                    block = q;
                    block_bound = bound;
                }
            }

            if block != NONE {
                // Partial step; the blocking variable joins the working set, exactly at its bound.
                let alpha = alpha.clamp(0.0, 1.0);
                for q in 0..k {
                    let i = self.free[q];
                    f[i] = (f[i] + alpha * (self.rhs[q] - f[i])).clamp(lo[i], hi[i]);
                }
                let j = self.free[block];
                let v = if block_bound == Bound::Lower {
                    lo[j]
                } else {
                    hi[j]
                };
                f[j] = v;
                self.status[j] = block_bound;
                if v != 0.0 {
                    axpy(v, &self.w[j * m..(j + 1) * m], &mut self.t);
                }
                self.factor_delete(block);
                stats.factorizations += 1;
                if alpha == 0.0 {
                    if j == last_released {
                        // Released and immediately blocked at zero step: the multiplier's
                        // sign was round-off. Keep it held for the rest of this call.
                        self.frozen[j] = true;
                    }
                    degenerate_run += 1;
                    bland |= degenerate_run >= BLAND_AFTER;
                } else {
                    degenerate_run = 0;
                }
                last_released = NONE;
                continue;
            }

            // Full step: F_F = x_F, the minimiser on the current working set.
            for q in 0..k {
                f[self.free[q]] = self.rhs[q];
            }
            degenerate_run = 0;
            // Slip rates w = b − t − W_{:,F} F_F.
            for ((s, bi), ti) in self.slip.iter_mut().zip(b).zip(&self.t) {
                *s = bi - ti;
            }
            for q in 0..k {
                let i = self.free[q];
                axpy(-f[i], &self.w[i * m..(i + 1) * m], &mut self.slip);
            }
            let f_norm = f.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let tol = tol_factor * (self.w_norm * f_norm + b_norm);

            // An updated factor may have drifted: check the free rows, refactorise if needed.
            if !self.fresh {
                let res = self
                    .free
                    .iter()
                    .fold(0.0f64, |a, &i| a.max(self.slip[i].abs()));
                if res > tol {
                    self.refactor()?;
                    stats.factorizations += 1;
                    continue;
                }
            }

            // Multipliers: among held variables whose sign is wrong by more than round-off,
            // release the one that alone would lower the objective most, w_i²/(2 W_ii)
            // (Bland: the first).
            let mut best = NONE;
            let mut best_score = 0.0;
            for i in 0..m {
                if self.frozen[i] || lo[i] == hi[i] {
                    continue;
                }
                let v = match self.status[i] {
                    Bound::Lower => self.slip[i],
                    Bound::Upper => -self.slip[i],
                    Bound::Free => continue,
                };
                if v > tol {
                    let score = v * self.inv_sqrt_diag[i];
                    if best == NONE || score > best_score {
                        best = i;
                        best_score = score;
                    }
                    if bland {
                        break;
                    }
                }
            }
            if best == NONE {
                if let Some(index) = f.iter().position(|v| !v.is_finite()) {
                    return Err(BoxQpError::NonFinite {
                        what: "solution",
                        index,
                        value: f[index],
                    });
                }
                return Ok(stats);
            }
            if f[best] != 0.0 {
                axpy(-f[best], &self.w[best * m..(best + 1) * m], &mut self.t);
            }
            self.status[best] = Bound::Free;
            self.factor_insert(best)?;
            stats.factorizations += 1;
            last_released = best;
        }
    }

    /// Brings the factor in line with the free set given by `status`.
    fn sync_factor(&mut self, stats: &mut BoxQpStats) -> Result<(), BoxQpError> {
        let k = self.free.len();
        let n_del = self
            .free
            .iter()
            .filter(|&&i| self.status[i] != Bound::Free)
            .count();
        let n_ins = (0..self.m)
            .filter(|&i| self.status[i] == Bound::Free && self.pos[i] == NONE)
            .count();
        let changes = n_del + n_ins;
        if changes == 0 {
            return Ok(());
        }
        let k_new = k - n_del + n_ins;
        // An update costs ~k², a factorisation ~k³/3: refactorise when a quarter or more change.
        if 4 * changes > k_new || self.updates as usize + changes > UPDATE_LIMIT as usize {
            for &i in &self.free {
                self.pos[i] = NONE;
            }
            self.free.clear();
            for i in 0..self.m {
                if self.status[i] == Bound::Free {
                    self.pos[i] = self.free.len();
                    self.free.push(i);
                }
            }
            self.refactor()?;
            stats.factorizations += 1;
        } else {
            for q in (0..k).rev() {
                if self.status[self.free[q]] != Bound::Free {
                    self.factor_delete(q);
                    stats.factorizations += 1;
                }
            }
            for i in 0..self.m {
                if self.status[i] == Bound::Free && self.pos[i] == NONE {
                    self.factor_insert(i)?;
                    stats.factorizations += 1;
                }
            }
        }
        Ok(())
    }

    /// Factorises `W_FF` from scratch in the order of `free`.
    fn refactor(&mut self) -> Result<(), BoxQpError> {
        let (m, k) = (self.m, self.free.len());
        if k == m && self.free.iter().enumerate().all(|(q, &i)| q == i) {
            self.l.copy_from_slice(&self.chol_full);
        } else {
            for q in 0..k {
                let col = &self.w[self.free[q] * m..(self.free[q] + 1) * m];
                for p in 0..=q {
                    self.l[q * m + p] = col[self.free[p]];
                }
            }
            let (w, free) = (&self.w, &self.free);
            cholesky_in_place(&mut self.l, k, m, |q| pivot_floor(m, w[free[q] * (m + 1)]))
                .map_err(|(q, pivot)| BoxQpError::NotPositiveDefinite {
                    index: self.free[q],
                    pivot,
                })?;
        }
        self.fresh = true;
        self.updates = 0;
        Ok(())
    }

    /// Appends variable `j` to the free set: borders the factor with one row (O(k²)).
    fn factor_insert(&mut self, j: usize) -> Result<(), BoxQpError> {
        let (m, k) = (self.m, self.free.len());
        let col = &self.w[j * m..(j + 1) * m];
        let (done, row) = self.l.split_at_mut(k * m);
        for p in 0..k {
            row[p] = col[self.free[p]];
        }
        for q in 0..k {
            let rq = q * m;
            let s = row[q] - dot(&done[rq..rq + q], &row[..q]);
            row[q] = s / done[rq + q];
        }
        let d = col[j] - dot(&row[..k], &row[..k]);
        self.pos[j] = k;
        self.free.push(j);
        if d > pivot_floor(m, col[j]) {
            row[k] = d.sqrt();
            self.fresh = false;
            self.updates += 1;
            Ok(())
        } else {
            // Round-off ate the pivot: recompute from scratch (errors only if W_FF is singular).
            self.refactor()
        }
    }

    /// Removes the variable at position `p` of the free set: deletes its row, then restores
    /// the triangle with Givens rotations on adjacent columns (O(k²)).
    fn factor_delete(&mut self, p: usize) {
        let (m, k) = (self.m, self.free.len());
        for r in p + 1..k {
            self.l.copy_within(r * m..r * m + r + 1, (r - 1) * m);
        }
        // Rows p..k-2 now have one entry above the diagonal, at column r + 1.
        for r in p..k - 1 {
            let a = self.l[r * m + r];
            let b = self.l[r * m + r + 1];
            let h = a.hypot(b);
            let (c, s) = (a / h, b / h);
            self.l[r * m + r] = h;
            self.l[r * m + r + 1] = 0.0;
            for i in r + 1..k - 1 {
                let x = self.l[i * m + r];
                let y = self.l[i * m + r + 1];
                self.l[i * m + r] = c * x + s * y;
                self.l[i * m + r + 1] = c * y - s * x;
            }
        }
        let j = self.free.remove(p);
        self.pos[j] = NONE;
        for q in p..k - 1 {
            self.pos[self.free[q]] = q;
        }
        self.fresh = false;
        self.updates += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fixed, well-conditioned 6×6 SPD matrix (tridiagonal 4, −1 plus a rank-one term).
    fn sample_w(m: usize) -> Vec<f64> {
        let mut w = vec![0.0; m * m];
        for i in 0..m {
            for j in 0..m {
                let v = if i == j {
                    4.0
                } else if i.abs_diff(j) == 1 {
                    -1.0
                } else {
                    0.0
                };
                w[i + j * m] = v + 0.1 * (i + 1) as f64 * (j + 1) as f64 / m as f64;
            }
        }
        w
    }

    /// max |L Lᵀ − W_FF| relative to ‖W‖∞, for the current factor (only the lower triangle of
    /// the stored block is meaningful; the rest is scratch).
    fn factor_error(qp: &BoxQp) -> f64 {
        let (m, k) = (qp.m, qp.free.len());
        let mut worst = 0.0f64;
        for a in 0..k {
            for c in 0..k {
                let llt: f64 = (0..=a.min(c))
                    .map(|p| qp.l[a * m + p] * qp.l[c * m + p])
                    .sum();
                let wv = qp.w[qp.free[a] + qp.free[c] * m];
                worst = worst.max((llt - wv).abs());
            }
        }
        worst / qp.w_norm
    }

    #[test]
    fn insert_and_delete_keep_the_factor_exact_to_round_off() {
        let m = 6;
        let mut qp = BoxQp::new(&sample_w(m), m).expect("sample W is SPD");
        assert!(factor_error(&qp) < 1e-15);
        // Delete from the middle, the front and the back, then insert in scrambled order.
        for p in [2, 0, 3, 1] {
            qp.factor_delete(p);
            // Bound from Givens rotations: a few ε per rotation; 1e-14 is ~45 ε.
            assert!(factor_error(&qp) < 1e-14, "after delete {p}");
        }
        for j in [4, 0, 2] {
            if qp.pos[j] == NONE {
                qp.factor_insert(j)
                    .expect("principal submatrix of SPD is SPD");
            }
            assert!(factor_error(&qp) < 1e-14, "after insert {j}");
        }
        assert_eq!(qp.free, [1, 4, 0, 2]);
        for (q, &i) in qp.free.iter().enumerate() {
            assert_eq!(qp.pos[i], q);
        }
    }

    #[test]
    fn delete_everything_then_rebuild() {
        let m = 5;
        let mut qp = BoxQp::new(&sample_w(m), m).expect("sample W is SPD");
        while !qp.free.is_empty() {
            let p = qp.free.len() / 2;
            qp.factor_delete(p);
            assert!(factor_error(&qp) < 1e-14);
        }
        for j in (0..m).rev() {
            qp.factor_insert(j).expect("SPD");
        }
        assert!(factor_error(&qp) < 1e-14);
        qp.refactor().expect("SPD");
        assert!(qp.fresh);
        assert!(factor_error(&qp) < 1e-15);
    }
}
