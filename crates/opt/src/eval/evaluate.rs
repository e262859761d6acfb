//! Running (design, record) tasks: one simulation each, in parallel across tasks (never
//! inside one), results collected in task order so every reduction is sequential and the
//! bits do not depend on the thread count.

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
/// The fidelity of a batch of runs, defined in [`crate::model::fidelity`].
use crate::model::fidelity::{Fidelity, hht_alpha};
use crate::model::fingerprint::Fingerprint;
use crate::model::sampler::FrictionLaw;
use crate::model::study::Study;
use crate::store::journal::{Appender, Reuse, open_journal};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use slipload_sim::scene::{InitialState, MethodSettings, OutputsConfig, Scene, default_dt};
use slipload_sim::{Plan, run_plan};
use std::collections::HashMap;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Simulates `slip_loads` (N per dissipator) under record `record` of the study.
pub fn run_one(
    study: &Study,
    slip_loads: &[f64],
    record: usize,
    fid: &Fidelity,
    label: &str,
) -> Result<RecordMetrics, OptError> {
    run_design(
        study,
        &DesignLoads::from(slip_loads.to_vec()),
        record,
        fid,
        label,
    )
}

/// A design as it runs: its slip loads (N per dissipator) and, for the building file's
/// design where the file writes more than symmetric slip loads, its friction law per
/// dissipator (which then is what runs).
#[derive(Debug, Clone, PartialEq)]
pub struct DesignLoads {
    /// Slip loads, N per dissipator.
    pub slip_loads_n: Vec<f64>,
    /// The friction law per dissipator, N, overriding the slip loads when present.
    pub friction_n: Option<Vec<FrictionLaw>>,
}

impl From<Vec<f64>> for DesignLoads {
    fn from(slip_loads_n: Vec<f64>) -> Self {
        DesignLoads {
            slip_loads_n,
            friction_n: None,
        }
    }
}

impl DesignLoads {
    /// The building file's design of `study`, as written ([`Study::file_friction`]).
    pub fn file(study: &Study) -> DesignLoads {
        DesignLoads {
            slip_loads_n: study.file_slip_loads(),
            friction_n: study.file_friction(),
        }
    }

    /// Every force times `k` (a locked contact stays locked).
    pub fn scaled(&self, k: f64) -> DesignLoads {
        DesignLoads {
            slip_loads_n: self.slip_loads_n.iter().map(|v| k * v).collect(),
            friction_n: self
                .friction_n
                .as_ref()
                .map(|l| l.iter().map(|x| x.scaled(k)).collect()),
        }
    }

    /// The study's building with this design's dampers.
    pub fn building(&self, study: &Study) -> slipload_sim::Building {
        let n = study.building.floors();
        match &self.friction_n {
            None => study
                .building
                .with_slip_loads(&study.space.per_floor(n, &self.slip_loads_n)),
            Some(laws) => {
                let mut b = study.building.clone();
                for (&f, law) in study.space.dampers.iter().zip(laws) {
                    if let Some(d) = b.dissipators[f].as_mut() {
                        (d.lower, d.upper) = law.bounds();
                    }
                }
                b
            }
        }
    }
}

/// Simulates `design` in run `run` of the study (a record at a property case,
/// [`Study::run`]): its responses. A record with further orientations (a pair run
/// `worst`) runs at each of them, and its responses are their envelope
/// ([`RecordMetrics::envelope`]).
pub fn run_design(
    study: &Study,
    design: &DesignLoads,
    run: usize,
    fid: &Fidelity,
    label: &str,
) -> Result<RecordMetrics, OptError> {
    let (case, record) = study.run(run);
    let heights = study
        .building
        .storey_heights
        .as_deref()
        .expect("a study's building has storey heights (checked when loading)");
    let runs = match study.orientations.get(record) {
        Some(o) if !o.is_empty() => &o[..],
        _ => std::slice::from_ref(&study.records[record]),
    };
    let mut m: Option<RecordMetrics> = None;
    for rec in runs {
        let scene = design_scene_of(study, design, run, rec, fid, label);
        let out = simulate_scene(study, &scene, run, label)?;
        let one = RecordMetrics::from_outcome(&out, heights).with_tangents(
            &out,
            heights,
            &study.space.dampers,
            case.slip_load,
        );
        if let Some(quantity) = one.first_non_finite() {
            return Err(OptError::NonFinite {
                design: label.to_string(),
                record: format!("{} ({})", study.run_name(run), rec.name()),
                quantity,
            });
        }
        m = Some(match m {
            None => one,
            Some(m) => m.envelope(&one),
        });
    }
    Ok(m.expect("a run simulates its record at least once"))
}

/// Compiles and runs one scene of run `run`.
fn simulate_scene(
    study: &Study,
    scene: &Scene,
    run: usize,
    label: &str,
) -> Result<slipload_sim::Outcome, OptError> {
    let wrap = |source| OptError::Simulation {
        design: label.to_string(),
        record: study.run_name(run),
        source: Box::new(source),
    };
    let plan = Plan::compile(scene).map_err(wrap)?;
    run_plan(&plan).map_err(wrap)
}

/// The simulation of [`run_one`], whole (responses and diagnostics).
pub fn simulate_one(
    study: &Study,
    slip_loads: &[f64],
    record: usize,
    fid: &Fidelity,
    label: &str,
) -> Result<slipload_sim::Outcome, OptError> {
    simulate_design(
        study,
        &DesignLoads::from(slip_loads.to_vec()),
        record,
        fid,
        label,
    )
}

/// The simulation of [`run_design`], whole (responses and diagnostics). At a bound
/// case every slip load (or friction law) is scaled by the case's factor and every
/// brace stiffness by its own.
pub fn simulate_design(
    study: &Study,
    design: &DesignLoads,
    run: usize,
    fid: &Fidelity,
    label: &str,
) -> Result<slipload_sim::Outcome, OptError> {
    let plan = design_plan(study, design, run, fid, label)?;
    run_plan(&plan).map_err(|source| OptError::Simulation {
        design: label.to_string(),
        record: study.run_name(run),
        source: Box::new(source),
    })
}

/// The compiled plan [`simulate_design`] runs (what its memory and its refusals are
/// judged on before it runs).
pub fn design_plan(
    study: &Study,
    design: &DesignLoads,
    run: usize,
    fid: &Fidelity,
    label: &str,
) -> Result<Plan, OptError> {
    let scene = design_scene(study, design, run, fid, label);
    let wrap = |source| OptError::Simulation {
        design: label.to_string(),
        record: study.run_name(run),
        source: Box::new(source),
    };
    Plan::compile(&scene).map_err(wrap)
}

/// The scene of one run of a design (its record scaled as the suite scales it, the
/// property case's factors on the slip loads and braces, the fidelity's method and
/// step), as [`design_plan`] compiles it.
pub fn design_scene(
    study: &Study,
    design: &DesignLoads,
    run: usize,
    fid: &Fidelity,
    label: &str,
) -> Scene {
    let (_, record) = study.run(run);
    design_scene_of(study, design, run, &study.records[record], fid, label)
}

/// [`design_scene`] with record `rec` in place of the run's own (one of its
/// orientations, [`Study::orientations`]).
pub fn design_scene_of(
    study: &Study,
    design: &DesignLoads,
    run: usize,
    rec: &std::sync::Arc<slipload_motion::Record>,
    fid: &Fidelity,
    label: &str,
) -> Scene {
    let (case, record) = study.run(run);
    let n = study.building.floors();
    let building = if case.is_nominal() {
        design.building(study)
    } else {
        let mut b = design.scaled(case.slip_load).building(study);
        for d in b.dissipators.iter_mut().flatten() {
            d.brace_stiffness *= case.brace_stiffness;
        }
        b
    };
    let dt = fid.dt_s.unwrap_or_else(|| {
        default_dt(
            fid.method,
            study.building.t1(),
            Some(rec.dt()),
            rec.duration(),
        )
    }) * fid.dt_factor;
    // the record, then the suite's rest (the ground still: free vibration)
    let duration = rec.duration() + study.rest_after(record);
    let alpha = hht_alpha(fid.method);
    Scene {
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
            dampers: fid.dampers,
            sensitivities: fid.sensitivities,
        },
        reduce: true,
        notes: Vec::new(),
    }
}

/// One task: slip loads (N per dissipator) and a record index.
#[derive(Debug, Clone, PartialEq)]
pub struct Task {
    /// Label for errors.
    pub label: String,
    /// Slip loads, N.
    pub slip_loads: Vec<f64>,
    /// The friction law per dissipator, N, overriding the slip loads (the building
    /// file's design as written).
    pub friction: Option<Vec<FrictionLaw>>,
    /// Run index (the record, at a property case: [`Study::run`]).
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
                let design = DesignLoads {
                    slip_loads_n: t.slip_loads.clone(),
                    friction_n: t.friction.clone(),
                };
                let m = run_design(study, &design, t.record, fid, &t.label)?;
                done(k, &m)?;
                Ok(m)
            },
        )
        .collect()
}

/// One finished task of a [`TaskJournal`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskEntry {
    /// The fidelity it ran at ([`Fidelity::tag`]).
    pub fidelity: String,
    /// Record index.
    pub record: usize,
    /// The record's name.
    pub record_name: String,
    /// Slip loads, N per dissipator.
    pub slip_loads_n: Vec<f64>,
    /// The friction law per dissipator, N, when it overrides the slip loads.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction_n: Option<Vec<FrictionLaw>>,
    /// The responses.
    pub metrics: RecordMetrics,
}

type TaskKey = (String, Vec<u64>, usize);

/// The key of a design's task: the bits of its slip loads, then (when it has one) of
/// its friction law, so that a locked or asymmetric design never shares a symmetric
/// design's runs.
fn design_key(loads: &[f64], friction: Option<&[FrictionLaw]>) -> Vec<u64> {
    let mut k = key(loads);
    for law in friction.into_iter().flatten() {
        let (lo, hi) = law.bounds();
        k.extend([u64::MAX, lo.to_bits(), hi.to_bits()]);
    }
    k
}

/// A journal of (design, record) tasks outside the sweep (`check.jsonl`: `optimize`'s
/// finalist check and design table): tasks found there are not run again, tasks run are
/// appended. Keys are the exact bits of the slip loads, the record and the fidelity.
#[derive(Debug)]
pub struct TaskJournal {
    appender: Appender,
    known: HashMap<TaskKey, RecordMetrics>,
    reused: AtomicUsize,
}

impl TaskJournal {
    /// Opens (or starts) the task journal `path` of `study` (fingerprint `fp`); a journal
    /// of another study is refused ([`crate::store::journal::open_journal`]).
    pub fn open(study: &Study, path: &Path, fp: &Fingerprint) -> Result<TaskJournal, OptError> {
        Self::open_kind(study, path, "check", fp)
    }

    /// As [`TaskJournal::open`], for a task journal of kind `kind` (`check`, `pareto`).
    pub fn open_kind(
        study: &Study,
        path: &Path,
        kind: &str,
        fp: &Fingerprint,
    ) -> Result<TaskJournal, OptError> {
        let (appender, entries) = open_journal::<TaskEntry>(path, kind, fp, Reuse::Resume)?;
        let mut known = HashMap::new();
        for (i, e) in entries.into_iter().enumerate() {
            let name = (e.record < study.runs()).then(|| study.run_name(e.record));
            if name.as_deref() != Some(e.record_name.as_str()) {
                return Err(OptError::Journal {
                    path: path.to_path_buf(),
                    line: i + 2,
                    message: format!(
                        "record {} is {:?} in the journal but {:?} in the study: the study changed; pass --fresh",
                        e.record, e.record_name, name
                    ),
                });
            }
            known
                .entry((
                    e.fidelity,
                    design_key(&e.slip_loads_n, e.friction_n.as_deref()),
                    e.record,
                ))
                .or_insert(e.metrics);
        }
        Ok(TaskJournal {
            appender,
            known,
            reused: AtomicUsize::new(0),
        })
    }

    /// Tasks taken from the journal so far.
    pub fn reused(&self) -> usize {
        self.reused.load(Ordering::Relaxed)
    }
}

fn key(loads: &[f64]) -> Vec<u64> {
    loads.iter().map(|v| v.to_bits()).collect()
}

/// Responses of several designs over every run (record at a property case,
/// [`Study::run`]): `result[d][r]`.
pub fn run_designs<D: Clone + Into<DesignLoads>>(
    study: &Study,
    designs: &[D],
    fid: &Fidelity,
    tick: &(dyn Fn() + Sync),
) -> Result<Vec<Vec<RecordMetrics>>, OptError> {
    run_designs_journalled(study, designs, fid, None, tick)
}

/// As [`run_designs`], taking finished tasks from `journal` and appending the others.
pub fn run_designs_journalled<D: Clone + Into<DesignLoads>>(
    study: &Study,
    designs: &[D],
    fid: &Fidelity,
    journal: Option<&TaskJournal>,
    tick: &(dyn Fn() + Sync),
) -> Result<Vec<Vec<RecordMetrics>>, OptError> {
    let nr = study.runs();
    let designs: Vec<DesignLoads> = designs.iter().cloned().map(Into::into).collect();
    let tasks: Vec<Task> = designs
        .iter()
        .enumerate()
        .flat_map(|(d, s)| {
            let what = match &s.friction_n {
                Some(laws) => format!(
                    "friction law {} kN",
                    laws.iter()
                        .map(|l| l.text(1e3))
                        .collect::<Vec<_>>()
                        .join(" / ")
                ),
                None => format!(
                    "slip loads {} kN",
                    s.slip_loads_n
                        .iter()
                        .map(|v| format!("{:.1}", v / 1e3))
                        .collect::<Vec<_>>()
                        .join(" / ")
                ),
            };
            (0..nr).map(move |r| Task {
                label: format!("#{d} ({what})"),
                slip_loads: s.slip_loads_n.clone(),
                friction: s.friction_n.clone(),
                record: r,
            })
        })
        .collect();
    let tag = fid.tag();
    let mut flat: Vec<Option<RecordMetrics>> = tasks
        .iter()
        .map(|t| {
            journal.and_then(|j| {
                j.known
                    .get(&(
                        tag.clone(),
                        design_key(&t.slip_loads, t.friction.as_deref()),
                        t.record,
                    ))
                    .cloned()
            })
        })
        .collect();
    let todo: Vec<usize> = (0..tasks.len()).filter(|&k| flat[k].is_none()).collect();
    if let Some(j) = journal {
        j.reused
            .fetch_add(tasks.len() - todo.len(), Ordering::Relaxed);
    }
    for _ in 0..tasks.len() - todo.len() {
        tick();
    }
    let run: Vec<Task> = todo.iter().map(|&k| tasks[k].clone()).collect();
    let ran = run_tasks(study, &run, fid, &|i, m| {
        if let Some(j) = journal {
            let t = &run[i];
            j.appender.append(&TaskEntry {
                fidelity: tag.clone(),
                record: t.record,
                record_name: study.run_name(t.record),
                slip_loads_n: t.slip_loads.clone(),
                friction_n: t.friction.clone(),
                metrics: m.clone(),
            })?;
        }
        tick();
        Ok(())
    })?;
    for (k, m) in todo.into_iter().zip(ran) {
        flat[k] = Some(m);
    }
    let flat: Vec<RecordMetrics> = flat.into_iter().flatten().collect();
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
