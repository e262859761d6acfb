//! Integrators: one trait, several methods (docs/MODEL.md § Integrators).

pub mod delacruz;
pub mod exact;
pub mod newmark;
pub(crate) mod state;

pub use delacruz::DelaCruz;
pub use exact::Exact;
pub use newmark::Newmark;

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
