//! One contact as every step loop reads it ([`Link`]): its predictors, the friction
//! law's free variable (the return mapping of an algebraic elastic–perfectly plastic
//! element) and its end-of-step bookkeeping, shared by the general, fixed-size and banded
//! loops.

use super::operators::{Operators, StepConstants};
use crate::integrator::state::EppState;
use crate::kinematics::Kin;
use crate::plan::{ContactKind, Plan};
use crate::response::Peaks;

/// Marks "the ground" as the other end of an elastic–perfectly plastic contact in the
/// chain-only loops' own indexing ([`Link::chain_ends`]).
pub(super) const GROUND: usize = usize::MAX;

/// What the step loop reads of one contact, flattened from the plan.
#[derive(Debug, Clone, Copy)]
pub(super) struct Link {
    /// The point the friction acts at (a chain: its floor's DOF).
    pub(super) top: Kin,
    /// The dissipator DOF (contact with DOF), or the point the brace starts from (EPP: a
    /// chain's floor below, or the ground).
    pub(super) other: Kin,
    /// Elastic–perfectly plastic element (m′ = 0 condensed).
    pub(super) epp: bool,
    /// An EPP element without a brace dashpot (c′ = 0): its dissipator DOF is algebraic
    /// (the brace force k′e is the friction force), so its friction law is imposed on the
    /// slip of the step (a return mapping) rather than on the slip rate at the step's end.
    pub(super) algebraic: bool,
    /// k′/κ of an EPP contact.
    pub(super) k_over_kappa: f64,
    /// Where its slip peak and transitions go in [`Peaks`]: its floor for a damper, n +
    /// floor for a yielding storey's plastic element (no branch in the step loop).
    pub(super) slot: usize,
}

/// The predictors of an EPP element's condensed DOF for one step: ũ′, ṽ′ (Newmark; with a
/// brace dashpot), or `base` = u′ − u_floor at the step's start (minus the slip so far;
/// algebraic).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct EppPred {
    pub(super) up: f64,
    pub(super) vp: f64,
    pub(super) base: f64,
}

impl Link {
    /// A chain's contact as the chain-only loops index it: its floor's DOF, and the
    /// dissipator DOF or the floor below ([`GROUND`] for the ground). Those loops run
    /// chains alone ([`Plan::is_chain`]), whose points are single DOFs.
    #[inline]
    pub(super) fn chain_ends(&self) -> (usize, usize) {
        let floor = self.top.as_dof().unwrap_or(GROUND);
        let other = if self.other.is_ground() {
            GROUND
        } else {
            self.other.as_dof().unwrap_or(GROUND)
        };
        (floor, other)
    }

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
    pub(super) fn free_slip_rate(
        &self,
        k: &StepConstants,
        e: EppState,
        (u0, ut, vt): (&[f64], &[f64], &[f64]),
        af: &[f64],
    ) -> (f64, EppPred) {
        // the floor's end-of-step velocity, which an algebraic element does not read
        let vf = || self.top.at(vt) + k.gdt * self.top.at(af);
        if !self.epp {
            return (
                vf() - (self.other.at(vt) + k.gdt * self.other.at(af)),
                EppPred::default(),
            );
        }
        let (uj, vj, aj) = (self.other.at(ut), self.other.at(vt), self.other.at(af));
        if self.algebraic {
            // (Δ̃ − Δ₀ + e₀)/(βΔt/γ) + γΔt (a_floor − a_below), free of friction
            let base = e.u - self.top.at(u0);
            let free =
                (self.top.at(ut) - uj + base) * self.k_over_kappa + k.gdt * (self.top.at(af) - aj);
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
    pub(super) fn finish_step(
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
                    self.algebraic_update(k, (pred.base, w), self.top.at(u), self.top.at(v));
                (epp.u, rate)
            } else {
                *epp = Link::epp_update(k, pred, self.top.at(v), w);
                (epp.u, w)
            }
        } else {
            (self.other.at(u), w)
        };
        self.observe_end(now_stuck, stuck, self.top.at(u) - x_other, peaks);
        rate
    }

    /// The end-of-step bookkeeping of this contact: a stick↔slip change counted against
    /// `stuck`, and its slip (floor minus the other end) kept if it is the largest.
    #[inline(always)]
    pub(super) fn observe_end(
        &self,
        now_stuck: bool,
        stuck: &mut bool,
        slip: f64,
        peaks: &mut Peaks,
    ) {
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
    pub(super) fn algebraic_update(
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
    pub(super) fn observe_start(&self, u: &[f64], x_other: f64, peaks: &mut Peaks) {
        peaks.observe_slip(self.slot, self.top.at(u) - x_other);
    }

    /// An EPP element's state at the end of the step, from its predictors, its floor's
    /// velocity and the contact's slip rate. A product by 1/(γΔt), not a division: the
    /// update sits on the step-to-step dependency chain.
    #[inline(always)]
    pub(super) fn epp_update(
        k: &StepConstants,
        pred: EppPred,
        v_floor: f64,
        slip_rate: f64,
    ) -> EppState {
        let v = v_floor - slip_rate;
        let a = (v - pred.vp) * k.inv_gdt;
        EppState {
            u: pred.up + k.bdt2 * a,
            v,
            a,
        }
    }
}

/// The contacts as the step loops read them.
pub(super) fn links(plan: &Plan, ops: &Operators) -> Vec<Link> {
    plan.contacts
        .iter()
        .enumerate()
        .map(|(c, ct)| match ct.kind {
            ContactKind::Dof { dof } => Link {
                top: ct.top,
                other: Kin::dof(dof),
                epp: false,
                algebraic: false,
                k_over_kappa: 0.0,
                slot: ct.slot,
            },
            ContactKind::Epp => Link {
                top: ct.top,
                other: ct.bottom,
                epp: true,
                algebraic: ct.is_algebraic(),
                k_over_kappa: ct.brace_stiffness / ops.kappa[c],
                slot: ct.slot,
            },
        })
        .collect()
}
