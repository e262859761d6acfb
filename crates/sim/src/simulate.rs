//! Running a scene: compile, integrate with the scene's method, time it.

use crate::error::SimError;
use crate::integrator::{DelaCruz, Exact, Integrator, Newmark};
use crate::plan::Plan;
use crate::response::Outcome;
use crate::scene::{MethodName, Scene};

/// The integrator for a method name.
pub fn integrator(name: MethodName) -> Box<dyn Integrator + Send + Sync> {
    match name {
        MethodName::Newmark | MethodName::Hht | MethodName::Bilinear => Box::new(Newmark),
        MethodName::Delacruz => Box::new(DelaCruz),
        MethodName::Exact => Box::new(Exact),
    }
}

/// What [`run_plan`] would refuse before its first step, found without stepping: the
/// method's own refusals ([`Plan::check_method`]), an initial state outside the friction
/// bounds, and (for `exact`) the memory and substep budgets. These are the checks the
/// integrators make as they start, called here rather than restated, so `slipload explain`
/// refuses what `slipload simulate` refuses.
pub fn check(plan: &Plan) -> Result<(), SimError> {
    plan.check_method()?;
    // the step-by-step methods' start; `exact` refuses the same inconsistent states
    crate::integrator::state::initial_state(plan)?;
    if plan.method.name == MethodName::Exact {
        crate::integrator::exact::check(plan)?;
    }
    Ok(())
}

/// Compiles and runs a scene; `cpu_seconds` is the wall-clock time of the run.
pub fn simulate(scene: &Scene) -> Result<Outcome, SimError> {
    let plan = Plan::compile(scene)?;
    run_plan(&plan)
}

/// Runs a compiled plan with its method.
pub fn run_plan(plan: &Plan) -> Result<Outcome, SimError> {
    let start = std::time::Instant::now();
    let mut out = integrator(plan.method.name).run(plan)?;
    out.response.cpu_seconds = start.elapsed().as_secs_f64();
    // every method, every response: a non-finite number is an error, never an output
    let area = out.diagnostics.strain_energy_area;
    let bad = out
        .response
        .first_non_finite()
        .or_else(|| (!area.is_finite()).then(|| ("strain_energy_area".to_string(), area)));
    if let Some((quantity, value)) = bad {
        return Err(SimError::NonFiniteResponse {
            quantity,
            value,
            record: plan.record.as_ref().map_or_else(
                || "no record".to_string(),
                |r| format!("record {}", r.name()),
            ),
        });
    }
    Ok(out)
}
