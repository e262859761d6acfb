//! `newmark` — Newmark/HHT-α with the friction forces of each step solved exactly and
//! implicitly (docs/MODEL.md § Integrators).
//!
//! With A = M + (1+α)(γΔt C + βΔt² K) factorised once, the step's accelerations are
//! a = a_free − G F with G = (1+α)A⁻¹B, and the slip rates at the end of the step are
//! w = w_free − W F with the Delassus matrix W = γΔt BᵀG (+ 1/κ on the diagonal of
//! elastic–perfectly plastic contacts, κ = k′βΔt/γ + c′, which is the exact condensation
//! of a massless dissipator DOF). The friction law is then the box QP
//! F = argmin_{F⁻≤F≤F⁺} ½FᵀWF − Fᵀw_free, solved exactly by [`BoxQp`].
//!
//! The linear part of a step is one precomputed n×2n operator [−A⁻¹K, −A⁻¹C] applied to the
//! (HHT-weighted) Newmark predictors of u and v.
//! Nothing is allocated inside the step loop unless histories are asked for; the ground
//! acceleration of each step is interpolated incrementally ([`Plan::ground_steps`]).
//! Runs without histories, of the sizes `fixed_dispatch!` lists, step in the fixed-size
//! loop of `newmark/fixed.rs` (DOF and contact counts compile-time constants, the friction
//! QP answered from its stick/slip pattern, energies when asked); runs that ask for
//! histories, and other sizes, step in the general loop below, compiled once per small DOF
//! count (1–8, 10, 12, 20) with the count a constant and once for any other count.
//! Banded frames of at least ten DOFs whose contacts are all elastic–perfectly plastic
//! (m′ = 0 shear buildings with Rayleigh or storey damping) step in O(N) in
//! `newmark/banded.rs`: the same QP, solved in the original banded variables.
//!
//! HHT-α (Hilber, Hughes & Taylor 1977): γ = ½ − α, β = (1 − α)²/4, α ∈ [−⅓, 0]; the
//! equation of motion is weighted (1+α) at t_{n+1} and −α at t_n, friction forces included.
//! α = 0 is Newmark's average acceleration, for which the energies below balance to
//! round-off (Δt·v̄ᵀ(equation averaged over the step) is an exact identity of the method).

mod banded;
mod fixed;

pub use banded::BandedStats;

use crate::error::SimError;
use crate::friction::BoxQp;
use crate::friction::box_qp::Bound;
use crate::integrator::method::Integrator;
use crate::integrator::state::{
    self, EnergyAccumulator, EppState, StepEnergyData, StepForms, history_columns, initial_state,
    record_row, slip, slip_rate,
};
use crate::plan::{ContactKind, ContactRole, Plan};
use crate::response::{Diagnostics, Energy, History, Outcome, Peaks};
use crate::units::is_positive;
use nalgebra::{DMatrix, DVector};

/// Marks "the ground" as the other end of an elastic–perfectly plastic contact.
const GROUND: usize = usize::MAX;

/// Newmark/HHT-α with exact implicit friction.
#[derive(Debug, Clone, Copy, Default)]
pub struct Newmark;

/// Operators fixed for a run.
struct Operators {
    n: usize,
    alpha: f64,
    beta: f64,
    gamma: f64,
    /// [−A⁻¹K, −A⁻¹C], n × 2n, applied to the weighted predictors ((1+α)ũ − αu,
    /// (1+α)ṽ − αv) with ũ = u + Δt v + (½−β)Δt² a, ṽ = v + (1−γ)Δt a.
    q: DMatrix<f64>,
    /// A⁻¹ M r.
    h: DVector<f64>,
    /// A⁻¹ e(force floor), when a harmonic force acts.
    hp: Option<(usize, DVector<f64>)>,
    /// (1+α) A⁻¹ B, n × nc.
    g: DMatrix<f64>,
    /// Delassus matrix, nc × nc.
    w: DMatrix<f64>,
    /// κ = k′βΔt/γ + c′ for elastic–perfectly plastic contacts (0 otherwise).
    kappa: Vec<f64>,
    /// M r.
    mr: DVector<f64>,
}

impl Operators {
    fn build(plan: &Plan) -> Result<Operators, SimError> {
        let n = plan.dofs();
        let dt = plan.method.dt;
        let alpha = plan.method.alpha;
        let gamma = 0.5 - alpha;
        let beta = (1.0 - alpha) * (1.0 - alpha) / 4.0;
        let (m, c, k) = (&plan.mass, &plan.damping, &plan.stiffness);
        let a = m + (c * (gamma * dt) + k * (beta * dt * dt)) * (1.0 + alpha);
        let chol = a.cholesky().ok_or_else(|| SimError::NotPositiveDefinite {
            what: "Newmark iteration matrix M + γΔtC + βΔt²K".into(),
            hint: " (a mass, damping or stiffness matrix is invalid)".into(),
        })?;
        let mut q = DMatrix::zeros(n, 2 * n);
        q.view_mut((0, 0), (n, n)).copy_from(&(-chol.solve(k)));
        q.view_mut((0, n), (n, n)).copy_from(&(-chol.solve(c)));
        let mr = plan.mass_influence();
        let h = chol.solve(&mr);
        let hp = plan.harmonic.map(|hm| {
            let mut e = DVector::zeros(n);
            e[hm.floor] = 1.0;
            (hm.floor, chol.solve(&e))
        });
        let bm = plan.contact_matrix();
        let g = chol.solve(&bm) * (1.0 + alpha);
        let mut w = bm.transpose() * &g * (gamma * dt);
        let kappa: Vec<f64> = plan
            .contacts
            .iter()
            .map(|ct| match ct.kind {
                ContactKind::Epp => ct.brace_stiffness * beta * dt / gamma + ct.brace_damping,
                ContactKind::Dof { .. } => 0.0,
            })
            .collect();
        for (i, kp) in kappa.iter().enumerate() {
            if *kp > 0.0 {
                w[(i, i)] += 1.0 / kp;
            }
        }
        let w = (&w + w.transpose()) * 0.5;
        Ok(Operators {
            n,
            alpha,
            beta,
            gamma,
            q,
            h,
            hp,
            g,
            w,
            kappa,
            mr,
        })
    }
}

/// What the step loop reads of one contact, flattened from the plan.
#[derive(Debug, Clone, Copy)]
struct Link {
    /// Floor DOF the friction acts on.
    floor: usize,
    /// The dissipator DOF (contact with DOF), or the floor below / [`GROUND`] (EPP).
    other: usize,
    /// Elastic–perfectly plastic element (m′ = 0 condensed).
    epp: bool,
    /// An EPP element without a brace dashpot (c′ = 0): its dissipator DOF is algebraic
    /// (the brace force k′e is the friction force), so its friction law is imposed on the
    /// slip of the step (a return mapping) rather than on the slip rate at the step's end.
    algebraic: bool,
    /// k′/κ of an EPP contact.
    k_over_kappa: f64,
    /// Where its slip peak and transitions go in [`Peaks`]: its floor for a damper, n +
    /// floor for a yielding storey's plastic element (no branch in the step loop).
    slot: usize,
}

/// The Newmark constants of a run's step.
#[derive(Debug, Clone, Copy)]
struct StepConstants {
    dt: f64,
    /// (½ − β)Δt² and (1 − γ)Δt: the predictors' weights of the acceleration.
    c_u: f64,
    c_v: f64,
    /// γΔt, βΔt², βΔt/γ and 1/(γΔt).
    gdt: f64,
    bdt2: f64,
    bg: f64,
    inv_gdt: f64,
}

impl StepConstants {
    fn new(dt: f64, beta: f64, gamma: f64) -> StepConstants {
        StepConstants {
            dt,
            c_u: (0.5 - beta) * dt * dt,
            c_v: (1.0 - gamma) * dt,
            gdt: gamma * dt,
            bdt2: beta * dt * dt,
            bg: beta * dt / gamma,
            inv_gdt: 1.0 / (gamma * dt),
        }
    }
}

/// The predictors of an EPP element's condensed DOF for one step: ũ′, ṽ′ (Newmark; with a
/// brace dashpot), or `base` = u′ − u_floor at the step's start (minus the slip so far;
/// algebraic).
#[derive(Debug, Clone, Copy, Default)]
struct EppPred {
    up: f64,
    vp: f64,
    base: f64,
}

impl Link {
    /// The friction law's free variable of the contact: the rate the QP's box bounds act on
    /// if the contact carried no friction force, from the start displacements `u0`, the
    /// predictors `ut`, `vt` and the free accelerations `af`; for an EPP element also its
    /// own predictors, from its state `e` (the condensed massless DOF).
    ///
    /// A contact with a DOF, or an EPP element with a brace dashpot: the slip rate at the
    /// end of the step, w = Bᵀv₁ (+ the condensed DOF's, through k′/κ).
    ///
    /// An algebraic EPP element (c′ = 0): the slip of the step Δp divided by βΔt/γ, so
    /// that its dependence on the friction forces is the same Delassus operator W (the
    /// sum γΔtBᵀG plus 1/κ, κ = k′βΔt/γ). With the drift Δ = u_floor − u_below and the brace elongation
    /// e = F/k′, Δp = Δ₁ − Δ₀ − (F₁ − F₀)/k′, and Δ₁ = Δ̃ + βΔt²(a_floor − a_below). The
    /// friction force is then at a bound exactly when the step slips — the return
    /// mapping of an elastic–perfectly plastic element. The slip rate at the step's end
    /// is not used: the massless DOF's Newmark velocity carries a sawtooth after every
    /// stick↔slip change (the trapezoidal rule on an algebraic variable does not damp it),
    /// which on that form misplaces the next change and costs accuracy.
    #[inline(always)]
    fn free_slip_rate(
        &self,
        k: &StepConstants,
        e: EppState,
        (u0, ut, vt): (&[f64], &[f64], &[f64]),
        af: &[f64],
    ) -> (f64, EppPred) {
        // the floor's end-of-step velocity, which an algebraic element does not read
        let vf = || vt[self.floor] + k.gdt * af[self.floor];
        if !self.epp {
            return (
                vf() - (vt[self.other] + k.gdt * af[self.other]),
                EppPred::default(),
            );
        }
        let (uj, vj, aj) = if self.other == GROUND {
            (0.0, 0.0, 0.0)
        } else {
            let j = self.other;
            (ut[j], vt[j], af[j])
        };
        if self.algebraic {
            // (Δ̃ − Δ₀ + e₀)/(βΔt/γ) + γΔt (a_floor − a_below), free of friction
            let base = e.u - u0[self.floor];
            let free =
                (ut[self.floor] - uj + base) * self.k_over_kappa + k.gdt * (af[self.floor] - aj);
            return (
                free,
                EppPred {
                    base,
                    ..EppPred::default()
                },
            );
        }
        let up = e.u + k.dt * e.v + k.c_u * e.a;
        let vp = e.v + k.c_v * e.a;
        let pred = EppPred { up, vp, base: 0.0 };
        let q = (up - uj) - k.bg * (vp - vj);
        (vf() - (vj + k.gdt * aj) + self.k_over_kappa * q, pred)
    }

    /// The end of a step for this contact, shared by both step loops: an EPP element's new
    /// state (from its predictors `pred` and the QP's variable `w` at the solution), a
    /// stick↔slip change counted against `stuck`, and the slip peak (floor minus the other
    /// end, `u` the new displacements, `v` the new velocities). Returns the slip rate the
    /// energies and histories get: at the end of the step, or for an algebraic EPP element
    /// its mean over the step (its slip / Δt: the DOF has no velocity of its own).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)] // one contact's end-of-step inputs, all distinct
    fn finish_step(
        &self,
        k: &StepConstants,
        (pred, w): (EppPred, f64),
        (u, v): (&[f64], &[f64]),
        now_stuck: bool,
        epp: &mut EppState,
        stuck: &mut bool,
        peaks: &mut Peaks,
    ) -> f64 {
        let (x_other, rate) = if self.epp {
            if self.algebraic {
                // the step's slip is w βΔt/γ = w/(k′/κ) (c′ = 0); its mean rate is what
                // the energies and histories get (zero while stuck)
                let rate;
                (*epp, rate) =
                    self.algebraic_update(k, (pred.base, w), u[self.floor], v[self.floor]);
                (epp.u, rate)
            } else {
                *epp = Link::epp_update(k, pred, v[self.floor], w);
                (epp.u, w)
            }
        } else {
            (u[self.other], w)
        };
        self.observe_end(now_stuck, stuck, u[self.floor] - x_other, peaks);
        rate
    }

    /// The end-of-step bookkeeping of this contact: a stick↔slip change counted against
    /// `stuck`, and its slip (floor minus the other end) kept if it is the largest.
    #[inline(always)]
    fn observe_end(&self, now_stuck: bool, stuck: &mut bool, slip: f64, peaks: &mut Peaks) {
        if now_stuck != *stuck {
            peaks.transitions[self.slot] += 1;
            *stuck = now_stuck;
        }
        peaks.observe_slip(self.slot, slip);
    }

    /// An algebraic EPP element's state at the end of the step, from its `base` (u′ − u_floor
    /// at the start, [`EppPred::base`]), the QP's variable `w` at the solution and its
    /// floor's new displacement and velocity; with the step's mean slip rate.
    #[inline(always)]
    fn algebraic_update(
        &self,
        k: &StepConstants,
        (base, w): (f64, f64),
        u_floor: f64,
        v_floor: f64,
    ) -> (EppState, f64) {
        let slip = w / self.k_over_kappa;
        let rate = slip / k.dt;
        (
            EppState {
                u: u_floor + base - slip,
                v: v_floor - rate,
                a: 0.0,
            },
            rate,
        )
    }

    /// The first observation of this contact's slip (or plastic drift), from the initial
    /// displacements `u` and the other end `x_other`.
    #[inline]
    fn observe_start(&self, u: &[f64], x_other: f64, peaks: &mut Peaks) {
        peaks.observe_slip(self.slot, u[self.floor] - x_other);
    }

    /// An EPP element's state at the end of the step, from its predictors, its floor's
    /// velocity and the contact's slip rate. A product by 1/(γΔt), not a division: the
    /// update sits on the step-to-step dependency chain.
    #[inline(always)]
    fn epp_update(k: &StepConstants, pred: EppPred, v_floor: f64, slip_rate: f64) -> EppState {
        let v = v_floor - slip_rate;
        let a = (v - pred.vp) * k.inv_gdt;
        EppState {
            u: pred.up + k.bdt2 * a,
            v,
            a,
        }
    }
}

/// A run's outcome from what its step loop recorded (both loops end here): the peaks, the
/// energies at the end state when asked, the energy diagnostics, the friction QP iterations
/// (total over the run, most in one step) and the histories when asked.
fn outcome(
    plan: &Plan,
    peaks: Peaks,
    acc: &EnergyAccumulator,
    energy: Option<Energy>,
    (qp_total, qp_max): (u64, u32),
    history: Option<History>,
) -> Outcome {
    let response = peaks.into_plan_response(plan, energy);
    // the steps run (fewer than the plan's when a collapse stopped the run)
    let work = work_per_step(plan) * response.steps as u64;
    Outcome {
        response,
        diagnostics: Diagnostics {
            // per step, 0 for a run of no steps
            qp_iterations_mean: if plan.steps > 0 {
                qp_total as f64 / plan.steps as f64
            } else {
                0.0
            },
            qp_iterations_max: qp_max,
            balance_error_max_relative: acc.balance_max_rel,
            initial_energy: acc.initial_energy(),
            strain_energy_area: acc.strain_area,
            work,
            ..Default::default()
        },
        history,
    }
}

/// Multiply-adds of one step (`Diagnostics::work`): the n × 2n linear operator, the
/// friction columns G F and slip rates BᵀG F, the Delassus product of the box QP and the
/// predictor and corrector vector updates.
fn work_per_step(plan: &Plan) -> u64 {
    let (n, c) = (plan.dofs() as u64, plan.contacts.len() as u64);
    2 * n * n + 2 * n * c + c * c + 12 * n
}

/// The error of a run whose state stopped being finite at `step` (from 1).
fn non_finite(step: usize, dt: f64) -> SimError {
    SimError::NonFinite {
        step,
        t: step as f64 * dt,
        hint: "the response grew without bound; check units of masses, stiffnesses and the record"
            .into(),
    }
}

/// The contacts as the step loops read them.
fn links(plan: &Plan, ops: &Operators) -> Vec<Link> {
    plan.contacts
        .iter()
        .enumerate()
        .map(|(c, ct)| match ct.kind {
            ContactKind::Dof { dof } => Link {
                floor: ct.floor,
                other: dof,
                epp: false,
                algebraic: false,
                k_over_kappa: 0.0,
                slot: match ct.role {
                    ContactRole::Damper => ct.floor,
                    ContactRole::Storey => plan.floors + ct.floor,
                },
            },
            ContactKind::Epp => Link {
                floor: ct.floor,
                other: ct.below.unwrap_or(GROUND),
                epp: true,
                algebraic: ct.is_algebraic(),
                k_over_kappa: ct.brace_stiffness / ops.kappa[c],
                slot: match ct.role {
                    ContactRole::Damper => ct.floor,
                    ContactRole::Storey => plan.floors + ct.floor,
                },
            },
        })
        .collect()
}

/// Dispatches a run without histories to the fixed-size loop of its DOF and contact counts, for
/// the counts listed (up to eight DOFs with up to four dampers; up to twelve storeys with
/// a massless damper on every floor; ten storeys with dissipator DOFs); `None` for any
/// other, which the general loop runs.
macro_rules! fixed_dispatch {
    ($plan:expr, $ops:expr, $links:expr; $(($n:literal, $nc:literal)),* $(,)?) => {
        match ($ops.n, $plan.contacts.len()) {
            $(($n, $nc) => Some(if $plan.outputs.energies {
                fixed::run::<$n, $nc, true>($plan, $ops, $links)
            } else {
                fixed::run::<$n, $nc, false>($plan, $ops, $links)
            }),)*
            _ => None,
        }
    };
}

impl Integrator for Newmark {
    fn name(&self) -> &'static str {
        "newmark"
    }

    fn run(&self, plan: &Plan) -> Result<Outcome, SimError> {
        let dt = plan.method.dt;
        if !is_positive(dt) {
            return Err(SimError::BadTimeStep { dt });
        }
        plan.check_method()?;
        if let Some(p) = banded::chosen(plan) {
            return banded::run(plan, p).map(|(outcome, _)| outcome);
        }
        run_dense(plan)
    }
}

/// Which step `newmark` takes (tests compare them).
#[doc(hidden)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepPath {
    /// The step `newmark` chooses by itself.
    Auto,
    /// The dense operators (the fixed-size or the general loop).
    Dense,
    /// The banded step; refused for a plan it cannot run exactly.
    Banded,
}

/// Runs `plan` with `newmark` on the step `path`; with the banded step's statistics when it
/// ran.
#[doc(hidden)]
pub fn run_on_path(
    plan: &Plan,
    path: StepPath,
) -> Result<(Outcome, Option<BandedStats>), SimError> {
    if !is_positive(plan.method.dt) {
        return Err(SimError::BadTimeStep { dt: plan.method.dt });
    }
    plan.check_method()?;
    let p = match path {
        StepPath::Auto => banded::chosen(plan),
        StepPath::Dense => None,
        StepPath::Banded => Some(banded::eligible(plan).ok_or_else(|| {
            SimError::Scene(format!(
                "the banded step needs no histories, elastic-perfectly plastic contacts only and a half-bandwidth of at most {} (this plan's is {})",
                banded::MAX_HALF_BANDWIDTH,
                plan.half_bandwidth()
            ))
        })?),
    };
    match p {
        Some(p) => banded::run(plan, p).map(|(o, s)| (o, Some(s))),
        None => run_dense(plan).map(|o| (o, None)),
    }
}

/// The run on the dense operators: the fixed-size loop of its sizes, or the general loop.
fn run_dense(plan: &Plan) -> Result<Outcome, SimError> {
    let ops = Operators::build(plan)?;
    if fixed::applies(plan) {
        let links = links(plan, &ops);
        let run = fixed_dispatch!(plan, &ops, &links;
            (1, 0), (1, 1),
            (2, 0), (2, 1), (2, 2),
            (3, 0), (3, 1), (3, 2), (3, 3),
            (4, 0), (4, 1), (4, 2), (4, 3), (4, 4),
            (5, 0), (5, 1), (5, 2), (5, 3), (5, 4),
            (6, 0), (6, 1), (6, 2), (6, 3), (6, 4),
            (7, 0), (7, 1), (7, 2), (7, 3), (7, 4),
            (8, 0), (8, 1), (8, 2), (8, 3), (8, 4),
            (5, 5), (6, 6), (7, 7), (8, 8), (10, 10), (12, 12), (20, 10),
        );
        if let Some(outcome) = run {
            return outcome;
        }
    }
    match ops.n {
        1 => run_loop::<1>(plan, &ops),
        2 => run_loop::<2>(plan, &ops),
        3 => run_loop::<3>(plan, &ops),
        4 => run_loop::<4>(plan, &ops),
        5 => run_loop::<5>(plan, &ops),
        6 => run_loop::<6>(plan, &ops),
        7 => run_loop::<7>(plan, &ops),
        8 => run_loop::<8>(plan, &ops),
        10 => run_loop::<10>(plan, &ops),
        12 => run_loop::<12>(plan, &ops),
        20 => run_loop::<20>(plan, &ops),
        _ => run_loop::<0>(plan, &ops),
    }
}

/// The step loop for `N` DOFs (`N = 0`: any count, read from the operators).
fn run_loop<const N: usize>(plan: &Plan, ops: &Operators) -> Result<Outcome, SimError> {
    let n = if N > 0 { N } else { ops.n };
    debug_assert_eq!(n, ops.n);
    let dt = plan.method.dt;
    let nf = plan.floors;
    let nc = plan.contacts.len();
    let (alpha, beta, gamma) = (ops.alpha, ops.beta, ops.gamma);
    let k = StepConstants::new(dt, beta, gamma);
    let (c_u, c_v, gdt, bdt2) = (k.c_u, k.c_v, k.gdt, k.bdt2);
    let msum: f64 = ops.mr.iter().sum();
    let lo: Vec<f64> = plan.contacts.iter().map(|c| c.lower).collect();
    let hi: Vec<f64> = plan.contacts.iter().map(|c| c.upper).collect();
    let links = links(plan, ops);
    // Flat operators: Q column-major n×2n, G column-major n×nc, W symmetric nc×nc.
    let qm = &ops.q.as_slice()[..2 * n * n];
    let h = &ops.h.as_slice()[..n];
    let g = &ops.g.as_slice()[..n * nc];
    let w = ops.w.as_slice();
    let mr = &ops.mr.as_slice()[..n];
    let hhht = alpha != 0.0 && nc > 0;

    let start = initial_state(plan)?;
    // State (u, v, a), 3n.
    let mut s = vec![0.0; 3 * n];
    s[..n].copy_from_slice(&start.u);
    s[n..2 * n].copy_from_slice(&start.v);
    s[2 * n..].copy_from_slice(&start.a);
    let mut f_old = start.f.clone();
    let mut f_new = vec![0.0; nc];
    let mut epp = start.epp;
    let mut stuck = start.stuck;
    let mut qp = if nc > 0 {
        Some(BoxQp::new(w, nc).map_err(|source| SimError::Friction { t: 0.0, source })?)
    } else {
        None
    };
    let mut af = vec![0.0; n];
    let mut ut = vec![0.0; n];
    let mut vt = vec![0.0; n];
    let mut z = vec![0.0; 2 * n];
    let mut wfree = vec![0.0; nc];
    let mut w_old: Vec<f64> = (0..nc)
        .map(|c| slip_rate(plan, c, &start.v, &epp))
        .collect();
    let mut w_new = vec![0.0; nc];
    let mut v_old = vec![0.0; n];
    let mut epp_pred = vec![EppPred::default(); nc];

    let energies = plan.outputs.energies;
    let mut acc = EnergyAccumulator::start(plan, &start.u, &start.v, &epp);

    let mut peaks = Peaks::for_plan(plan);
    debug_assert_eq!(peaks.drift.len(), nf);
    let mut ag0 = plan.ground_accel(0.0);
    let mut ground = plan.ground_steps();
    let mut p0 = plan.force(0.0);
    peaks.observe_floors(&start.u, &start.a, ag0);
    let hf = ops.hp.as_ref().map(|(f, _)| *f);
    let base_shear = |a: &[f64], ag: f64, p: f64| state::base_shear(mr, msum, a, ag, p);
    peaks.observe_base_shear(base_shear(&start.a, ag0, p0));
    for c in 0..nc {
        let fl = plan.contacts[c].floor;
        match plan.contacts[c].role {
            ContactRole::Damper => peaks.observe_slip(fl, slip(plan, c, &start.u, &epp)),
            ContactRole::Storey => peaks.observe_plastic(fl, slip(plan, c, &start.u, &epp)),
        }
    }

    let mut history = plan
        .outputs
        .histories
        .then(|| history_columns(plan, energies));
    if let Some(hist) = history.as_mut() {
        let e = energies.then(|| acc.initial_row());
        record_row(plan, hist, 0.0, ag0, &start.u, &f_old, &w_old, &epp, e);
    }

    let mut qp_iter_total: u64 = 0;
    let mut qp_iter_max: u32 = 0;
    for step in 0..plan.steps {
        let t1 = (step + 1) as f64 * dt;
        let ag1 = ground.next_accel();
        let p1 = if hf.is_some() { plan.force(t1) } else { 0.0 };
        // Predictors ũ, ṽ; then the linear part a_free = Q z + loads (+ HHT friction memory)
        // with z = (1+α)(ũ, ṽ) − α(u, v).
        for i in 0..n {
            let (u, v, a) = (s[i], s[n + i], s[2 * n + i]);
            ut[i] = u + dt * v + c_u * a;
            vt[i] = v + c_v * a;
        }
        let zs: &[f64] = if alpha == 0.0 {
            z[..n].copy_from_slice(&ut);
            z[n..].copy_from_slice(&vt);
            &z
        } else {
            for i in 0..n {
                z[i] = (1.0 + alpha) * ut[i] - alpha * s[i];
                z[n + i] = (1.0 + alpha) * vt[i] - alpha * s[n + i];
            }
            &z
        };
        let load = -((1.0 + alpha) * ag1 - alpha * ag0);
        for i in 0..n {
            af[i] = load * h[i];
        }
        for (j, &zj) in zs.iter().enumerate() {
            let col = &qm[j * n..(j + 1) * n];
            for i in 0..n {
                af[i] += col[i] * zj;
            }
        }
        if let Some((_, hp)) = &ops.hp {
            let c = (1.0 + alpha) * p1 - alpha * p0;
            for i in 0..n {
                af[i] += c * hp[i];
            }
        }
        if hhht {
            let c = alpha / (1.0 + alpha);
            for (j, &fj) in f_old.iter().enumerate() {
                let col = &g[j * n..(j + 1) * n];
                for i in 0..n {
                    af[i] += c * fj * col[i];
                }
            }
        }
        if let Some(qp) = qp.as_mut() {
            for (c, l) in links.iter().enumerate() {
                (wfree[c], epp_pred[c]) = l.free_slip_rate(&k, epp[c], (&s[..n], &ut, &vt), &af);
            }
            let stats = qp
                .solve(&wfree, &lo, &hi, &mut f_new)
                .map_err(|source| SimError::Friction { t: t1, source })?;
            qp_iter_total += u64::from(stats.iterations);
            qp_iter_max = qp_iter_max.max(stats.iterations);
            for (j, &fj) in f_new.iter().enumerate() {
                if fj != 0.0 {
                    let col = &g[j * n..(j + 1) * n];
                    for i in 0..n {
                        af[i] -= fj * col[i];
                    }
                }
            }
        }
        if energies {
            v_old.copy_from_slice(&s[n..2 * n]);
        }
        let mut finite = 0.0;
        for i in 0..n {
            let a = af[i];
            s[2 * n + i] = a;
            s[i] = ut[i] + bdt2 * a;
            s[n + i] = vt[i] + gdt * a;
            finite += s[i];
        }
        if !finite.is_finite() {
            return Err(non_finite(step + 1, dt));
        }
        let (u_now, rest) = s.split_at(n);
        let (v_now, a_now) = rest.split_at(n);
        if let Some(qp) = qp.as_ref() {
            for (c, l) in links.iter().enumerate() {
                let wc = &w[c * nc..(c + 1) * nc];
                let mut wf = 0.0;
                for (wcj, fj) in wc.iter().zip(&f_new) {
                    wf += wcj * fj;
                }
                w_new[c] = l.finish_step(
                    &k,
                    (epp_pred[c], wfree[c] - wf),
                    (u_now, v_now),
                    qp.status(c) == Bound::Free,
                    &mut epp[c],
                    &mut stuck[c],
                    &mut peaks,
                );
            }
        }
        peaks.observe_floors(u_now, a_now, ag1);
        peaks.observe_base_shear(base_shear(a_now, ag1, p1));
        let mut e_row = None;
        if energies {
            let data = StepEnergyData {
                dt,
                mr,
                ag: (ag0, ag1),
                p: (p0, p1),
                force_floor: hf,
                v: (&v_old, v_now),
                f: (&f_old, &f_new),
                w: (&w_old, &w_new),
                epp_mean_rate: true,
            };
            let q = StepForms::of_plan(plan, (&v_old, v_now), u_now, &epp);
            e_row = Some(acc.step(plan, &data, q, &epp));
        }
        if let Some(hist) = history.as_mut() {
            record_row(plan, hist, t1, ag1, u_now, &f_new, &w_new, &epp, e_row);
        }
        std::mem::swap(&mut f_old, &mut f_new);
        std::mem::swap(&mut w_old, &mut w_new);
        ag0 = ag1;
        p0 = p1;
        if peaks.collapsed(t1) {
            break;
        }
    }
    let (u_end, rest) = s.split_at(n);
    let v_end = &rest[..n];
    let energy = energies.then(|| acc.finish(plan, u_end, v_end, &epp));
    Ok(outcome(
        plan,
        peaks,
        &acc,
        energy,
        (qp_iter_total, qp_iter_max),
        history,
    ))
}
