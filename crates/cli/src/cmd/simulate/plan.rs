//! `slipload simulate` on a scene in plan: the same command, the library's
//! [`slipload_sim::floorplan`] run, its responses as the output contract (JSON) or a table
//! by line, floor and damper.

use anyhow::Context;
use slipload_opt::base::output::write_atomic;
use slipload_sim::floorplan::FloorPlanScene;
use slipload_sim::{MethodName, Outcome};
use std::fmt::Write as _;
use std::path::Path;

/// What `slipload simulate` asks of a run in plan: the overrides it applies, where the
/// histories go, and the output's format.
pub(super) struct PlanRun<'a> {
    /// `--method`.
    pub(super) method: Option<MethodName>,
    /// `--dt`, s.
    pub(super) dt: Option<f64>,
    /// `--duration`, s.
    pub(super) duration: Option<f64>,
    /// `--history FILE` (checked by the caller: writable, not an input).
    pub(super) history: Option<&'a Path>,
    /// `--format json`.
    pub(super) json: bool,
}

/// Runs `slipload simulate` on the scene in plan at `path`.
pub(super) fn run(path: &Path, run: &PlanRun<'_>) -> anyhow::Result<()> {
    let mut scene = FloorPlanScene::load(path)?;
    scene.override_with(run.method, run.dt, run.duration, run.history.is_some())?;
    let out = slipload_sim::floorplan::simulate(&scene)
        .with_context(|| format!("simulating {}", scene.name))?;
    if let (Some(h), Some(hist)) = (run.history, &out.history) {
        write_atomic(h, hist.to_csv().as_bytes())?;
    }
    if run.json {
        outln!("{}", serde_json::to_string_pretty(&out.response)?);
    } else {
        out!("{}", table(&scene, &out));
    }
    Ok(())
}

/// The responses of a run in plan, for people: drifts by line and edge, floors' motion,
/// dampers, torsional irregularity.
fn table(scene: &FloorPlanScene, out: &Outcome) -> String {
    let r = &out.response;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} (building in plan: {} floors, {} lines) — {}, dt = {:.4e} s, {} steps, {:.3} s",
        scene.name,
        scene.building.storeys(),
        scene.building.lines.len(),
        r.method,
        r.dt,
        r.steps,
        r.cpu_seconds
    );
    for g in &scene.ground {
        let _ = writeln!(
            s,
            "ground: {} at {:.1} deg from x, PGA {:.3} g",
            g.record.name(),
            g.angle.to_degrees(),
            g.record.pga() / slipload_motion::G
        );
    }
    let Some(ip) = &r.in_plan else {
        return s;
    };
    let _ = writeln!(
        s,
        "\n{:<18} {:>12} {:>10} {:>12}",
        "drift", "peak (m)", "ratio (%)", "residual (m)"
    );
    for (k, name) in ip.drifts.iter().enumerate() {
        let ratio = r
            .peak_drift_ratio
            .as_ref()
            .map_or_else(|| "—".to_string(), |v| format!("{:.3}", 100.0 * v[k]));
        let _ = writeln!(
            s,
            "{name:<18} {:>12.4e} {ratio:>10} {:>12.4e}",
            r.peak_drift[k], r.residual_drift[k]
        );
    }
    let _ = writeln!(
        s,
        "\n{:<10} {:>14} {:>18}",
        "point", "peak displ.", "peak abs. accel."
    );
    for (k, name) in ip.points.iter().enumerate() {
        let (du, au) = if name.ends_with("rot") {
            ("rad", "rad/s2")
        } else {
            ("m", "m/s2")
        };
        let _ = writeln!(
            s,
            "{name:<10} {:>10.4e} {du:<3} {:>12.4e} {au}",
            r.peak_displacement[k], r.peak_abs_acceleration[k]
        );
    }
    if !ip.dampers.is_empty() {
        let _ = writeln!(
            s,
            "\n{:<10} {:>14} {:>12}",
            "damper", "peak slip (m)", "transitions"
        );
        for (k, name) in ip.dampers.iter().enumerate() {
            let _ = writeln!(
                s,
                "{name:<10} {:>14.4e} {:>12}",
                r.peak_slip[k], r.transitions[k]
            );
        }
    }
    if let Some(t) = &ip.torsional_irregularity {
        let _ = writeln!(
            s,
            "\ntorsional irregularity (largest edge drift over the edges' mean; 1.2 irregular, 1.4 extreme)"
        );
        for (i, [x, y]) in t.iter().enumerate() {
            let _ = writeln!(s, "storey {:>3}: along x {x:.3}, along y {y:.3}", i + 1);
        }
    }
    let _ = writeln!(
        s,
        "\npeak base shear along the first component: {:.4e} N",
        r.peak_base_shear
    );
    if let Some(b) = &ip.peak_base {
        let _ = writeln!(
            s,
            "peak base shear along x {:.4e} N, along y {:.4e} N; peak base torque about the centre of mass ({:.3}, {:.3}) m {:.4e} N m",
            b.shear_x_n, b.shear_y_n, b.torque_about_m[0], b.torque_about_m[1], b.torque_nm
        );
    }
    if let Some(e) = &r.energy {
        let _ = writeln!(
            s,
            "energy: input {:.4e} J, friction {:.4e} J, balance error {:.2e} J",
            e.input, e.friction, e.balance_error
        );
    }
    if let Some(c) = &r.collapse {
        let _ = writeln!(
            s,
            "COLLAPSE: storey {} at t = {:.3} s (drift {:.4e} m past {:.4e} m)",
            c.storey, c.time, c.drift, c.limit
        );
    }
    s
}
