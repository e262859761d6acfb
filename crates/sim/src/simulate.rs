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
