//! The [`Integrator`] trait: what every time-integration method offers (docs/MODEL.md
//! § Integrators). The methods implement it in the sibling modules; nothing here depends
//! on them.

use crate::error::SimError;
use crate::plan::Plan;
use crate::response::Outcome;

/// A time-integration method: runs a compiled plan from its initial state to its end,
/// recording only what the plan asks for.
pub trait Integrator {
    /// Method name as written in configs.
    fn name(&self) -> &'static str;
    /// Runs the plan.
    fn run(&self, plan: &Plan) -> Result<Outcome, SimError>;
}
