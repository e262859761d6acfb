//! Box-constrained convex QP for the friction forces of one implicit time step.
//!
//! # Contract
//!
//! [`BoxQp`] solves
//!
//! ```text
//! F = argmin_{lo ≤ F ≤ hi}  ½ FᵀWF − Fᵀb
//! ```
//!
//! for a symmetric positive definite `W` (the Delassus matrix, m×m, fixed for the whole run and
//! checked by a Cholesky factorisation in [`BoxQp::new`]), a right-hand side `b` (the free slip
//! rates `w_free`, new every step) and bounds `lo ≤ hi` (per damper; `lo = hi` fixes a
//! variable, infinite bounds are allowed). Because `W` is positive definite the minimiser is
//! unique and is characterised by the KKT conditions, written with the slip rates
//! `w = b − WF`:
//!
//! * `lo_i < F_i < hi_i` (stick): `w_i = 0`;
//! * `F_i = hi_i`: `w_i ≥ 0`;  `F_i = lo_i`: `w_i ≤ 0` (slip).
//!
//! The returned `F` lies inside the box *exactly*: a variable reported at a bound
//! ([`BoxQp::status`]) holds exactly `lo_i` or `hi_i`, bit for bit. The KKT conditions hold to
//! round-off: [`kkt_residual`] is a small multiple of `m · ε` relative to `‖W‖∞‖F‖∞ + ‖b‖∞`
//! (the tests assert `≤ 1e-10`; in practice it is ~1e-15).
//!
//! # Algorithm
//!
//! A primal active-set method for strictly convex QP (Nocedal & Wright, *Numerical
//! Optimization*, 2nd ed., §16.5), specialised to bounds. The working set is the set of
//! variables held at a bound; the others ("free") solve the equality-constrained subproblem
//! `W_FF F_F = b_F − W_FB F_B`. Each iteration either
//!
//! 1. steps from the current feasible iterate towards that subproblem's solution, stopping at
//!    the first bound it meets (the blocking variable joins the working set), or
//! 2. having reached the subproblem's solution, computes `w` on the bound variables (their
//!    multipliers) and releases one whose multiplier has the wrong sign (the one that alone
//!    would lower the objective most, `w_i²/(2 W_ii)`); when none has, the iterate is
//!    optimal.
//!
//! The objective decreases strictly at every step of positive length, so a working set is
//! never revisited except through zero-length (degenerate) steps. After a few consecutive
//! degenerate steps the choices switch to a least-index rule (Bland's rule), and a variable
//! that is blocked again, at zero step, right after being released is not released again in
//! that call (its multiplier's sign was lost in round-off). An iteration cap of `10·m + 50`
//! turns any remaining failure into [`BoxQpError::IterationLimit`]; the method never loops
//! forever and never returns a non-finite `F`.
//!
//! The free-set matrix `W_FF` is kept as a Cholesky factor that is updated, not recomputed,
//! when one variable enters (bordering, O(k²)) or leaves (Givens rotations, O(k²)) the free
//! set, and it survives between calls. Each call starts from the previous call's working set
//! (warm start), so when the stick/slip pattern of consecutive time steps is unchanged a call
//! costs one triangular solve pair plus one product with `W` and does not touch the factor.
//! The factor is recomputed from scratch when many variables change at once, after many
//! updates, or when the computed free-variable residual exceeds the round-off threshold.
//!
//! Round-off thresholds are relative: a multiplier counts as having the wrong sign only if it
//! exceeds `8 (m + 1) ε (‖W‖∞‖F‖∞ + ‖b‖∞)`, so grazing contacts do not flip-flop.
//!
//! `solve` does not allocate: all scratch space is sized in [`BoxQp::new`].
//!
//! Files: `outcome` (what a solve reports: [`Bound`], [`BoxQpStats`], [`BoxQpError`]),
//! `cholesky` (the dense kernels: dot products and the in-place Cholesky factorisation and
//! solve), `solver` (the active-set method, [`BoxQp`]) and `kkt` (the certificate any answer
//! is checked against, [`kkt_residual`]).

mod cholesky;
mod kkt;
mod outcome;
mod solver;

pub use kkt::kkt_residual;
pub use outcome::{Bound, BoxQpError, BoxQpStats};
pub use solver::BoxQp;
