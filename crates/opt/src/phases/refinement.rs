//! Optimisation: after a sweep, refine from its best points, then verify the finalists
//! at reference accuracy (the study's check method and time step) and report whether
//! their ranking held.

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::eval::evaluate::{TaskJournal, run_designs, run_designs_journalled};
use crate::model::check::DesignCheck;
use crate::model::config::RefineMethod;
use crate::model::fidelity::Fidelity;
use crate::model::study::Study;
use crate::phases::gradient::gradient;
use crate::phases::refine::{
    Evaluations, LimitValues, Point, Stationarity, StopReason, post_check, refine_starts,
    screened_check,
};
use crate::phases::sweep::Manifest;
use slipload_sim::scene::MethodName;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

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
    /// Its check against the study's limits at the check fidelity (`None`: the study has
    /// no limits).
    pub check: Option<DesignCheck>,
}

impl Finalist {
    /// Whether it meets every limit (a study without limits: always).
    pub fn passes(&self) -> bool {
        self.check.as_ref().is_none_or(DesignCheck::passes)
    }
}

/// What the refiners minimise.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RefineTarget {
    /// The objective (a study without limits).
    Objective,
    /// The objective of designs that meet every limit; +∞ for one that does not (a
    /// rejected step), so that no failing design wins over a passing one.
    PassingObjective,
    /// The sum of the exceedances ([`DesignCheck::violation`]): no design of the sweep
    /// meets the limits, so the refiners look for the closest one (0: it passes).
    Violation,
}

impl RefineTarget {
    /// The value a design takes: `f` its objective, `check` its check (present with limits).
    pub fn value(self, f: f64, check: Option<&DesignCheck>) -> f64 {
        match (self, check) {
            (RefineTarget::Objective, _) | (_, None) => f,
            (RefineTarget::PassingObjective, Some(c)) => {
                if c.passes() {
                    f
                } else {
                    f64::INFINITY
                }
            }
            (RefineTarget::Violation, Some(c)) => c.violation(),
        }
    }

    /// The limit values the model refiner keeps to ([`LimitValues`]): for the objective
    /// of passing designs, the objective and the smooth ratios of the check; none for
    /// the other targets.
    pub fn limit_values(self, f: f64, check: Option<&DesignCheck>) -> Option<LimitValues> {
        match (self, check) {
            (RefineTarget::PassingObjective, Some(c)) => {
                Some(LimitValues::new(f, c.smooth_ratios()))
            }
            _ => None,
        }
    }
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
    /// Whether the bare frame meets the study's limits at the sweep fidelity (`None`: the
    /// study has no limits). With a cost objective, a bare frame that meets them needs
    /// no damper.
    pub bare_passes: Option<bool>,
    /// Whether the building file's design meets the limits as the sweep ran it (a study
    /// with limits).
    pub file_passes: Option<bool>,
    /// Objective of the building file's slip loads.
    pub file_objective: f64,
    /// What the refiners minimised.
    pub target: RefineTarget,
    /// The recommended design's runs at the check fidelity and the bare frame's (a study
    /// with limits: the first finalist's, for the code check).
    pub recommended_runs: Option<(Vec<RecordMetrics>, Vec<RecordMetrics>)>,
    /// Simulations run by refinement and check in this run (the sweep's not included,
    /// nor refinement points replayed from the journal of an earlier run).
    pub simulations: usize,
    /// Refinement evaluations replayed from the journal of an earlier run.
    pub replayed: usize,
    /// The runs of the refinement's evaluations made now ([`Refinement::runs`]).
    pub refined_runs: RefinedRuns,
    /// Why each start's refiner stopped, in the order of the starts.
    pub stops: Vec<StopReason>,
    /// The post-check of the optimum (the `model` refiner): no single-floor or profile
    /// move improves it by more than [`crate::phases::refine::STATIONARY_GAIN`].
    pub stationarity: Option<Stationarity>,
}

/// Objective of designs (slip loads, N) at `fid`; `bare`: the bare frame at the same
/// fidelity; each mapped to what `target` minimises.
pub fn objectives(
    study: &Study,
    designs: &[Vec<f64>],
    bare: &[RecordMetrics],
    fid: &Fidelity,
    target: RefineTarget,
    tick: &(dyn Fn() + Sync),
) -> Result<Vec<f64>, OptError> {
    Ok(values_of(
        study,
        designs,
        &run_designs(study, designs, fid, tick)?,
        bare,
        target,
    )?
    .into_iter()
    .map(|(f, _)| f)
    .collect())
}

/// What `target` minimises of each design (slip loads `designs`, N) from its `runs`
/// (`bare`: the bare frame's), with its limit values where the refiners keep to the
/// limits ([`RefineTarget::limit_values`]).
fn values_of(
    study: &Study,
    designs: &[Vec<f64>],
    runs: &[Vec<RecordMetrics>],
    bare: &[RecordMetrics],
    target: RefineTarget,
) -> Result<Vec<(f64, Option<LimitValues>)>, OptError> {
    runs.iter()
        .zip(designs)
        .map(|(rows, loads)| {
            let f = study.objective_value(rows, bare, loads)?;
            let check = match target {
                RefineTarget::Objective => None,
                _ => Some(study.check_design(rows)?),
            };
            let mut limits = target.limit_values(f, check.as_ref());
            // runs that carry derivatives (the `sqp` refiner's) give the design's
            if target != RefineTarget::Violation
                && let Some(g) = gradient(study, rows, bare, loads, check.is_some())?
            {
                limits
                    .get_or_insert_with(|| LimitValues::new(f, Vec::new()))
                    .gradient = Some(g);
            }
            Ok((target.value(f, check.as_ref()), limits))
        })
        .collect()
}

/// A design evaluated at the sweep fidelity by another phase (the front's search): its
/// scaled variables, its objective, and its check (a study with limits).
pub type Scored = (Vec<f64>, f64, Option<DesignCheck>);

/// What a study with a front shares with its refinement: the search's designs (starts
/// and finalist candidates beside the sweep's), and the front's task journal
/// (`pareto.jsonl`), where the refinement's runs are journalled so that the front takes
/// them as candidates after a resumed run too. Empty for a study without a front.
#[derive(Debug, Clone, Copy, Default)]
pub struct FromFront<'a> {
    /// The search's designs.
    pub designs: &'a [Scored],
    /// The front's task journal.
    pub journal: Option<&'a TaskJournal>,
}

/// The runs of refinement evaluations, keyed by the bits of their scaled variables
/// ([`RefinedRuns::get`]).
#[derive(Debug, Clone, Default)]
pub struct RefinedRuns(HashMap<Vec<u64>, Vec<RecordMetrics>>);

impl RefinedRuns {
    fn key(z: &[f64]) -> Vec<u64> {
        z.iter().map(|v| v.to_bits()).collect()
    }

    /// The runs of the evaluation at `z` (sweep fidelity), when this run computed them
    /// (not for an evaluation replayed from the journal).
    pub fn get(&self, z: &[f64]) -> Option<&[RecordMetrics]> {
        self.0.get(&Self::key(z)).map(Vec::as_slice)
    }
}

/// A refinement of a sweep whose finalists are not yet checked ([`refine_sweep`]).
#[derive(Debug, Clone)]
pub struct Refinement {
    /// Refiner used.
    pub method: RefineMethod,
    /// The sweep's sample points with their objectives, then the building file's design
    /// where the space holds it (the bare frame excluded): every design the sweep
    /// evaluated is a start and a finalist candidate.
    pub known: Vec<Point>,
    /// How many of `known` are the sweep's sample.
    pub sampled: usize,
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
    /// Whether the bare frame meets the study's limits (`None`: no limits).
    pub bare_passes: Option<bool>,
    /// Whether the building file's design meets the limits as the sweep ran it (a study
    /// with limits).
    pub file_passes: Option<bool>,
    /// Objective of the building file's slip loads (sweep fidelity).
    pub file_objective: f64,
    /// What the refiners minimised.
    pub target: RefineTarget,
    /// The runs of the evaluations made now, kept for a study with a front (whose
    /// candidates they are); empty otherwise.
    pub runs: RefinedRuns,
    /// Why each start's refiner stopped, in the order of the starts.
    pub stops: Vec<StopReason>,
    /// The post-check of the optimum (the `model` refiner).
    pub stationarity: Option<Stationarity>,
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
    let refinement = refine_sweep(
        study,
        manifest,
        rows,
        method,
        journal,
        FromFront::default(),
        tick,
    )?;
    check_finalists(study, refinement, check_journal, tick)
}

/// The refinement phase of [`optimize`]: from the study's best sweep points, at the
/// sweep fidelity, journalled in `journal` (when given) and replayed from it. `front`:
/// what a study with a front shares ([`FromFront`]), so the optimum is the best design
/// the study evaluated.
pub fn refine_sweep(
    study: &Study,
    manifest: &Manifest,
    rows: &[RecordMetrics],
    method: RefineMethod,
    journal: Option<&Path>,
    front: FromFront<'_>,
    tick: &(dyn Fn() + Sync),
) -> Result<Refinement, OptError> {
    let cfg = study.config.refine;
    let nr = manifest.records.len();
    let obj = manifest.objectives(rows)?;
    let checks = manifest.checks_of(rows)?;
    let bare = rows[..nr].to_vec();
    let sweep_fid = Fidelity::sweep(study);
    // with limits: the passing designs' objective, or (none passing) the exceedances
    let target = match &checks {
        None => RefineTarget::Objective,
        Some(c) => {
            let sampled = manifest
                .designs
                .iter()
                .zip(c)
                .filter(|(d, _)| d.z.is_some());
            if sampled.clone().any(|(_, c)| c.passes()) {
                RefineTarget::PassingObjective
            } else {
                RefineTarget::Violation
            }
        }
    };
    let mut known: Vec<Point> = manifest
        .designs
        .iter()
        .zip(&obj)
        .enumerate()
        .filter_map(|(i, (d, (f, _)))| {
            let check = checks.as_ref().map(|c| &c[i]);
            d.z.clone().map(|z| Point {
                z,
                f: target.value(*f, check),
                limits: target.limit_values(*f, check),
            })
        })
        .collect();
    let sampled = known.len();
    // the building file's design (design 1) is a design the sweep evaluated: where the
    // space holds it (symmetric slip loads on the space), it competes with the sample
    if let Some(file) = manifest.designs.get(1).filter(|d| d.friction_n.is_none())
        && let Some(z) = study.space.point_of(&file.slip_loads_n)
        && !known.iter().any(|p| p.z == z)
    {
        let check = checks.as_ref().map(|c| &c[1]);
        known.push(Point {
            z,
            f: target.value(obj[1].0, check),
            limits: target.limit_values(obj[1].0, check),
        });
    }
    // with a cost objective the bare frame is the design without dampers: where the
    // space holds it (every lower bound 0) it competes too, and wins when it meets the
    // limits (no damper is needed)
    if study.objective.cost.is_some()
        && let Some(z) = study.space.point_of(&vec![0.0; study.space.dampers.len()])
        && !known.iter().any(|p| p.z == z)
    {
        let check = checks.as_ref().map(|c| &c[0]);
        known.push(Point {
            z,
            f: target.value(obj[0].0, check),
            limits: target.limit_values(obj[0].0, check),
        });
    }
    // with limits, no design meeting them makes the refiners look for the closest
    // (the smallest sum of exceedances, finite for a collapsing design too): where every
    // design the sweep ran collapses on some record there is no closest design to
    // recommend, and the study stops as a study without limits does
    if target == RefineTarget::Violation && obj.iter().skip(1).all(|(f, _)| !f.is_finite()) {
        return Err(OptError::Missing(format!(
            "every sampled design collapses on some record of the study (the drift limit of the building): widen the slip-load range or lower the suites' intensity ({} designs)",
            obj.len() - 1
        )));
    }
    let by_value = |known: &[Point]| {
        let mut order: Vec<usize> = (0..known.len()).collect();
        order.sort_by(|&a, &b| known[a].f.total_cmp(&known[b].f).then(a.cmp(&b)));
        order
    };
    let best_sweep = known
        .get(
            *by_value(&known)
                .first()
                .ok_or_else(|| OptError::Missing("the sweep sampled no feasible design".into()))?,
        )
        .cloned()
        .expect("index from the list");
    // the front search's designs compete too (after the sweep's, in their order)
    for (z, f, check) in front.designs {
        if !known.iter().any(|p| p.z == *z) {
            known.push(Point {
                z: z.clone(),
                f: target.value(*f, check.as_ref()),
                limits: target.limit_values(*f, check.as_ref()),
            });
        }
    }
    let order = by_value(&known);
    // (the best of every design evaluated, the search's included)
    if !order.first().is_some_and(|&i| known[i].f.is_finite()) {
        // (with limits: the designs that meet them collapse on a record the count allows,
        // and a collapse makes the objective +inf)
        return Err(OptError::Missing(format!(
            "every sampled design{} collapses on some record of the study (the drift limit of the building): widen the slip-load range or lower the suites' intensity ({} designs)",
            if target == RefineTarget::PassingObjective {
                " that meets the limits"
            } else {
                ""
            },
            known.len()
        )));
    }
    // the `sqp` refiner reads the derivatives of every evaluation; without a design that
    // meets the limits there is no objective to differentiate, and the `model` refiner
    // looks for the closest design
    let method = if method == RefineMethod::Sqp && target == RefineTarget::Violation {
        RefineMethod::Model
    } else {
        method
    };
    // (the refiner's evaluations carry derivatives; its post-check's do not)
    let derivatives = AtomicBool::new(method == RefineMethod::Sqp);
    // a study with a front keeps the runs of the evaluations: they are its candidates
    let keep_runs = !study.objectives.is_empty();
    let kept = Mutex::new(RefinedRuns::default());
    let oracle = || {
        let bare = &bare;
        let kept = &kept;
        let sweep_fid = &sweep_fid;
        let derivatives = &derivatives;
        move |zs: &[Vec<f64>]| -> Result<Vec<(f64, Option<LimitValues>)>, OptError> {
            let designs: Vec<Vec<f64>> = zs.iter().map(|z| study.space.slip_loads(z)).collect();
            let fid = Fidelity {
                sensitivities: derivatives.load(Ordering::Relaxed),
                ..*sweep_fid
            };
            let runs = run_designs_journalled(study, &designs, &fid, front.journal, tick)?;
            let values = values_of(study, &designs, &runs, bare, target)?;
            if keep_runs {
                let mut k = kept
                    .lock()
                    .unwrap_or_else(std::sync::PoisonError::into_inner);
                for (z, r) in zs.iter().zip(runs) {
                    k.0.insert(RefinedRuns::key(z), r);
                }
            }
            Ok(values)
        }
    };
    let journal = match journal {
        Some(path) => Some(crate::store::journal::open_journal::<Point>(
            path,
            "refine",
            &manifest.fingerprint,
            crate::store::journal::Reuse::Resume,
        )?),
        None => None,
    };
    // the evaluations of a refiner: the known points, the journal's replay and its hook
    let evaluations = || {
        let ev = Evaluations::with_limits(Box::new(oracle()), known.clone());
        match &journal {
            Some((appender, replay)) => ev.with_journal(
                replay.clone(),
                Box::new(move |p: &Point| appender.append(p)),
            ),
            None => ev,
        }
    };
    let starts: Vec<&Point> = order.iter().take(cfg.starts).map(|&s| &known[s]).collect();
    let budget = cfg.max_evaluations * starts.len();
    let (mut ev, stops) = refine_starts(method, &study.space, &starts, evaluations, &cfg)?;
    // the model refiner shows its optimum is stationary: single-floor and profile moves
    // of max(tolerance, 1 %) of the range, a batch of at most 2d + 2 evaluations; while
    // a move still gains and the starts' budget has room for another batch, the poll
    // goes on from the better design (a pattern search: a refiner that stopped on its
    // tolerance with a move left that gains is not done)
    let stationarity = if method == RefineMethod::Model {
        let step = cfg.tolerance.max(0.01);
        let batch = 2 * study.space.dim() + 2;
        let mut s = post_check(
            &study.space,
            &ev.best().expect("the sweep gave points"),
            &mut ev,
            step,
        )?;
        let mut polls = 1;
        while s.as_ref().is_some_and(|s| !s.stationary) && ev.count() + batch <= budget {
            let at = ev.best().expect("the sweep gave points");
            s = post_check(&study.space, &at, &mut ev, step)?;
            polls += 1;
        }
        s.map(|s| Stationarity { polls, ..s })
    } else if method == RefineMethod::Sqp {
        // the sqp refiner's design carries its derivatives: its moves are screened by them
        // (the re-evaluated point, which holds them, not the sweep's copy), and the moves
        // they flag are simulated, without derivatives
        let best = ev.best().expect("the sweep gave points");
        derivatives.store(false, Ordering::Relaxed);
        ev.release_gradients();
        match ev.point(&best.z) {
            Some(at) => screened_check(&study.space, &at, &mut ev, cfg.tolerance.max(0.01))?,
            None => None,
        }
    } else {
        None
    };
    let optimum = ev.best().expect("the sweep gave points");
    let log = ev.log.clone();
    let replayed = ev.replayed;
    drop(ev);
    let runs = kept
        .into_inner()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    Ok(Refinement {
        runs,
        stops,
        stationarity,
        method,
        known,
        sampled,
        best_sweep,
        log,
        optimum,
        replayed,
        bare_objective: obj[0].0,
        bare_passes: checks.as_ref().map(|c| c[0].passes()),
        file_passes: checks.as_ref().map(|c| c[1].passes()),
        file_objective: obj[1].0,
        target,
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
    let nr = study.runs();
    let Refinement {
        method,
        known,
        sampled,
        best_sweep,
        log,
        optimum,
        replayed,
        bare_objective,
        bare_passes,
        file_passes,
        file_objective,
        target,
        runs: refined_runs,
        stops,
        stationarity,
    } = refinement;
    let limits = study.checks.has_limits();
    let sweep_designs = sampled;
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
    // (a study with limits checks its finalists' responses: they run at the check
    // fidelity even when the sweep ran it, taken from the journal where they are there)
    let check_reran = limits
        || !(check.method == MethodName::Exact
            && Fidelity::sweep(study).method == MethodName::Exact);
    let mut runs_check = Vec::new();
    let fc = if check_reran {
        let mut designs = vec![vec![0.0; study.space.dampers.len()]];
        designs.extend(loads.iter().cloned());
        let mut runs = run_designs_journalled(study, &designs, &check, check_journal, tick)?;
        let bare_check = runs.remove(0);
        let fc = runs
            .iter()
            .zip(&loads)
            .map(|(rows, l)| study.objective_value(rows, &bare_check, l))
            .collect::<Result<Vec<f64>, OptError>>()?;
        runs_check = runs;
        runs_check.push(bare_check);
        fc
    } else {
        all.iter().map(|p| p.f).collect()
    };
    let checks: Vec<Option<DesignCheck>> = if limits {
        runs_check[..all.len()]
            .iter()
            .map(|rows| study.check_design(rows).map(Some))
            .collect::<Result<_, _>>()?
    } else {
        vec![None; all.len()]
    };
    let mut finalists: Vec<Finalist> = all
        .iter()
        .zip(loads)
        .zip(fc)
        .zip(checks)
        .map(|(((p, l), f), check)| Finalist {
            z: p.z.clone(),
            slip_loads_n: l,
            f_sweep: p.f,
            f_check: f,
            check,
        })
        .collect();
    let sweep_order: Vec<Vec<f64>> = finalists.iter().map(|f| f.z.clone()).collect();
    // a finalist that meets the limits ranks before every one that does not; those that
    // do not rank by how far they miss
    let key = |f: &Finalist| match &f.check {
        Some(c) if !c.passes() => (1, c.violation()),
        _ => (0, f.f_check),
    };
    let order: Vec<usize> = {
        let mut o: Vec<usize> = (0..finalists.len()).collect();
        o.sort_by(|&a, &b| {
            let (ka, kb) = (key(&finalists[a]), key(&finalists[b]));
            ka.0.cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
        });
        o
    };
    let recommended_runs = match (limits, order.first()) {
        (true, Some(&i)) => Some((
            runs_check[i].clone(),
            runs_check.last().expect("the bare frame's runs").clone(),
        )),
        _ => None,
    };
    let mut sorted: Vec<Finalist> = order.iter().map(|&i| finalists[i].clone()).collect();
    std::mem::swap(&mut finalists, &mut sorted);
    drop(sorted);
    let ranking_held = finalists.iter().map(|f| &f.z).eq(sweep_order.iter());
    let checked = if check_reran { 1 + finalists.len() } else { 0 };
    let simulations = (log.len() - replayed + checked) * nr;
    // with limits the optimum is the recommended design: the best finalist that passes
    // (or, none passing, the closest)
    let optimum = match (limits, finalists.first()) {
        (true, Some(f)) => Point::new(f.z.clone(), f.f_sweep),
        _ => optimum,
    };
    Ok(OptimizeReport {
        method,
        sweep_designs,
        best_sweep,
        optimum_loads: study.space.slip_loads(&optimum.z),
        optimum,
        target,
        recommended_runs,
        log,
        finalists,
        ranking_held,
        check_reran,
        bare_objective,
        bare_passes,
        file_passes,
        file_objective,
        simulations,
        replayed,
        refined_runs,
        stops,
        stationarity,
    })
}
