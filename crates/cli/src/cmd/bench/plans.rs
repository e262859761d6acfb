//! The cases of `slipload bench` for buildings in plan: a ten-storey plan with four lines
//! per direction (massless dampers on every line, stiffness eccentricity 15 % of the
//! width) under both components of a 15 s synthetic pair, `newmark` at its default step
//! against `exact` and each one's time per simulation; a sixty-storey plan's time per
//! step (peaks only: memory independent of the record's length); the same plans with
//! Rayleigh damping (banded operators) on `newmark`'s banded and dense steps, per step,
//! and the banded step's speed-up; and the example study in plan's wall-clock time (`configs/study-plan-ten-story.json`, into a scratch folder,
//! on every core, one run) with what it found.

use super::figure::Figure;
use super::measure::{Bench, max_rel, seconds_banded_dense, seconds_per_run};
use anyhow::Context;
use slipload_motion::{DEFAULT_SUITE_PGA_G, DEFAULT_SUITE_SEED, G, SuiteTarget, Synthetic};
use slipload_sim::floorplan::{FloorPlan, FloorPlanConfig, FloorPlanScene, GroundComponent};
use slipload_sim::scene::OutputsConfig;
use slipload_sim::{MethodName, Plan};
use std::path::Path;
use std::sync::Arc;

/// A plan of `storeys` storeys, 30 m × 18 m, 350 t floors, 3.5 m storeys: four lines along
/// y at x = 0, 10, 20, 30 m carrying 40/30/20/10 % of the storey stiffness (the centre of
/// rigidity at 10 m, 5 m = 17 % of the width from the centre of mass), four equal lines
/// along x; a massless damper per line and storey on a brace as stiff as the line's storey,
/// its slip load 1.5 % of the weight above times the line's share. Modal damping 2 % (full
/// operators: the dense step), or with `rayleigh` 2 % Rayleigh damping at the first and
/// sixth modes (operators of half-bandwidth 5: the banded step can run it).
fn building(storeys: usize, rayleigh: bool) -> anyhow::Result<FloorPlan> {
    let k = |i: usize| 480e6 * (1.0 - 0.5 * i as f64 / storeys as f64);
    let weight_above = |i: usize| 350e3 * 9.80665 * (storeys - i) as f64;
    let line = |name: String, dir: &str, at: f64, share: f64| {
        serde_json::json!({
            "name": name, "direction": dir, "at": at,
            "storey_stiffness": (0..storeys).map(|i| k(i) * share).collect::<Vec<_>>(),
            "dissipators": (0..storeys).map(|i| serde_json::json!({
                "floor": i + 1,
                "brace_stiffness": k(i) * share,
                "slip_load": 0.015 * weight_above(i) * share,
            })).collect::<Vec<_>>(),
        })
    };
    let mut lines = Vec::new();
    for (j, share) in [0.4, 0.3, 0.2, 0.1].into_iter().enumerate() {
        lines.push(line(format!("Y{}", j + 1), "y", 10.0 * j as f64, share));
        lines.push(line(format!("X{}", j + 1), "x", 6.0 * j as f64, 0.25));
    }
    let cfg = serde_json::json!({
        "name": format!("plan-{storeys}"),
        "plan_size": [30.0, 18.0],
        "floors": (0..storeys).map(|_| serde_json::json!({"mass": 350e3})).collect::<Vec<_>>(),
        "storey_heights": vec![3.5; storeys],
        "damping": if rayleigh {
            serde_json::json!({"rayleigh": {"ratio": 0.02, "modes": [1, 6]}})
        } else {
            serde_json::json!({"modal": {"ratio": 0.02}})
        },
        "lines": lines,
    });
    let cfg: FloorPlanConfig = serde_json::from_value(cfg).context("the bench's plan")?;
    Ok(FloorPlan::from_config(&cfg, Path::new("<bench plan>"))?)
}

/// The plan of `b` under records 0 and 1 of the seeded synthetic suite (15 s, PGA 0.4 g)
/// along x and y at once, peaks only.
fn plan(b: &FloorPlan, method: MethodName, duration: Option<f64>) -> anyhow::Result<Plan> {
    let params = Synthetic {
        dt_s: 0.01,
        duration_s: 15.0,
        ..Synthetic::default()
    };
    let target = SuiteTarget::Pga {
        pga_m_s2: DEFAULT_SUITE_PGA_G * G,
    };
    let records = slipload_motion::synthetic_suite(&params, 2, DEFAULT_SUITE_SEED, target)?;
    let ground: Vec<GroundComponent> = records
        .into_iter()
        .zip([0.0f64, 90.0])
        .map(|(r, a)| GroundComponent {
            record: Arc::new(r),
            angle: a.to_radians(),
        })
        .collect();
    let outputs = OutputsConfig {
        energies: false,
        histories: false,
        dampers: false,
        sensitivities: false,
    };
    let mut scene = FloorPlanScene::new(Arc::new(b.clone()), ground, 15.0, method, outputs);
    if let Some(d) = duration {
        scene.duration = d;
    }
    Ok(slipload_sim::floorplan::compile(&scene)?)
}

/// The plan rows.
pub(super) fn plans(bench: &mut Bench) -> anyhow::Result<()> {
    let case = "building in plan: ten storeys, four lines per direction, pair of 15 s synthetic";
    if bench.want(case) {
        let b = building(10, false)?;
        let nm = plan(&b, MethodName::Newmark, None)?;
        let ex = plan(&b, MethodName::Exact, None)?;
        let reference = slipload_sim::run_plan(&ex)?;
        let out = slipload_sim::run_plan(&nm)?;
        let err = max_rel(&out.response.peak_drift, &reference.response.peak_drift);
        bench.figs.push(Figure::new(
            case,
            "newmark default dt: max rel. peak-drift error vs exact",
            err,
            "-",
        ));
        let s = seconds_per_run(&nm, &bench.clock, bench.budget)?;
        bench
            .figs
            .push(Figure::new(case, "newmark: seconds per simulation", s, "s"));
        let se = seconds_per_run(&ex, &bench.clock, bench.budget)?;
        bench
            .figs
            .push(Figure::new(case, "exact: seconds per simulation", se, "s"));
        bench.figs.push(Figure::new(
            case,
            "DOFs (3 per floor; massless dampers condensed)",
            nm.dofs() as f64,
            "-",
        ));
    }
    example_study(bench)?;
    let case = "building in plan: sixty storeys, four lines per direction, newmark";
    if bench.want(case) {
        let b = building(60, false)?;
        let nm = plan(&b, MethodName::Newmark, Some(5.0))?;
        let s = seconds_per_run(&nm, &bench.clock, bench.budget)?;
        bench.figs.push(Figure::new(
            case,
            "time per step (5 s of the pair)",
            s / nm.steps as f64 * 1e6,
            "µs",
        ));
    }
    banded(bench)
}

/// The plans of [`building`] with Rayleigh damping (ten and sixty storeys, 5 s of the
/// pair, peaks only) on the banded and the dense step, timed in alternation: each one's
/// time per step and the banded step's speed-up. The guards sit 20 % under the speed-ups
/// recorded when the banded step learnt plans (results/performance/README.md, "Buildings
/// in plan"), as the chain's banded rows' guards are set.
fn banded(bench: &mut Bench) -> anyhow::Result<()> {
    let case = "building in plan, Rayleigh damping: banded vs dense step, newmark, 5 s of the pair";
    if !bench.want(case) {
        return Ok(());
    }
    for (storeys, guard) in [(10, GUARD_10), (60, GUARD_60)] {
        let b = building(storeys, true)?;
        let nm = plan(&b, MethodName::Newmark, Some(5.0))?;
        let (banded, dense) = seconds_banded_dense(&nm, &bench.clock, bench.budget)?;
        let per_step = |s: f64| s / nm.steps as f64 * 1e6;
        bench.figs.push(Figure::new(
            case,
            &format!("banded step: time per step, {storeys} storeys"),
            per_step(banded),
            "µs",
        ));
        bench.figs.push(Figure::new(
            case,
            &format!("dense step: time per step, {storeys} storeys"),
            per_step(dense),
            "µs",
        ));
        bench.figs.push(
            Figure::new(
                case,
                &format!("banded step's speed-up over the dense step, {storeys} storeys"),
                dense / banded,
                "x",
            )
            .at_least(guard),
        );
    }
    Ok(())
}

/// The banded step's speed-up guards on the ten- and sixty-storey plans in plan.
const GUARD_10: f64 = 1.7;
const GUARD_60: f64 = 16.0;

/// The example study in plan, where a clone of the project holds it.
const EXAMPLE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../configs/study-plan-ten-story.json"
);

/// `optimize` of the example study in plan into a scratch folder: its wall-clock time, its
/// designs and simulations, the flexible line's share of the y slip load at the optimum
/// and the optimum's edge drift over its planar split's.
fn example_study(bench: &mut Bench) -> anyhow::Result<()> {
    let case = "study in plan: configs/study-plan-ten-story.json, 7 pairs x 2 orientations, one slip load per line";
    if !bench.want(case) {
        return Ok(());
    }
    let study = slipload_opt::plan::PlanStudy::load(Path::new(EXAMPLE)).with_context(|| {
        format!("the example {EXAMPLE} (run the bench from a clone of the project)")
    })?;
    let dir = std::env::temp_dir().join(format!("slipload-bench-plan-{}", std::process::id()));
    let t = std::time::Instant::now();
    let run = slipload_opt::pipeline::optimize_in_plan(
        &study,
        slipload_opt::store::folder::FolderRequest {
            path: &dir,
            option: "scratch folder",
            fresh: true,
        },
        &slipload_opt::eval::progress::NoProgress,
        &slipload_opt::pipeline::NoFigures,
    );
    let wall = t.elapsed().as_secs_f64();
    let _ = std::fs::remove_dir_all(&dir);
    let run = run?;
    let r = &run.report;
    let designs = r.sweep_designs + r.refine_designs;
    bench.figs.push(Figure::new(
        case,
        &format!(
            "wall-clock seconds, {} thread(s) ({designs} designs, {} simulations, + the final table)",
            rayon::current_num_threads(),
            designs * r.runs_per_design
        ),
        wall,
        "s",
    ));
    if let (Some(opt), Some(planar)) = (r.row("optimum"), r.row("planar split")) {
        let shares = slipload_opt::plan::report::line_shares(&study, &opt.eval.loads);
        if let Some((_, d)) = shares.iter().find(|(n, _)| n == "D") {
            bench.figs.push(Figure::new(
                case,
                "flexible line D's share of the y slip load at the optimum (planar: 0.35)",
                *d,
                "-",
            ));
        }
        bench.figs.push(Figure::new(
            case,
            "optimum's edge drift over its planar split's (same total slip load)",
            opt.objective / planar.objective,
            "-",
        ));
    }
    Ok(())
}
