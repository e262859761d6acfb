//! The data of one `exact` run and of its mode sets: the contacts' modes ([`Mode`]), the
//! augmented state's layout ([`Layout`]), the run-wide model ([`Model`]: mass inverse,
//! contact columns, the forces without contacts, the spectral bound ρ of any mode set),
//! and what is fixed for one mode set ([`ModeOps`], with its event functions and its grid
//! propagators [`Stepping`]). The files above this one form these (`modes` the operators,
//! `propagate` the propagators, `energy` the powers, `cache` the mode sets kept, `decide`
//! the contacts at an event).

use super::kernels::SparseRows;
use crate::error::SimError;
use crate::kinematics::add_between;
use crate::plan::{ContactKind, Plan};
use nalgebra::{DMatrix, DVector};
use std::cell::OnceCell;

/// State of one contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Mode {
    Stuck,
    Upper,
    Lower,
}

/// Positions in the augmented state.
pub(super) struct Layout {
    pub(super) n: usize,
    /// State index of x′ for elastic–perfectly plastic contacts.
    pub(super) epp_slot: Vec<Option<usize>>,
    pub(super) i_ag: usize,
    pub(super) i_slope: usize,
    pub(super) i_sin: usize,
    pub(super) i_cos: usize,
    pub(super) i_one: usize,
    /// A second ground component's acceleration and slope (a plan under both
    /// components), after the chain's states so a chain's layout is unchanged.
    pub(super) second: Option<(usize, usize)>,
    pub(super) dim: usize,
}

#[derive(Clone, Copy, PartialEq)]
pub(super) enum Scale {
    Force(f64),
    Velocity,
}

/// g(y) = row·y ≥ 0 while the mode is consistent.
pub(super) struct EventFn {
    pub(super) contact: usize,
    pub(super) row: DVector<f64>,
    pub(super) scale: Scale,
}

/// Everything fixed for one mode set.
pub(super) struct ModeOps {
    pub(super) a: DMatrix<f64>,
    /// `a` by rows, its nonzeros only ([`SparseRows`]): the velocity rows are one entry,
    /// the generators' one or none, the elements' few; only the acceleration rows are
    /// full. Products with it cost n·dim instead of dim².
    pub(super) a_rows: SparseRows,
    /// The acceleration rows n..2n of `a`, stored transposed (dim × n: column i is the
    /// acceleration of DOF i as a row on y), for the peaks at every output step.
    pub(super) acc_rows: DMatrix<f64>,
    /// Friction force of each contact as a row on y, stored transposed (dim × contacts:
    /// column c is contact c's row, contiguous for [`row_dot`](super::kernels::row_dot)).
    pub(super) force: DMatrix<f64>,
    /// Slip rate of each contact as a row on y, transposed likewise.
    pub(super) slip_rate: DMatrix<f64>,
    /// ẋ′ rows of elastic–perfectly plastic contacts (zero rows for others), transposed
    /// likewise.
    pub(super) xdot: DMatrix<f64>,
    pub(super) events: Vec<EventFn>,
    /// |row| of each event function, componentwise: with the far Taylor terms' sizes it
    /// bounds the part of g past its leading coefficients on a summed substep.
    pub(super) event_abs: Vec<DVector<f64>>,
    /// The M-orthogonal projector of the velocities onto B_Sᵀv = 0 for the stuck contacts
    /// with a DOF, I − M⁻¹B_S W_S⁻¹B_Sᵀ (n × n); `None` when none sticks.
    pub(super) proj: Option<DMatrix<f64>>,
    /// The sampled peaks' quantities as rows on y, transposed (dim × functions), in the
    /// order of `observed_peak` (`modes`): storey drifts, floor displacements, absolute floor
    /// accelerations, base shear, then each contact's slip. Formed only when a grid
    /// substep holds several output steps and testing them costs less than observing
    /// those (dim × 0 otherwise: every output step is observed).
    pub(super) obs_rows: DMatrix<f64>,
    /// Longest substep, [`SUBSTEP_PHASE`](super::params::SUBSTEP_PHASE)/ρ (ρ this mode set's spectral bound).
    pub(super) delta_max: f64,
    /// Substeps per frame of q output steps ([`frame_steps`]), m, and the grid interval
    /// h = qΔt/m: m = q⌈Δt/δ_max⌉ where an output step is longer than δ_max, else
    /// q/s with s the largest divisor of q such that sΔt ≤ δ_max. Output steps are
    /// grid points either way.
    pub(super) per_step: usize,
    /// Output steps per grid substep, s (0 when a substep is shorter than an output step).
    pub(super) out_steps: usize,
    pub(super) h: f64,
    /// How many grid substeps taken with the Taylor sums make the mode set worth its
    /// propagators in a run (forming them costs about dim + scanned functions substeps).
    pub(super) prepare_after: usize,
    /// The grid propagators ([`Model::stepping`]), formed the first time a run's use of
    /// the mode set reaches `prepare_after` (and kept for later runs of the same
    /// building, `Cache`).
    pub(super) stepping: OnceCell<Stepping>,
}

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

/// Run-wide model data.
pub(super) struct Model<'a> {
    pub(super) plan: &'a Plan,
    pub(super) lay: Layout,
    pub(super) minv: DMatrix<f64>,
    /// L⁻¹ of the mass matrix's Cholesky factor M = LLᵀ.
    pub(super) linv: DMatrix<f64>,
    pub(super) mr: DVector<f64>,
    /// M r₂ of a second ground component.
    pub(super) mr2: Option<DVector<f64>>,
    /// Contact columns of B.
    pub(super) bcols: Vec<DVector<f64>>,
    /// Forces without contacts as rows on y (n × dim).
    pub(super) f0: DMatrix<f64>,
    pub(super) omega_h: f64,
    /// Whether a storey yields (the plastic work is then kept apart from friction).
    pub(super) storeys: bool,
    /// Output steps per frame, q ([`frame_steps`]): a frame of qΔt is the interval a mode
    /// set's grid divides.
    pub(super) frame_steps: usize,
}

/// Output steps per frame: the record's sample interval in output steps when the run asks
/// for peaks only (no histories, no energies) and Δt divides that interval, else 1. A
/// frame is one record interval, the span a mode set's grid divides; the output steps
/// inside it are observed only where a peak can change there (the observed functions'
/// bounds, [`ModeOps::obs_rows`]), so a fine output step costs no substeps of its own.
/// Histories, energies and per-damper demands need the state at every output step: their
/// frames are the output steps.
pub(super) fn frame_steps(plan: &Plan) -> usize {
    let Some(r) = plan.record.as_ref() else {
        return 1;
    };
    if plan.outputs.histories || plan.outputs.energies || plan.outputs.dampers {
        return 1;
    }
    let (rdt, dt) = (r.dt(), plan.method.dt);
    let q = (rdt / dt).round();
    if (2.0..=1e6).contains(&q) && (q * dt - rdt).abs() <= 1e-9 * rdt {
        q as usize
    } else {
        1
    }
}

impl<'a> Model<'a> {
    pub(super) fn new(plan: &'a Plan) -> Result<Model<'a>, SimError> {
        let n = plan.dofs();
        let mut epp_slot = vec![None; plan.contacts.len()];
        let mut next = 2 * n;
        for (c, ct) in plan.contacts.iter().enumerate() {
            match ct.kind {
                ContactKind::Epp => {
                    epp_slot[c] = Some(next);
                    next += 1;
                }
                // zero-mass DOFs are refused by Plan::check_method before a run
                ContactKind::Dof { .. } => {}
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
            second: plan.second.as_ref().map(|_| (next + 5, next + 6)),
            dim: next + if plan.second.is_some() { 7 } else { 5 },
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
        let mr2 = plan.mass_influence2();
        if let (Some(m2), Some((i_ag2, _))) = (&mr2, lay.second) {
            for i in 0..n {
                f0[(i, i_ag2)] = -m2[i];
            }
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
            mr2,
            bcols,
            f0,
            omega_h,
            storeys: plan.has_yielding_storeys(),
            frame_steps: frame_steps(plan),
        })
    }

    /// Bound ρ on |λ(A)| for every mode set: ν_max + ω_max over all-stuck elastic
    /// braces (constraints only lower both), k′/c′ of sliding damped massless
    /// dissipators, and the harmonic frequency. Used for the run's substep budget.
    pub(super) fn spectral_bound(&self) -> f64 {
        self.bound(None)
    }

    /// Bound ρ on |λ(A)| of one mode set. A nonzero eigenvalue λ of the mode matrix has
    /// an eigenvector u in null(B_Sᵀ) (the stuck dissipators with mass move with their
    /// floors) with λ²uᴴMu + λuᴴC_mu + uᴴK_mu = 0, so |λ| ≤ ν + ω with ν, ω² the largest
    /// Rayleigh quotients of C_m and K_m over M on that subspace (M-orthogonal projection
    /// keeps the quotients of the unconstrained matrices there). K_m, C_m carry the braces
    /// of stuck massless dissipators; a sliding damped one adds its rate k′/c′. `None`:
    /// the bound over every mode set (no constraints, every brace, every rate).
    pub(super) fn bound(&self, modes: Option<&[Mode]>) -> f64 {
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
                        add_between(&mut k, &ct.top, &ct.bottom, ct.brace_stiffness);
                        add_between(&mut c, &ct.top, &ct.bottom, ct.brace_damping);
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
}
