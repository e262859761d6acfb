//! Buildings in plan (docs/MODEL.md § Buildings in plan): rigid floors with two
//! translations and a rotation, lateral lines placed in plan, friction dampers on the
//! lines, one or two horizontal ground components at an angle to the plan's axes.
//!
//! A [`FloorPlanConfig`] is what a JSON file says; [`FloorPlan::from_config`] validates
//! it into SI units with the bare frame's matrices on the floors' DOFs (ux, uy, θ of each
//! floor's origin, floor by floor: a 3×3 block per floor); [`compile`] turns a
//! [`FloorPlanScene`] into the same [`Plan`](crate::plan::Plan) the chain compiles to,
//! its contacts acting along the lines' kinematic vectors ([`crate::kinematics`]), so every
//! integrator that steps a general plan steps it.
//!
//! Files: `config` (the file as written), `model` (the validated building), `build`
//! (validation and assembly), `compile` (scene to plan), `scene` (a scene in plan as
//! written and resolved), `dynamics` (the periods a code-scaled suite's range is built
//! from).

mod build;
mod compile;
mod config;
mod dynamics;
mod model;
mod opensees;
mod scene;

pub use compile::compile;
pub use config::{DirectionConfig, FloorConfig, FloorPlanConfig, LineConfig};
pub use model::{Floor, FloorPlan, Line, cos_sin};
pub use opensees::opensees_script;
pub use scene::{
    FloorPlanRef, FloorPlanScene, FloorPlanSceneConfig, GroundComponent, GroundConfig,
};

/// What `slipload explain` prints of a scene in plan: the bare frame's periods with each
/// mode's share of mass along x and y and of rotational inertia, then the plan it compiles
/// into, after the checks a run makes before its first step.
pub fn explain(scene: &FloorPlanScene) -> Result<String, crate::error::SimError> {
    use std::fmt::Write as _;
    let plan = compile(scene)?;
    crate::simulate::check(&plan)?;
    let b = &scene.building;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "bare frame in plan: {} floors x 3 DOFs, {} lines; modes (period; effective mass along x and along y, and effective rotational inertia about the centres of mass, as fractions of the totals)",
        b.storeys(),
        b.lines.len()
    );
    let n = b.mass.nrows();
    let unit = |k: usize| nalgebra::DVector::from_fn(n, |i, _| if i % 3 == k { 1.0 } else { 0.0 });
    let (ex, ey) = (unit(0), unit(1));
    // a unit rotation of every floor about its own centre of mass (x_c, y_c) moves the
    // floor's origin by (y_c, −x_c)
    let et = nalgebra::DVector::from_fn(n, |i, _| {
        let c = b.floors[i / 3].centre;
        [c[1], -c[0], 1.0][i % 3]
    });
    let total = |e: &nalgebra::DVector<f64>| e.dot(&(&b.mass * e));
    for (k, t) in b.modes.periods().iter().enumerate() {
        let phi = b.modes.shapes.column(k);
        let share = |e: &nalgebra::DVector<f64>| {
            let g = phi.dot(&(&b.mass * e));
            g * g / total(e)
        };
        let _ = writeln!(
            s,
            "  mode {:>3}: T = {t:.4} s   x {:.3}   y {:.3}   rotation {:.3}",
            k + 1,
            share(&ex),
            share(&ey),
            share(&et)
        );
    }
    s.push_str(&plan.explain());
    Ok(s)
}

/// Compiles and runs a scene in plan; `cpu_seconds` is the run's wall-clock time.
pub fn simulate(
    scene: &FloorPlanScene,
) -> Result<crate::response::Outcome, crate::error::SimError> {
    crate::simulate::run_plan(&compile(scene)?)
}

/// Whether the JSON file at `path` is a scene in plan (it names `ground` components, or
/// its `building` is a building in plan, inline or by path) or a building in plan (it has
/// `floors` and `lines`). A file that cannot be read or parsed is not (the chain's
/// reader then says what is wrong with it).
pub fn is_in_plan(path: &std::path::Path) -> bool {
    let read = |p: &std::path::Path| -> Option<serde_json::Value> {
        let text = slipload_motion::limits::read_input_text(
            p,
            "scene",
            slipload_motion::limits::MAX_CONFIG_BYTES,
        )
        .ok()?;
        serde_json::from_str(&text).ok()
    };
    let is_building = |v: &serde_json::Value| {
        v.as_object()
            .is_some_and(|o| o.contains_key("lines") && o.contains_key("floors"))
    };
    let Some(v) = read(path) else { return false };
    if is_building(&v) || v.get("ground").is_some() {
        return true;
    }
    match v.get("building") {
        Some(b @ serde_json::Value::Object(_)) => is_building(b),
        Some(serde_json::Value::String(p)) => {
            let base = path.parent().unwrap_or(std::path::Path::new("."));
            read(&base.join(p)).is_some_and(|b| is_building(&b))
        }
        _ => false,
    }
}
