//! Optimisation: after a sweep, refine from its best points, then verify the finalists
//! at reference accuracy (the study's check method and time step) and report whether
//! their ranking held.

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::eval::evaluate::{TaskJournal, run_designs, run_designs_journalled, suite_ranges};
use crate::model::config::RefineMethod;
use crate::model::fidelity::Fidelity;
use crate::model::study::Study;
use crate::phases::refine::{Evaluations, Point, refine};
use crate::phases::sweep::Manifest;
use slipload_sim::scene::MethodName;
use std::path::Path;

/// Finalists differ by at least this much in some scaled variable (5 % of its range), so
/// that the check compares designs, not round-off around one design.
pub const FINALIST_SPACING: f64 = 0.05;

/// A design checked at reference accuracy.
#[derive(Debug, Clone, PartialEq)]
pub struct Finalist {
    /// Scaled variables.
    pub z: Vec<f64>,
    /// Slip loads, N per dissipator.
    pub slip_loads_n: Vec<f64>,
    /// Objective at the sweep's fidelity.
    pub f_sweep: f64,
    /// Objective at the check fidelity.
    pub f_check: f64,
}

/// What `optimize` found.
#[derive(Debug, Clone)]
pub struct OptimizeReport {
    /// Refiner used.
    pub method: RefineMethod,
    /// Sampled sweep designs (bare and file designs excluded).
    pub sweep_designs: usize,
    /// Best sweep point.
    pub best_sweep: Point,
    /// Refinement evaluations, in order.
    pub log: Vec<Point>,
    /// The optimum (sweep fidelity).
    pub optimum: Point,
    /// Its slip loads, N.
    pub optimum_loads: Vec<f64>,
    /// Finalists, best (by the check) first.
    pub finalists: Vec<Finalist>,
    /// Whether the check kept the sweep-fidelity order of the finalists.
    pub ranking_held: bool,
    /// Whether the finalists were run again at the check fidelity: not when the sweep
    /// itself ran the check's method, `exact` (then each check objective is the sweep's
    /// and the ranking holds by construction).
    pub check_reran: bool,
    /// Objective of the bare frame and of the building file's design (sweep fidelity).
    pub bare_objective: f64,
    /// Objective of the building file's slip loads.
    pub file_objective: f64,
    /// Simulations run by refinement and check in this run (the sweep's not included,
    /// nor refinement points replayed from the journal of an earlier run).
    pub simulations: usize,
    /// Refinement evaluations replayed from the journal of an earlier run.
    pub replayed: usize,
}

/// Objective of designs (slip loads, N) at `fid`; `bare`: the bare frame at the same fidelity.
pub fn objectives(
    study: &Study,
    designs: &[Vec<f64>],
    bare: &[RecordMetrics],
    fid: &Fidelity,
    tick: &(dyn Fn() + Sync),
) -> Result<Vec<f64>, OptError> {
    let ranges = suite_ranges(study);
    run_designs(study, designs, fid, tick)?
        .iter()
        .map(|rows| study.objective.value(rows, Some(bare), &ranges))
        .collect()
}

/// A refinement of a sweep whose finalists are not yet checked ([`refine_sweep`]).
#[derive(Debug, Clone)]
pub struct Refinement {
    /// Refiner used.
    pub method: RefineMethod,
    /// The sweep's sample points with their objectives (bare and file designs excluded).
    pub known: Vec<Point>,
    /// Best sweep point.
    pub best_sweep: Point,
    /// Refinement evaluations, in order.
    pub log: Vec<Point>,
    /// The optimum (sweep fidelity).
    pub optimum: Point,
    /// Refinement evaluations replayed from the journal of an earlier run.
    pub replayed: usize,
    /// Objective of the bare frame (sweep fidelity).
    pub bare_objective: f64,
    /// Objective of the building file's slip loads (sweep fidelity).
    pub file_objective: f64,
}

/// Refines from the sweep (`manifest`, its complete `rows`) with `method`, then checks
/// the finalists: [`refine_sweep`], then [`check_finalists`]. With a `journal` path
/// every refinement evaluation is appended there (one JSON point per line after the
/// study's fingerprint), and the points of an earlier, interrupted run found there are
/// replayed instead of simulated again — the refiners then take the same path, so the
/// answer is the same. With a `check` journal the finalists' check takes the tasks it
/// holds and appends the others. A journal of another study is refused.
pub fn optimize(
    study: &Study,
    manifest: &Manifest,
    rows: &[RecordMetrics],
    method: RefineMethod,
    journal: Option<&Path>,
    check_journal: Option<&TaskJournal>,
    tick: &(dyn Fn() + Sync),
) -> Result<OptimizeReport, OptError> {
    let refinement = refine_sweep(study, manifest, rows, method, journal, tick)?;
    check_finalists(study, refinement, check_journal, tick)
}

/// The refinement phase of [`optimize`]: from the study's best sweep points, at the
/// sweep fidelity, journalled in `journal` (when given) and replayed from it.
pub fn refine_sweep(
    study: &Study,
    manifest: &Manifest,
    rows: &[RecordMetrics],
    method: RefineMethod,
    journal: Option<&Path>,
    tick: &(dyn Fn() + Sync),
) -> Result<Refinement, OptError> {
    let cfg = study.config.refine;
    let nr = manifest.records.len();
    let obj = manifest.objectives(rows)?;
    let bare = rows[..nr].to_vec();
    let sweep_fid = Fidelity::sweep(study);
    let known: Vec<Point> = manifest
        .designs
        .iter()
        .zip(&obj)
        .filter_map(|(d, (f, _))| d.z.clone().map(|z| Point { z, f: *f }))
        .collect();
    let mut order: Vec<usize> = (0..known.len()).collect();
    order.sort_by(|&a, &b| known[a].f.total_cmp(&known[b].f).then(a.cmp(&b)));
    let best_sweep = known
        .get(
            *order
                .first()
                .ok_or_else(|| OptError::Missing("the sweep sampled no feasible design".into()))?,
        )
        .cloned()
        .expect("index from the list");
    if !best_sweep.f.is_finite() {
        return Err(OptError::Missing(format!(
            "every sampled design collapses on some record of the study (the drift limit of the building): widen the slip-load range or lower the suites' intensity ({} designs)",
            known.len()
        )));
    }
    let oracle = {
        let bare = bare.clone();
        move |zs: &[Vec<f64>]| -> Result<Vec<f64>, OptError> {
            let designs: Vec<Vec<f64>> = zs.iter().map(|z| study.space.slip_loads(z)).collect();
            objectives(study, &designs, &bare, &sweep_fid, tick)
        }
    };
    let mut ev = Evaluations::new(Box::new(oracle), known.clone());
    if let Some(path) = journal {
        let (appender, replay) = crate::store::journal::open_journal::<Point>(
            path,
            "refine",
            &manifest.fingerprint,
            crate::store::journal::Reuse::Resume,
        )?;
        ev = ev.with_journal(replay, Box::new(move |p: &Point| appender.append(p)));
    }
    let mut budget = 0;
    for &s in order.iter().take(cfg.starts) {
        budget += cfg.max_evaluations;
        refine(method, &study.space, &known[s], &mut ev, &cfg, budget)?;
    }
    let optimum = ev.best().expect("the sweep gave points");
    let log = ev.log.clone();
    let replayed = ev.replayed;
    drop(ev);
    Ok(Refinement {
        method,
        known,
        best_sweep,
        log,
        optimum,
        replayed,
        bare_objective: obj[0].0,
        file_objective: obj[1].0,
    })
}

/// The finalist check of [`optimize`]: the best distinct points of the sweep and the
/// refinement, run again at the check fidelity (reference accuracy), taking the tasks
/// `check_journal` holds and appending the others.
pub fn check_finalists(
    study: &Study,
    refinement: Refinement,
    check_journal: Option<&TaskJournal>,
    tick: &(dyn Fn() + Sync),
) -> Result<OptimizeReport, OptError> {
    let cfg = study.config.refine;
    let nr = study.records.len();
    let Refinement {
        method,
        known,
        best_sweep,
        log,
        optimum,
        replayed,
        bare_objective,
        file_objective,
    } = refinement;
    let sweep_designs = known.len();
    // finalists: the best distinct points of everything evaluated
    // (a design that collapsed at the sweep's fidelity is no finalist)
    let mut all: Vec<Point> = known
        .iter()
        .chain(log.iter())
        .filter(|p| p.f.is_finite())
        .cloned()
        .collect();
    all.sort_by(|a, b| a.f.total_cmp(&b.f));
    let mut picked: Vec<Point> = Vec::new();
    for p in all {
        // distinct designs: at least 5 % of the range apart in some variable
        let far = |q: &Point| {
            p.z.iter()
                .zip(&q.z)
                .any(|(a, b)| (a - b).abs() >= FINALIST_SPACING)
        };
        if picked.iter().all(far) {
            picked.push(p);
        }
        if picked.len() == cfg.finalists {
            break;
        }
    }
    let all = picked;
    let check = Fidelity::check(study);
    let loads: Vec<Vec<f64>> = all.iter().map(|p| study.space.slip_loads(&p.z)).collect();
    // A sweep that ran the reference itself leaves the check nothing to correct: exact's
    // responses are exact between events whatever its output step, so the finalists'
    // objectives are the sweep's.
    let check_reran =
        !(check.method == MethodName::Exact && Fidelity::sweep(study).method == MethodName::Exact);
    let fc = if check_reran {
        let mut designs = vec![vec![0.0; study.space.dampers.len()]];
        designs.extend(loads.iter().cloned());
        let mut runs = run_designs_journalled(study, &designs, &check, check_journal, tick)?;
        let bare_check = runs.remove(0);
        let ranges = suite_ranges(study);
        runs.iter()
            .map(|rows| study.objective.value(rows, Some(&bare_check), &ranges))
            .collect::<Result<Vec<f64>, OptError>>()?
    } else {
        all.iter().map(|p| p.f).collect()
    };
    let mut finalists: Vec<Finalist> = all
        .iter()
        .zip(loads)
        .zip(fc)
        .map(|((p, l), f)| Finalist {
            z: p.z.clone(),
            slip_loads_n: l,
            f_sweep: p.f,
            f_check: f,
        })
        .collect();
    let sweep_order: Vec<Vec<f64>> = finalists.iter().map(|f| f.z.clone()).collect();
    finalists.sort_by(|a, b| a.f_check.total_cmp(&b.f_check));
    let ranking_held = finalists.iter().map(|f| &f.z).eq(sweep_order.iter());
    let checked = if check_reran { 1 + finalists.len() } else { 0 };
    let simulations = (log.len() - replayed + checked) * nr;
    Ok(OptimizeReport {
        method,
        sweep_designs,
        best_sweep,
        optimum_loads: study.space.slip_loads(&optimum.z),
        optimum,
        log,
        finalists,
        ranking_held,
        check_reran,
        bare_objective,
        file_objective,
        simulations,
        replayed,
    })
}
