//! The box QP of a few contacts, answered from its stick/slip pattern.
//!
//! From one time step to the next the pattern of a box QP (which forces are free, which
//! sit at a bound) rarely changes, and when it does it usually changes in one contact. For
//! a pattern P with free set S and held set H, the only candidate is
//! F_H at its bounds, F_S = W_SS⁻¹ (b_S − W_SH F_H), and it is the minimiser exactly when it
//! satisfies the KKT conditions: F_S inside its box, and the slip rate b − W F of each held
//! row of the sign its bound allows (a held force at its upper bound slides forward). The
//! check is a certificate: W is symmetric positive definite, so the QP is strictly convex
//! and a KKT point is its unique minimiser.
//!
//! For a fixed pattern both the candidate and its slip rates are affine in `b`:
//! F = c + T b and w = d + S b, with T = [W_SS⁻¹ on the free block, 0 elsewhere],
//! c = (F_H on the held rows, −W_SS⁻¹ W_SH F_H on the free ones), S = I − W T and d = −W c
//! (the free rows of S and d are zero: a stuck contact does not slip). [`PatternQp`] keeps
//! the contact count a compile-time constant (the products unroll and no slice is
//! checked), caches (T, c, S, d) per pattern, and tries the previous pattern, then the one
//! change the failed check points to; anything else is left to the general active-set
//! solver [`BoxQp`](super::BoxQp), whose answer the caller hands back through
//! [`PatternQp::adopt`].
//!
//! An explicit inverse is not backward stable: its free rows' residual grows with the
//! condition number of W_SS. A pattern whose block is worse conditioned than
//! [`COND_MAX`] (κ₁ = ‖W_SS‖₁‖W_SS⁻¹‖₁) is never answered here, so every accepted answer
//! satisfies the KKT conditions to a residual within `COND_MAX · M · ε` of
//! `‖W‖‖F‖ + ‖b‖`, the factor-based solver's own forward accuracy on such a block.

// Index loops over compile-time sizes read as the formulas they compute, and unroll.
#![allow(clippy::needless_range_loop)]

use super::box_qp::Bound;

/// Largest condition number κ₁ of a free block answered from its explicit inverse.
pub(crate) const COND_MAX: f64 = 1e4;

/// Cache slots of patterns beyond four contacts (up to four, one slot per pattern).
const SLOTS: usize = 64;

/// Marks an empty slot.
const EMPTY: u64 = u64::MAX;

/// One cached pattern: F = c + T b and w = d + S b (rows by contact), or `usable = false`
/// when its free block is singular or too ill-conditioned for an explicit inverse.
#[derive(Clone)]
struct Slot<const M: usize> {
    key: u64,
    usable: bool,
    t: [[f64; M]; M],
    c: [f64; M],
    s: [[f64; M]; M],
    d: [f64; M],
}

/// What a pattern's KKT check found.
enum Verdict {
    /// The pattern's candidate is the minimiser.
    Optimal,
    /// One change the check points to: this contact should take this status.
    Change(usize, Bound),
    /// The pattern has no usable inverse, or the candidate is not finite.
    Undecided,
}

/// The box QP `min ½FᵀWF − Fᵀb, lo ≤ F ≤ hi` of `M` contacts, answered from its pattern.
///
/// Bounds must be finite with `lo < hi` (the caller checks; fixed or unbounded contacts
/// go to the general solver); `M ≤ 32`.
pub(crate) struct PatternQp<const M: usize> {
    /// W by rows (symmetric).
    w: [[f64; M]; M],
    /// 8 (M + 1) ε ‖W‖∞ max|bounds| and 8 (M + 1) ε: the round-off threshold of a slip
    /// rate is `tol_w + tol_b ‖b‖∞`.
    tol_w: f64,
    tol_b: f64,
    lo: [f64; M],
    hi: [f64; M],
    status: [Bound; M],
    /// Slot of `status` and its key (the slot may since hold another pattern).
    current: (usize, u64),
    slots: Vec<Slot<M>>,
}

impl<const M: usize> PatternQp<M> {
    /// A solver for `W` (symmetric, `M × M`, either storage order) and the bounds, starting
    /// from every contact free.
    pub(crate) fn new(w: &[f64], lo: &[f64], hi: &[f64]) -> PatternQp<M> {
        assert!(M <= 32, "PatternQp keys patterns in 64 bits");
        let mut wm = [[0.0; M]; M];
        for (i, row) in wm.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                // Symmetrise exactly as the general solver does.
                *x = 0.5 * (w[i + j * M] + w[j + i * M]);
            }
        }
        let w_norm = wm
            .iter()
            .map(|r| r.iter().map(|x| x.abs()).sum::<f64>())
            .fold(0.0, f64::max);
        let empty = Slot {
            key: EMPTY,
            usable: false,
            t: [[0.0; M]; M],
            c: [0.0; M],
            s: [[0.0; M]; M],
            d: [0.0; M],
        };
        let mut l = [0.0; M];
        let mut h = [0.0; M];
        l.copy_from_slice(&lo[..M]);
        h.copy_from_slice(&hi[..M]);
        let slots = if M <= 4 { 3usize.pow(M as u32) } else { SLOTS };
        let f_max = l.iter().chain(&h).fold(0.0f64, |m, x| m.max(x.abs()));
        let tol_b = 8.0 * (M as f64 + 1.0) * f64::EPSILON;
        PatternQp {
            w: wm,
            tol_w: tol_b * w_norm * f_max,
            tol_b,
            lo: l,
            hi: h,
            status: [Bound::Free; M],
            current: (usize::MAX, EMPTY),
            slots: vec![empty; slots],
        }
    }

    /// The status of contact `i` after the last successful solve or adoption.
    #[inline]
    pub(crate) fn status(&self, i: usize) -> Bound {
        self.status[i]
    }

    /// Solves for `b`: writes the forces to `f` and the slip rates `b − W F` to `slip`
    /// and returns the number of patterns tried (1 or 2), or `None` when the general solver
    /// must decide (then `f` and `slip` hold nothing of use and the pattern is unchanged).
    #[inline]
    pub(crate) fn solve(
        &mut self,
        b: &[f64; M],
        f: &mut [f64; M],
        slip: &mut [f64; M],
    ) -> Option<u32> {
        let status = self.status;
        let (mut slot, key) = self.current;
        if self.slots.get(slot).is_none_or(|e| e.key != key) {
            slot = self.slot(&status);
            self.current = (slot, self.slots[slot].key);
        }
        match self.check(slot, &status, b, f, slip) {
            Verdict::Optimal => Some(1),
            Verdict::Change(i, to) => {
                let mut next = status;
                next[i] = to;
                let slot = self.slot(&next);
                match self.check(slot, &next, b, f, slip) {
                    Verdict::Optimal => {
                        self.status = next;
                        self.current = (slot, self.slots[slot].key);
                        Some(2)
                    }
                    _ => None,
                }
            }
            Verdict::Undecided => None,
        }
    }

    /// Takes the general solver's answer `f` for `b` and its statuses (`status(i)` for
    /// each contact), and writes the slip rates `b − W F`.
    pub(crate) fn adopt(
        &mut self,
        status: impl Fn(usize) -> Bound,
        b: &[f64; M],
        f: &[f64; M],
        slip: &mut [f64; M],
    ) {
        for (i, s) in self.status.iter_mut().enumerate() {
            *s = status(i);
        }
        self.current = (usize::MAX, EMPTY);
        for i in 0..M {
            slip[i] = b[i] - dot(&self.w[i], f);
        }
    }

    /// The KKT check of pattern `status`, cached in `slot`, for `b`; writes its candidate
    /// to `f` and its slip rates to `slip`.
    #[inline(always)]
    fn check(
        &self,
        slot: usize,
        status: &[Bound; M],
        b: &[f64; M],
        f: &mut [f64; M],
        slip: &mut [f64; M],
    ) -> Verdict {
        let Some(e) = self.slots.get(slot) else {
            return Verdict::Undecided;
        };
        if !e.usable {
            return Verdict::Undecided;
        }
        let mut b_norm = 0.0f64;
        for i in 0..M {
            f[i] = e.c[i] + dot(&e.t[i], b);
            slip[i] = e.d[i] + dot(&e.s[i], b);
            b_norm = b_norm.max(b[i].abs());
        }
        // The general solver's round-off threshold (box_qp/solver.rs), with ‖F‖∞ bounded by the
        // box (a threshold at most that much larger, still at round-off).
        let tol = self.tol_w + self.tol_b * b_norm;
        let mut slide = None;
        for i in 0..M {
            match status[i] {
                Bound::Free => {
                    let x = f[i];
                    if x < self.lo[i] {
                        return Verdict::Change(i, Bound::Lower);
                    } else if x > self.hi[i] {
                        return Verdict::Change(i, Bound::Upper);
                    } else if x.is_nan() {
                        return Verdict::Undecided;
                    }
                }
                Bound::Lower if slip[i] > tol && slide.is_none() => slide = Some(i),
                Bound::Upper if -slip[i] > tol && slide.is_none() => slide = Some(i),
                _ => {}
            }
        }
        match slide {
            None => Verdict::Optimal,
            Some(i) => Verdict::Change(i, Bound::Free),
        }
    }

    /// The cache slot of pattern `status`, filled if it held another pattern.
    #[inline]
    fn slot(&mut self, status: &[Bound; M]) -> usize {
        let mut key = 0u64;
        let mut code = 0usize;
        for i in (0..M).rev() {
            let (bits, digit) = match status[i] {
                Bound::Free => (0, 0),
                Bound::Lower => (1, 1),
                Bound::Upper => (1 << 32, 2),
            };
            key |= bits << i;
            code = 3 * code + digit;
        }
        let s = if M <= 4 {
            code
        } else {
            (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 58) as usize
        };
        if self.slots[s].key != key {
            self.fill(s, key, status);
        }
        s
    }

    /// Writes pattern `status` (key `key`) into slot `s`: W_SS⁻¹ by Cholesky and one
    /// solve per column, then (T, c, S, d). Marks it unusable when a pivot falls to
    /// round-off or κ₁(W_SS) exceeds [`COND_MAX`].
    fn fill(&mut self, s: usize, key: u64, status: &[Bound; M]) {
        let mut idx = [0usize; M];
        let mut k = 0;
        let mut fh = [0.0; M];
        for i in 0..M {
            match status[i] {
                Bound::Free => {
                    idx[k] = i;
                    k += 1;
                }
                Bound::Lower => fh[i] = self.lo[i],
                Bound::Upper => fh[i] = self.hi[i],
            }
        }
        let w = &self.w;
        let mut l = [[0.0; M]; M];
        let mut usable = true;
        'factor: for j in 0..k {
            let mut d = w[idx[j]][idx[j]];
            for p in 0..j {
                d -= l[j][p] * l[j][p];
            }
            // The general solver's pivot floor (box_qp/cholesky.rs).
            if d.is_nan() || d <= 4.0 * M as f64 * f64::EPSILON * w[idx[j]][idx[j]] {
                usable = false;
                break 'factor;
            }
            let d = d.sqrt();
            l[j][j] = d;
            for i in j + 1..k {
                let mut x = w[idx[i]][idx[j]];
                for p in 0..j {
                    x -= l[i][p] * l[j][p];
                }
                l[i][j] = x / d;
            }
        }
        let mut inv = [[0.0; M]; M];
        if usable {
            for col in 0..k {
                // Solve L Lᵀ y = e_col.
                let mut y = [0.0; M];
                for q in 0..k {
                    let mut x = if q == col { 1.0 } else { 0.0 };
                    for p in 0..q {
                        x -= l[q][p] * y[p];
                    }
                    y[q] = x / l[q][q];
                }
                for q in (0..k).rev() {
                    let mut x = y[q];
                    for p in q + 1..k {
                        x -= l[p][q] * y[p];
                    }
                    y[q] = x / l[q][q];
                }
                for q in 0..k {
                    inv[q][col] = y[q];
                }
            }
            let norm1 = |a: &dyn Fn(usize, usize) -> f64| {
                (0..k)
                    .map(|c| (0..k).map(|r| a(r, c).abs()).sum::<f64>())
                    .fold(0.0, f64::max)
            };
            let kappa = norm1(&|r, c| w[idx[r]][idx[c]]) * norm1(&|r, c| inv[r][c]);
            usable = kappa.is_finite() && kappa <= COND_MAX;
        }
        let mut e = Slot {
            key,
            usable,
            t: [[0.0; M]; M],
            c: fh,
            s: [[0.0; M]; M],
            d: [0.0; M],
        };
        if usable {
            // Free rows: T = W_SS⁻¹ on the free columns, c = −W_SS⁻¹ (W F_H) restricted.
            let mut wfh = [0.0; M];
            for (i, x) in wfh.iter_mut().enumerate() {
                *x = dot(&w[i], &fh);
            }
            for q in 0..k {
                let i = idx[q];
                let mut ci = 0.0;
                for p in 0..k {
                    e.t[i][idx[p]] = inv[q][p];
                    ci -= inv[q][p] * wfh[idx[p]];
                }
                e.c[i] = ci;
            }
            // Held rows: S = I − W T, d = −W c; free rows stay zero.
            for i in 0..M {
                if status[i] == Bound::Free {
                    continue;
                }
                for j in 0..M {
                    let mut wt = 0.0;
                    for p in 0..M {
                        wt += w[i][p] * e.t[p][j];
                    }
                    e.s[i][j] = if i == j { 1.0 } else { 0.0 } - wt;
                }
                e.d[i] = -dot(&w[i], &e.c);
            }
        }
        self.slots[s] = e;
    }
}

#[inline]
fn dot<const M: usize>(a: &[f64; M], b: &[f64; M]) -> f64 {
    let mut s = 0.0;
    for i in 0..M {
        s += a[i] * b[i];
    }
    s
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
    use super::*;
    use crate::friction::box_qp::{BoxQp, kkt_residual};
    use nalgebra::{DMatrix, DVector};
    use proptest::collection::vec;
    use proptest::prelude::*;

    /// W = Q diag(λ) Qᵀ, Q orthogonal, λ log-spaced over 10^[−log_cond, 0] (column-major).
    fn spd(m: usize, max_log_cond: f64) -> impl Strategy<Value = Vec<f64>> {
        (
            vec(-1.0..1.0f64, m * m),
            vec(0.0..1.0f64, m),
            0.0..=max_log_cond,
        )
            .prop_map(move |(a, t, log_cond)| {
                let q = DMatrix::from_column_slice(m, m, &a).qr().q();
                let lam = DVector::from_iterator(m, (0..m).map(|i| 10f64.powf(-log_cond * t[i])));
                let w = &q * DMatrix::from_diagonal(&lam) * q.transpose();
                ((&w + w.transpose()) * 0.5).as_slice().to_vec()
            })
    }

    /// A run of `M`-contact solves along a random walk of right-hand sides (the warm start
    /// of one step is the pattern of the last, as in the step loop): every answer the
    /// pattern solver gives is the general solver's minimiser, its held forces exactly at
    /// their bounds. κ₂(W) ≤ 10^2.5, so every principal block has κ₁ ≤ M κ₂ < COND_MAX.
    fn agrees<const M: usize>(w: &[f64], bounds: &[(f64, f64)], walk: &[Vec<f64>]) {
        let lo: Vec<f64> = bounds.iter().map(|b| b.0).collect();
        let hi: Vec<f64> = bounds.iter().map(|b| b.1).collect();
        let mut general = BoxQp::new(w, M).unwrap();
        let mut pattern = PatternQp::<M>::new(w, &lo, &hi);
        let mut b = [0.0; M];
        let mut answered = 0;
        for step in walk {
            for (bi, s) in b.iter_mut().zip(step) {
                *bi += s;
            }
            let mut reference = [0.0; M];
            general.solve(&b, &lo, &hi, &mut reference).unwrap();
            let (mut f, mut slip) = ([0.0; M], [0.0; M]);
            match pattern.solve(&b, &mut f, &mut slip) {
                Some(_) => {
                    answered += 1;
                    // KKT to round-off amplified by at most COND_MAX (module docs).
                    let r = kkt_residual(w, M, &b, &lo, &hi, &f);
                    assert!(r <= 1e-10, "KKT residual {r:e}");
                    let scale = reference
                        .iter()
                        .chain(&f)
                        .fold(1e-300f64, |m, x| m.max(x.abs()));
                    for i in 0..M {
                        assert!(
                            (f[i] - reference[i]).abs() <= 1e-9 * scale,
                            "F[{i}] {} vs general {}",
                            f[i],
                            reference[i]
                        );
                        assert!(f[i] >= lo[i] && f[i] <= hi[i], "F[{i}] outside its box");
                        let at_bound = f[i] == lo[i] || f[i] == hi[i];
                        if pattern.status(i) != Bound::Free {
                            assert!(at_bound, "held F[{i}] = {} is not at a bound", f[i]);
                        }
                    }
                }
                None => {
                    pattern.adopt(|i| general.status(i), &b, &reference, &mut slip);
                    // The adopted pattern is tried first: the same right-hand side again is
                    // answered at once (every block here is within COND_MAX).
                    assert_eq!(pattern.solve(&b, &mut f, &mut slip), Some(1));
                    for i in 0..M {
                        let scale = reference.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
                        assert!((f[i] - reference[i]).abs() <= 1e-9 * scale);
                    }
                }
            }
        }
        assert!(answered > 0, "no step answered from its pattern");
    }

    /// W (column-major), the bounds, and the steps of the right-hand side's walk.
    type Case = (Vec<f64>, Vec<(f64, f64)>, Vec<Vec<f64>>);

    fn case<const M: usize>() -> impl Strategy<Value = Case> {
        (
            spd(M, 2.5),
            vec((-1.5..-0.01f64, 0.01..1.5f64), M),
            vec(vec(-0.05..0.05f64, M), 60),
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]
        #[test]
        fn three_contacts_agree_with_the_general_solver((w, bounds, walk) in case::<3>()) {
            agrees::<3>(&w, &bounds, &walk);
        }
        #[test]
        fn six_contacts_agree_with_the_general_solver((w, bounds, walk) in case::<6>()) {
            agrees::<6>(&w, &bounds, &walk);
        }
        #[test]
        fn ten_contacts_use_the_hashed_cache_and_agree((w, bounds, walk) in case::<10>()) {
            agrees::<10>(&w, &bounds, &walk);
        }
    }

    /// A free block beyond COND_MAX is never answered from its inverse.
    #[test]
    fn ill_conditioned_blocks_go_to_the_general_solver() {
        let e = 1e-6; // W = [[1, 1−e], [1−e, 1]]: κ ≈ 2/e
        let w = [1.0, 1.0 - e, 1.0 - e, 1.0];
        let mut p = PatternQp::<2>::new(&w, &[-10.0, -10.0], &[10.0, 10.0]);
        let (mut f, mut slip) = ([0.0; 2], [0.0; 2]);
        assert!(p.solve(&[0.1, 0.1], &mut f, &mut slip).is_none());
        // A well-conditioned one is answered.
        let w = [2.0, 0.5, 0.5, 1.0];
        let mut p = PatternQp::<2>::new(&w, &[-10.0, -10.0], &[10.0, 10.0]);
        assert_eq!(p.solve(&[0.1, 0.2], &mut f, &mut slip), Some(1));
        assert!((2.0 * f[0] + 0.5 * f[1] - 0.1).abs() < 1e-15);
        assert!((0.5 * f[0] + f[1] - 0.2).abs() < 1e-15);
    }
}
