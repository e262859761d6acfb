//! `exact` — the event-driven reference integrator (docs/MODEL.md § Integrators).
//!
//! Between stick↔slip events the plan is linear and time-invariant, driven by a ground
//! acceleration that is linear between record samples, a harmonic force and constant slip
//! forces. The state is augmented with the generators of those inputs,
//! y = (u, v, x′ of the elastic–perfectly plastic contacts, a_g, ȧ_g, sin, cos, 1), so that
//! each mode set (which contacts stick, which slide and which way) is one autonomous linear
//! system ẏ = A y, and y(t + τ) = exp(Aτ) y(t) exactly (Van Loan 1978). The exponential is
//! applied as its Taylor series p_k = Aᵏy/k!, truncated at [`TAYLOR_TERMS`] terms on
//! substeps with ρτ ≤ [`SUBSTEP_PHASE`], where ρ bounds the spectral radius of the current
//! mode set's A (|λ| ≤ ν_max + ω_max for the quadratic eigenproblem, ν and ω² the extreme
//! Rayleigh quotients of C and K over M on the subspace the stuck dissipators leave free,
//! plus k′/c′ of sliding damped massless dissipators and the harmonic ω): the remainder is
//! below (ρτ)²²/22! ≈ 2e-28 of the state, i.e. the series is exact to round-off. The bound
//! is per mode set because a stuck dissipator with mass moves with its floor: the
//! dissipator's own fast mode (k′/m′ on a stiff brace, hundreds of rad/s) rings only while
//! it slides, and the substeps of the stuck phases follow the frame's modes. The same
//! polynomial gives every quantity inside the substep as a scalar polynomial in τ, which is
//! where events and peaks are located. Mode matrices are cached per mode set
//! ([`MODE_CACHE`] entries, cleared when full).
//!
//! Whole output steps run on the mode set's grid h = Δt/m (m = ⌈Δt ρ/[`SUBSTEP_PHASE`]⌉).
//! Once a mode set has lasted as many grid substeps as forming them costs, it caches the
//! same truncated series as a matrix, exp(A h) (and, when energies are asked for, the work
//! over h as quadratic forms of the starting state, below), and each scanned function's
//! Taylor rows r Aᵏ/k!; a grid
//! substep is then one matrix–vector product, and a scan starts from the bound
//! |g(τ) − g(0)| ≤ Σ_j |y_j| Σ_{k≥1} |r Aᵏ/k!|_j hᵏ, which rules out most of them; failing
//! that, from the same bound on the terms past the first [`LEAD_TERMS`] coefficients,
//! which are formed exactly (their negative parts at their largest). That second test
//! rules out functions that are near zero but moving away from it, which the first
//! cannot (on the benchmark it saves about 7 % of the run time). Substeps
//! off the grid (after an event, or where record samples cut an output step) sum the
//! series for their own length.
//!
//! Contacts:
//! - a dissipator with mass that sticks is the constraint w = 0, imposed by a Lagrange
//!   multiplier λ = W_S⁻¹B_SᵀM⁻¹f (W_S = B_SᵀM⁻¹B_S): the dissipator moves with its floor and
//!   its brace acts between floors i−1 and i; the multiplier is the stuck friction force;
//! - a sliding contact applies its constant bound F⁺ or F⁻;
//! - a massless dissipator (plan `ContactKind::Epp`) carries its position x′ as a state:
//!   stuck, ẋ′ = ẋᵢ and its force is k′(x′ − xᵢ₋₁) + c′(ẋᵢ − ẋᵢ₋₁) (an elastic brace between
//!   the floors); sliding, its force is the bound and the brace follows
//!   k′(x′ − xᵢ₋₁) + c′(ẋ′ − ẋᵢ₋₁) = F±, i.e. ẋ′ = ẋᵢ₋₁ for c′ = 0 and the first-order law
//!   ẋ′ = ẋᵢ₋₁ + (F± − k′(x′ − xᵢ₋₁))/c′ for c′ > 0 (a Maxwell element, exact as well; its
//!   rate k′/c′ enters ρ, so a tiny c′ costs substeps).
//! - a dissipator with zero mass that keeps a DOF (unreduced plan) is rejected: compile
//!   with `reduce` on, which turns it into the equivalent elastic–perfectly plastic element.
//!
//! Events: a stuck contact's force reaching a bound, a sliding contact's slip rate reaching
//! zero. Each event function g (positive while the mode is consistent) is scanned at
//! [`SCAN_POINTS`] points per substep together with ġ; a sign change, or a local minimum
//! (ġ from − to +) below −ε, brackets the first crossing, which the Illinois method locates
//! to about 1e-14 s. ε is the grazing threshold: [`GRAZE_REL`] times the force bound (force
//! functions) or the largest floor velocity so far (slip-rate functions). A function that
//! touches zero without going below −ε is a grazing contact and no event. At an event:
//! - a stuck contact whose force reached a bound slides toward it (forces are continuous
//!   there, so no other contact changes);
//! - a massless dissipator whose slip rate reached zero sticks;
//! - a dissipator with mass whose slip rate reached zero, together with every stuck one,
//!   is decided at once by the box QP at the acceleration level (Delassus B_UᵀM⁻¹B_U, as
//!   `newmark`'s initial state): Free = stick, a bound = slide that way (reversal). The
//!   velocities are then projected M-orthogonally onto B_Sᵀv = 0 (the residual of the
//!   located root, ~1e-11 m/s; its kinetic energy goes to friction). The same projection
//!   is repeated at every output step, so round-off drift of the stuck constraints cannot
//!   accumulate over many substeps (it matters on very stiff braces, k′ ~ 1e12 N/m);
//! - a contact with F⁻ = F⁺ (μN = 0 in an unreduced plan) applies that force and has no
//!   events.
//!
//! Chattering rule: a run whose substep estimate duration·ρ/[`SUBSTEP_PHASE`] exceeds
//! [`MAX_SUBSTEPS`], or whose events exceed [`MAX_EVENTS`], stops with
//! [`SimError::ExactBudget`] (light, stiff dissipators ring too fast for an event-driven
//! reference: use `newmark`, or the massless limit). More than 4·contacts + 16 events at one
//! instant (less than 1e-14 s apart) is Zeno behaviour: [`SimError::ExactZeno`].
//!
//! Peaks: drift peaks are those of the continuous solution (each storey's drift extremum
//! located inside its substep by the same root finding on the drift rate); the peaks at
//! the output steps are reported beside them (`Diagnostics::sampled_peak_drift`). Other
//! peaks (displacement, acceleration, base shear, slip) are taken at the output steps.
//! Energies: input, viscous and friction powers integrated by 6-point Gauss–Legendre on
//! every substep (exact to degree 11; with phase 2ρτ ≤ 1 the rule's error term is below
//! 2e-16 of the powers' scale: Davis & Rabinowitz 1984, §2.7).
//! Each power is a quadratic form p(y) = yᵀ Q_p y of the augmented state, so on the grid
//! substeps of a lasting mode set the rule is summed once, W_p = h Σ_g w_g Φ_gᵀ Q_p Φ_g
//! (Φ_g = exp(A x_g h)), and a substep's work is yᵀ W_p y: the same quadrature, three
//! matrix–vector products instead of six states and their powers.

use crate::error::SimError;
use crate::friction::BoxQp;
use crate::friction::box_qp::Bound;
use crate::integrator::Integrator;
use crate::integrator::state::{base_shear, history_columns};
use crate::plan::{ContactKind, Plan};
use crate::response::{Diagnostics, Energy, History, Outcome, Peaks};
use crate::units::is_positive;
use nalgebra::{DMatrix, DVector};
use std::cell::{Cell, OnceCell, RefCell};
use std::collections::HashMap;
use std::rc::Rc;

/// Event-driven integrator, exact between events.
#[derive(Debug, Clone, Copy, Default)]
pub struct Exact;

/// Terms of the exponential's Taylor series kept on a substep.
pub const TAYLOR_TERMS: usize = 22;
/// Largest ρ·τ of a substep (ρ bounds the spectral radius of the mode matrices).
pub const SUBSTEP_PHASE: f64 = 0.5;
/// Scan intervals per substep for event and extremum detection.
pub const SCAN_POINTS: usize = 8;
/// Cap on the substeps of one run.
pub const MAX_SUBSTEPS: u64 = 4_000_000;
/// Cap on the events of one run.
pub const MAX_EVENTS: u64 = 5_000_000;
/// Mode sets kept in the cache.
pub const MODE_CACHE: usize = 4096;
/// Leading Taylor coefficients of a scanned function formed exactly on a grid substep
/// before its full series is (the second exclusion test).
pub const LEAD_TERMS: usize = 4;
/// Grazing threshold, relative to the force bound or the velocity scale.
pub const GRAZE_REL: f64 = 1e-10;

/// 6-point Gauss–Legendre nodes on [0, 1] and weights (sum 1). Exact to degree 11; on a
/// power p(t) = y(t)ᵀQy(t) over a substep of length τ its error is
/// τ¹³(6!)⁴/(13·(12!)³)·p⁽¹²⁾(ξ) (Davis & Rabinowitz, *Methods of Numerical Integration*,
/// 2nd ed., 1984, §2.7). With the state's derivatives bounded by ρᵏ‖y‖ (ρ the substep's
/// spectral bound, as the Taylor truncation takes it), |p⁽ᵏ⁾| ≤ (2ρ)ᵏ‖Q‖‖y‖², and with
/// 2ρτ ≤ 2·[`SUBSTEP_PHASE`] = 1 the error is at most 1.9e-16·τ·‖Q‖·max‖y‖²: round-off.
const GAUSS: [(f64, f64); 6] = {
    const X: [f64; 3] = [
        0.238_619_186_083_196_9,
        0.661_209_386_466_264_5,
        0.932_469_514_203_152,
    ];
    const W: [f64; 3] = [
        0.467_913_934_572_691,
        0.360_761_573_048_138_6,
        0.171_324_492_379_170_3,
    ];
    [
        (0.5 - 0.5 * X[2], 0.5 * W[2]),
        (0.5 - 0.5 * X[1], 0.5 * W[1]),
        (0.5 - 0.5 * X[0], 0.5 * W[0]),
        (0.5 + 0.5 * X[0], 0.5 * W[0]),
        (0.5 + 0.5 * X[1], 0.5 * W[1]),
        (0.5 + 0.5 * X[2], 0.5 * W[2]),
    ]
};

/// State of one contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Mode {
    Stuck,
    Upper,
    Lower,
}

/// Positions in the augmented state.
struct Layout {
    n: usize,
    /// State index of x′ for elastic–perfectly plastic contacts.
    epp_slot: Vec<Option<usize>>,
    i_ag: usize,
    i_slope: usize,
    i_sin: usize,
    i_cos: usize,
    i_one: usize,
    dim: usize,
}

#[derive(Clone, Copy, PartialEq)]
enum Scale {
    Force(f64),
    Velocity,
}

/// g(y) = row·y ≥ 0 while the mode is consistent.
struct EventFn {
    contact: usize,
    row: DVector<f64>,
    scale: Scale,
}

/// Everything fixed for one mode set.
struct ModeOps {
    a: DMatrix<f64>,
    /// Friction force of each contact as a row on y, stored transposed (dim × contacts:
    /// column c is contact c's row, contiguous for [`row_dot`]).
    force: DMatrix<f64>,
    /// Slip rate of each contact as a row on y, transposed likewise.
    slip_rate: DMatrix<f64>,
    /// ẋ′ rows of elastic–perfectly plastic contacts (zero rows for others), transposed
    /// likewise.
    xdot: DMatrix<f64>,
    events: Vec<EventFn>,
    /// The M-orthogonal projector of the velocities onto B_Sᵀv = 0 for the stuck contacts
    /// with a DOF, I − M⁻¹B_S W_S⁻¹B_Sᵀ (n × n); `None` when none sticks.
    proj: Option<DMatrix<f64>>,
    /// Longest substep, [`SUBSTEP_PHASE`]/ρ (ρ this mode set's spectral bound).
    delta_max: f64,
    /// Substeps per output step, m = ⌈Δt/δ_max⌉, and the grid interval h = Δt/m.
    per_step: usize,
    h: f64,
    /// Grid substeps taken with the Taylor sums so far, and how many make the mode set
    /// worth its propagators (forming them costs about dim + scanned functions substeps).
    uses: Cell<usize>,
    prepare_after: usize,
    /// The grid propagators ([`Model::stepping`]), formed once the mode set has lasted.
    stepping: OnceCell<Stepping>,
}

/// What the grid substeps of one long-lived mode set reuse: the propagator over one grid
/// interval, and every scanned function (events, then storey drifts) as Taylor rows so its
/// coefficients are one product with y.
struct Stepping {
    /// exp(A h) (its Taylor polynomial, exact to round-off as above), dim × dim.
    phi: DMatrix<f64>,
    /// The input, viscous and friction work over one grid interval as quadratic forms of
    /// its starting state, h Σ_g w_g exp(A x_g h)ᵀ Q_p exp(A x_g h) for each power
    /// p(y) = yᵀ Q_p y: the same 6-point Gauss–Legendre rule as [`Model::integrate_powers`],
    /// summed once per mode set instead of once per substep. `None` when energies are off.
    work: Option<[DMatrix<f64>; 3]>,
    /// Column f·K + k: the k-th Taylor row r Aᵏ/k! of scanned function f, so that its
    /// coefficient on τᵏ over a substep from y is that column · y.
    rows: DMatrix<f64>,
    /// Column f: Σ_{k≥1} |r Aᵏ/k!| hᵏ componentwise, so that |g(τ) − g(0)| ≤ Σ_j |y_j|·tail_j
    /// for τ ≤ h (every term is nonnegative and grows with τ).
    tails: DMatrix<f64>,
    /// Column f: Σ_{k≥LEAD_TERMS} |r Aᵏ/k!| hᵏ componentwise, the part of the tail past the
    /// leading coefficients, which the second test forms exactly.
    tails_far: DMatrix<f64>,
}

/// Run-wide model data.
struct Model<'a> {
    plan: &'a Plan,
    lay: Layout,
    minv: DMatrix<f64>,
    /// L⁻¹ of the mass matrix's Cholesky factor M = LLᵀ.
    linv: DMatrix<f64>,
    mr: DVector<f64>,
    /// Contact columns of B.
    bcols: Vec<DVector<f64>>,
    /// Forces without contacts as rows on y (n × dim).
    f0: DMatrix<f64>,
    omega_h: f64,
}

impl<'a> Model<'a> {
    fn new(plan: &'a Plan) -> Result<Model<'a>, SimError> {
        let n = plan.dofs();
        let mut epp_slot = vec![None; plan.contacts.len()];
        let mut next = 2 * n;
        for (c, ct) in plan.contacts.iter().enumerate() {
            match ct.kind {
                ContactKind::Epp => {
                    epp_slot[c] = Some(next);
                    next += 1;
                }
                ContactKind::Dof { dof } => {
                    if plan.mass[(dof, dof)] <= 0.0 {
                        return Err(SimError::Scene(format!(
                            "exact: the dissipator of floor {} has zero mass but keeps a DOF (unreduced plan); compile the scene with \"reduce\": true so it becomes the equivalent elastic-perfectly plastic element",
                            ct.floor + 1
                        )));
                    }
                }
            }
        }
        let lay = Layout {
            n,
            epp_slot,
            i_ag: next,
            i_slope: next + 1,
            i_sin: next + 2,
            i_cos: next + 3,
            i_one: next + 4,
            dim: next + 5,
        };
        let chol = plan
            .mass
            .clone()
            .cholesky()
            .ok_or_else(|| SimError::NotPositiveDefinite {
                what: "mass matrix".into(),
                hint: " (exact needs every DOF to carry mass)".into(),
            })?;
        let minv = chol.inverse();
        let linv = chol
            .l()
            .try_inverse()
            .expect("the Cholesky factor of an SPD matrix is invertible");
        let mr = plan.mass_influence();
        let bm = plan.contact_matrix();
        let bcols = (0..plan.contacts.len())
            .map(|c| bm.column(c).into_owned())
            .collect();
        let dim = lay.dim;
        let mut f0 = DMatrix::zeros(n, dim);
        f0.view_mut((0, 0), (n, n)).copy_from(&(-&plan.stiffness));
        f0.view_mut((0, n), (n, n)).copy_from(&(-&plan.damping));
        for i in 0..n {
            f0[(i, lay.i_ag)] = -mr[i];
        }
        let mut omega_h = 0.0;
        if let Some(h) = &plan.harmonic {
            f0[(h.floor, lay.i_sin)] = h.amplitude;
            omega_h = h.omega;
        }
        Ok(Model {
            plan,
            lay,
            minv,
            linv,
            mr,
            bcols,
            f0,
            omega_h,
        })
    }

    /// Bound ρ on |λ(A)| for every mode set: ν_max + ω_max over all-stuck elastic
    /// braces (constraints only lower both), k′/c′ of sliding damped massless
    /// dissipators, and the harmonic frequency. Used for the run's substep budget.
    fn spectral_bound(&self) -> f64 {
        self.bound(None)
    }

    /// Bound ρ on |λ(A)| of one mode set. A nonzero eigenvalue λ of the mode matrix has
    /// an eigenvector u in null(B_Sᵀ) (the stuck dissipators with mass move with their
    /// floors) with λ²uᴴMu + λuᴴC_mu + uᴴK_mu = 0, so |λ| ≤ ν + ω with ν, ω² the largest
    /// Rayleigh quotients of C_m and K_m over M on that subspace (M-orthogonal projection
    /// keeps the quotients of the unconstrained matrices there). K_m, C_m carry the braces
    /// of stuck massless dissipators; a sliding damped one adds its rate k′/c′. `None`:
    /// the bound over every mode set (no constraints, every brace, every rate).
    fn bound(&self, modes: Option<&[Mode]>) -> f64 {
        let plan = self.plan;
        let mut k = plan.stiffness.clone();
        let mut c = plan.damping.clone();
        let mut maxwell: f64 = 0.0;
        let mut stuck_cols = Vec::new();
        for (i, ct) in plan.contacts.iter().enumerate() {
            let mode = modes.map(|m| m[i]);
            match ct.kind {
                ContactKind::Epp => {
                    if matches!(mode, None | Some(Mode::Stuck)) {
                        add_link(&mut k, ct.floor, ct.below, ct.brace_stiffness);
                        add_link(&mut c, ct.floor, ct.below, ct.brace_damping);
                    }
                    if !matches!(mode, Some(Mode::Stuck)) && ct.brace_damping > 0.0 {
                        maxwell = maxwell.max(ct.brace_stiffness / ct.brace_damping);
                    }
                }
                ContactKind::Dof { .. } => {
                    // A contact with F⁻ = F⁺ never sticks (its force is fixed).
                    if mode == Some(Mode::Stuck) && ct.lower != ct.upper {
                        stuck_cols.push(&self.linv * &self.bcols[i]);
                    }
                }
            }
        }
        let n = self.lay.n;
        // Orthogonal projector onto the complement of L⁻¹B_S (y = Lᵀu coordinates).
        let proj = if stuck_cols.is_empty() {
            None
        } else {
            let d = DMatrix::from_columns(&stuck_cols);
            let dtd = d.transpose() * &d;
            dtd.cholesky()
                .map(|ch| DMatrix::identity(n, n) - &d * ch.solve(&d.transpose()))
        };
        let top = |m: &DMatrix<f64>| -> f64 {
            let mut s = &self.linv * m * self.linv.transpose();
            if let Some(p) = &proj {
                s = p * s * p;
            }
            let s = (&s + s.transpose()) * 0.5;
            s.symmetric_eigenvalues()
                .iter()
                .fold(0.0f64, |a, &x| a.max(x.abs()))
        };
        top(&k).sqrt() + top(&c) + maxwell + self.omega_h
    }

    fn build(&self, modes: &[Mode]) -> ModeOps {
        let plan = self.plan;
        let lay = &self.lay;
        let (n, dim) = (lay.n, lay.dim);
        let nc = plan.contacts.len();
        let mut f = self.f0.clone();
        let mut force = DMatrix::zeros(nc, dim);
        let mut xdot = DMatrix::zeros(nc, dim);
        let mut stuck = Vec::new();
        for (c, ct) in plan.contacts.iter().enumerate() {
            match (modes[c], ct.kind) {
                (Mode::Upper, _) => force[(c, lay.i_one)] = ct.upper,
                (Mode::Lower, _) => force[(c, lay.i_one)] = ct.lower,
                (Mode::Stuck, ContactKind::Dof { .. }) => stuck.push(c),
                (Mode::Stuck, ContactKind::Epp) => {
                    let s = lay.epp_slot[c].expect("EPP contacts have a slot");
                    force[(c, s)] += ct.brace_stiffness;
                    force[(c, n + ct.floor)] += ct.brace_damping;
                    if let Some(j) = ct.below {
                        force[(c, j)] -= ct.brace_stiffness;
                        force[(c, n + j)] -= ct.brace_damping;
                    }
                }
            }
            if let Some(s) = lay.epp_slot[c] {
                match modes[c] {
                    Mode::Stuck => xdot[(c, n + ct.floor)] = 1.0,
                    Mode::Upper | Mode::Lower => {
                        if let Some(j) = ct.below {
                            xdot[(c, n + j)] = 1.0;
                        }
                        if ct.brace_damping > 0.0 {
                            let bound = force[(c, lay.i_one)];
                            let r = 1.0 / ct.brace_damping;
                            xdot[(c, lay.i_one)] += bound * r;
                            xdot[(c, s)] -= ct.brace_stiffness * r;
                            if let Some(j) = ct.below {
                                xdot[(c, j)] += ct.brace_stiffness * r;
                            }
                        }
                    }
                }
            }
            if !(modes[c] == Mode::Stuck && matches!(ct.kind, ContactKind::Dof { .. })) {
                // f −= b_c ⊗ force_c
                let row = force.row(c).into_owned();
                for i in 0..n {
                    let b = self.bcols[c][i];
                    if b != 0.0 {
                        for j in 0..dim {
                            f[(i, j)] -= b * row[j];
                        }
                    }
                }
            }
        }
        let minv_f = &self.minv * &f;
        let (acc, proj) = if stuck.is_empty() {
            (minv_f, None)
        } else {
            let s = stuck.len();
            let mut bs = DMatrix::zeros(n, s);
            for (k, &c) in stuck.iter().enumerate() {
                bs.set_column(k, &self.bcols[c]);
            }
            let y = &self.minv * &bs;
            let ws = bs.transpose() * &y;
            let ws = (&ws + ws.transpose()) * 0.5;
            let wsinv = ws
                .cholesky()
                .expect("B_SᵀM⁻¹B_S is SPD: contact columns are independent")
                .inverse();
            let lam = &wsinv * (bs.transpose() * &minv_f);
            for (k, &c) in stuck.iter().enumerate() {
                force.set_row(c, &lam.row(k));
            }
            let proj = DMatrix::identity(n, n) - &y * &wsinv * bs.transpose();
            (minv_f - &y * &lam, Some(proj))
        };
        let mut a = DMatrix::zeros(dim, dim);
        for i in 0..n {
            a[(i, n + i)] = 1.0;
        }
        a.view_mut((n, 0), (n, dim)).copy_from(&acc);
        let mut slip_rate = DMatrix::zeros(nc, dim);
        for (c, ct) in plan.contacts.iter().enumerate() {
            slip_rate[(c, n + ct.floor)] = 1.0;
            match (ct.kind, lay.epp_slot[c]) {
                (ContactKind::Dof { dof }, _) => slip_rate[(c, n + dof)] -= 1.0,
                (ContactKind::Epp, Some(s)) => {
                    a.set_row(s, &xdot.row(c));
                    let r = slip_rate.row(c) - xdot.row(c);
                    slip_rate.set_row(c, &r);
                }
                (ContactKind::Epp, None) => unreachable!("EPP contacts have a slot"),
            }
        }
        a[(lay.i_ag, lay.i_slope)] = 1.0;
        a[(lay.i_sin, lay.i_cos)] = self.omega_h;
        a[(lay.i_cos, lay.i_sin)] = -self.omega_h;
        let mut events = Vec::new();
        for (c, ct) in plan.contacts.iter().enumerate() {
            if ct.lower == ct.upper {
                // Zero-width bounds (μN = 0 kept in an unreduced plan): the force is that
                // value whatever the contact does; no events.
                continue;
            }
            let bound_scale = Scale::Force(
                [ct.upper, ct.lower]
                    .iter()
                    .filter(|b| b.is_finite())
                    .fold(0.0f64, |m, b| m.max(b.abs())),
            );
            match modes[c] {
                Mode::Stuck => {
                    if ct.upper.is_finite() {
                        let mut row = -force.row(c).transpose();
                        row[lay.i_one] += ct.upper;
                        events.push(EventFn {
                            contact: c,
                            row,
                            scale: bound_scale,
                        });
                    }
                    if ct.lower.is_finite() {
                        let mut row = force.row(c).transpose();
                        row[lay.i_one] -= ct.lower;
                        events.push(EventFn {
                            contact: c,
                            row,
                            scale: bound_scale,
                        });
                    }
                }
                Mode::Upper => events.push(EventFn {
                    contact: c,
                    row: slip_rate.row(c).transpose(),
                    scale: Scale::Velocity,
                }),
                Mode::Lower => events.push(EventFn {
                    contact: c,
                    row: -slip_rate.row(c).transpose(),
                    scale: Scale::Velocity,
                }),
            }
        }
        let dt = plan.method.dt;
        let rho = self.bound(Some(modes));
        let delta_max = if rho > 0.0 {
            SUBSTEP_PHASE / rho
        } else {
            f64::INFINITY
        };
        let per_step = if delta_max.is_finite() {
            ((dt / delta_max) * (1.0 - 1e-12)).ceil().max(1.0) as usize
        } else {
            1
        };
        let prepare_after = dim + events.len() + plan.floors;
        ModeOps {
            a,
            force: force.transpose(),
            slip_rate: slip_rate.transpose(),
            xdot: xdot.transpose(),
            events,
            proj,
            delta_max,
            per_step,
            h: dt / per_step as f64,
            uses: Cell::new(0),
            prepare_after,
            stepping: OnceCell::new(),
        }
    }
}

impl Model<'_> {
    /// The grid propagators of a mode set.
    fn stepping(&self, ops: &ModeOps) -> Stepping {
        let dim = self.lay.dim;
        let nf = self.plan.floors;
        let h = ops.h;
        // exp(A τ) = Σ_k (Aᵏ/k!) τᵏ, the powers formed once for every τ.
        let mut powers = Vec::with_capacity(TAYLOR_TERMS);
        powers.push(DMatrix::identity(dim, dim));
        for k in 1..TAYLOR_TERMS {
            let next = &ops.a * &powers[k - 1] / k as f64;
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
        let work = self.plan.outputs.energies.then(|| {
            let forms = self.power_forms(ops);
            let mut work = [(); 3].map(|_| DMatrix::zeros(dim, dim));
            for (x, w) in GAUSS {
                let phi_g = expm(x * h);
                for (wp, q) in work.iter_mut().zip(&forms) {
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
        let at = ops.a.transpose();
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
            for k in 0..TAYLOR_TERMS {
                if k > 0 {
                    r = &at * r / k as f64;
                    hk *= h;
                    for j in 0..dim {
                        tails[(j, f)] += r[j].abs() * hk;
                        if k >= LEAD_TERMS {
                            tails_far[(j, f)] += r[j].abs() * hk;
                        }
                    }
                }
                rows.set_column(f * TAYLOR_TERMS + k, &r);
            }
        }
        Stepping {
            phi,
            work,
            rows,
            tails,
            tails_far,
        }
    }
}

fn add_link(m: &mut DMatrix<f64>, i: usize, j: Option<usize>, k: f64) {
    m[(i, i)] += k;
    if let Some(j) = j {
        m[(j, j)] += k;
        m[(i, j)] -= k;
        m[(j, i)] -= k;
    }
}

/// Contact `r`'s row on y, stored as column `r` of `m` (a [`ModeOps`] row set), times `y`,
/// summed in order without allocating.
#[inline]
fn row_dot(m: &DMatrix<f64>, r: usize, y: &DVector<f64>) -> f64 {
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

/// The leading terms c_k hᵏ, 1 ≤ k < [`LEAD_TERMS`], of scanned function `f` over a grid
/// substep from `y` (c_k = its Taylor row · y), each the largest |c_k τᵏ| on [0, h]: so
/// g(0) + Σ min(0, ·) bounds g(0) + Σ c_k τᵏ from below there, |g(0)| + Σ |·| from above.
#[inline]
fn lead_terms(st: &Stepping, f: usize, y: &DVector<f64>, h: f64) -> [f64; LEAD_TERMS - 1] {
    let mut hk = 1.0;
    std::array::from_fn(|i| {
        hk *= h;
        st.rows.column(f * TAYLOR_TERMS + i + 1).dot(y) * hk
    })
}

/// yᵀ Q y, with `scratch` for Q y.
#[inline]
fn quadratic(q: &DMatrix<f64>, y: &DVector<f64>, scratch: &mut DVector<f64>) -> f64 {
    scratch.gemv(1.0, q, y, 0.0);
    y.dot(scratch)
}

/// The Taylor coefficients p_k = Aᵏ y / k! of exp(Aτ) y.
fn taylor(a: &DMatrix<f64>, y: &DVector<f64>, p: &mut [DVector<f64>]) {
    p[0].copy_from(y);
    for k in 1..p.len() {
        let (lo, hi) = p.split_at_mut(k);
        hi[0].gemv(1.0 / k as f64, a, &lo[k - 1], 0.0);
    }
}

/// Scalar polynomial Σ c_k τᵏ and its derivative.
#[inline]
fn poly(c: &[f64], t: f64) -> (f64, f64) {
    let mut p = 0.0;
    let mut d = 0.0;
    for k in (0..c.len()).rev() {
        d = d * t + p;
        p = p * t + c[k];
    }
    (p, d)
}

/// Root of `f` in [a, b] with f(a)·f(b) ≤ 0 (Illinois), to ~1e-15 s.
fn illinois(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let mut fa = f(a);
    let mut fb = f(b);
    if fa == 0.0 {
        return a;
    }
    if fb == 0.0 {
        return b;
    }
    let mut side = 0i8;
    for _ in 0..200 {
        let tol = 1e-15 + 4.0 * f64::EPSILON * b.abs();
        if (b - a).abs() <= tol {
            break;
        }
        let mut c = (a * fb - b * fa) / (fb - fa);
        if !(c > a.min(b) && c < a.max(b)) {
            c = 0.5 * (a + b);
        }
        let fc = f(c);
        if fc == 0.0 {
            return c;
        }
        if (fc > 0.0) == (fb > 0.0) {
            b = c;
            fb = fc;
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            fa = fc;
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        }
    }
    if fa.abs() < fb.abs() { a } else { b }
}

/// Σ_{k≥1} |c_k| lenᵏ, and the degree past which the terms add less than 1e-17 of
/// Σ_k |c_k| lenᵏ (the polynomial is scanned without them: a change far below round-off of
/// its values, and of its roots below the root finder's 1e-15 s).
fn tail_and_degree(c: &[f64], len: f64) -> (f64, usize) {
    let mut terms = [0.0; TAYLOR_TERMS];
    let mut tail = 0.0;
    let mut tk = 1.0;
    for (k, ck) in c.iter().enumerate() {
        terms[k] = ck.abs() * tk;
        if k > 0 {
            tail += terms[k];
        }
        tk *= len;
    }
    let total = tail + terms[0];
    let mut dropped = 0.0;
    let mut degree = c.len() - 1;
    while degree > 1 && dropped + terms[degree] < 1e-17 * total {
        dropped += terms[degree];
        degree -= 1;
    }
    (tail, degree)
}

/// First τ in (0, len] where the polynomial goes below −thr (a crossing, or a minimum
/// between scan points), located at its zero (or at −thr when it started in (−thr, 0)).
fn first_crossing(c: &[f64], len: f64, thr: f64) -> Option<f64> {
    let g0 = c[0];
    if g0 < -thr {
        // Already past: a contact recovering from round-off after its switch.
        return None;
    }
    // g(τ) ≥ g(0) − Σ_{k≥1} |c_k| τᵏ: nothing to find when that stays nonnegative.
    let (tail, degree) = tail_and_degree(c, len);
    if g0 - tail >= 0.0 {
        return None;
    }
    let c = &c[..=degree];
    let mut prev = (0.0, poly(c, 0.0));
    for j in 1..=SCAN_POINTS {
        let t = len * j as f64 / SCAN_POINTS as f64;
        let cur = (t, poly(c, t));
        let (ta, (ga, da)) = prev;
        let (tb, (gb, db)) = cur;
        let shift = if ga >= 0.0 { 0.0 } else { thr };
        if gb < -thr {
            return Some(illinois(|t| poly(c, t).0 + shift, ta, tb));
        }
        if da < 0.0 && db > 0.0 {
            let tm = illinois(|t| poly(c, t).1, ta, tb);
            if poly(c, tm).0 < -thr {
                return Some(illinois(|t| poly(c, t).0 + shift, ta, tm));
            }
        }
        prev = cur;
    }
    None
}

struct Cache {
    modes: HashMap<Vec<Mode>, Rc<ModeOps>>,
}

impl Cache {
    fn get(&mut self, model: &Model, key: &[Mode]) -> Rc<ModeOps> {
        if let Some(m) = self.modes.get(key) {
            return Rc::clone(m);
        }
        if self.modes.len() >= MODE_CACHE {
            self.modes.clear();
        }
        let ops = Rc::new(model.build(key));
        self.modes.insert(key.to_vec(), Rc::clone(&ops));
        ops
    }
}

/// Running integrals.
#[derive(Default, Clone, Copy)]
struct Integrals {
    input: f64,
    viscous: f64,
    friction: f64,
}

impl Model<'_> {
    /// The symmetric matrices Q_p with p(y) = yᵀ Q_p y of the input, viscous and friction
    /// powers of [`Model::powers`] (each is a quadratic form of the augmented state: the
    /// ground acceleration, the harmonic force and the constant slip forces are states).
    fn power_forms(&self, ops: &ModeOps) -> [DMatrix<f64>; 3] {
        let lay = &self.lay;
        let (n, dim) = (lay.n, lay.dim);
        let plan = self.plan;
        let mut input = DMatrix::zeros(dim, dim);
        let mut viscous = DMatrix::zeros(dim, dim);
        let mut friction = DMatrix::zeros(dim, dim);
        // −a_g (M r · v), and the harmonic force's F sin · v_floor.
        for i in 0..n {
            input[(lay.i_ag, n + i)] -= self.mr[i];
        }
        if let Some(h) = &plan.harmonic {
            input[(lay.i_sin, n + h.floor)] += h.amplitude;
        }
        // vᵀ C v.
        for j in 0..n {
            for i in 0..n {
                viscous[(n + i, n + j)] += plan.damping[(i, j)];
            }
        }
        for (c, ct) in plan.contacts.iter().enumerate() {
            // (force row · y)(slip-rate row · y).
            let f = ops.force.column(c);
            let w = ops.slip_rate.column(c);
            friction.ger(1.0, &f, &w, 1.0);
            if ct.kind == ContactKind::Epp && ct.brace_damping > 0.0 {
                // c′ (ẋ′ − v_below)².
                let mut e = ops.xdot.column(c).into_owned();
                if let Some(j) = ct.below {
                    e[n + j] -= 1.0;
                }
                viscous.ger(ct.brace_damping, &e, &e, 1.0);
            }
        }
        [input, viscous, friction].map(|q| (&q + q.transpose()) * 0.5)
    }

    fn powers(&self, ops: &ModeOps, y: &DVector<f64>) -> (f64, f64, f64) {
        let lay = &self.lay;
        let n = lay.n;
        let plan = self.plan;
        let v = &y.as_slice()[n..2 * n];
        let mut mrv = 0.0;
        let mut viscous = 0.0;
        for i in 0..n {
            mrv += self.mr[i] * v[i];
            let mut cv = 0.0;
            for (j, vj) in v.iter().enumerate() {
                cv += plan.damping[(i, j)] * vj;
            }
            viscous += v[i] * cv;
        }
        let mut input = -y[lay.i_ag] * mrv;
        if let Some(h) = &plan.harmonic {
            input += h.amplitude * y[lay.i_sin] * v[h.floor];
        }
        let mut friction = 0.0;
        for (c, ct) in plan.contacts.iter().enumerate() {
            friction += row_dot(&ops.force, c, y) * row_dot(&ops.slip_rate, c, y);
            if ct.kind == ContactKind::Epp && ct.brace_damping > 0.0 {
                let vb = ct.below.map_or(0.0, |j| v[j]);
                let ed = row_dot(&ops.xdot, c, y) - vb;
                viscous += ct.brace_damping * ed * ed;
            }
        }
        (input, viscous, friction)
    }

    /// Adds the input, viscous and friction work over a substep of length `len` by
    /// 6-point Gauss–Legendre ([`GAUSS`]); `node(g, out)` writes the state at the g-th node.
    fn integrate_powers(
        &self,
        ops: &ModeOps,
        integ: &mut Integrals,
        len: f64,
        ynode: &mut DVector<f64>,
        mut node: impl FnMut(usize, &mut DVector<f64>),
    ) {
        let (mut di, mut dv, mut df) = (0.0, 0.0, 0.0);
        for (g, (_, w)) in GAUSS.iter().enumerate() {
            node(g, ynode);
            let (pi, pv, pf) = self.powers(ops, ynode);
            di += w * pi;
            dv += w * pv;
            df += w * pf;
        }
        integ.input += di * len;
        integ.viscous += dv * len;
        integ.friction += df * len;
    }

    fn stored(&self, y: &DVector<f64>) -> (f64, f64) {
        let plan = self.plan;
        let n = self.lay.n;
        let u = y.rows(0, n);
        let v = y.rows(n, n);
        // Quadratic forms without temporaries (called at every output step).
        let quad = |m: &DMatrix<f64>, x: &nalgebra::DVectorView<f64>| -> f64 {
            let mut q = 0.0;
            for (j, xj) in x.iter().enumerate() {
                q += xj * m.column(j).dot(x);
            }
            q
        };
        let kinetic = 0.5 * quad(&plan.mass, &v);
        let mut strain = 0.5 * quad(&plan.stiffness, &u);
        for (c, ct) in plan.contacts.iter().enumerate() {
            if let Some(s) = self.lay.epp_slot[c] {
                let e = y[s] - ct.below.map_or(0.0, |j| u[j]);
                strain += 0.5 * ct.brace_stiffness * e * e;
            }
        }
        (kinetic, strain)
    }

    /// Modes decided by the acceleration-level box QP for the contacts in `decide`
    /// (all other contacts keep `modes`).
    fn decide(
        &self,
        cache: &mut Cache,
        y: &DVector<f64>,
        modes: &mut [Mode],
        decide: &[usize],
        t: f64,
    ) -> Result<(), SimError> {
        if decide.is_empty() {
            return Ok(());
        }
        let plan = self.plan;
        let lay = &self.lay;
        let n = lay.n;
        // Forces of all non-decided contacts from the current modes.
        let mut tmp: Vec<Mode> = modes.to_vec();
        for &c in decide {
            tmp[c] = Mode::Upper; // placeholder: its force is excluded below
        }
        let ops = cache.get(self, &tmp);
        let mut g = &self.f0 * y;
        for (c, _) in plan.contacts.iter().enumerate() {
            if decide.contains(&c) {
                continue;
            }
            let fc = row_dot(&ops.force, c, y);
            g.axpy(-fc, &self.bcols[c], 1.0);
        }
        let m = decide.len();
        let mut bu = DMatrix::zeros(n, m);
        for (k, &c) in decide.iter().enumerate() {
            bu.set_column(k, &self.bcols[c]);
        }
        let wa = bu.transpose() * &self.minv * &bu;
        let wa = (&wa + wa.transpose()) * 0.5;
        let b = bu.transpose() * (&self.minv * g);
        let lo: Vec<f64> = decide.iter().map(|&c| plan.contacts[c].lower).collect();
        let hi: Vec<f64> = decide.iter().map(|&c| plan.contacts[c].upper).collect();
        let mut f = vec![0.0; m];
        let mut qp =
            BoxQp::new(wa.as_slice(), m).map_err(|source| SimError::Friction { t, source })?;
        qp.solve(b.as_slice(), &lo, &hi, &mut f)
            .map_err(|source| SimError::Friction { t, source })?;
        for (k, &c) in decide.iter().enumerate() {
            modes[c] = match qp.status(k) {
                Bound::Free => Mode::Stuck,
                Bound::Upper => Mode::Upper,
                Bound::Lower => Mode::Lower,
            };
        }
        Ok(())
    }
}

/// Adds the history row of state `y` at time `t`.
fn history_row(
    model: &Model,
    ops: &ModeOps,
    h: &mut History,
    t: f64,
    y: &DVector<f64>,
    e: Option<[f64; 5]>,
) {
    let plan = model.plan;
    let lay = &model.lay;
    let nf = plan.floors;
    h.rows.push(t);
    h.rows.push(y[lay.i_ag]);
    h.rows.extend(y.rows(0, nf).iter());
    for (c, ct) in plan.contacts.iter().enumerate() {
        h.rows.push(match (ct.kind, lay.epp_slot[c]) {
            (ContactKind::Dof { dof }, _) => y[dof],
            (_, Some(s)) => y[s],
            (ContactKind::Epp, None) => 0.0,
        });
    }
    let mut below = 0.0;
    for i in 0..nf {
        h.rows.push(y[i] - below);
        below = y[i];
    }
    for c in 0..plan.contacts.len() {
        h.rows.push(row_dot(&ops.force, c, y));
    }
    for c in 0..plan.contacts.len() {
        h.rows.push(row_dot(&ops.slip_rate, c, y));
    }
    if let Some(e) = e {
        h.rows.extend_from_slice(&e);
    }
}

/// Ground acceleration at the start of [ta, tb] and its slope on it (0 after the record).
fn ground_segment(plan: &Plan, ta: f64, tb: f64) -> (f64, f64) {
    match &plan.record {
        Some(r) => {
            let dur = r.duration();
            if ta >= dur - 1e-12 * r.dt() {
                return (0.0, 0.0);
            }
            let a0 = r.accel_at(ta);
            let a1 = r.accel_at(tb.min(dur));
            (a0, (a1 - a0) / (tb - ta))
        }
        None => (0.0, 0.0),
    }
}

/// End of the piece starting at `ta` (next record sample or record end, else `t_end`).
fn piece_end(plan: &Plan, ta: f64, t_end: f64) -> f64 {
    match &plan.record {
        Some(r) => {
            let rdt = r.dt();
            let dur = r.duration();
            if ta >= dur - 1e-12 * rdt {
                return t_end;
            }
            let mut k = (ta / rdt).floor() + 1.0;
            if k * rdt - ta <= 1e-9 * rdt {
                k += 1.0;
            }
            let ts = (k * rdt).min(dur);
            if ts < t_end - 1e-9 * rdt { ts } else { t_end }
        }
        None => t_end,
    }
}

impl Integrator for Exact {
    fn name(&self) -> &'static str {
        "exact"
    }

    #[allow(clippy::too_many_lines)]
    fn run(&self, plan: &Plan) -> Result<Outcome, SimError> {
        let dt = plan.method.dt;
        if !is_positive(dt) {
            return Err(SimError::BadTimeStep { dt });
        }
        let model = Model::new(plan)?;
        let lay = &model.lay;
        let (n, dim) = (lay.n, lay.dim);
        let nf = plan.floors;
        let nc = plan.contacts.len();
        let rho = model.spectral_bound();
        let delta_max = if rho > 0.0 {
            SUBSTEP_PHASE / rho
        } else {
            f64::INFINITY
        };
        let duration = plan.steps as f64 * dt;
        let needed = (duration / delta_max).ceil();
        if needed > MAX_SUBSTEPS as f64 {
            return Err(SimError::ExactBudget {
                what: "substeps".into(),
                t: 0.0,
                needed: needed as u64,
                limit: MAX_SUBSTEPS,
                hint: format!(
                    "the fastest mode rings at {rho:.3e} rad/s (very light or very stiff dissipators); use newmark, or the massless limit (mass 0)"
                ),
            });
        }
        let energies = plan.outputs.energies;

        // Initial state.
        let mut y = DVector::zeros(dim);
        y.rows_mut(0, n).copy_from_slice(&plan.u0);
        y.rows_mut(n, n).copy_from_slice(&plan.v0);
        y[lay.i_one] = 1.0;
        for (c, s) in lay.epp_slot.iter().enumerate() {
            if let Some(s) = s {
                y[*s] = plan.contact_x0[c].0;
            }
        }
        let set_inputs = |y: &mut DVector<f64>, ta: f64, tb: f64| {
            let (a0, slope) = ground_segment(plan, ta, tb);
            y[lay.i_ag] = a0;
            y[lay.i_slope] = slope;
            if let Some(h) = &plan.harmonic {
                let ph = h.omega * ta + h.phase;
                y[lay.i_sin] = ph.sin();
                y[lay.i_cos] = ph.cos();
            }
        };
        let first_end = piece_end(plan, 0.0, dt.min(duration.max(dt)));
        set_inputs(&mut y, 0.0, first_end);
        let mut v_ref = plan.v0[..n].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut modes = vec![Mode::Stuck; nc];
        let mut to_decide = Vec::new();
        for (c, ct) in plan.contacts.iter().enumerate() {
            match ct.kind {
                ContactKind::Epp => {
                    let s = lay.epp_slot[c].expect("EPP contacts have a slot");
                    let (uj, vj) = ct.below.map_or((0.0, 0.0), |j| (y[j], y[n + j]));
                    let vd = plan.contact_x0[c].1;
                    let force = ct.brace_stiffness * (y[s] - uj) + ct.brace_damping * (vd - vj);
                    let tol = 1e-12
                        * (ct.upper.abs().min(1e300) + ct.lower.abs().min(1e300) + force.abs());
                    if force > ct.upper + tol || force < ct.lower - tol {
                        return Err(SimError::Scene(format!(
                            "initial state: the massless dissipator of floor {} carries a brace force of {force:.6e} N, outside its friction bounds [{:.6e}, {:.6e}] N",
                            ct.floor + 1,
                            ct.lower,
                            ct.upper
                        )));
                    }
                    let w = y[n + ct.floor] - vd;
                    modes[c] = if force >= ct.upper - tol && w > 0.0 {
                        Mode::Upper
                    } else if force <= ct.lower + tol && w < 0.0 {
                        Mode::Lower
                    } else {
                        Mode::Stuck
                    };
                }
                ContactKind::Dof { .. } if ct.lower == ct.upper => modes[c] = Mode::Upper,
                ContactKind::Dof { dof } => {
                    let w0 = y[n + ct.floor] - y[n + dof];
                    let tol = 1e-12 * (y[n + ct.floor].abs() + y[n + dof].abs());
                    if w0.abs() > tol {
                        let bound = if w0 > 0.0 { ct.upper } else { ct.lower };
                        if !bound.is_finite() {
                            return Err(SimError::Scene(format!(
                                "initial state: the locked dissipator of floor {} cannot slip, but its initial slip rate is {w0:.6e} m/s",
                                ct.floor + 1
                            )));
                        }
                        modes[c] = if w0 > 0.0 { Mode::Upper } else { Mode::Lower };
                    } else {
                        to_decide.push(c);
                    }
                }
            }
        }
        let mut cache = Cache {
            modes: HashMap::new(),
        };
        model.decide(&mut cache, &y, &mut modes, &to_decide, 0.0)?;
        let mut ops = cache.get(&model, &modes);
        let mut integ = Integrals::default();
        let (k0, s0) = model.stored(&y);
        let initial_energy = k0 + s0;
        // ∫ E_strain dt by the trapezoid rule at the output steps (as the step methods do).
        let mut strain_area = 0.0;
        let mut strain_prev = s0;
        // Project the initial velocities onto the stuck constraints (a no-op for
        // consistent initial states).
        let scratch = RefCell::new(DVector::zeros(n));
        let project = |y: &mut DVector<f64>, ops: &ModeOps| {
            if let Some(p) = &ops.proj {
                let mut v = scratch.borrow_mut();
                v.gemv(1.0, p, &y.rows(n, n), 0.0);
                y.rows_mut(n, n).copy_from(&*v);
            }
        };
        project(&mut y, &ops);
        // The same during the run, the kinetic energy it removes booked as friction work
        // (when energies are asked for).
        let project_counted = |y: &mut DVector<f64>, ops: &ModeOps, integ: &mut Integrals| {
            if energies {
                let (ke_before, _) = model.stored(y);
                project(y, ops);
                let (ke_after, _) = model.stored(y);
                integ.friction += ke_before - ke_after;
            } else {
                project(y, ops);
            }
        };

        let mut peaks = Peaks::new(nf);
        let mut cont_drift = vec![0.0; nf];
        let msum: f64 = model.mr.iter().sum();
        let mut acc = DVector::zeros(dim);
        let observe =
            |peaks: &mut Peaks, ops: &ModeOps, y: &DVector<f64>, acc: &mut DVector<f64>| {
                acc.gemv(1.0, &ops.a, y, 0.0);
                let ag = y[lay.i_ag];
                let p = plan
                    .harmonic
                    .as_ref()
                    .map_or(0.0, |h| h.amplitude * y[lay.i_sin]);
                peaks.observe_floors(y.as_slice(), &acc.as_slice()[n..2 * n], ag);
                peaks.observe_base_shear(base_shear(
                    model.mr.as_slice(),
                    msum,
                    &acc.as_slice()[n..2 * n],
                    ag,
                    p,
                ));
                for (c, ct) in plan.contacts.iter().enumerate() {
                    let other = match (ct.kind, lay.epp_slot[c]) {
                        (ContactKind::Dof { dof }, _) => y[dof],
                        (_, Some(s)) => y[s],
                        (ContactKind::Epp, None) => 0.0,
                    };
                    peaks.observe_slip(ct.floor, y[ct.floor] - other);
                }
            };
        observe(&mut peaks, &ops, &y, &mut acc);
        cont_drift.copy_from_slice(&peaks.drift);

        let mut history = plan
            .outputs
            .histories
            .then(|| history_columns(plan, energies));
        if let Some(h) = history.as_mut() {
            let e = energies.then_some([0.0, k0, s0, 0.0, 0.0]);
            history_row(&model, &ops, h, 0.0, &y, e);
        }

        // Work buffers.
        let mut p: Vec<DVector<f64>> = vec![DVector::zeros(dim); TAYLOR_TERMS];
        let mut coef = vec![0.0; TAYLOR_TERMS];
        let mut dcoef = [0.0; TAYLOR_TERMS];
        let mut ynode = DVector::zeros(dim);
        let mut yabs = DVector::zeros(dim);
        let eval = |p: &[DVector<f64>], t: f64, out: &mut DVector<f64>| {
            out.copy_from(&p[TAYLOR_TERMS - 1]);
            for k in (0..TAYLOR_TERMS - 1).rev() {
                *out *= t;
                *out += &p[k];
            }
        };
        let mut events: u64 = 0;
        let mut same_instant: u32 = 0;
        let mut last_event_t = f64::NEG_INFINITY;
        let mut balance_max_rel: f64 = 0.0;

        for step in 0..plan.steps {
            let t_step_end = (step + 1) as f64 * dt;
            let mut ta = step as f64 * dt;
            let step_start = ta;
            while ta < t_step_end {
                let tb = piece_end(plan, ta, t_step_end);
                set_inputs(&mut y, ta, tb);
                // A piece that is a whole output step runs on its mode set's grid
                // ta + j·h (h = Δt/m): a substep from one grid point to the next is one
                // product with the cached exp(A h), and its scans start with a bound that
                // rules most of them out. Substeps off the grid (after an event, or in
                // pieces cut by record samples) sum the Taylor series for their length.
                let whole = ta == step_start && tb == t_step_end;
                let mut t = ta;
                let mut on_grid = whole.then_some(0usize);
                while t < tb {
                    let rem = tb - t;
                    // (length, grid index reached, whether it starts on the grid)
                    let (len, reach, regular) = if whole {
                        let m = ops.per_step;
                        match on_grid {
                            Some(j) => (ops.h, Some(j + 1), true),
                            None => {
                                let j = (((t - ta) / ops.h).floor() as usize + 1).min(m);
                                let tn = if j >= m { tb } else { ta + j as f64 * ops.h };
                                if tn <= t {
                                    // Already at that grid point (to round-off).
                                    on_grid = Some(j);
                                    t = tn;
                                    continue;
                                }
                                (tn - t, Some(j), false)
                            }
                        }
                    } else {
                        let len = if rem <= ops.delta_max * (1.0 + 1e-12) {
                            rem
                        } else {
                            rem / (rem / ops.delta_max).ceil()
                        };
                        (len, None, false)
                    };
                    // A grid substep of a mode set that has lasted uses its propagators;
                    // any other substep sums the Taylor coefficients p_k = Aᵏ y / k!.
                    if regular && ops.stepping.get().is_none() {
                        let u = ops.uses.get() + 1;
                        ops.uses.set(u);
                        if u > ops.prepare_after {
                            let _ = ops.stepping.set(model.stepping(&ops));
                        }
                    }
                    let fast = if regular { ops.stepping.get() } else { None };
                    if fast.is_some() {
                        for (a, b) in yabs.iter_mut().zip(y.iter()) {
                            *a = b.abs();
                        }
                    } else {
                        taylor(&ops.a, &y, &mut p);
                    }
                    let nev = ops.events.len();
                    let coefs =
                        |f: usize, y: &DVector<f64>, p: &[DVector<f64>], coef: &mut [f64]| {
                            if let Some(st) = fast {
                                for (k, c) in coef.iter_mut().enumerate() {
                                    *c = st.rows.column(f * TAYLOR_TERMS + k).dot(y);
                                }
                            } else if f < nev {
                                let row = &ops.events[f].row;
                                for (c, pk) in coef.iter_mut().zip(p) {
                                    *c = row.dot(pk);
                                }
                            } else {
                                let i = f - nev;
                                for (c, pk) in coef.iter_mut().zip(p) {
                                    *c = pk[i] - if i == 0 { 0.0 } else { pk[i - 1] };
                                }
                            }
                        };
                    // Earliest event.
                    let mut tau_end = len;
                    let mut fired: Option<usize> = None;
                    for (e, ef) in ops.events.iter().enumerate() {
                        if let Some(st) = fast {
                            let g0 = ef.row.dot(&y);
                            if g0 >= st.tails.column(e).dot(&yabs) {
                                // g(τ) ≥ g(0) − Σ|y_j|·tail_j ≥ 0 on the whole substep.
                                continue;
                            }
                            if g0 >= 0.0
                                && lead_terms(st, e, &y, ops.h)
                                    .iter()
                                    .fold(g0, |low, t| low + t.min(0.0))
                                    >= st.tails_far.column(e).dot(&yabs)
                            {
                                // g(τ) ≥ Σ_{k<L} min(0, c_k hᵏ) − Σ|y_j|·tail_far_j ≥ 0
                                // (the leading terms formed exactly).
                                continue;
                            }
                        }
                        coefs(e, &y, &p, &mut coef);
                        let thr = match ef.scale {
                            Scale::Force(b) => GRAZE_REL * b,
                            Scale::Velocity => GRAZE_REL * v_ref,
                        };
                        if let Some(te) = first_crossing(&coef, tau_end, thr)
                            && te <= tau_end
                        {
                            tau_end = te;
                            fired = Some(e);
                        }
                    }
                    // Drift extrema inside (0, tau_end].
                    for i in 0..nf {
                        if let Some(st) = fast {
                            let d0 = y[i] - if i == 0 { 0.0 } else { y[i - 1] };
                            if d0.abs() + st.tails.column(nev + i).dot(&yabs) <= cont_drift[i] {
                                continue;
                            }
                            if lead_terms(st, nev + i, &y, ops.h)
                                .iter()
                                .fold(d0.abs(), |high, t| high + t.abs())
                                + st.tails_far.column(nev + i).dot(&yabs)
                                <= cont_drift[i]
                            {
                                continue;
                            }
                        }
                        coefs(nev + i, &y, &p, &mut coef);
                        let (tail, degree) = tail_and_degree(&coef, tau_end);
                        if coef[0].abs() + tail <= cont_drift[i] {
                            continue;
                        }
                        let coef = &coef[..=degree];
                        for k in 1..=degree {
                            dcoef[k - 1] = coef[k] * k as f64;
                        }
                        let dcoef = &dcoef[..degree];
                        let mut prev = (0.0, poly(dcoef, 0.0).0);
                        for j in 1..=SCAN_POINTS {
                            let tj = tau_end * j as f64 / SCAN_POINTS as f64;
                            let dj = poly(dcoef, tj).0;
                            if (prev.1 > 0.0 && dj < 0.0) || (prev.1 < 0.0 && dj > 0.0) {
                                let tm = illinois(|t| poly(dcoef, t).0, prev.0, tj);
                                cont_drift[i] = cont_drift[i].max(poly(coef, tm).0.abs());
                            }
                            prev = (tj, dj);
                        }
                        cont_drift[i] = cont_drift[i].max(poly(coef, tau_end).0.abs());
                    }
                    if let (Some(st), None) = (fast, fired) {
                        if let Some([wi, wv, wf]) = &st.work {
                            // One grid interval: its work is a quadratic form of y.
                            integ.input += quadratic(wi, &y, &mut ynode);
                            integ.viscous += quadratic(wv, &y, &mut ynode);
                            integ.friction += quadratic(wf, &y, &mut ynode);
                        }
                        ynode.gemv(1.0, &st.phi, &y, 0.0);
                        std::mem::swap(&mut y, &mut ynode);
                    } else {
                        if fast.is_some() {
                            // A grid substep cut by an event.
                            taylor(&ops.a, &y, &mut p);
                        }
                        if energies {
                            model.integrate_powers(
                                &ops,
                                &mut integ,
                                tau_end,
                                &mut ynode,
                                |g, out| {
                                    eval(&p, GAUSS[g].0 * tau_end, out);
                                },
                            );
                        }
                        eval(&p, tau_end, &mut y);
                    }
                    match (fired, reach) {
                        (None, Some(j)) => {
                            t = if j >= ops.per_step {
                                tb
                            } else {
                                ta + j as f64 * ops.h
                            };
                            on_grid = Some(j);
                        }
                        (None, None) if len == rem => t = tb,
                        _ => {
                            t += tau_end;
                            on_grid = None;
                        }
                    }
                    for i in 0..nf {
                        v_ref = v_ref.max(y[n + i].abs());
                    }
                    if !y.iter().all(|x| x.is_finite()) {
                        return Err(SimError::NonFinite {
                            step: step + 1,
                            t,
                            hint: "exact: the state became non-finite".into(),
                        });
                    }
                    let Some(e) = fired else { continue };
                    // Event: decide the new modes.
                    events += 1;
                    if events > MAX_EVENTS {
                        return Err(SimError::ExactBudget {
                            what: "stick-slip events".into(),
                            t,
                            needed: events,
                            limit: MAX_EVENTS,
                            hint: "the dissipators chatter; use newmark, or the massless limit"
                                .into(),
                        });
                    }
                    let c_fired = ops.events[e].contact;
                    if t - last_event_t <= 1e-14 * t.max(1.0) {
                        same_instant += 1;
                        if same_instant > 4 * nc as u32 + 16 {
                            return Err(SimError::ExactZeno {
                                t,
                                events: same_instant,
                                floor: plan.contacts[c_fired].floor + 1,
                            });
                        }
                    } else {
                        same_instant = 0;
                    }
                    last_event_t = t;
                    let old = modes.clone();
                    // Every function at (or past) zero and heading down fires with it.
                    acc.gemv(1.0, &ops.a, &y, 0.0);
                    let mut decide: Vec<usize> = Vec::new();
                    for (k, ef) in ops.events.iter().enumerate() {
                        let g = ef.row.dot(&y);
                        let gd = ef.row.dot(&acc);
                        let thr = match ef.scale {
                            Scale::Force(b) => GRAZE_REL * b,
                            Scale::Velocity => GRAZE_REL * v_ref,
                        };
                        let fires = k == e || (g <= thr && gd < 0.0);
                        if !fires {
                            continue;
                        }
                        let c = ef.contact;
                        let ct = &plan.contacts[c];
                        match old[c] {
                            Mode::Stuck => {
                                // Which bound: the force row sign tells.
                                let fc = row_dot(&ops.force, c, &y);
                                modes[c] = if (fc - ct.upper).abs() <= (fc - ct.lower).abs() {
                                    Mode::Upper
                                } else {
                                    Mode::Lower
                                };
                                if let (Some(s), true) = (lay.epp_slot[c], ct.brace_damping == 0.0)
                                {
                                    // Snap the brace onto the bound (a root-finding residual).
                                    let bound = if modes[c] == Mode::Upper {
                                        ct.upper
                                    } else {
                                        ct.lower
                                    };
                                    let uj = ct.below.map_or(0.0, |j| y[j]);
                                    let e_old = y[s] - uj;
                                    let e_new = bound / ct.brace_stiffness;
                                    integ.friction +=
                                        0.5 * ct.brace_stiffness * (e_old * e_old - e_new * e_new);
                                    y[s] = uj + e_new;
                                }
                            }
                            Mode::Upper | Mode::Lower => match ct.kind {
                                ContactKind::Epp => modes[c] = Mode::Stuck,
                                ContactKind::Dof { .. } => {
                                    if !decide.contains(&c) {
                                        decide.push(c);
                                    }
                                }
                            },
                        }
                    }
                    if !decide.is_empty() {
                        for (c, ct) in plan.contacts.iter().enumerate() {
                            if matches!(ct.kind, ContactKind::Dof { .. })
                                && modes[c] == Mode::Stuck
                                && old[c] == Mode::Stuck
                                && !decide.contains(&c)
                            {
                                decide.push(c);
                            }
                        }
                        decide.sort_unstable();
                        model.decide(&mut cache, &y, &mut modes, &decide, t)?;
                    }
                    for c in 0..nc {
                        if (modes[c] == Mode::Stuck) != (old[c] == Mode::Stuck) {
                            peaks.transitions[plan.contacts[c].floor] += 1;
                        }
                    }
                    ops = cache.get(&model, &modes);
                    project_counted(&mut y, &ops, &mut integ);
                }
                ta = tb;
            }
            // Output step. Re-impose B_Sᵀv = 0 on the stuck contacts: the projected
            // dynamics keep it only to round-off, which accumulates over many substeps on
            // very stiff braces (the kinetic energy removed, ~ε², goes to friction).
            if ops.proj.is_some() {
                project_counted(&mut y, &ops, &mut integ);
            }
            observe(&mut peaks, &ops, &y, &mut acc);
            let mut e_row = None;
            if energies {
                let (ek, es) = model.stored(&y);
                strain_area += 0.5 * dt * (strain_prev + es);
                strain_prev = es;
                let bal = integ.input + initial_energy - (ek + es + integ.viscous + integ.friction);
                let scale = (integ.input.abs() + initial_energy).max(f64::MIN_POSITIVE);
                balance_max_rel = balance_max_rel.max(bal.abs() / scale);
                e_row = Some([integ.input, ek, es, integ.viscous, integ.friction]);
            }
            if let Some(h) = history.as_mut() {
                history_row(&model, &ops, h, t_step_end, &y, e_row);
            }
        }
        for (c, s) in cont_drift.iter_mut().zip(&peaks.drift) {
            *c = c.max(*s);
        }
        let energy = energies.then(|| {
            let (ek, es) = model.stored(&y);
            Energy {
                input: integ.input,
                kinetic: ek,
                strain: es,
                viscous: integ.viscous,
                friction: integ.friction,
                balance_error: integ.input + initial_energy
                    - (ek + es + integ.viscous + integ.friction),
            }
        });
        let sampled = peaks.drift.clone();
        peaks.drift = cont_drift;
        let response = peaks.into_plan_response(plan, energy);
        Ok(Outcome {
            response,
            diagnostics: Diagnostics {
                balance_error_max_relative: balance_max_rel,
                initial_energy,
                sampled_peak_drift: Some(sampled),
                events,
                strain_energy_area: strain_area,
                ..Default::default()
            },
            history,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn power_forms_are_the_powers() {
        // Two storeys: a massless dissipator with a damped brace (its c′ term), one with
        // mass (a Lagrange multiplier while stuck), a harmonic force and Rayleigh damping.
        // For every mode set, yᵀ Q_p y must be the power itself at any augmented state, to
        // round-off of the sums (relative to their absolute terms, ~1e-15).
        let text = r#"{ "building": { "floor_masses": [4.0e5, 3.0e5], "storey_stiffness": [2.0e8, 1.5e8],
                "damping": { "rayleigh": { "alpha": 0.2, "beta": 1e-3 } },
                "dissipators": [
                  { "floor": 1, "brace_stiffness": 4.0e8, "mass": 0, "brace_damping": 3e5, "slip_load": 4e5 },
                  { "floor": 2, "brace_stiffness": 3.0e8, "mass": 350, "brace_damping": 0, "slip_load": 2e5 } ] },
              "excitation": { "harmonic": { "floor": 2, "amplitude": 1e5, "omega": 9.0 } },
              "duration": 1.0, "method": { "name": "exact", "dt": 0.01 }, "outputs": { "energies": true } }"#;
        let scene = crate::scene::Scene::from_json(
            text,
            std::path::Path::new("inline.json"),
            &crate::scene::SceneOverrides::default(),
        )
        .unwrap();
        let plan = Plan::compile(&scene).unwrap();
        let model = Model::new(&plan).unwrap();
        let dim = model.lay.dim;
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut uniform = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        use Mode::{Lower, Stuck, Upper};
        for modes in [
            [Stuck, Stuck],
            [Upper, Lower],
            [Lower, Stuck],
            [Stuck, Upper],
        ] {
            let ops = model.build(&modes);
            let forms = model.power_forms(&ops);
            for _ in 0..20 {
                let y = DVector::from_fn(dim, |_, _| uniform());
                let (pi, pv, pf) = model.powers(&ops, &y);
                for (q, p, what) in [
                    (&forms[0], pi, "input"),
                    (&forms[1], pv, "viscous"),
                    (&forms[2], pf, "friction"),
                ] {
                    let from_form = (q * &y).dot(&y);
                    let scale = (q.abs() * y.abs()).dot(&y.abs());
                    assert!(
                        (from_form - p).abs() <= 1e-13 * scale,
                        "{modes:?} {what}: form {from_form:e}, power {p:e}, scale {scale:e}"
                    );
                }
            }
        }
    }

    #[test]
    fn polynomial_and_derivative() {
        let c = [1.0, -2.0, 3.0];
        let (p, d) = poly(&c, 2.0);
        assert_eq!(p, 1.0 - 4.0 + 12.0);
        assert_eq!(d, -2.0 + 12.0);
    }

    #[test]
    fn illinois_finds_a_simple_root_to_round_off() {
        let r = illinois(|t| t * t - 2.0, 0.0, 2.0);
        assert!((r - 2f64.sqrt()).abs() < 1e-14, "{r}");
    }

    #[test]
    fn crossing_between_scan_points_is_found_from_the_minimum() {
        // g(τ) = (τ − 0.5)² − 1e-6 dips below zero between scan points 0.5 ± 0.001.
        let c = [0.25 - 1e-6, -1.0, 1.0];
        let t = first_crossing(&c, 1.0, 1e-12).expect("a crossing");
        assert!((t - (0.5 - 1e-3)).abs() < 1e-12, "{t}");
        // A graze within the threshold is no event.
        let c = [0.25 + 1e-13, -1.0, 1.0];
        assert!(first_crossing(&c, 1.0, 1e-12).is_none());
    }

    #[test]
    fn gauss_rule_is_exact_to_degree_11_and_not_beyond() {
        // ∫₀¹ xᵏ dx = 1/(k+1) for every k ≤ 2·6 − 1, to round-off of the nodes' digits.
        for k in 0..=11 {
            let s: f64 = GAUSS.iter().map(|(x, w)| w * x.powi(k)).sum();
            assert!((s - 1.0 / (k + 1) as f64).abs() < 1e-15, "degree {k}: {s}");
        }
        // Degree 12 carries the rule's error term: (6!)⁴·12!/(13·(12!)³) ≈ 8.9e-8.
        let s: f64 = GAUSS.iter().map(|(x, w)| w * x.powi(12)).sum();
        let e = 720f64.powi(4) / (13.0 * 479_001_600f64.powi(2));
        assert!(
            ((1.0 / 13.0 - s) - e).abs() < 1e-3 * e,
            "{}",
            1.0 / 13.0 - s
        );
    }
}
