//! How every step loop ends: the run's [`Outcome`] from what it recorded, its work count,
//! and the error of a state that stopped being finite.

use crate::error::SimError;
use crate::integrator::state::EnergyAccumulator;
use crate::plan::Plan;
use crate::response::{Diagnostics, Energy, History, Outcome, Peaks};

/// A run's outcome from what its step loop recorded (both loops end here): the peaks, the
/// energies at the end state when asked, the energy diagnostics, the friction QP iterations
/// (total over the run, most in one step) and the histories when asked.
pub(super) fn outcome(
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
pub(super) fn non_finite(step: usize, dt: f64) -> SimError {
    SimError::NonFinite {
        step,
        t: step as f64 * dt,
        hint: "the response grew without bound; check units of masses, stiffnesses and the record"
            .into(),
    }
}
