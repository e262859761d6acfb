//! The study file's configuration as written (the serde structs of a study: suites,
//! objective, fidelity, sweep, refine, and the front's settings by reference), parsed
//! strictly and checked in full before any file is read ([`StudyConfig::validate`]):
//! unknown fields, empty suites, reversed bounds and out-of-range settings are errors that
//! name the field. The limits on a study's size are here too.

use crate::base::error::OptError;
use crate::model::objective::Term;
use crate::model::space::{ConstraintsConfig, SpaceConfig};
use serde::{Deserialize, Serialize};
use slipload_motion::Units;
use slipload_sim::scene::{BuildingRef, MethodName};
use std::path::Path;

pub use super::code_spectrum::{
    CodeSpectrumConfig, En1998Config, Hazard, ScalingRule, TableConfig,
};
use super::code_spectrum::{finite_positive, intensity_g};
pub use super::refine_config::{RefineConfig, RefineMethod};

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
    /// its `objective` ([`crate::phases::pareto`]); absent: a one-objective study, as before.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub objectives: Option<Vec<crate::model::objectives::ParetoObjective>>,
    /// Settings of the front's search (only with `objectives`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pareto: Option<crate::model::objectives::ParetoConfig>,
    /// The dampers' lower- and upper-bound properties, each case analysed
    /// ([`crate::model::check`]); absent: nominal properties only, as before.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub property_bounds: Option<crate::model::check::PropertyBoundsConfig>,
    /// What the device table needs beyond the building ([`DevicesConfig`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub devices: Option<DevicesConfig>,
    /// The building's Risk Category (`"I"` to `"IV"`, ASCE 7-16 Table 1.5-1): each suite's
    /// count of unacceptable responses follows it where the suite gives none, and a count
    /// above what it allows is refused (§16.4.1.1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub risk_category: Option<crate::model::check::RiskCategory>,
    /// The check of the frame's strength without its dampers against a fraction of the
    /// equivalent-lateral-force demand of a frame without a damping system
    /// ([`FrameStrengthConfig`]; ASCE 7-16 §18.2.1.1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame_strength: Option<FrameStrengthConfig>,
    /// The design wind's storey shears: no damper may slip under them ([`WindConfig`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wind: Option<WindConfig>,
    /// The drift deformation-sensitive nonstructural components are designed for, and
    /// the flag on the storeys whose drift passes it ([`NonstructuralConfig`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nonstructural: Option<NonstructuralConfig>,
}

pub use crate::model::devices_config::{
    DevicesConfig, MAX_BRACES_PER_DAMPER, MAX_TEST_CYCLES, TestProtocolConfig,
};

pub use crate::model::checks_config::{FrameStrengthConfig, NonstructuralConfig, WindConfig};

/// One suite of records.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SuiteConfig {
    /// Name used in tables.
    pub name: String,
    /// Record files or `*` patterns, relative to the study file, or pairs of files: the two
    /// horizontal components of one event ([`RecordEntry`]).
    #[serde(default)]
    pub records: Vec<RecordEntry>,
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
    /// The suite's acceptance limits ([`crate::model::check::SuiteLimits`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limits: Option<crate::model::check::SuiteLimits>,
    /// Seconds of rest after each record of the suite: every run goes on with the ground
    /// at rest this long, so the residual drifts are read after the free vibration has
    /// died out instead of at the record's end (none: the run ends with the record).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub free_vibration_s: Option<f64>,
    /// How its pairs run ([`crate::model::orientation`]; none: each component a run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pairs: Option<crate::model::orientation::PairsConfig>,
}

/// Longest rest after a record (`suites[].free_vibration_s`), s.
pub const MAX_FREE_VIBRATION_S: f64 = 600.0;

/// One entry of a suite's `records`: a file or `*` pattern (single components), or
/// `[first, second]`, the two horizontal components of one event (no patterns), run as
/// the suite's `pairs` says and scaled to a code spectrum by their maximum-direction
/// spectrum (docs/MODEL.md § Ground motions in code form).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum RecordEntry {
    /// A file or a `*` pattern.
    File(String),
    /// The two horizontal components of one event.
    Pair([String; 2]),
}

impl From<&str> for RecordEntry {
    fn from(s: &str) -> RecordEntry {
        RecordEntry::File(s.to_string())
    }
}

/// Scaling of every record of a suite.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ScaleConfig {
    /// Multiply by this factor.
    Factor(f64),
    /// Scale to this peak ground acceleration, g.
    PgaG(f64),
    /// Scale to this 5 %-damped pseudo-spectral acceleration at the bare frame's T₁, g.
    SaT1G(f64),
    /// One factor for the whole suite, so that its mean 5 %-damped spectrum is at least
    /// 90 % of a code spectrum over [0.2 T, 2 T] (ASCE 7-16 §16.2.3).
    CodeSpectrum(CodeSpectrumConfig),
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

/// The objective: a weighted sum of suite statistics of response metrics, or the
/// dampers' cost subject to the study's limits.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectiveConfig {
    /// The terms (at least one, unless `cost` is given).
    #[serde(default)]
    pub terms: Vec<Term>,
    /// The dampers' cost ([`crate::model::objective::Cost`]): the objective becomes the
    /// least cost that meets the limits (the study must have some).
    #[serde(default)]
    pub cost: Option<crate::model::objective::Cost>,
}

/// Methods and time steps.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FidelityConfig {
    /// Method of the sweep and refinement. Absent: chosen for the study's building,
    /// `exact` where a probe run costs it at most [`crate::model::fidelity::EXACT_SWEEP_COST`]
    /// times `newmark`'s work, else `newmark` ([`crate::eval::probe::choose_sweep_method`]).
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

/// The smallest peak ground acceleration a study's suites may ask for, g: about the
/// threshold of perceptible shaking. Below it no dissipator of a real frame slips, every
/// design answers as the bare frame and an optimum would be rounding noise (at 1e-300 g
/// the responses are subnormal numbers).
/// The same floor as a scene's target PGA ([`slipload_sim::scene::TARGET_PGA_BAND_G`]).
pub const MIN_STUDY_PGA_G: f64 = slipload_sim::scene::TARGET_PGA_BAND_G.0;

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

pub(crate) fn too_large(
    what: String,
    estimate: f64,
    limit: f64,
    unit: &str,
) -> Result<(), OptError> {
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

/// Longest suite or design name, characters: a label of tables, not a text.
pub const MAX_LABEL_CHARS: usize = 200;

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

/// The first place where `written` (a study as its file gives it) has an array and the
/// study as parsed (`parsed`, serialized back) an object: a key whose value is an object
/// of named fields, given as an array. serde reads such an array by position, so values
/// in another order than the fields' would pass silently in the wrong fields; the study
/// refuses it, naming the key and its fields. Returns the key's path and the fields.
fn object_as_array(
    written: &serde_json::Value,
    parsed: &serde_json::Value,
    at: &str,
) -> Option<(String, Vec<String>)> {
    use serde_json::Value;
    let join = |k: &str| {
        if at.is_empty() {
            k.to_string()
        } else {
            format!("{at}.{k}")
        }
    };
    match (written, parsed) {
        (Value::Array(_), Value::Object(fields)) => {
            Some((at.to_string(), fields.keys().cloned().collect()))
        }
        (Value::Object(w), Value::Object(p)) => w
            .iter()
            .filter_map(|(k, wv)| p.get(k).map(|pv| (k, wv, pv)))
            .find_map(|(k, wv, pv)| object_as_array(wv, pv, &join(k))),
        (Value::Array(w), Value::Array(p)) if w.len() == p.len() => w
            .iter()
            .zip(p)
            .enumerate()
            .find_map(|(i, (wv, pv))| object_as_array(wv, pv, &format!("{at}[{i}]"))),
        _ => None,
    }
}

impl StudyConfig {
    /// Parses a study from JSON text; `path` names it in errors. A key whose value is an
    /// object given as an array (read by position) is refused, naming the key and its fields.
    pub fn from_json(text: &str, path: &Path) -> Result<StudyConfig, OptError> {
        let cfg = StudyConfig::parse(text, path)?;
        if let (Ok(written), Ok(parsed)) = (
            serde_json::from_str::<serde_json::Value>(text),
            serde_json::to_value(&cfg),
        ) && let Some((field, keys)) = object_as_array(&written, &parsed, "")
        {
            return Err(OptError::invalid(
                path,
                field,
                format!(
                    "expected an object {{{}}}, got an array: its values would be read by position, not by name; write the keys",
                    keys.iter()
                        .map(|k| format!("{k:?}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        }
        Ok(cfg)
    }

    fn parse(text: &str, path: &Path) -> Result<StudyConfig, OptError> {
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
            if let Some(t) = s.free_vibration_s
                && !(t.is_finite() && t > 0.0 && t <= MAX_FREE_VIBRATION_S)
            {
                return Err(OptError::invalid(
                    path,
                    f("free_vibration_s"),
                    format!(
                        "must be a rest after each record of more than 0 and at most {MAX_FREE_VIBRATION_S} s, got {t}"
                    ),
                ));
            }
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
            match &s.scale {
                Some(ScaleConfig::Factor(v)) => finite_positive(path, &f("scale.factor"), *v)?,
                Some(ScaleConfig::PgaG(v)) => intensity_g(path, &f("scale.pga_g"), *v)?,
                Some(ScaleConfig::SaT1G(v)) => intensity_g(path, &f("scale.sa_t1_g"), *v)?,
                Some(ScaleConfig::CodeSpectrum(c)) => c.validate(path, i)?,
                None => {}
            }
            if let Some(l) = &s.limits {
                l.validate(path, i)?;
            }
        }
        if let Some(b) = &self.property_bounds {
            b.validate(path)?;
        }
        if let Some(d) = &self.devices {
            d.validate(path)?;
        }
        if let Some(w) = &self.wind {
            if let Some((i, v)) = w
                .storey_shears_kn
                .iter()
                .enumerate()
                .find(|(_, v)| !(v.is_finite() && **v >= 0.0))
            {
                return Err(OptError::invalid(
                    path,
                    format!("wind.storey_shears_kn[{i}]"),
                    format!("must be a storey shear ≥ 0 kN, got {v}"),
                ));
            }
            if let Some(f) = w.factor
                && !(f.is_finite() && (1.0..=5.0).contains(&f))
            {
                return Err(OptError::invalid(
                    path,
                    "wind.factor",
                    format!("must be a margin from 1 to 5 over the wind shear, got {f}"),
                ));
            }
        }
        if let Some(f) = &self.frame_strength {
            let bad = |field: &str, msg: String| {
                Err(OptError::invalid(
                    path,
                    format!("frame_strength.{field}"),
                    msg,
                ))
            };
            let r = f.response_modification;
            if !(r.is_finite() && (1.0..=10.0).contains(&r)) {
                return bad(
                    "response_modification",
                    format!("must be R from 1 to 10 (ASCE 7-16 Table 12.2-1), got {r}"),
                );
            }
            if let Some(i) = f.importance
                && !(i.is_finite() && (1.0..=1.5).contains(&i))
            {
                return bad(
                    "importance",
                    format!("must be I_e from 1 to 1.5 (ASCE 7-16 Table 1.5-2), got {i}"),
                );
            }
            if let Some(x) = f.fraction
                && !(x.is_finite() && x > 0.0 && x <= 1.0)
            {
                return bad("fraction", format!("must be in (0, 1], got {x}"));
            }
            if let Some(t) = f.period_s
                && !(t.is_finite() && t > 0.0)
            {
                return bad("period_s", format!("must be a period > 0 s, got {t}"));
            }
            let code: Vec<&CodeSpectrumConfig> = self
                .suites
                .iter()
                .filter_map(|s| match &s.scale {
                    Some(ScaleConfig::CodeSpectrum(c)) => Some(c),
                    _ => None,
                })
                .collect();
            if code.is_empty() {
                return bad(
                    "response_modification",
                    "the demand needs the design spectrum: scale a suite to `code_spectrum` (S_DS, S_D1, T_L are read from the first)".into(),
                );
            }
            if code.iter().all(|c| c.asce7().is_none()) {
                return bad(
                    "response_modification",
                    "the demand is ASCE 7-16 §12.8's C_s, read from S_DS, S_D1 and T_L: scale a suite to the ASCE form of `code_spectrum` (sds_g, sd1_g, tl_s); a table or an EN 1998-1 spectrum gives neither, and the project does not derive them".into(),
                );
            }
        }
        // the device table is written beside the code check, which a study with limits
        // has: without them `devices` would be dropped without a word
        if self.devices.is_some() && self.suites.iter().all(|s| s.limits.is_none()) {
            return Err(OptError::invalid(
                path,
                "devices",
                "the device table is written beside the code check, which needs acceptance limits: give a suite `limits`, or leave `devices` out",
            ));
        }
        match (&self.objective.cost, self.objective.terms.is_empty()) {
            (None, true) => {
                return Err(OptError::invalid(
                    path,
                    "objective.terms",
                    "must have at least one term (or give `objective.cost` for the least dampers that meet the limits)",
                ));
            }
            (Some(_), false) => {
                return Err(OptError::invalid(
                    path,
                    "objective.cost",
                    "is an objective of its own: give `terms` (a response to minimise) or `cost` (the least dampers that meet the limits), not both",
                ));
            }
            (Some(c), true) => {
                for (key, v) in [("per_kn", c.per_kn), ("per_device", c.per_device)] {
                    if !(v.is_finite() && v >= 0.0) {
                        return Err(OptError::invalid(
                            path,
                            format!("objective.cost.{key}"),
                            format!("must be a finite price >= 0, got {v}"),
                        ));
                    }
                }
                if c.per_kn == 0.0 && c.per_device == 0.0 {
                    return Err(OptError::invalid(
                        path,
                        "objective.cost",
                        "prices nothing: give per_kn > 0 (per kN of slip load) or per_device > 0",
                    ));
                }
                if !self.suites.iter().any(|s| s.limits.is_some()) {
                    return Err(OptError::invalid(
                        path,
                        "objective.cost",
                        "minimises the dampers' cost subject to the limits, but no suite has `limits`: without limits to meet, the least cost is no damper at all",
                    ));
                }
            }
            (None, false) => {}
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
                crate::model::objectives::validate(list, None, path)?;
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
