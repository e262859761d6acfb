//! Running (design, record) tasks: one simulation each, in parallel across tasks (never
//! inside one), results collected in task order so every reduction is sequential and the
//! bits do not depend on the thread count.

use crate::error::OptError;
use crate::metrics::RecordMetrics;
use crate::study::Study;
use rayon::prelude::*;
use slipload_sim::scene::{
    InitialState, MethodName, MethodSettings, OutputsConfig, Scene, default_dt,
};
use slipload_sim::{Plan, run_plan};

/// Method and accuracy of a batch of simulations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fidelity {
    /// Method.
    pub method: MethodName,
    /// Time step, s; `None`: sim's default for each record ([`default_dt`]).
    pub dt_s: Option<f64>,
    /// Factor on that time step (1 for the sweep, `check_dt_factor` for the check).
    pub dt_factor: f64,
    /// Accumulate energies (E_friction/E_input, strain-energy area).
    pub energies: bool,
}

impl Fidelity {
    /// The study's sweep fidelity (energies only when the objective needs them).
    pub fn sweep(study: &Study) -> Fidelity {
        Fidelity {
            method: study.config.fidelity.method,
            dt_s: study.config.fidelity.dt_s,
            dt_factor: 1.0,
            energies: study.needs_energies(),
        }
    }
    /// The study's reference check fidelity (energies on).
    pub fn check(study: &Study) -> Fidelity {
        Fidelity {
            method: study.config.fidelity.check_method,
            dt_s: study.config.fidelity.dt_s,
            dt_factor: study.config.fidelity.check_dt_factor,
            energies: true,
        }
    }
}

/// Simulates `slip_loads` (N per dissipator) under record `record` of the study.
pub fn run_one(
    study: &Study,
    slip_loads: &[f64],
    record: usize,
    fid: &Fidelity,
    label: &str,
) -> Result<RecordMetrics, OptError> {
    let rec = &study.records[record];
    let n = study.building.floors();
    let building = study
        .building
        .with_slip_loads(&study.space.per_floor(n, slip_loads));
    let duration = rec.duration();
    let dt = fid
        .dt_s
        .unwrap_or_else(|| default_dt(fid.method, study.building.t1(), Some(rec.dt()), duration))
        * fid.dt_factor;
    let alpha = if fid.method == MethodName::Hht {
        -0.05
    } else {
        0.0
    };
    let scene = Scene {
        name: label.to_string(),
        building,
        record: Some(rec.clone()),
        harmonic: None,
        initial: InitialState::rest(n),
        duration,
        method: MethodSettings {
            name: fid.method,
            dt,
            alpha,
            eps_a: None,
            eps_f: None,
            max_iterations: None,
        },
        outputs: OutputsConfig {
            energies: fid.energies,
            histories: false,
        },
        reduce: true,
    };
    let wrap = |source| OptError::Simulation {
        design: label.to_string(),
        record: rec.name().to_string(),
        source: Box::new(source),
    };
    let plan = Plan::compile(&scene).map_err(wrap)?;
    let out = run_plan(&plan).map_err(wrap)?;
    let heights = study
        .building
        .storey_heights
        .as_deref()
        .expect("a study's building has storey heights (checked when loading)");
    let m = RecordMetrics::from_outcome(&out, heights);
    if !m.is_finite() {
        return Err(OptError::Missing(format!(
            "design {label}, record {}: a response is not finite",
            rec.name()
        )));
    }
    Ok(m)
}

/// One task: slip loads (N per dissipator) and a record index.
#[derive(Debug, Clone, PartialEq)]
pub struct Task {
    /// Label for errors.
    pub label: String,
    /// Slip loads, N.
    pub slip_loads: Vec<f64>,
    /// Record index.
    pub record: usize,
}

/// Runs tasks in parallel (rayon's global pool), in task order; `done` is called after
/// each task with its index and result (journal append, progress bar), from worker
/// threads.
pub fn run_tasks(
    study: &Study,
    tasks: &[Task],
    fid: &Fidelity,
    done: &(dyn Fn(usize, &RecordMetrics) -> Result<(), OptError> + Sync),
) -> Result<Vec<RecordMetrics>, OptError> {
    tasks
        .par_iter()
        .enumerate()
        // map_init is where per-worker scratch goes; a task needs none beyond its own
        // plan today, so the worker state is empty
        .map_init(
            || (),
            |_, (k, t)| {
                let m = run_one(study, &t.slip_loads, t.record, fid, &t.label)?;
                done(k, &m)?;
                Ok(m)
            },
        )
        .collect()
}

/// Responses of several designs over every record: `result[d][r]`.
pub fn run_designs(
    study: &Study,
    designs: &[Vec<f64>],
    fid: &Fidelity,
    tick: &(dyn Fn() + Sync),
) -> Result<Vec<Vec<RecordMetrics>>, OptError> {
    let nr = study.records.len();
    let tasks: Vec<Task> = designs
        .iter()
        .enumerate()
        .flat_map(|(d, s)| {
            (0..nr).map(move |r| Task {
                label: format!("#{d}"),
                slip_loads: s.clone(),
                record: r,
            })
        })
        .collect();
    let flat = run_tasks(study, &tasks, fid, &|_, _| {
        tick();
        Ok(())
    })?;
    let mut out = Vec::with_capacity(designs.len());
    let mut it = flat.into_iter();
    for _ in designs {
        out.push(it.by_ref().take(nr).collect());
    }
    Ok(out)
}

/// Suite ranges of a study.
pub fn suite_ranges(study: &Study) -> Vec<std::ops::Range<usize>> {
    study.suites.iter().map(|s| s.range.clone()).collect()
}
