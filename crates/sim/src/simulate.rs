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
    Ok(out)
}
