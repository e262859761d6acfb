//! `slipload simulate`: one building under one excitation, responses as the output
//! contract (JSON) or a table.
//!
//! The table names the ground motion with its PGA (and, when it was scaled, the factor
//! and the PGA before); stderr carries the notes of the scene and of the record's reader
//! (units that override an AT2 title's), and says when the time step does not divide
//! the duration, so that the last step ends past it.

mod plan;

use super::scene_args::SceneArgs;
use anyhow::Context;
use slipload_motion::{G, Record};
use slipload_opt::base::output::write_atomic;
use slipload_sim::{Outcome, Scene, simulate};
use std::fmt::Write as _;
use std::path::PathBuf;

/// Output format.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum Format {
    /// The output contract's JSON object.
    Json,
    /// A table for people.
    Table,
}

/// Arguments of `slipload simulate`.
#[derive(Debug, clap::Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Output format
    #[arg(long, value_enum, default_value = "table")]
    format: Format,
    /// Write time histories (floor and dissipator displacements, drifts, friction forces,
    /// energies) to this CSV file
    #[arg(long)]
    history: Option<PathBuf>,
    /// Draw the run's figures into this folder (SVG + PNG): displacement histories with
    /// the ±μN/k′ thresholds, friction hysteresis, energies, peak drift profile. Turns on
    /// histories and energies; the data go beside the figures (history.csv,
    /// drift-profile.csv, response.json) with the scene that ran (scene.json)
    #[arg(long, value_name = "DIR", conflicts_with = "study")]
    plot: Option<PathBuf>,
    /// With --plot: also run the bare frame — the same scene with no braces, i.e. every
    /// slip load 0 (a brace without friction carries no force) — and draw floor
    /// displacements with and without dampers on one axis
    #[arg(long, requires = "plot")]
    compare_bare: bool,
    /// Compute the per-damper demands (slip each way, peak slip velocity, cumulative
    /// travel, slip excursions and cycles, peak friction force, energy per damper) and
    /// show them; the same as the scene's `"outputs": { "dampers": true }`
    #[arg(long)]
    dampers: bool,
    /// Run the simulation this many times in this process and report the median
    /// `cpu_seconds` (for timing scripts: a warm process, as a program timed inside its
    /// own interpreter is)
    #[arg(long, default_value_t = 1, hide = true,
          value_parser = clap::value_parser!(u32).range(1..))]
    repeat: u32,
}

/// Runs `slipload simulate`.
pub fn run(args: SimulateArgs) -> anyhow::Result<()> {
    if let Some(dir) = &args.plot {
        crate::figures::check_plot_folder(dir)?;
        slipload_figures::check_fonts()?;
    }
    crate::args::count_flag("--repeat", args.repeat as usize, crate::args::MAX_REPEATS)?;
    if let Some(path) = &args.scene.scene
        && slipload_sim::floorplan::is_in_plan(path)
    {
        return run_in_plan(&args, path);
    }
    if let Some(path) = &args.history {
        // refuse a FIFO or device before the run, not after it
        slipload_opt::base::output::write_target(path)
            .with_context(|| format!("--history {}", path.display()))?;
        refuse_input_as_output("--history", path, &args.scene.input_files())?;
    }
    let mut scene = args
        .scene
        .load(args.history.is_some() || args.plot.is_some())?;
    for note in scene.record.iter().flat_map(|r| r.notes()) {
        eprintln!("note: {note}");
    }
    // what the inputs make doubtful without making them wrong: a slip load that looks
    // like kN written as N, a time step that runs past the duration
    for warning in slipload_sim::building::plausibility(
        &scene.building,
        scene.method.dt,
        scene.duration,
        scene.steps(),
    ) {
        eprintln!("warning: {warning}");
    }
    if args.plot.is_some() {
        scene.outputs.energies = true;
    }
    if args.dampers {
        scene.outputs.dampers = true;
    }
    let mut out = simulate(&scene).with_context(|| format!("simulating {}", scene.name))?;
    if args.repeat > 1 {
        let mut cpu = vec![out.response.cpu_seconds];
        for _ in 1..args.repeat {
            let again = simulate(&scene).with_context(|| format!("simulating {}", scene.name))?;
            cpu.push(again.response.cpu_seconds);
        }
        out.response.cpu_seconds = slipload_sim::accuracy::median(&mut cpu);
    }
    if let (Some(path), Some(h)) = (&args.history, &out.history) {
        write_atomic(path, h.to_csv().as_bytes())?;
    }
    if let Some(dir) = &args.plot {
        let bare = if args.compare_bare {
            let mut b = scene.clone();
            b.name = format!("{} (bare frame)", scene.name);
            b.building.dissipators = vec![None; b.building.floors()];
            Some(simulate(&b).with_context(|| format!("simulating {}", b.name))?)
        } else {
            None
        };
        let scene_json = crate::figures::scene_file::resolved(&args.scene, &scene, dir)
            .context("writing down the scene that ran")?;
        let files =
            crate::figures::simulation::write_all(dir, &scene, &scene_json, &out, bare.as_ref())
                .with_context(|| format!("writing figures to {}", dir.display()))?;
        eprintln!("wrote {} files to {}", files.len(), dir.display());
    }
    match args.format {
        Format::Json => outln!("{}", serde_json::to_string_pretty(&out.response)?),
        Format::Table => out!("{}", table(&scene, &out)),
    }
    Ok(())
}

/// `slipload simulate` on a scene in plan: the flags it takes checked here, the run and
/// its output in `plan`.
fn run_in_plan(args: &SimulateArgs, path: &std::path::Path) -> anyhow::Result<()> {
    let s = &args.scene;
    for (flag, given) in [
        ("--record", s.record.is_some()),
        ("--units", s.units.is_some()),
        ("--scale-pga-g", s.scale_pga_g.is_some()),
        ("--scale", s.scale.is_some()),
        ("--window", s.window.is_some()),
        ("--plot", args.plot.is_some()),
        ("--dampers", args.dampers),
    ] {
        if given {
            anyhow::bail!(
                "{flag}: {} is a scene in plan; its ground components (records, scaling, angles) are the scene's `ground` list, and --plot and --dampers are not drawn for plans yet",
                path.display()
            );
        }
    }
    if let Some(h) = &args.history {
        slipload_opt::base::output::write_target(h)
            .with_context(|| format!("--history {}", h.display()))?;
        refuse_input_as_output(
            "--history",
            h,
            &slipload_sim::floorplan::FloorPlanScene::input_files(path),
        )?;
    }
    plan::run(
        path,
        &plan::PlanRun {
            method: s.method.map(Into::into),
            dt: s.dt,
            duration: s.duration,
            history: args.history.as_deref(),
            json: matches!(args.format, Format::Json),
        },
    )
}

/// Refuses an output file `out` (flag `flag`) that is one of the run's `inputs` — the
/// same file by another name too (a symlink, `./`, `..`): a run never writes over what it
/// reads. Paths that do not exist yet cannot be inputs.
pub fn refuse_input_as_output(
    flag: &str,
    out: &std::path::Path,
    inputs: &[PathBuf],
) -> anyhow::Result<()> {
    let Ok(target) = std::fs::canonicalize(out) else {
        return Ok(());
    };
    for input in inputs {
        if std::fs::canonicalize(input).is_ok_and(|i| i == target) {
            anyhow::bail!(
                "{flag} {}: that is {}, an input of this run; a run never writes over its inputs: give another {flag} file",
                out.display(),
                input.display()
            );
        }
    }
    Ok(())
}

/// The per-damper demands as a table, one row per storey with a damper ("—" for the
/// others); a damper that never slipped is flagged as the rigid brace it acted as.
pub fn damper_table(
    d: &[slipload_sim::response::DamperDemand],
    has_damper: &dyn Fn(usize) -> bool,
) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "per-damper demands (sampled at the output steps; slip from the start of the run)"
    );
    let _ = writeln!(
        s,
        "{:>6} {:>12} {:>12} {:>13} {:>12} {:>10} {:>7} {:>13} {:>12}",
        "storey",
        "slip + (m)",
        "slip - (m)",
        "vel. (m/s)",
        "travel (m)",
        "excursions",
        "cycles",
        "force (N)",
        "energy (kJ)"
    );
    let mut rigid = Vec::new();
    for (i, x) in d.iter().enumerate() {
        if !has_damper(i) {
            let _ = writeln!(s, "{:>6} {:>12}", i + 1, "—");
            continue;
        }
        let _ = writeln!(
            s,
            "{:>6} {:>12.4e} {:>12.4e} {:>13.4e} {:>12.4e} {:>10} {:>7.1} {:>13.6e} {:>12.4}",
            i + 1,
            x.slip_max_pos_m,
            x.slip_max_neg_m,
            x.peak_slip_velocity_m_s,
            x.cumulative_travel_m,
            x.slip_excursions,
            x.cycles,
            x.peak_force_n,
            x.energy_j / 1e3
        );
        if x.slip_excursions == 0 {
            rigid.push((i + 1).to_string());
        }
    }
    if !rigid.is_empty() {
        let _ = writeln!(
            s,
            "never slipped: the damper of storey {} (acts as a rigid brace at this slip load)",
            rigid.join(", ")
        );
    }
    s
}

/// A number for people (six significant digits), as the library's messages write them.
fn short(x: f64) -> String {
    slipload_sim::units::short_number(x)
}

/// The ground motion as the table names it: its PGA in g and m/s², and when it was
/// scaled, the factor and the PGA before scaling.
pub fn record_line(record: &Record) -> String {
    let pga = record.pga();
    let mut line = format!(
        "ground motion {}: PGA {:.4} g ({:.4} m/s2)",
        record.name(),
        pga / G,
        pga
    );
    let factor = record.scale_factor();
    if factor != 1.0 {
        let _ = write!(
            line,
            ", scaled by {} from PGA {:.4} g",
            short(factor),
            pga / factor / G
        );
    }
    line
}

/// Plastic drift below this fraction of the storey's yield drift is round-off of a storey
/// that never yielded (its elastic-plastic element never slipped): shown as 0.
pub const PLASTIC_DRIFT_NOISE: f64 = 1e-6;

/// A storey's peak plastic drift for people: "0" for a storey that never yielded (below
/// [`PLASTIC_DRIFT_NOISE`] of its yield drift), else in m.
pub fn plastic_drift_text(plastic_m: f64, yield_drift_m: Option<f64>) -> String {
    match yield_drift_m {
        Some(y) if plastic_m.abs() < PLASTIC_DRIFT_NOISE * y => "0".to_string(),
        None if plastic_m == 0.0 => "0".to_string(),
        _ => format!("{plastic_m:.4e}"),
    }
}

/// The responses as a table: a storey without a damper shows "—" for its slip and
/// transitions.
pub fn table(scene: &Scene, out: &Outcome) -> String {
    let name = &scene.name;
    let has_damper = |i: usize| matches!(scene.building.dissipators.get(i), Some(Some(_)));
    let r = &out.response;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{name}: method {}, dt = {:.6e} s, {} steps, {:.4} s of CPU",
        r.method, r.dt, r.steps, r.cpu_seconds
    );
    if let Some(record) = &scene.record {
        let _ = writeln!(s, "{}", record_line(record));
    }
    let _ = writeln!(
        s,
        "{}",
        if out.diagnostics.sampled_peak_drift.is_some() {
            "drift peaks of the continuous solution (located between steps); other peaks at the output steps"
        } else {
            "peaks sampled at the integration steps"
        }
    );
    let _ = writeln!(
        s,
        "{:>6} {:>12} {:>10} {:>12} {:>14} {:>12} {:>12} {:>11}",
        "storey",
        "drift (m)",
        "ratio (%)",
        "displ. (m)",
        "abs acc (m/s2)",
        "residual (m)",
        "slip (m)",
        "transitions"
    );
    for i in 0..r.peak_drift.len() {
        let ratio = r
            .peak_drift_ratio
            .as_ref()
            .map_or("-".to_string(), |v| format!("{:.4}", 100.0 * v[i]));
        let (slip, transitions) = if has_damper(i) {
            (
                format!("{:.4e}", r.peak_slip[i]),
                r.transitions[i].to_string(),
            )
        } else {
            ("—".to_string(), "—".to_string())
        };
        let _ = writeln!(
            s,
            "{:>6} {:>12.5e} {:>10} {:>12.5e} {:>14.4} {:>12.3e} {slip:>12} {transitions:>11}",
            i + 1,
            r.peak_drift[i],
            ratio,
            r.peak_displacement[i],
            r.peak_abs_acceleration[i],
            r.residual_drift[i],
        );
    }
    let _ = writeln!(s, "peak base shear: {:.6e} N", r.peak_base_shear);
    if let (Some(mu), Some(plastic)) = (&r.peak_ductility, &r.peak_plastic_drift) {
        // A yielding frame: each storey's ductility and plastic drift.
        let _ = writeln!(
            s,
            "{:>6} {:>12} {:>17}",
            "storey", "ductility", "plastic drift (m)"
        );
        for (i, (m, p)) in mu.iter().zip(plastic).enumerate() {
            let m = m.map_or("elastic".to_string(), |m| format!("{m:.4}"));
            let y = scene
                .building
                .storey_yield
                .get(i)
                .copied()
                .flatten()
                .map(|y| y.yield_drift());
            let p = plastic_drift_text(*p, y);
            let _ = writeln!(s, "{:>6} {m:>12} {p:>17}", i + 1);
        }
    }
    if let Some(d) = &r.dampers {
        s.push_str(&damper_table(d, &has_damper));
    }
    if let Some(c) = &r.collapse {
        let _ = writeln!(
            s,
            "COLLAPSE: storey {} drifted {:.4e} m at t = {:.4} s, past its limit {:.4e} m; the run stopped there (peaks up to that instant)",
            c.storey, c.drift, c.time, c.limit
        );
    }
    if let Some(e) = &r.energy {
        let scale = (e.input.abs() + out.diagnostics.initial_energy).max(f64::MIN_POSITIVE);
        let _ = writeln!(
            s,
            "energy (kJ): input {:.3}, kinetic {:.3}, strain {:.3}, viscous {:.3}, friction {:.3}; balance error {:.3e} kJ ({:.2e} of input + initial)",
            e.input / 1e3,
            e.kinetic / 1e3,
            e.strain / 1e3,
            e.viscous / 1e3,
            e.friction / 1e3,
            e.balance_error / 1e3,
            e.balance_error.abs() / scale
        );
        if let Some(p) = e.plastic {
            let share = e
                .friction_share()
                .map_or("-".to_string(), |f| format!("{:.1} %", 100.0 * f));
            let _ = writeln!(
                s,
                "plastic (hysteretic) energy of the frame {:.3} kJ (in the balance); friction share of the dissipated energy {share}",
                p / 1e3
            );
        }
    }
    match &out.diagnostics.loop_iterations {
        Some(l) => {
            let _ = writeln!(
                s,
                "fixed-point iterations per loop invocation (mean / max): inner {:.3} / {}, middle {:.3} / {}, outer {:.3} / {}; {} re-solves (rule 1); {:.3e} kJ removed by rule-2 projections",
                l.inner_mean,
                l.inner_max,
                l.middle_mean,
                l.middle_max,
                l.outer_mean,
                l.outer_max,
                l.resolves,
                l.projection_energy / 1e3
            );
        }
        None => {
            let _ = writeln!(
                s,
                "friction QP iterations per step: mean {:.3}, max {}",
                out.diagnostics.qp_iterations_mean, out.diagnostics.qp_iterations_max
            );
        }
    }
    s
}
