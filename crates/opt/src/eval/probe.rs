//! The automatic choice of a study's sweep method (a probe run of each candidate method,
//! compared by counted work), and the constructors of a [`Study`] that make it: a study
//! is loaded, checked, and its sweep method chosen before anything else runs.

use crate::base::error::OptError;
use crate::eval::evaluate::{DesignLoads, design_plan, simulate_design};
use crate::eval::memory;
use crate::model::config::StudyConfig;
use crate::model::fidelity::{EXACT_SWEEP_COST, Fidelity, SweepMethod};
use crate::model::study::Study;
use slipload_sim::scene::MethodName;
use std::path::Path;

/// The sweep's method: the one `fidelity.method` names; unnamed, `exact` where it costs
/// at most [`EXACT_SWEEP_COST`] times `newmark` on the study's building, else `newmark`.
/// The cost is each method's counted work (`Diagnostics::work`, multiply-adds of its
/// dominant operations) on a probe: the study's first record at the building file's own
/// slip loads, at the sweep's step and outputs. Counted work, not time, so the choice
/// (and every byte after it) is the same on every machine and under any load;
/// `slipload bench` reports each method's time per unit of work beside it. Where `exact`
/// refuses the probe (a chattering or too-stiff dissipator exceeds its budget), the sweep
/// is `newmark` and the reason says so.
pub fn choose_sweep_method(study: &Study) -> Result<SweepMethod, OptError> {
    Ok(probe_sweep(study)?.0)
}

/// [`choose_sweep_method`], with `exact`'s counted work over `newmark`'s on the probe
/// where the probe ran both. A study that names `fidelity.method` is probed too where its
/// check is `exact`: the check's bound on `exact`'s cost ([`EXACT_CHECK_COST`]) holds
/// whichever way the sweep's method was chosen.
fn probe_sweep(study: &Study) -> Result<(SweepMethod, Option<f64>), OptError> {
    let Some(method) = study.config.fidelity.method else {
        if study.config.refine.method == crate::model::config::RefineMethod::Sqp {
            // (whether the check probes exact is decided as for a named method)
            let named = SweepMethod {
                method: MethodName::Newmark,
                reason: "the sqp refiner reads newmark's sensitivities".into(),
            };
            if study.config.fidelity.check_method != MethodName::Exact {
                return Ok((named, None));
            }
            return Ok((named, probe_methods(study)?.1));
        }
        return probe_methods(study);
    };
    let named = SweepMethod {
        method,
        reason: "named by the study (fidelity.method)".into(),
    };
    if study.config.fidelity.check_method != MethodName::Exact {
        return Ok((named, None));
    }
    let (_, ratio) = probe_methods(study)?;
    Ok((named, ratio))
}

/// The probe of both methods: the method it chooses, and `exact`'s counted work over
/// `newmark`'s where it ran both.
fn probe_methods(study: &Study) -> Result<(SweepMethod, Option<f64>), OptError> {
    let probe = |method: MethodName| {
        let fid = Fidelity {
            method,
            dt_s: study.config.fidelity.dt_s,
            dt_factor: 1.0,
            energies: study.needs_energies(),
            dampers: false,
            sensitivities: false,
        };
        // the building file's design as written (a locked or asymmetric damper as such)
        simulate_design(
            study,
            &DesignLoads::file(study),
            0,
            &fid,
            "file (the sweep-method probe)",
        )
    };
    let record = study.records[0].name();
    let newmark = probe(MethodName::Newmark)?.diagnostics.work;
    // Nothing runs unbounded: exact's probe runs only where a sweep of it, on every
    // thread, would fit the study's memory limit (each run's mode sets are bounded by
    // its budget, `MemoryBudget::for_plan`).
    let exact_fid = Fidelity {
        method: MethodName::Exact,
        dt_s: study.config.fidelity.dt_s,
        dt_factor: 1.0,
        energies: study.needs_energies(),
        dampers: false,
        sensitivities: false,
    };
    let exact_plan = design_plan(
        study,
        &DesignLoads::file(study),
        0,
        &exact_fid,
        "file (the sweep-method probe)",
    )?;
    // (one run against the limit, whatever the thread count: the choice, and with it
    // every result, must not depend on the threads; the study's memory estimate then
    // refuses a pool too large for the limit)
    let run_bytes = memory::run_bytes(&exact_plan);
    if run_bytes as f64 > memory::MAX_STUDY_MEMORY_BYTES {
        let b = |v: f64| slipload_sim::limits::bytes(v);
        return Ok((
            SweepMethod {
                method: MethodName::Newmark,
                reason: format!(
                    "chosen: exact was not probed: one run of it would hold {}, more than the study's limit of {}",
                    b(run_bytes as f64),
                    b(memory::MAX_STUDY_MEMORY_BYTES)
                ),
            },
            None,
        ));
    }
    memory::check_probe_fits(&study.path, run_bytes, memory::AddressSpace::read())?;
    let exact = probe(MethodName::Exact);
    // this thread will not run exact again: the study's runs go to the pool's threads,
    // whose budgets the memory estimate counts
    slipload_sim::integrator::exact::release_thread_cache();
    let mut measured = None;
    let (method, reason) = match exact {
        Ok(exact) => {
            let ratio = exact.diagnostics.work as f64 / newmark.max(1) as f64;
            measured = Some(ratio);
            let method = if ratio <= EXACT_SWEEP_COST {
                MethodName::Exact
            } else {
                MethodName::Newmark
            };
            (
                method,
                format!(
                    "chosen: exact costs {ratio:.2} x newmark's work on a probe (record {record}, the building's own slip loads); the sweep runs exact where that is at most {EXACT_SWEEP_COST}"
                ),
            )
        }
        Err(e) => (
            MethodName::Newmark,
            format!("chosen: exact refused the probe (record {record}): {e}"),
        ),
    };
    Ok((SweepMethod { method, reason }, measured))
}

/// Largest cost of `exact` on a study's building, in `newmark`'s counted work on the
/// sweep-method probe, at which the finalists' check runs `exact`: beyond it (a tall frame
/// whose every floor slips: about 940 at 100 storeys, against 7-27 on the shipped
/// studies) the check's runs would outweigh the whole study, and the check runs
/// `newmark` at the check's step instead, with its step-halving error.
pub const EXACT_CHECK_COST: f64 = 200.0;

/// The method of the finalists' check: the study's `fidelity.check_method`, except where
/// that is `exact` and `exact` cannot run the study's check within its bounds (its checks
/// refuse the check's plan, e.g. `SimError::ExactMemory`; one run of it would not fit
/// [`memory::MAX_STUDY_MEMORY_BYTES`], whatever the thread count, so the choice is the
/// same on every machine; or its counted work on the sweep-method
/// probe, `exact_work_ratio`, exceeds [`EXACT_CHECK_COST`] times `newmark`'s): the check then runs `newmark` at the
/// check's step, and the reason says so with that check's measured error — the largest
/// difference of peak drifts between the check's step and half of it over the largest
/// peak drift (its step-halving error), on the building file's design under the first record. Nothing
/// unbounded runs to decide: only the plan's checks, the estimate, and two `newmark` runs.
pub fn choose_check_method(
    study: &Study,
    exact_work_ratio: Option<f64>,
) -> Result<SweepMethod, OptError> {
    let named = study.config.fidelity.check_method;
    let kept = |why: &str| SweepMethod {
        method: named,
        reason: why.to_string(),
    };
    if named != MethodName::Exact {
        return Ok(kept("named by the study (fidelity.check_method)"));
    }
    let fid = Fidelity::check(study);
    let design = DesignLoads::file(study);
    let plan = design_plan(study, &design, 0, &fid, "file (the check-method probe)")?;
    // one run against the limit, whatever the thread count (the choice must not depend
    // on the threads; the study's memory estimate refuses a pool too large)
    let bytes = memory::run_bytes(&plan);
    let b = |v: f64| slipload_sim::limits::bytes(v);
    let refused = match slipload_sim::simulate::check(&plan) {
        Err(e) => Some(format!("exact refused the check: {e}")),
        Ok(()) if bytes as f64 > memory::MAX_STUDY_MEMORY_BYTES => Some(format!(
            "one run of exact's check would hold {}, more than the study's limit of {}",
            b(bytes as f64),
            b(memory::MAX_STUDY_MEMORY_BYTES)
        )),
        Ok(()) => exact_work_ratio
            .filter(|&r| r > EXACT_CHECK_COST)
            .map(|r| format!(
                "exact costs {r:.0} x newmark's work on the sweep-method probe, more than {EXACT_CHECK_COST} at which the check runs it"
            )),
    };
    let Some(why) = refused else {
        return Ok(kept(&format!(
            "the study's fidelity.check_method (exact by default), within its bounds: {} per run",
            b(memory::run_bytes(&plan) as f64)
        )));
    };
    let newmark = Fidelity {
        method: MethodName::Newmark,
        ..fid
    };
    let half = Fidelity {
        dt_factor: newmark.dt_factor / 2.0,
        ..newmark
    };
    let label = "file (the check-method probe)";
    let a = simulate_design(study, &design, 0, &newmark, label)?;
    let h = simulate_design(study, &design, 0, &half, label)?;
    // relative to the largest peak drift: a floor that barely moves (the top of a tall
    // frame under a short record) has no relative error worth the name
    let (drift, halved) = (&a.response.peak_drift, &h.response.peak_drift);
    let largest = halved.iter().fold(0.0, |m: f64, y| m.max(y.abs()));
    let error = drift
        .iter()
        .zip(halved)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / largest.max(f64::MIN_POSITIVE);
    Ok(SweepMethod {
        method: MethodName::Newmark,
        reason: format!(
            "{why}; the check runs newmark at dt = {:e} s instead, whose step-halving error (the largest peak-drift difference against dt/2, over the largest peak drift; record {}, the building's own slip loads) is {error:.2e}",
            plan.method.dt,
            study.records[0].name()
        ),
    })
}

/// How the summary names the finalists' check as it runs: `check at reference accuracy
/// (exact at 1 × dt)` where the study's `fidelity.check_method` runs; where it could not
/// run within its bounds ([`choose_check_method`]), the method that runs instead, which is
/// not the reference, and in place of what.
pub fn check_label(study: &Study) -> String {
    let ran = study.check_method.method;
    let named = study.config.fidelity.check_method;
    let factor = study.config.fidelity.check_dt_factor;
    if ran == named {
        format!(
            "check at reference accuracy ({} at {factor} × dt)",
            ran.as_str()
        )
    } else {
        format!(
            "check at the check's step ({} at {factor} × dt, in place of the study's {}, which could not run within its bounds)",
            ran.as_str(),
            named.as_str()
        )
    }
}

/// A base-shear limit (N) below this fraction of the building's weight is doubtful: a
/// bare number a study meant in kN, read as newtons ([`Study::warnings`]).
pub const MIN_PLAUSIBLE_BASE_SHEAR_PER_WEIGHT: f64 = 0.01;

/// A suite's record whose scaled PGA is more than this factor above (or below) the
/// suite's median PGA is named in [`Study::warnings`]: the suites of the examples keep
/// within 3.6 × (a near-fault record among distant ones), a record 4 × off is an outlier a
/// scale factor or a wrong file made.
pub const EXTREME_PGA_RATIO: f64 = 4.0;

impl Study {
    /// What the study's inputs make doubtful without making them wrong, in the words the
    /// command line prints after "warning: study FILE, ": a slip load of the building file
    /// that looks like kN written as N; a base-shear limit (a number of newtons) below
    /// [`MIN_PLAUSIBLE_BASE_SHEAR_PER_WEIGHT`] of the building's weight — "did you mean
    /// kN?"; a record shorter than the bare frame's first period. Every front gives
    /// these.
    pub fn warnings(&self) -> Vec<String> {
        let mut out: Vec<String> = slipload_sim::building::slip_load_plausibility(&self.building)
            .iter()
            .map(|w| format!("the building file's slip loads: {w}"))
            .collect();
        let weight = self.building.mass.trace() * slipload_motion::G;
        let n = |v: f64| slipload_sim::units::short_number(v);
        let base_shear = crate::model::check::LimitMetric::BaseShear;
        for (i, s) in self.config.suites.iter().enumerate() {
            let Some(l) = &s.limits else { continue };
            let criteria = l
                .criteria
                .iter()
                .enumerate()
                .map(|(j, c)| (format!("criteria[{j}]"), c.metric, c.max));
            let records = l
                .unacceptable
                .record_limits
                .iter()
                .enumerate()
                .map(|(j, c)| (format!("unacceptable.record_limits[{j}]"), c.metric, c.max));
            for (field, metric, max) in criteria.chain(records) {
                if metric == base_shear && max < MIN_PLAUSIBLE_BASE_SHEAR_PER_WEIGHT * weight {
                    out.push(format!(
                        "suites[{i}].limits.{field}.max: the base-shear limit {} N is below {} % of the building's weight (W = {} N): a limit's number is in the response's SI unit, base shear in N; did you mean kN ({} N)?",
                        n(max),
                        n(100.0 * MIN_PLAUSIBLE_BASE_SHEAR_PER_WEIGHT),
                        n(weight),
                        n(max * 1e3)
                    ));
                }
            }
        }
        out.extend(self.model_limits());
        // a record shorter than one period of the bare frame is a pulse to it: the
        // building does not go through one cycle of its first mode before the ground stops
        let t1 = self.building.t1();
        for suite in &self.suites {
            for r in suite.range.clone() {
                let rec = &self.records[r];
                let lasts = rec.dt() * rec.len().saturating_sub(1) as f64;
                if lasts < t1 {
                    out.push(format!(
                        "suite {}: record {} lasts {} s ({} samples), shorter than the bare frame's first period ({} s): the frame does not go through one cycle of its first mode before the ground stops, so its peaks are a pulse's; check the record",
                        suite.name,
                        rec.name(),
                        n(lasts),
                        rec.len(),
                        n(t1)
                    ));
                }
            }
        }
        // a record scaled far outside the rest of its suite drives the suite's mean
        for suite in &self.suites {
            let pgas: Vec<(usize, f64)> = suite
                .range
                .clone()
                .map(|r| (r, self.records[r].pga()))
                .collect();
            if pgas.len() < 3 {
                continue;
            }
            let mut sorted: Vec<f64> = pgas.iter().map(|p| p.1).collect();
            sorted.sort_by(f64::total_cmp);
            let m = sorted.len();
            let median = if m % 2 == 1 {
                sorted[m / 2]
            } else {
                0.5 * (sorted[m / 2 - 1] + sorted[m / 2])
            };
            for (r, pga) in pgas {
                let ratio = pga / median;
                if !(1.0 / EXTREME_PGA_RATIO..=EXTREME_PGA_RATIO).contains(&ratio) {
                    out.push(format!(
                        "suite {}: record {} is scaled to a PGA of {} g, {} x the suite's median PGA ({} g): a record this far from the rest drives the suite's statistics; check its factor, or whether it belongs to this suite",
                        suite.name,
                        self.records[r].name(),
                        n(pga / slipload_motion::G),
                        n(ratio),
                        n(median / slipload_motion::G)
                    ));
                }
            }
        }
        out
    }

    /// What the model cannot show that a suite's check counts: an elastic frame checked
    /// at MCE_R (its members would yield; an elastic model's drifts there are not the
    /// drifts the limits mean), and a count of unacceptable responses the study writes
    /// (`unacceptable`) on a frame that cannot collapse (no collapse limit) with no
    /// per-record limit and no stroke capacity (the count is then 0 whatever the design). In the words the summary and `code-check.md` print.
    pub fn model_limits(&self) -> Vec<String> {
        let mut out = Vec::new();
        let elastic = !self.building.is_nonlinear_frame();
        let collapses = self.building.collapse_drift.is_some();
        for (i, (cfg, suite)) in self.config.suites.iter().zip(&self.suites).enumerate() {
            let Some(limits) = &cfg.limits else { continue };
            if elastic
                && suite
                    .code_scaling
                    .as_ref()
                    .is_some_and(|c| c.hazard == crate::model::config::Hazard::MceR)
            {
                out.push(format!(
                    "suites[{i}] ({}) is checked at MCE_R on an elastic frame: no storey of the building yields (no `storey_yield`), so its drifts are an elastic model's, not the drifts the limits mean there; give the storeys' yield laws",
                    suite.name
                ));
            }
            if limits.unacceptable.written
                && !collapses
                && limits.unacceptable.record_limits.is_empty()
                && self.checks.stroke_capacity_m.is_none()
            {
                out.push(format!(
                    "suites[{i}].limits.unacceptable counts unacceptable responses, but the frame cannot collapse (no collapse limit: it needs yielding storeys or P-Δ, and storey heights) and no `record_limits` is given: the count is 0 for every design"
                ));
            }
        }
        out
    }

    /// The embedded benchmark study (`configs/study-benchmark.json` with the embedded
    /// benchmark building inlined): what every front optimises when no study is named.
    pub fn benchmark() -> Result<Study, OptError> {
        let name = Path::new(crate::model::study::BENCHMARK_STUDY_ORIGIN);
        let mut cfg = StudyConfig::from_json(crate::model::study::BENCHMARK_STUDY, name)?;
        let b: slipload_sim::BuildingConfig =
            serde_json::from_str(slipload_sim::scene::BENCHMARK_BUILDING)
                .map_err(|e| OptError::Argument(format!("the embedded benchmark building: {e}")))?;
        cfg.building = slipload_sim::scene::BuildingRef::Inline(Box::new(b));
        Study::from_config(cfg, name)
    }

    /// Reads, validates and resolves a study file.
    pub fn load(path: &Path) -> Result<Study, OptError> {
        let text = crate::model::study::read_text(path)?;
        Study::from_json(&text, path)
    }

    /// Parses, validates and resolves a study; `path` names it in errors and anchors
    /// relative paths.
    pub fn from_json(text: &str, path: &Path) -> Result<Study, OptError> {
        let cfg = StudyConfig::from_json(text, path)?;
        Study::from_config(cfg, path)
    }

    /// Validates and resolves a config — building, space, constraints, then records —,
    /// chooses the sweep's method ([`choose_sweep_method`]) and estimates the memory the
    /// study holds at once, refusing it beyond [`memory::MAX_STUDY_MEMORY_BYTES`]
    /// ([`memory::estimate`]).
    pub fn from_config(cfg: StudyConfig, path: &Path) -> Result<Study, OptError> {
        let mut study = Study::described(cfg, path)?;
        let (sweep, exact_work_ratio) = probe_sweep(&study)?;
        study.sweep_method = sweep;
        study.check_method = choose_check_method(&study, exact_work_ratio)?;
        study.memory = memory::estimate(&study, rayon::current_num_threads())?;
        let exact_check = study.check_method.method == MethodName::Exact;
        study
            .memory
            .check(&study.path, exact_check, memory::MAX_STUDY_MEMORY_BYTES)?;
        study
            .memory
            .check_address_space(&study.path, exact_check, memory::AddressSpace::read())?;
        Ok(study)
    }
}
