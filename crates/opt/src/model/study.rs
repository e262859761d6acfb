//! Studies: which building, which ground-motion suites, which design space, which
//! objective, and how to sweep and refine — read from JSON, validated in full before any
//! simulation runs (unknown fields, empty suites, reversed bounds, infeasible constraints
//! are errors that name the field).
//!
//! Paths (building, records) are relative to the study file. Record patterns may use `*`
//! in the file name (not in folder names); matches are sorted by name.

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::model::check::{CaseName, Checks, DesignCheck, PropertyCase, short};
pub use crate::model::code_scaling::{CodeScaling, MIN_CODE_PAIRS, MIN_CODE_RECORDS};
use crate::model::config::{
    MAX_DESIGNS, MAX_SWEEP_STEPS, MAX_TASKS, SamplerKind, StudyConfig, too_large,
};
use crate::model::fidelity::{Fidelity, SweepMethod};
use crate::model::objective::{Metric, Objective};
use crate::model::space::DesignSpace;
pub use crate::model::suites::SuiteInfo;
use slipload_motion::Record;
use slipload_sim::scene::{BuildingRef, MethodName};
use slipload_sim::{Building, BuildingConfig};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A validated study with its building and records loaded.
#[derive(Debug, Clone)]
pub struct Study {
    /// Name.
    pub name: String,
    /// The file it came from (or `<embedded>`).
    pub path: PathBuf,
    /// The config as written.
    pub config: StudyConfig,
    /// The building (slip loads of the file kept: the "paper" design).
    pub building: Building,
    /// The building as its file (or the study, inline) writes it, before validation:
    /// how its damping, yield laws and limits were given, for the study folder's copy
    /// ([`crate::phases::building`]).
    pub building_config: BuildingConfig,
    /// All records of all suites, suite after suite.
    pub records: Vec<Arc<Record>>,
    /// Per record, the orientations whose responses envelope into its run (a pair run
    /// `worst`, [`crate::model::orientation`]; the record is the first of them, named for
    /// the pair); empty for a record that runs alone (every record but those).
    pub orientations: Vec<Vec<Arc<Record>>>,
    /// The suites.
    pub suites: Vec<SuiteInfo>,
    /// The design space.
    pub space: DesignSpace,
    /// The objective.
    pub objective: Objective,
    /// The sweep's method, and why ([`crate::eval::probe::choose_sweep_method`]).
    pub sweep_method: SweepMethod,
    /// The objectives of the front (empty: a one-objective study).
    pub objectives: Vec<crate::model::objectives::ParetoObjective>,
    /// The property bounds and acceptance limits (empty: none, as before).
    pub checks: Checks,
    /// What the study holds at once, estimated when it is loaded
    /// ([`crate::eval::memory::estimate`]).
    pub memory: crate::model::memory::MemoryEstimate,
    /// The method of the finalists' check, and why
    /// ([`crate::eval::probe::choose_check_method`]).
    pub check_method: SweepMethod,
}

/// A building file as written (read and parsed as [`Building::load`] reads it, with its
/// errors), for [`Building::from_config`].
fn read_building(path: &Path) -> Result<BuildingConfig, slipload_sim::SimError> {
    let text = slipload_motion::limits::read_input_text(
        path,
        "building",
        slipload_motion::limits::MAX_CONFIG_BYTES,
    )?;
    slipload_sim::kind::parse(&text, path, slipload_sim::kind::Expected::Building)
}

pub(crate) fn read_text(path: &Path) -> Result<String, OptError> {
    Ok(slipload_motion::limits::read_input_text(
        path,
        "study",
        slipload_motion::limits::MAX_CONFIG_BYTES,
    )?)
}

/// Estimates the sweep's designs, tasks and steps and each record's run before anything
/// is sampled or simulated; refuses a time step that would skip record samples or
/// outlast a record.
fn check_work(
    cfg: &StudyConfig,
    path: &Path,
    building: &Building,
    space: &DesignSpace,
    records: &[Arc<Record>],
) -> Result<(), OptError> {
    let p = path.display();
    let sw = &cfg.sweep;
    let designs = 2.0
        + match sw.sampler {
            SamplerKind::Grid => (sw.levels as f64).powi(space.dim() as i32),
            SamplerKind::Lhs | SamplerKind::Halton => sw.points as f64,
        };
    let field = match sw.sampler {
        SamplerKind::Grid => "sweep.levels",
        _ => "sweep.points",
    };
    too_large(
        format!("{p}: field `{field}`: the sweep's designs"),
        designs,
        MAX_DESIGNS,
        "designs",
    )?;
    // each property case runs every record again
    let cases = if cfg.property_bounds.is_some() {
        3.0
    } else {
        1.0
    };
    let tasks = designs * records.len() as f64 * cases;
    too_large(
        format!("{p}: the sweep's (design, record) tasks"),
        tasks,
        MAX_TASKS,
        "tasks",
    )?;
    let fid = &cfg.fidelity;
    // Unnamed, the sweep's method is chosen later; newmark's step checks are the stricter.
    let method = fid.method.unwrap_or(MethodName::Newmark);
    let t1 = building.t1();
    let mut steps = 0.0;
    // (the longest rest after a record, on every record: an upper bound of the work)
    let rest = cfg
        .suites
        .iter()
        .filter_map(|s| s.free_vibration_s)
        .fold(0.0, f64::max);
    for r in records {
        let duration = r.duration() + rest;
        let dt = match fid.dt_s {
            Some(dt) => {
                slipload_sim::scene::check_step_against_record(method, dt, r)
                    .map_err(|e| OptError::invalid(path, "fidelity.dt_s", e.to_string()))?;
                dt
            }
            None => slipload_sim::scene::default_dt(method, t1, Some(r.dt()), duration),
        };
        if dt > duration * (1.0 + 1e-9) {
            return Err(OptError::invalid(
                path,
                "fidelity.dt_s",
                format!(
                    "time step {dt} s is longer than record {} ({duration} s): the run would be one step past its end",
                    r.name()
                ),
            ));
        }
        let run = duration / dt;
        let check = duration / (dt * fid.check_dt_factor);
        too_large(
            format!(
                "{p}: field `fidelity.dt_s`: record {} ({duration} s) at the check's dt = {} s needs",
                r.name(),
                dt * fid.check_dt_factor
            ),
            check,
            slipload_sim::limits::MAX_STEPS,
            "steps",
        )?;
        steps += run;
    }
    too_large(
        format!(
            "{p}: the whole sweep ({} designs x {} records)",
            designs,
            records.len()
        ),
        steps * designs * cases,
        MAX_SWEEP_STEPS,
        "integration steps",
    )
}

/// The benchmark study (`configs/study-benchmark.json`), embedded so that every front
/// runs the main job with no files; its building is the embedded benchmark building.
pub const BENCHMARK_STUDY: &str = include_str!("../../../../configs/study-benchmark.json");

/// How errors name the embedded benchmark study.
pub const BENCHMARK_STUDY_ORIGIN: &str = "configs/study-benchmark.json (embedded)";

/// Each brace's largest force over the design space, λ_max F / (n cos θ) at the space's
/// upper corner, against its axial design strength (`devices.brace_capacity_kn`): a space
/// whose slip loads could overload a brace is refused naming the bound to lower.
fn check_braces(
    d: &crate::model::config::DevicesConfig,
    space: &DesignSpace,
    checks: &Checks,
    path: &Path,
) -> Result<(), OptError> {
    let (Some(caps), Some(angle)) = (&d.brace_capacity_kn, d.brace_angle_deg) else {
        return Ok(());
    };
    if caps.len() != space.dampers.len() {
        return Err(OptError::invalid(
            path,
            "devices.brace_capacity_kn",
            format!(
                "gives {} capacities for {} dampers: one per damper, bottom to top",
                caps.len(),
                space.dampers.len()
            ),
        ));
    }
    let hi = checks.slip_load_range().1;
    let per = d.braces_per_damper.unwrap_or(1) as f64 * angle.to_radians().cos();
    let most = space.slip_loads(&vec![1.0; space.dim()]);
    for (k, (&floor, &f)) in space.dampers.iter().zip(&most).enumerate() {
        let allowed = caps[k] * 1e3 * per / hi;
        if f > allowed * (1.0 + 1e-9) {
            let field = match space.shape {
                None => format!("space.free.upper_kn[{k}]"),
                Some(_) => "space.profile.scale_kn[1]".to_string(),
            };
            return Err(OptError::invalid(
                path,
                field,
                format!(
                    "lets floor {}'s damper overload its brace: at its largest slip load in the space, {} kN, ×{hi} at the upper property bound, the brace carries {} kN against its {} kN (devices.brace_capacity_kn[{k}]); the slip load may be at most {} kN",
                    floor + 1,
                    short(f / 1e3),
                    short(hi * f / per / 1e3),
                    short(caps[k]),
                    short(allowed / 1e3)
                ),
            ));
        }
    }
    Ok(())
}

/// The `sqp` refiner differentiates the objective and the limits through the runs'
/// sensitivities, which `newmark` computes for the peak drift, residual drift, floor
/// acceleration and base shear: a study whose objective or limits read another response
/// (an energy, a ductility), or whose sweep names a method without sensitivities, is
/// refused naming the field.
fn check_sqp(
    cfg: &StudyConfig,
    objective: &Objective,
    checks: &Checks,
    path: &Path,
) -> Result<(), OptError> {
    let smooth = |m: Metric| {
        matches!(
            m,
            Metric::PeakDriftRatio
                | Metric::ResidualDriftRatio
                | Metric::PeakFloorAcceleration
                | Metric::BaseShear
        )
    };
    let why = "the sqp refiner differentiates the peak drift ratio, residual drift ratio, peak floor acceleration and base shear; use refine.method \"model\" for";
    for (i, t) in objective.terms.iter().enumerate() {
        if !smooth(t.metric) {
            return Err(OptError::invalid(
                path,
                format!("objective.terms[{i}].metric"),
                format!("{why} {}", t.metric.as_str()),
            ));
        }
    }
    for (i, lim) in checks.limits.iter().enumerate() {
        for (j, c) in lim.iter().flat_map(|l| l.criteria.iter()).enumerate() {
            if !smooth(c.metric.metric()) {
                return Err(OptError::invalid(
                    path,
                    format!("suites[{i}].limits.criteria[{j}].metric"),
                    format!("{why} {}", c.metric.as_str()),
                ));
            }
        }
    }
    if let Some(m) = cfg.fidelity.method
        && matches!(m, MethodName::Exact | MethodName::Delacruz)
    {
        return Err(OptError::invalid(
            path,
            "fidelity.method",
            format!(
                "the sqp refiner reads the sensitivities of newmark, hht or bilinear, which {} does not compute; name one of those, or refine.method \"model\"",
                m.as_str()
            ),
        ));
    }
    Ok(())
}

/// The design wind against the design space: one shear per storey, and the space's least
/// slip load of each damper (its lower corner) at the lower property bound at least
/// `factor` × its storey's wind shear — else the study is refused naming the bound to
/// raise (no design of the space may let a damper slip in the design wind).
fn check_wind(
    w: &crate::model::config::WindConfig,
    building: &Building,
    space: &DesignSpace,
    checks: &Checks,
    path: &Path,
) -> Result<(), OptError> {
    let floors = building.floors();
    if w.storey_shears_kn.len() != floors {
        return Err(OptError::invalid(
            path,
            "wind.storey_shears_kn",
            format!(
                "gives {} storey shears for a building of {floors} storeys: one per storey, bottom to top",
                w.storey_shears_kn.len()
            ),
        ));
    }
    let lo = checks.slip_load_range().0;
    let factor = w.factor.unwrap_or(1.3);
    let least = space.slip_loads(&vec![0.0; space.dim()]);
    for (k, (&floor, &f)) in space.dampers.iter().zip(&least).enumerate() {
        let need = factor * w.storey_shears_kn[floor] * 1e3 / lo;
        if f < need * (1.0 - 1e-9) {
            let field = match space.shape {
                None => format!("space.free.lower_kn[{k}]"),
                Some(_) => "space.profile.scale_kn[0]".to_string(),
            };
            return Err(OptError::invalid(
                path,
                field,
                format!(
                    "lets floor {}'s damper slip in the design wind: its least slip load in the space is {} kN, and {factor} × the storey's wind shear {} kN at the lower property bound ×{lo} needs at least {} kN; raise the space's lower bound",
                    floor + 1,
                    short(f / 1e3),
                    short(w.storey_shears_kn[floor]),
                    short(need / 1e3)
                ),
            ));
        }
    }
    Ok(())
}

impl Fidelity {
    /// The study's sweep fidelity (energies only when the objective needs them).
    pub fn sweep(study: &Study) -> Fidelity {
        Fidelity {
            method: study.sweep_method.method,
            dt_s: study.config.fidelity.dt_s,
            dt_factor: 1.0,
            energies: study.needs_energies(),
            dampers: false,
            sensitivities: false,
        }
    }
    /// The study's reference check fidelity (energies on; the per-damper demands for a
    /// study with limits, whose device table reads them).
    pub fn check(study: &Study) -> Fidelity {
        Fidelity {
            method: study.check_method.method,
            dt_s: study.config.fidelity.dt_s,
            dt_factor: study.config.fidelity.check_dt_factor,
            energies: true,
            dampers: study.checks.has_limits(),
            sensitivities: false,
        }
    }
}

/// A study that reads `peak_ductility` (an objective's term, a suite's criterion or
/// record limit) on a building whose storeys do not yield is refused when it loads,
/// naming the field: the response does not exist on an elastic frame, and would
/// otherwise fail only after the sweep.
fn refuse_ductility_on_elastic(
    cfg: &StudyConfig,
    building: &Building,
    path: &Path,
) -> Result<(), OptError> {
    if building.storey_yield.iter().any(Option::is_some) {
        return Ok(());
    }
    let mut fields: Vec<String> = cfg
        .objective
        .terms
        .iter()
        .enumerate()
        .filter(|(_, t)| t.metric == crate::model::objective::Metric::PeakDuctility)
        .map(|(j, _)| format!("objective.terms[{j}].metric"))
        .collect();
    for (i, s) in cfg.suites.iter().enumerate() {
        let Some(l) = &s.limits else { continue };
        let duct = crate::model::check::LimitMetric::PeakDuctility;
        fields.extend(
            l.criteria
                .iter()
                .enumerate()
                .filter(|(_, c)| c.metric == duct)
                .map(|(j, _)| format!("suites[{i}].limits.criteria[{j}].metric")),
        );
        fields.extend(
            l.unacceptable
                .record_limits
                .iter()
                .enumerate()
                .filter(|(_, c)| c.metric == duct)
                .map(|(j, _)| format!("suites[{i}].limits.unacceptable.record_limits[{j}].metric")),
        );
    }
    match fields.first() {
        None => Ok(()),
        Some(field) => Err(OptError::invalid(
            path,
            field.clone(),
            "peak_ductility needs a frame whose storeys yield (storey_yield in the building); this building is elastic: give the storeys' yield, or limit another response",
        )),
    }
}

impl Study {
    /// Validates and resolves a config: building, space, constraints, then records; the
    /// sweep method is left for [`crate::eval::probe`] to choose (every public constructor,
    /// [`Study::from_config`] among them, goes through it).
    pub(crate) fn described(mut cfg: StudyConfig, path: &Path) -> Result<Study, OptError> {
        cfg.validate(path)?;
        let base = path.parent().unwrap_or(Path::new("."));
        // what `Building::load` does, keeping the file as written
        let (building_config, file) = match &cfg.building {
            BuildingRef::Path(p) => {
                let file = base.join(p);
                (read_building(&file)?, file)
            }
            BuildingRef::Inline(b) => ((**b).clone(), path.to_path_buf()),
        };
        let mut building = Building::from_config(&building_config, &file)?;
        let Some(heights) = building.storey_heights.clone() else {
            return Err(OptError::invalid(
                path,
                "building",
                "the building needs storey_heights: drift ratios are the responses every study reports",
            ));
        };
        if let Some(r) = cfg.collapse_drift_ratio {
            if !(r.is_finite() && r > 0.0) {
                return Err(OptError::invalid(
                    path,
                    "collapse_drift_ratio",
                    format!("must be positive and finite, got {r}"),
                ));
            }
            building.collapse_drift = Some(heights.iter().map(|h| r * h).collect());
        }
        let space = DesignSpace::new(&cfg.space, &cfg.constraints, &building, path)?;
        let objectives = cfg.objectives.clone().unwrap_or_default();
        if !objectives.is_empty() {
            let yielding = building.storey_yield.iter().any(Option::is_some);
            crate::model::objectives::validate(&objectives, Some(yielding), path)?;
        }
        refuse_ductility_on_elastic(&cfg, &building, path)?;
        let objective = Objective {
            terms: cfg.objective.terms.clone(),
            cost: cfg.objective.cost,
        };
        let (records, orientations, suites) =
            crate::model::suites::load_suites(&cfg, &building, base, path)?;
        // every simulation a design costs: a record, or each of its orientations
        let simulated: Vec<Arc<Record>> = records
            .iter()
            .zip(&orientations)
            .flat_map(|(r, o)| {
                if o.is_empty() {
                    std::slice::from_ref(r)
                } else {
                    &o[..]
                }
            })
            .cloned()
            .collect();
        check_work(&cfg, path, &building, &space, &simulated)?;
        let name = cfg.name.clone().unwrap_or_else(|| {
            path.file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "study".into())
        });
        // each suite's count of unacceptable responses, as given or as its risk category
        // allows for its number of ground motions (pairs count once)
        let mut limits: Vec<_> = cfg.suites.iter().map(|s| s.limits.clone()).collect();
        for (i, (lim, suite)) in limits.iter_mut().zip(&suites).enumerate() {
            let Some(lim) = lim else {
                continue;
            };
            let motions = suite.motions();
            lim.unacceptable
                .resolve(cfg.risk_category, motions)
                .map_err(|allowed| {
                    OptError::invalid(
                        path,
                        format!("suites[{i}].limits.unacceptable.max_count"),
                        format!(
                            "{} unacceptable responses exceed what Risk Category {} allows a suite of {motions} ground motions: {allowed} (ASCE 7-16 §16.4.1.1); lower the count or leave it out",
                            lim.unacceptable.max_count.unwrap_or(1),
                            cfg.risk_category.map_or("", |r| r.as_str())
                        ),
                    )
                })?;
        }
        let checks = Checks::of(cfg.property_bounds.clone(), limits).with_stroke_capacity(
            cfg.devices
                .as_ref()
                .and_then(|d| d.stroke_capacity_mm)
                .map(|mm| mm * 1e-3),
        );
        if let Some(w) = &cfg.wind {
            check_wind(w, &building, &space, &checks, path)?;
        }
        if let Some(c) = &cfg.nonstructural {
            crate::model::checks_config::validate_nonstructural(c, building.floors(), path)?;
        }
        if let Some(d) = &cfg.devices {
            check_braces(d, &space, &checks, path)?;
        }
        // a study that names sqp must be one it can differentiate; `auto` becomes the
        // refiner the study can use (the one written to the manifest)
        let differentiable = match check_sqp(&cfg, &objective, &checks, path) {
            Err(e) if cfg.refine.method == crate::model::config::RefineMethod::Sqp => {
                return Err(e);
            }
            r => r.is_ok(),
        };
        cfg.refine.method = cfg.refine.method.resolve(differentiable);
        let cfg_check_method = cfg.fidelity.check_method;
        let study = Study {
            name,
            path: path.to_path_buf(),
            config: cfg,
            building,
            building_config,
            records,
            orientations,
            suites,
            space,
            objective,
            objectives,
            checks,
            sweep_method: SweepMethod {
                method: MethodName::Newmark,
                reason: String::new(),
            },
            check_method: SweepMethod {
                method: cfg_check_method,
                reason: String::new(),
            },
            memory: crate::model::memory::MemoryEstimate {
                threads: 1,
                sweep_run_bytes: 0,
                check_run_bytes: 0,
                records_bytes: 0,
            },
        };
        Ok(study)
    }

    /// The runs of every design: the property cases × the records, nominal first (the
    /// records alone for a study without property bounds).
    pub fn runs(&self) -> usize {
        self.checks.cases().len() * self.records.len()
    }

    /// The property case and the record of run `i`.
    pub fn run(&self, i: usize) -> (PropertyCase, usize) {
        let n = self.records.len();
        (self.checks.cases()[i / n], i % n)
    }

    /// The seconds of rest after record `r` (its suite's `free_vibration_s`; 0: none).
    pub fn rest_after(&self, r: usize) -> f64 {
        self.suites
            .iter()
            .find(|s| s.range.contains(&r))
            .map_or(0.0, |s| s.free_vibration_s)
    }

    /// The name of run `i`: the record's, with the case after it (`NAME [lower]`) for a
    /// bound case.
    pub fn run_name(&self, i: usize) -> String {
        let (case, r) = self.run(i);
        let name = self.records[r].name();
        if case.is_nominal() {
            name.to_string()
        } else {
            format!("{name} [{}]", case.name.as_str())
        }
    }

    /// The names of every run, in order.
    pub fn run_names(&self) -> Vec<String> {
        (0..self.runs()).map(|i| self.run_name(i)).collect()
    }

    /// The objective of one design (slip loads `loads_n`, N, per damper of the space)
    /// from its runs (`rows`, [`Study::runs`] long) and the bare frame's: at the case the
    /// study's objective reads (with a cost objective, the design's cost; +∞ when it
    /// collapses).
    pub fn objective_value(
        &self,
        rows: &[RecordMetrics],
        bare: &[RecordMetrics],
        loads_n: &[f64],
    ) -> Result<f64, OptError> {
        let ranges: Vec<Range<usize>> = self.suites.iter().map(|s| s.range.clone()).collect();
        self.checks.objective(
            &self.objective,
            rows,
            Some(bare),
            &ranges,
            self.records.len(),
            loads_n,
        )
    }

    /// The objective of each property case the objective reads, with the design's cost
    /// ([`Checks::case_objectives`]; [`Study::objective_value`] is their largest).
    pub fn case_objectives(
        &self,
        rows: &[RecordMetrics],
        bare: &[RecordMetrics],
        loads_n: &[f64],
    ) -> Result<Vec<f64>, OptError> {
        let ranges: Vec<Range<usize>> = self.suites.iter().map(|s| s.range.clone()).collect();
        self.checks.case_objectives(
            &self.objective,
            rows,
            Some(bare),
            &ranges,
            self.records.len(),
            loads_n,
        )
    }

    /// Whether `method` can refine this study: the `sqp` refiner needs an objective and
    /// limits it can differentiate and a sweep run by a method with sensitivities (a
    /// refiner named on the command line is held to what the study file's would be).
    pub fn check_refiner(
        &self,
        method: crate::model::config::RefineMethod,
    ) -> Result<crate::model::config::RefineMethod, OptError> {
        use crate::model::config::RefineMethod;
        if method == RefineMethod::Auto {
            // the study resolved its own `auto` when it loaded; `--refine auto` asks the
            // same of this study
            let sqp = self.check_refiner(RefineMethod::Sqp).is_ok();
            return Ok(method.resolve(sqp));
        }
        if method != RefineMethod::Sqp {
            return Ok(method);
        }
        check_sqp(&self.config, &self.objective, &self.checks, &self.path)?;
        let m = self.sweep_method.method;
        if matches!(m, MethodName::Exact | MethodName::Delacruz) {
            return Err(OptError::invalid(
                &self.path,
                "fidelity.method",
                format!(
                    "the sweep runs {} ({}), which computes no sensitivities; the sqp refiner needs newmark, hht or bilinear: name one in fidelity.method",
                    m.as_str(),
                    self.sweep_method.reason
                ),
            ));
        }
        Ok(method)
    }

    /// The check of one design's runs against every limit at every property case.
    pub fn check_design(&self, rows: &[RecordMetrics]) -> Result<DesignCheck, OptError> {
        let suites: Vec<(&str, Range<usize>)> = self
            .suites
            .iter()
            .map(|s| (s.name.as_str(), s.range.clone()))
            .collect();
        self.checks.check(rows, &suites, self.records.len())
    }

    /// This study at its nominal properties only (no bound cases; the limits kept): its
    /// runs are the first [`Study::records`] runs of this study's, under the same names,
    /// so that journalled nominal runs are shared.
    pub fn nominal(&self) -> Study {
        let mut s = self.clone();
        s.checks.property_bounds = None;
        s
    }

    /// The cases' names, in run order.
    pub fn case_names(&self) -> Vec<CaseName> {
        self.checks.cases().iter().map(|c| c.name).collect()
    }

    /// Whether any objective term needs the energies.
    pub fn needs_energies(&self) -> bool {
        self.objectives.iter().any(|o| o.needs_energies())
            || self.objective.terms.iter().any(|t| {
                matches!(
                    t.metric,
                    Metric::EnergyRatio
                        | Metric::Rpi
                        | Metric::HystereticEnergy
                        | Metric::FrictionShare
                )
            })
    }

    /// The building file's friction law per dissipator of the space, when some
    /// dissipator's is not a symmetric slip load (`locked`, or bounds with F⁻ ≠ −F⁺):
    /// the file's design as written, which every run of "the file's design" carries
    /// ([`crate::model::sampler::Design::friction_n`]). `None` when [`Study::file_slip_loads`]
    /// says it all.
    pub fn file_friction(&self) -> Option<Vec<crate::model::sampler::FrictionLaw>> {
        use crate::model::sampler::FrictionLaw;
        let laws: Vec<(FrictionLaw, bool)> = self
            .space
            .dampers
            .iter()
            .map(|&f| match self.building.dissipators[f] {
                Some(d) if d.is_locked() => (FrictionLaw::Locked, false),
                Some(d) => (
                    FrictionLaw::Bounds([d.lower, d.upper]),
                    d.upper.is_finite() && d.lower == -d.upper,
                ),
                None => (FrictionLaw::Bounds([0.0, 0.0]), true),
            })
            .collect();
        (!laws.iter().all(|&(_, symmetric)| symmetric))
            .then(|| laws.into_iter().map(|(l, _)| l).collect())
    }

    /// Slip loads of the building file per dissipator, N (the "paper" design): the upper
    /// bound F⁺ (0 for a locked contact, which [`Study::file_friction`] carries).
    pub fn file_slip_loads(&self) -> Vec<f64> {
        self.space
            .dampers
            .iter()
            .map(|&f| {
                self.building.dissipators[f]
                    .map(|d| if d.upper.is_finite() { d.upper } else { 0.0 })
                    .unwrap_or(0.0)
            })
            .collect()
    }
}
