//! Studies: which building, which ground-motion suites, which design space, which
//! objective, and how to sweep and refine — read from JSON, validated in full before any
//! simulation runs (unknown fields, empty suites, reversed bounds, infeasible constraints
//! are errors that name the field).
//!
//! Paths (building, records) are relative to the study file. Record patterns may use `*`
//! in the file name (not in folder names); matches are sorted by name.

use crate::error::OptError;
use crate::fidelity::SweepMethod;
use crate::objective::{Metric, Objective, Term};
use crate::space::{ConstraintsConfig, DesignSpace, SpaceConfig};
use serde::{Deserialize, Serialize};
use slipload_motion::{G, Record, SuiteTarget, Synthetic, Units};
use slipload_sim::Building;
use slipload_sim::scene::{BuildingRef, MethodName};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A study file, as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyConfig {
    /// Short name (default: the file stem).
    #[serde(default)]
    pub name: Option<String>,
    /// Free text.
    #[serde(default)]
    pub description: Option<String>,
    /// The building: a path relative to the study file, or inline.
    pub building: BuildingRef,
    /// One or more ground-motion suites.
    pub suites: Vec<SuiteConfig>,
    /// The design space.
    pub space: SpaceConfig,
    /// Optional linear constraints on the slip loads.
    #[serde(default)]
    pub constraints: ConstraintsConfig,
    /// What to minimise.
    pub objective: ObjectiveConfig,
    /// Methods and time steps.
    #[serde(default)]
    pub fidelity: FidelityConfig,
    /// The sweep's sample of designs.
    #[serde(default)]
    pub sweep: SweepConfig,
    /// The refinement after the sweep.
    #[serde(default)]
    pub refine: RefineConfig,
    /// The storey drift ratio past which a run counts as a collapse (the design fails that
    /// record), overriding the building's `collapse_drift_ratio` for this study.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collapse_drift_ratio: Option<f64>,
    /// Two to four objectives whose trade-off (Pareto front) the study searches besides
    /// its `objective` ([`crate::pareto`]); absent: a one-objective study, as before.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub objectives: Option<Vec<crate::pareto::ParetoObjective>>,
    /// Settings of the front's search (only with `objectives`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pareto: Option<crate::pareto::ParetoConfig>,
}

/// One suite of records.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SuiteConfig {
    /// Name used in tables.
    pub name: String,
    /// Record files or `*` patterns, relative to the study file.
    #[serde(default)]
    pub records: Vec<String>,
    /// Units of the record values ("g", "m/s2", "cm/s2"); default: by format (AT2 = g).
    #[serde(default)]
    pub units: Option<String>,
    /// Sample interval (s) of one-column text records.
    #[serde(default)]
    pub dt_s: Option<f64>,
    /// How each record is scaled (default: as recorded).
    #[serde(default)]
    pub scale: Option<ScaleConfig>,
    /// The embedded synthetic suite instead of files.
    #[serde(default)]
    pub synthetic: Option<SyntheticSuiteConfig>,
}

/// Scaling of every record of a suite.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ScaleConfig {
    /// Multiply by this factor.
    Factor(f64),
    /// Scale to this peak ground acceleration, g.
    PgaG(f64),
    /// Scale to this 5 %-damped pseudo-spectral acceleration at the bare frame's T₁, g.
    SaT1G(f64),
}

/// The embedded synthetic suite (Clough–Penzien, firm soil; slipload_motion).
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SyntheticSuiteConfig {
    /// Number of records (default 10).
    #[serde(default = "default_count")]
    pub count: usize,
    /// Seed (default 2007, the embedded default suite).
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// PGA of every record, g (default 0.4).
    #[serde(default = "default_pga")]
    pub pga_g: f64,
    /// Duration of every record, s (default 20).
    #[serde(default = "default_duration")]
    pub duration_s: f64,
}

fn default_count() -> usize {
    slipload_motion::DEFAULT_SUITE_SIZE
}
fn default_seed() -> u64 {
    slipload_motion::DEFAULT_SUITE_SEED
}
fn default_pga() -> f64 {
    slipload_motion::DEFAULT_SUITE_PGA_G
}
fn default_duration() -> f64 {
    20.0
}

/// The objective: a weighted sum of suite statistics of response metrics.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectiveConfig {
    /// The terms (at least one).
    pub terms: Vec<Term>,
}

/// Methods and time steps.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FidelityConfig {
    /// Method of the sweep and refinement. Absent: chosen for the study's building,
    /// `exact` where a probe run costs it at most [`crate::fidelity::EXACT_SWEEP_COST`]
    /// times `newmark`'s work, else `newmark` ([`crate::fidelity::choose_sweep_method`]).
    #[serde(default)]
    pub method: Option<MethodName>,
    /// Time step, s (default: the simulation's, T₁/400 rounded to divide the record's dt).
    #[serde(default)]
    pub dt_s: Option<f64>,
    /// Method of the final check (default `exact`, the event-driven reference).
    #[serde(default = "default_check_method")]
    pub check_method: MethodName,
    /// Time step of the final check as a fraction of the sweep's (default 0.25).
    #[serde(default = "default_check_factor")]
    pub check_dt_factor: f64,
}

fn default_check_method() -> MethodName {
    MethodName::Exact
}

fn default_check_factor() -> f64 {
    0.25
}

impl Default for FidelityConfig {
    fn default() -> Self {
        FidelityConfig {
            method: None,
            dt_s: None,
            check_method: default_check_method(),
            check_dt_factor: default_check_factor(),
        }
    }
}

/// Samplers of the sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SamplerKind {
    /// Full factorial grid with `levels` levels per variable.
    Grid,
    /// Latin hypercube of `points` points (seeded).
    Lhs,
    /// Halton sequence (bases 2, 3, 5, …) with a seeded random shift (Cranley–Patterson).
    Halton,
}

/// The sweep's sample.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepConfig {
    /// Sampler (default lhs).
    #[serde(default = "default_sampler")]
    pub sampler: SamplerKind,
    /// Points of lhs/halton (default 32).
    #[serde(default = "default_points")]
    pub points: usize,
    /// Levels per variable of the grid (default 5).
    #[serde(default = "default_levels")]
    pub levels: usize,
    /// Seed (default 1).
    #[serde(default = "default_sweep_seed")]
    pub seed: u64,
}

fn default_sampler() -> SamplerKind {
    SamplerKind::Lhs
}
fn default_points() -> usize {
    32
}
fn default_levels() -> usize {
    5
}
fn default_sweep_seed() -> u64 {
    1
}

impl Default for SweepConfig {
    fn default() -> Self {
        SweepConfig {
            sampler: default_sampler(),
            points: default_points(),
            levels: default_levels(),
            seed: default_sweep_seed(),
        }
    }
}

/// Refiners.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RefineMethod {
    /// Trust region on a fitted quadratic model, subproblem solved by clarabel.
    TrustRegion,
    /// Nelder–Mead simplex.
    NelderMead,
    /// Adaptive random search.
    Random,
}

impl std::str::FromStr for RefineMethod {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "trust-region" => Ok(RefineMethod::TrustRegion),
            "nelder-mead" => Ok(RefineMethod::NelderMead),
            "random" => Ok(RefineMethod::Random),
            o => Err(format!(
                "unknown refiner {o:?}: expected trust-region, nelder-mead or random"
            )),
        }
    }
}

impl RefineMethod {
    /// The name as written.
    pub fn as_str(self) -> &'static str {
        match self {
            RefineMethod::TrustRegion => "trust-region",
            RefineMethod::NelderMead => "nelder-mead",
            RefineMethod::Random => "random",
        }
    }
}

/// Refinement settings.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RefineConfig {
    /// Refiner (default trust-region).
    #[serde(default = "default_refiner")]
    pub method: RefineMethod,
    /// Refine from this many of the best sweep points (default 2).
    #[serde(default = "default_starts")]
    pub starts: usize,
    /// Most design evaluations per start (default 40).
    #[serde(default = "default_max_evals")]
    pub max_evaluations: usize,
    /// Stop when the step (trust radius, simplex size) falls below this, in variables
    /// scaled to [0, 1] (default 2e-3).
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// Initial trust radius / simplex size, scaled (default 0.15).
    #[serde(default = "default_radius")]
    pub initial_radius: f64,
    /// Designs verified at reference accuracy (default 3).
    #[serde(default = "default_finalists")]
    pub finalists: usize,
    /// Seed of the random refiner (default 1).
    #[serde(default = "default_sweep_seed")]
    pub seed: u64,
}

fn default_refiner() -> RefineMethod {
    RefineMethod::TrustRegion
}
fn default_starts() -> usize {
    2
}
fn default_max_evals() -> usize {
    40
}
fn default_tolerance() -> f64 {
    2e-3
}
fn default_radius() -> f64 {
    0.15
}
fn default_finalists() -> usize {
    3
}

impl Default for RefineConfig {
    fn default() -> Self {
        RefineConfig {
            method: default_refiner(),
            starts: default_starts(),
            max_evaluations: default_max_evals(),
            tolerance: default_tolerance(),
            initial_radius: default_radius(),
            finalists: default_finalists(),
            seed: default_sweep_seed(),
        }
    }
}

/// A suite, resolved: its name and the range of its records in [`Study::records`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SuiteInfo {
    /// Name.
    pub name: String,
    /// Indices into the study's records.
    pub range: Range<usize>,
}

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
    /// All records of all suites, suite after suite.
    pub records: Vec<Arc<Record>>,
    /// The suites.
    pub suites: Vec<SuiteInfo>,
    /// The design space.
    pub space: DesignSpace,
    /// The objective.
    pub objective: Objective,
    /// The sweep's method, and why ([`crate::fidelity::choose_sweep_method`]).
    pub sweep_method: SweepMethod,
    /// The objectives of the front (empty: a one-objective study).
    pub objectives: Vec<crate::pareto::ParetoObjective>,
}

fn read_text(path: &Path) -> Result<String, OptError> {
    Ok(slipload_motion::limits::read_input_text(
        path,
        "study",
        slipload_motion::limits::MAX_CONFIG_BYTES,
    )?)
}

/// `*` matching of one file name (no other wildcards).
fn wildcard(pattern: &str, name: &str) -> bool {
    let parts: Vec<&str> = pattern.split('*').collect();
    if parts.len() == 1 {
        return pattern == name;
    }
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !name.starts_with(first) || name.len() < first.len() + last.len() || !name.ends_with(last) {
        return false;
    }
    let mut rest = &name[first.len()..name.len() - last.len()];
    for mid in &parts[1..parts.len() - 1] {
        match rest.find(mid) {
            Some(i) => rest = &rest[i + mid.len()..],
            None => return false,
        }
    }
    true
}

/// Files of one record entry: the file itself, or the sorted matches of a `*` pattern.
fn expand(base: &Path, entry: &str, path: &Path, field: &str) -> Result<Vec<PathBuf>, OptError> {
    let full = base.join(entry);
    let name = full
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    if !name.contains('*') {
        if !full.is_file() {
            let what = if full.is_dir() {
                "is a folder, not a record file (name the files, or a pattern such as folder/*.AT2)"
            } else if full.exists() {
                "is not a regular file"
            } else {
                "does not exist"
            };
            return Err(OptError::invalid(
                path,
                field,
                format!("record file {} {what}", full.display()),
            ));
        }
        return Ok(vec![full]);
    }
    let dir = full.parent().unwrap_or(Path::new("."));
    if dir.to_string_lossy().contains('*') {
        return Err(OptError::invalid(
            path,
            field,
            "`*` is allowed in the file name only, not in folder names",
        ));
    }
    let listing = std::fs::read_dir(dir).map_err(|source| OptError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut found: Vec<PathBuf> = listing
        .filter_map(|e| e.ok())
        .filter(|e| e.path().is_file() && wildcard(&name, &e.file_name().to_string_lossy()))
        .map(|e| e.path())
        .collect();
    found.sort();
    if found.is_empty() {
        return Err(OptError::invalid(
            path,
            field,
            format!("pattern {} matches no file", full.display()),
        ));
    }
    Ok(found)
}

fn finite_positive(path: &Path, field: &str, v: f64) -> Result<(), OptError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(OptError::invalid(
            path,
            field,
            format!("must be finite and > 0, got {v}"),
        ))
    }
}

/// The smallest peak ground acceleration a study's suites may ask for, g: about the
/// threshold of perceptible shaking. Below it no dissipator of a real frame slips, every
/// design answers as the bare frame and an optimum would be rounding noise (at 1e-300 g
/// the responses are subnormal numbers).
/// The same floor as a scene's target PGA ([`slipload_sim::scene::TARGET_PGA_BAND_G`]).
pub const MIN_STUDY_PGA_G: f64 = slipload_sim::scene::TARGET_PGA_BAND_G.0;

/// A suite's target intensity (g) within [[`MIN_STUDY_PGA_G`], `MAX_ABS_ACCEL_G`].
fn intensity_g(path: &Path, field: &str, v: f64) -> Result<(), OptError> {
    finite_positive(path, field, v)?;
    let max = slipload_motion::MAX_ABS_ACCEL_G;
    if !(MIN_STUDY_PGA_G..=max).contains(&v) {
        return Err(OptError::invalid(
            path,
            field,
            format!(
                "{v:e} g is outside {MIN_STUDY_PGA_G} … {max} g: below it no dissipator slips and every design is the bare frame, beyond it no ground has shaken (wrong units?)"
            ),
        ));
    }
    Ok(())
}

/// Most designs of a sweep (grid levels^variables, or points), bare and file included.
pub const MAX_DESIGNS: f64 = 1e6;
/// Most (design, record) tasks of a sweep (each keeps a row of responses in memory).
pub const MAX_TASKS: f64 = 5e6;
/// Most refine starts (and finalists) of a study: real studies use a handful.
pub const MAX_REFINE_STARTS: usize = 1000;
/// Most design evaluations per refine start: real studies use tens to hundreds.
pub const MAX_REFINE_EVALUATIONS: usize = 100_000;
/// Most integration steps of a whole sweep (about half a day of one core on a small
/// building).
pub const MAX_SWEEP_STEPS: f64 = 1e12;

fn too_large(what: String, estimate: f64, limit: f64, unit: &str) -> Result<(), OptError> {
    if estimate <= limit || slipload_sim::limits::allow_large() {
        return Ok(());
    }
    let c = slipload_sim::limits::count;
    Err(OptError::TooLarge {
        what,
        estimate: format!("{} {unit}", c(estimate)),
        limit: format!("{} {unit}", c(limit)),
    })
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
    let tasks = designs * records.len() as f64;
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
    for r in records {
        let duration = r.duration();
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
        steps * designs,
        MAX_SWEEP_STEPS,
        "integration steps",
    )
}

/// Longest suite or design name, characters: a label of tables, not a text.
pub const MAX_LABEL_CHARS: usize = 200;

/// The benchmark study (`configs/study-benchmark.json`), embedded so that every front
/// runs the main job with no files; its building is the embedded benchmark building.
pub const BENCHMARK_STUDY: &str = include_str!("../../../configs/study-benchmark.json");

/// How errors name the embedded benchmark study.
pub const BENCHMARK_STUDY_ORIGIN: &str = "configs/study-benchmark.json (embedded)";

/// What is wrong with a suite or design name, if anything. Names label rows of the CSV
/// and Markdown tables, which write them as they are: an empty name prints as nothing,
/// and a comma, double quote, `|` or control character (a newline) would split or shift
/// the row it labels.
pub fn label_problem(name: &str) -> Option<String> {
    if name.trim().is_empty() {
        return Some("is empty: give it a name".into());
    }
    let n = name.chars().count();
    if n > MAX_LABEL_CHARS {
        return Some(format!("has {n} characters, more than {MAX_LABEL_CHARS}"));
    }
    if let Some(c) = name
        .chars()
        .find(|c| c.is_control() || matches!(c, ',' | '"' | '|'))
    {
        return Some(format!(
            "holds {c:?}: a name may not hold a comma, double quote, `|` or control character"
        ));
    }
    None
}

/// A study whose JSON is well formed but not shaped as a study, said in the file's own
/// terms (serde would name Rust types, or stop at `}` with "expected value").
fn shape_error(text: &str, path: &Path) -> Option<OptError> {
    let v: serde_json::Value = serde_json::from_str(text).ok()?;
    let kind = |v: &serde_json::Value| match v {
        serde_json::Value::Null => "null",
        serde_json::Value::Bool(_) => "a boolean",
        serde_json::Value::Number(_) => "a number",
        serde_json::Value::String(_) => "a string",
        serde_json::Value::Array(_) => "an array",
        serde_json::Value::Object(_) => "an object",
    };
    let Some(obj) = v.as_object() else {
        return Some(OptError::invalid(
            path,
            "(top level)",
            format!(
                "a study is a JSON object {{\"building\", \"suites\", \"space\", \"objective\", …}}, got {}",
                kind(&v)
            ),
        ));
    };
    for (field, expected) in [
        ("space", "an object with one key, \"free\" or \"profile\""),
        ("objective", "an object {\"terms\": [...]}"),
        ("sweep", "an object {\"sampler\", \"points\", \"seed\"}"),
        ("refine", "an object"),
        ("fidelity", "an object"),
        ("constraints", "an object"),
    ] {
        let Some(x) = obj.get(field) else { continue };
        let bad = match x.as_object() {
            None => true,
            Some(o) => field == "space" && o.len() != 1,
        };
        if bad {
            let got = match x.as_object() {
                Some(o) if o.is_empty() => "an empty object".to_string(),
                Some(o) => format!(
                    "an object with the keys {}",
                    o.keys()
                        .map(|k| format!("{k:?}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                None => kind(x).to_string(),
            };
            return Some(OptError::invalid(
                path,
                field,
                format!("expected {expected}, got {got}"),
            ));
        }
    }
    None
}

impl StudyConfig {
    /// Parses a study from JSON text; `path` names it in errors.
    pub fn from_json(text: &str, path: &Path) -> Result<StudyConfig, OptError> {
        serde_json::from_str(text).map_err(|source| {
            // A building or scene given as a study: say so, and what to run.
            match slipload_sim::kind::wrong_kind(text, path, slipload_sim::kind::Expected::Study) {
                Some(e) => OptError::from(e),
                None => shape_error(text, path).unwrap_or(OptError::Json {
                    path: path.to_path_buf(),
                    source,
                }),
            }
        })
    }

    /// Checks what can be checked without files: counts, ranges, settings.
    pub fn validate(&self, path: &Path) -> Result<(), OptError> {
        // The name heads the summaries, tables and report: blank or holding a newline it
        // prints as nothing or splits their lines (leave it out to take the file's stem).
        if let Some(name) = &self.name
            && (name.trim().is_empty() || name.chars().any(char::is_control))
        {
            return Err(OptError::invalid(
                path,
                "name",
                format!(
                    "{name:?} is blank or holds a control character: give a name on one line, or leave it out to take the file's name"
                ),
            ));
        }
        if self.suites.is_empty() {
            return Err(OptError::invalid(
                path,
                "suites",
                "must name at least one suite",
            ));
        }
        for (i, s) in self.suites.iter().enumerate() {
            let f = |x: &str| format!("suites[{i}].{x}");
            // Results, statistics and tables are keyed by suite name: an empty name
            // prints as nothing and two suites of one name would be pooled as one.
            if let Some(problem) = label_problem(&s.name) {
                return Err(OptError::invalid(
                    path,
                    f("name"),
                    format!(
                        "{:?} {problem} (a suite name labels rows of the CSV and Markdown tables)",
                        s.name
                    ),
                ));
            }
            if let Some(j) = self.suites[..i].iter().position(|o| o.name == s.name) {
                return Err(OptError::invalid(
                    path,
                    f("name"),
                    format!(
                        "{:?} is already the name of suites[{j}]: suite names must be distinct \
                         (results are grouped by suite name)",
                        s.name
                    ),
                ));
            }
            match (&s.synthetic, s.records.is_empty()) {
                (Some(_), false) => {
                    return Err(OptError::invalid(
                        path,
                        f("synthetic"),
                        "give either records or synthetic, not both",
                    ));
                }
                (None, true) => {
                    return Err(OptError::invalid(
                        path,
                        f("records"),
                        "the suite is empty: name record files (or patterns) or a synthetic suite",
                    ));
                }
                (Some(syn), true) => {
                    if syn.count == 0 {
                        return Err(OptError::invalid(
                            path,
                            f("synthetic.count"),
                            "the suite is empty: count must be at least 1",
                        ));
                    }
                    intensity_g(path, &f("synthetic.pga_g"), syn.pga_g)?;
                    finite_positive(path, &f("synthetic.duration_s"), syn.duration_s)?;
                    if s.scale.is_some() || s.units.is_some() || s.dt_s.is_some() {
                        return Err(OptError::invalid(
                            path,
                            f("synthetic"),
                            "a synthetic suite takes no units, dt_s or scale (give pga_g)",
                        ));
                    }
                }
                (None, false) => {}
            }
            if let Some(u) = &s.units {
                u.parse::<Units>()
                    .map_err(|e| OptError::invalid(path, f("units"), e.to_string()))?;
            }
            if let Some(dt) = s.dt_s {
                finite_positive(path, &f("dt_s"), dt)?;
            }
            match s.scale {
                Some(ScaleConfig::Factor(v)) => finite_positive(path, &f("scale.factor"), v)?,
                Some(ScaleConfig::PgaG(v)) => intensity_g(path, &f("scale.pga_g"), v)?,
                Some(ScaleConfig::SaT1G(v)) => intensity_g(path, &f("scale.sa_t1_g"), v)?,
                None => {}
            }
        }
        if self.objective.terms.is_empty() {
            return Err(OptError::invalid(
                path,
                "objective.terms",
                "must have at least one term",
            ));
        }
        for (i, t) in self.objective.terms.iter().enumerate() {
            if !(t.weight.is_finite() && t.weight > 0.0) {
                return Err(OptError::invalid(
                    path,
                    format!("objective.terms[{i}].weight"),
                    format!("must be finite and > 0, got {}", t.weight),
                ));
            }
        }
        if let Some(dt) = self.fidelity.dt_s {
            finite_positive(path, "fidelity.dt_s", dt)?;
        }
        let cf = self.fidelity.check_dt_factor;
        if !(cf.is_finite() && cf > 0.0 && cf <= 1.0) {
            return Err(OptError::invalid(
                path,
                "fidelity.check_dt_factor",
                format!("must be in (0, 1], got {cf}"),
            ));
        }
        let sw = &self.sweep;
        match sw.sampler {
            SamplerKind::Grid if sw.levels < 2 => {
                return Err(OptError::invalid(
                    path,
                    "sweep.levels",
                    format!("a grid needs at least 2 levels, got {}", sw.levels),
                ));
            }
            SamplerKind::Lhs | SamplerKind::Halton if sw.points == 0 => {
                return Err(OptError::invalid(
                    path,
                    "sweep.points",
                    "must be at least 1",
                ));
            }
            _ => {}
        }
        let r = &self.refine;
        if r.starts == 0 {
            return Err(OptError::invalid(
                path,
                "refine.starts",
                "must be at least 1",
            ));
        }
        if r.finalists == 0 {
            return Err(OptError::invalid(
                path,
                "refine.finalists",
                "must be at least 1",
            ));
        }
        if !(r.tolerance.is_finite() && r.tolerance > 0.0 && r.tolerance < 1.0) {
            return Err(OptError::invalid(
                path,
                "refine.tolerance",
                format!("must be in (0, 1), got {}", r.tolerance),
            ));
        }
        if !(r.initial_radius.is_finite()
            && r.initial_radius > r.tolerance
            && r.initial_radius <= 1.0)
        {
            return Err(OptError::invalid(
                path,
                "refine.initial_radius",
                format!(
                    "must be in (tolerance, 1], got {} (tolerance {})",
                    r.initial_radius, r.tolerance
                ),
            ));
        }
        match (&self.objectives, &self.pareto) {
            (Some(list), pareto) => {
                crate::pareto::objectives::validate(list, None, path)?;
                if let Some(p) = pareto {
                    p.validate(path)?;
                }
            }
            (None, Some(_)) => {
                return Err(OptError::invalid(
                    path,
                    "pareto",
                    "sets the search of a front, but the study names no `objectives` (give 2 to 4, or leave `pareto` out)",
                ));
            }
            (None, None) => {}
        }
        self.check_counts(path)
    }

    /// Every count the study gives against the limits no real study comes near
    /// ([`MAX_REFINE_STARTS`], [`MAX_REFINE_EVALUATIONS`],
    /// [`slipload_motion::limits::MAX_SUITE_RECORDS`]), liftable with `--allow-large`.
    fn check_counts(&self, path: &Path) -> Result<(), OptError> {
        let p = path.display();
        let r = &self.refine;
        for (field, v, limit, unit) in [
            ("refine.starts", r.starts, MAX_REFINE_STARTS, "starts"),
            (
                "refine.finalists",
                r.finalists,
                MAX_REFINE_STARTS,
                "finalists",
            ),
            (
                "refine.max_evaluations",
                r.max_evaluations,
                MAX_REFINE_EVALUATIONS,
                "evaluations",
            ),
        ] {
            too_large(
                format!("{p}: field `{field}`"),
                v as f64,
                limit as f64,
                unit,
            )?;
        }
        for (i, s) in self.suites.iter().enumerate() {
            if let Some(syn) = &s.synthetic {
                too_large(
                    format!("{p}: field `suites[{i}].synthetic.count`"),
                    syn.count as f64,
                    slipload_motion::limits::MAX_SUITE_RECORDS as f64,
                    "records",
                )?;
            }
        }
        Ok(())
    }
}

impl Study {
    /// The embedded benchmark study (`configs/study-benchmark.json` with the embedded
    /// benchmark building inlined): what every front optimises when no study is named.
    pub fn benchmark() -> Result<Study, OptError> {
        let name = Path::new(BENCHMARK_STUDY_ORIGIN);
        let mut cfg = StudyConfig::from_json(BENCHMARK_STUDY, name)?;
        let b: slipload_sim::BuildingConfig =
            serde_json::from_str(slipload_sim::scene::BENCHMARK_BUILDING)
                .map_err(|e| OptError::Argument(format!("the embedded benchmark building: {e}")))?;
        cfg.building = slipload_sim::scene::BuildingRef::Inline(Box::new(b));
        Study::from_config(cfg, name)
    }

    /// Reads, validates and resolves a study file.
    pub fn load(path: &Path) -> Result<Study, OptError> {
        let text = read_text(path)?;
        Study::from_json(&text, path)
    }

    /// Parses, validates and resolves a study; `path` names it in errors and anchors
    /// relative paths.
    pub fn from_json(text: &str, path: &Path) -> Result<Study, OptError> {
        let cfg = StudyConfig::from_json(text, path)?;
        Study::from_config(cfg, path)
    }

    /// Validates and resolves a config: building, space, constraints, then records.
    pub fn from_config(cfg: StudyConfig, path: &Path) -> Result<Study, OptError> {
        cfg.validate(path)?;
        let base = path.parent().unwrap_or(Path::new("."));
        let mut building = match &cfg.building {
            BuildingRef::Path(p) => Building::load(&base.join(p))?,
            BuildingRef::Inline(b) => Building::from_config(b, path)?,
        };
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
            crate::pareto::objectives::validate(&objectives, Some(yielding), path)?;
        }
        let objective = Objective {
            terms: cfg.objective.terms.clone(),
        };
        let t1 = building.t1();
        let mut records = Vec::new();
        let mut suites = Vec::new();
        for (i, s) in cfg.suites.iter().enumerate() {
            let start = records.len();
            if let Some(syn) = &s.synthetic {
                let params = Synthetic {
                    duration_s: syn.duration_s,
                    ..Synthetic::default()
                };
                let rs = slipload_motion::synthetic_suite(
                    &params,
                    syn.count,
                    syn.seed,
                    SuiteTarget::Pga {
                        pga_m_s2: syn.pga_g * G,
                    },
                )?;
                records.extend(rs.into_iter().map(Arc::new));
            } else {
                let units = match &s.units {
                    Some(u) => Some(u.parse::<Units>().map_err(|e| {
                        OptError::invalid(path, format!("suites[{i}].units"), e.to_string())
                    })?),
                    None => None,
                };
                // one file twice in a suite would count its record twice in every statistic
                let mut seen: Vec<(PathBuf, usize)> = Vec::new();
                for (j, entry) in s.records.iter().enumerate() {
                    let field = format!("suites[{i}].records[{j}]");
                    for file in expand(base, entry, path, &field)? {
                        let key = std::fs::canonicalize(&file).unwrap_or_else(|_| file.clone());
                        if let Some((_, k)) = seen.iter().find(|(f, _)| *f == key) {
                            return Err(OptError::invalid(
                                path,
                                field,
                                format!(
                                    "{} is already in this suite (suites[{i}].records[{k}]): a record counts once in a suite's statistics; name it once",
                                    file.display()
                                ),
                            ));
                        }
                        seen.push((key, j));
                        let r = slipload_motion::read_record(&file, units, s.dt_s)?;
                        let r = match s.scale {
                            None => r,
                            Some(ScaleConfig::Factor(f)) => {
                                let r = r.try_scaled(f)?;
                                let pga_g = r.pga() / G;
                                if pga_g < MIN_STUDY_PGA_G {
                                    return Err(OptError::invalid(
                                        path,
                                        format!("suites[{i}].scale.factor"),
                                        format!(
                                            "scales {} to a PGA of {pga_g:.3e} g, below {MIN_STUDY_PGA_G} g: no dissipator slips and every design is the bare frame (give scale.pga_g, or check the factor)",
                                            file.display()
                                        ),
                                    ));
                                }
                                r
                            }
                            Some(ScaleConfig::PgaG(p)) => r.scaled_to_pga(p * G)?,
                            Some(ScaleConfig::SaT1G(sa)) => {
                                slipload_motion::scale_to_spectral_acceleration(
                                    std::slice::from_ref(&r),
                                    t1,
                                    0.05,
                                    sa * G,
                                )?
                                .records
                                .remove(0)
                            }
                        };
                        records.push(Arc::new(r));
                    }
                }
            }
            suites.push(SuiteInfo {
                name: s.name.clone(),
                range: start..records.len(),
            });
        }
        check_work(&cfg, path, &building, &space, &records)?;
        let name = cfg.name.clone().unwrap_or_else(|| {
            path.file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "study".into())
        });
        let mut study = Study {
            name,
            path: path.to_path_buf(),
            config: cfg,
            building,
            records,
            suites,
            space,
            objective,
            objectives,
            sweep_method: SweepMethod {
                method: MethodName::Newmark,
                reason: String::new(),
            },
        };
        study.sweep_method = crate::fidelity::choose_sweep_method(&study)?;
        Ok(study)
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
    /// ([`crate::sampler::Design::friction_n`]). `None` when [`Study::file_slip_loads`]
    /// says it all.
    pub fn file_friction(&self) -> Option<Vec<crate::sampler::FrictionLaw>> {
        use crate::sampler::FrictionLaw;
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

#[cfg(test)]
mod tests {
    use super::wildcard;

    #[test]
    fn wildcard_matches_like_a_shell() {
        assert!(wildcard("*.AT2", "RSN6.AT2"));
        assert!(wildcard("RSN*_*.AT2", "RSN6_IMPVALL.AT2"));
        assert!(!wildcard("RSN*.AT2", "ELC.AT2"));
        assert!(!wildcard("*.AT2", "x.at2"));
        assert!(wildcard("a*a", "aa"));
        assert!(!wildcard("a*a", "a"));
    }
}
