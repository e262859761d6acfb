//! The [`Newmark`] integrator and the choice of its step: the banded step for the banded
//! frames it suits (`banded.rs`), else the dense one (`dense.rs`); [`run_on_path`] lets
//! tests and benches ask for either.

use super::banded::{self, BandedStats};
use super::dense::run_dense;
use crate::error::SimError;
use crate::integrator::method::Integrator;
use crate::plan::Plan;
use crate::response::Outcome;
use crate::units::is_positive;

/// Newmark/HHT-α with exact implicit friction.
#[derive(Debug, Clone, Copy, Default)]
pub struct Newmark;

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
            return banded::run(plan, p, banded::MAX_PASSES).map(|(outcome, _)| outcome);
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
    /// The banded step with at most this many active-set passes a step before the dense
    /// box QP answers the step (1: every step whose stick/slip pattern changes; tests of
    /// that fallback).
    BandedPasses(u32),
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
    let (p, passes) = match path {
        StepPath::Auto => (banded::chosen(plan), banded::MAX_PASSES),
        StepPath::Dense => (None, banded::MAX_PASSES),
        StepPath::Banded | StepPath::BandedPasses(_) => {
            let passes = match path {
                StepPath::BandedPasses(k) => k.max(1),
                _ => banded::MAX_PASSES,
            };
            (Some(banded_eligible(plan)?), passes)
        }
    };
    match p {
        Some(p) => banded::run(plan, p, passes).map(|(o, s)| (o, Some(s))),
        None => run_dense(plan).map(|o| (o, None)),
    }
}

/// The plan's half-bandwidth when the banded step can run it; else what it needs.
fn banded_eligible(plan: &Plan) -> Result<usize, SimError> {
    banded::eligible(plan).ok_or_else(|| {
            SimError::Scene(format!(
                "the banded step needs no histories, elastic-perfectly plastic contacts only and a half-bandwidth of at most {} (this plan's is {})",
                banded::max_half_bandwidth(plan),
                plan.half_bandwidth()
            ))
    })
}
