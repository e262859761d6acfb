//! Scenes: a building, an excitation, what is asked for, and a method with its settings.
//!
//! A scene file names a building (inline or by path relative to the scene file) and may
//! name a record or a synthetic ground motion (not both), a harmonic floor force and an
//! initial state. A building file alone is a valid scene (no excitation: give a record or
//! a duration through [`SceneOverrides`]). Overrides (the CLI's flags) win over the file.
//!
//! Rules a scene is held to (each refusal names the file, the field and what was expected):
//! - **Window.** A record's `window` `[start, duration]` keeps that span of the ground
//!   motion; the `--window` flag ([`SceneOverrides::window`]) *replaces* the scene's
//!   window (it is not applied on top of it), and applies to whichever ground motion the
//!   scene ends up with (a record, `--record`'s file, or a synthetic one). A window that
//!   starts at or past the record's end is refused. One that runs past the end is padded
//!   with the ground at rest, the same rule as a `duration` longer than the record: the
//!   simulated time defaults to the window's duration, and the scene carries a note
//!   ([`Scene::notes`]) that says how many seconds have no ground motion. (A window inside
//!   the record lasts the whole sample intervals it keeps, as before.)
//! - **Quantities with units.** Times (`duration`, `window`, `method.dt`, a record's
//!   `dt`, a synthetic record's `duration` and `dt`) are a number of seconds or a string
//!   with a unit (`"10 s"`, `"5 ms"`); so are a harmonic force's `omega` (`"2.5 Hz"`) and
//!   `phase` (`"90 deg"`) and the initial velocities (`"50 cm/s"`), all parsed by
//!   [`crate::units::parse_quantity`].
//! - **Method options.** Each method reads only some of the `method` fields
//!   ([`MethodName::options`]); one it does not read is refused, naming the option, the
//!   method and the options it takes.
//! - **Exclusive excitation fields.** `record` and `synthetic`; a record's `scale` and
//!   `scale_pga_g`; a synthetic's `index` and `seed`.

use crate::building::{Building, BuildingConfig};
use crate::error::SimError;
use crate::kind::Expected;
use crate::units::{Angle, AngularFrequency, Force, Length, Time, Velocity, is_positive};
use serde::{Deserialize, Serialize};
use slipload_motion::{G, Record, Units};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A scene file, as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneConfig {
    /// Short name.
    #[serde(default)]
    pub name: Option<String>,
    /// Free text.
    #[serde(default)]
    pub description: Option<String>,
    /// The building: a path (relative to this file) or an inline building object.
    pub building: BuildingRef,
    /// Loads and initial state; default: none.
    #[serde(default)]
    pub excitation: ExcitationConfig,
    /// Simulated time (s); default: the window's duration when the record has a window,
    /// else the record's duration. Past the ground motion's end the ground is at rest.
    #[serde(default)]
    pub duration: Option<Time>,
    /// Integration method and its accuracy settings.
    #[serde(default)]
    pub method: MethodConfig,
    /// What to compute beyond peak responses.
    #[serde(default)]
    pub outputs: OutputsConfig,
    /// Compile the scene into a reduced plan (default true). `false` keeps every
    /// dissipator degree of freedom: the full 2N model, for checking the reductions.
    #[serde(default = "default_true")]
    pub reduce: bool,
}

fn default_true() -> bool {
    true
}

/// A building given by path or inline.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum BuildingRef {
    /// Path relative to the scene file.
    Path(PathBuf),
    /// The building itself.
    Inline(Box<BuildingConfig>),
}

/// A string is a path, an object an inline building, read by [`BuildingConfig`]'s own
/// deserializer so that its errors (an unknown field, a wrong type) surface as they do
/// in a building file instead of "did not match any variant".
impl<'de> Deserialize<'de> for BuildingRef {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = BuildingRef;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a building file's path (a string) or a building object")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<BuildingRef, E> {
                Ok(BuildingRef::Path(PathBuf::from(v)))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<BuildingRef, A::Error> {
                BuildingConfig::deserialize(serde::de::value::MapAccessDeserializer::new(map))
                    .map(|b| BuildingRef::Inline(Box::new(b)))
            }
        }
        d.deserialize_any(Visitor)
    }
}

/// Loads acting on the building.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExcitationConfig {
    /// A ground-motion record file.
    #[serde(default)]
    pub record: Option<RecordConfig>,
    /// A member of the embedded synthetic suite (used when no record file is named).
    #[serde(default)]
    pub synthetic: Option<SyntheticConfig>,
    /// A harmonic force on one floor.
    #[serde(default)]
    pub harmonic: Option<HarmonicConfig>,
    /// Initial displacements and velocities.
    #[serde(default)]
    pub initial: Option<InitialConfig>,
}

/// A record file and how to use it.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordConfig {
    /// Path, relative to the scene file.
    pub file: PathBuf,
    /// Units of the values ("g", "m/s2", "cm/s2"); AT2 files are in g.
    #[serde(default)]
    pub units: Option<String>,
    /// Sample interval (s) for one-column text files.
    #[serde(default)]
    pub dt: Option<Time>,
    /// Scale factor on the accelerations.
    #[serde(default)]
    pub scale: Option<f64>,
    /// Scale to this peak ground acceleration, in g.
    #[serde(default)]
    pub scale_pga_g: Option<f64>,
    /// Window [start, duration] in s (`[0, 10]`, `["2 s", "10 s"]`): the span of the
    /// record that is used; past the record's end the ground is at rest (see the module
    /// docs). `--window` replaces it.
    #[serde(default)]
    pub window: Option<[Time; 2]>,
}

/// A synthetic ground motion: a member of the embedded suite (`index`), or a fresh
/// Clough–Penzien record drawn from `seed` with the suite's filter and envelope.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SyntheticConfig {
    /// Index in the embedded suite, from 0 (default 0; not with `seed`).
    #[serde(default)]
    pub index: Option<usize>,
    /// Draw a new record from this seed instead.
    #[serde(default)]
    pub seed: Option<u64>,
    /// Peak ground acceleration, g (default: the suite's 0.4 g).
    #[serde(default)]
    pub pga_g: Option<f64>,
    /// Duration of a seeded record, s (default 20).
    #[serde(default)]
    pub duration: Option<Time>,
    /// Sample interval of a seeded record, s (default 0.01).
    #[serde(default)]
    pub dt: Option<Time>,
}

/// P(t) = amplitude · sin(ω t + phase) on one floor.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HarmonicConfig {
    /// Floor number, 1 = first floor.
    pub floor: usize,
    /// Amplitude, N.
    pub amplitude: Force,
    /// Circular frequency ω, rad/s (`"2.5 Hz"` is 2π·2.5 rad/s).
    pub omega: AngularFrequency,
    /// Phase, rad (default 0; `"90 deg"` accepted).
    #[serde(default = "zero_angle")]
    pub phase: Angle,
}

fn zero_angle() -> Angle {
    Angle(0.0)
}

/// Initial state (relative to the ground); missing vectors are zero.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialConfig {
    /// Floor displacements x₀ (m), bottom to top.
    #[serde(default)]
    pub floor_displacement: Option<Vec<Length>>,
    /// Floor velocities (m/s).
    #[serde(default)]
    pub floor_velocity: Option<Vec<Velocity>>,
    /// Dissipator displacements x′₀ (m); floors without a dissipator ignore theirs.
    #[serde(default)]
    pub dissipator_displacement: Option<Vec<Length>>,
    /// Dissipator velocities (m/s).
    #[serde(default)]
    pub dissipator_velocity: Option<Vec<Velocity>>,
}

/// The integration methods.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MethodName {
    /// Newmark average acceleration (γ = ½, β = ¼) with exact implicit friction.
    #[default]
    Newmark,
    /// HHT-α (default α = −0.05) with exact implicit friction.
    Hht,
    /// What frame programs (DRAIN-2D, SAP2000, OpenSees) do: each brace + damper as one
    /// elastic–perfectly plastic spring, dissipator mass ignored, stepped by `newmark`.
    Bilinear,
    /// The paper's method (De la Cruz, López-Almansa & Oller 2007, §4): linear
    /// acceleration, stick/slip decided per floor at every step, three nested fixed-point
    /// loops. Conditionally stable.
    Delacruz,
    /// Event-driven reference: each stick/slip mode integrated exactly (matrix
    /// exponential series), every stick↔slip event located by root finding.
    Exact,
}

impl MethodName {
    /// The name as written in configs and on the command line.
    pub fn as_str(self) -> &'static str {
        match self {
            MethodName::Newmark => "newmark",
            MethodName::Hht => "hht",
            MethodName::Bilinear => "bilinear",
            MethodName::Delacruz => "delacruz",
            MethodName::Exact => "exact",
        }
    }
}

impl MethodName {
    /// Every method, in the order the docs list them.
    pub const ALL: [MethodName; 5] = [
        MethodName::Newmark,
        MethodName::Hht,
        MethodName::Delacruz,
        MethodName::Exact,
        MethodName::Bilinear,
    ];

    /// The `method` fields (beyond `name`) this method reads; any other is refused.
    pub fn options(self) -> &'static [&'static str] {
        match self {
            MethodName::Newmark | MethodName::Bilinear | MethodName::Exact => &["dt"],
            MethodName::Hht => &["dt", "alpha"],
            MethodName::Delacruz => &["dt", "eps_a", "eps_f", "max_iterations"],
        }
    }
}

impl MethodConfig {
    /// The option fields that are set, by name.
    fn given(&self) -> Vec<&'static str> {
        [
            ("dt", self.dt.is_some()),
            ("alpha", self.alpha.is_some()),
            ("eps_a", self.eps_a.is_some()),
            ("eps_f", self.eps_f.is_some()),
            ("max_iterations", self.max_iterations.is_some()),
        ]
        .into_iter()
        .filter_map(|(name, set)| set.then_some(name))
        .collect()
    }
}

/// Refuses a `method` option that `name` does not read: it would be ignored, and the run
/// would not be the one asked for. `from_flag`: the method was chosen with `--method`.
fn check_method_options(
    cfg: &MethodConfig,
    name: MethodName,
    from_flag: bool,
    path: &Path,
) -> Result<(), SimError> {
    let takes = name.options();
    let Some(unused) = cfg.given().into_iter().find(|o| !takes.contains(o)) else {
        return Ok(());
    };
    let users: Vec<&str> = MethodName::ALL
        .iter()
        .filter(|m| m.options().contains(&unused))
        .map(|m| m.as_str())
        .collect();
    Err(SimError::invalid(
        path,
        format!("method.{unused}"),
        format!(
            "method {}{} does not use {unused} (it takes {}); {unused} is an option of {}: remove it or choose that method",
            name.as_str(),
            if from_flag { " (from --method)" } else { "" },
            takes.join(", "),
            users.join(", ")
        ),
    ))
}

/// Cuts `window = (start, duration)` out of `r`, refusing a start at or past the record's
/// end (nothing of it would be left). A window that runs past the end keeps what there is:
/// the simulated duration then defaults to the window's, with the ground at rest after the
/// record ([`pad_note`] says so). `what` names the window in errors.
fn apply_window(r: &Record, window: (f64, f64), what: &str) -> Result<Record, SimError> {
    let (start, duration) = window;
    if !(start.is_finite() && start >= 0.0 && duration.is_finite() && duration > 0.0) {
        return Err(SimError::Scene(format!(
            "{what}: a window needs a start >= 0 s and a duration > 0 s, got [{start}, {duration}]"
        )));
    }
    let end = r.duration();
    // at the end to round-off (39.98 against 1999 × 0.02 = 39.980000000000004) is at it
    if start >= end - 1e-9 * r.dt() {
        return Err(SimError::Scene(format!(
            "{what}: the window starts at {} s, at or past the end of {} ({} s long): no ground motion would be left; give a start below {} s",
            secs(start),
            r.name(),
            secs(end),
            secs(end)
        )));
    }
    Ok(r.window(start, duration)?)
}

/// Seconds as people write them: round-off below a nanosecond dropped (39.98, not
/// 39.980000000000004).
fn secs(t: f64) -> String {
    format!("{}", (t * 1e9).round() / 1e9)
}

/// The note of a run longer than its ground motion (a `duration` or a window past the
/// record's end): the ground is at rest for the rest, which is free vibration.
fn pad_note(record: &Record, duration: f64, window: Option<(f64, f64, &str)>) -> Option<String> {
    let end = record.duration();
    // the same slack as Scene::steps: a duration that is the record's to round-off is it
    if duration <= end * (1.0 + 1e-9) + 1e-12 {
        return None;
    }
    let rest = secs(duration - end);
    Some(match window {
        Some((s, d, what)) => format!(
            "{what} [{} s, {} s] runs past the end of {}: {} s of ground motion from {} s, then the ground at rest for the last {rest} s of the {} s run (free vibration), as with a duration longer than the record",
            secs(s),
            secs(d),
            record.name(),
            secs(end),
            secs(s),
            secs(duration)
        ),
        None => format!(
            "the run lasts {} s but the ground motion {} lasts {} s: the ground is at rest for the last {rest} s (free vibration)",
            secs(duration),
            record.name(),
            secs(end)
        ),
    })
}

impl std::str::FromStr for MethodName {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "newmark" => Ok(MethodName::Newmark),
            "hht" => Ok(MethodName::Hht),
            "bilinear" => Ok(MethodName::Bilinear),
            "delacruz" => Ok(MethodName::Delacruz),
            "exact" => Ok(MethodName::Exact),
            other => Err(format!(
                "unknown method {other:?}: expected newmark, hht, bilinear, delacruz or exact"
            )),
        }
    }
}

/// Method and accuracy settings, as written.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MethodConfig {
    /// Method (default newmark).
    #[serde(default)]
    pub name: MethodName,
    /// Time step (s); default T₁/400 (`delacruz` T₁/200) rounded to divide the record's dt
    /// ([`default_dt`]).
    #[serde(default)]
    pub dt: Option<Time>,
    /// HHT α in [−1/3, 0] (default −0.05 for hht, 0 for newmark).
    #[serde(default)]
    pub alpha: Option<f64>,
    /// `delacruz`: tolerance on accelerations, m/s² (default |a_g|max/10⁵).
    #[serde(default)]
    pub eps_a: Option<f64>,
    /// `delacruz`: tolerance on friction forces, N (default μN/10⁵ per damper).
    #[serde(default)]
    pub eps_f: Option<f64>,
    /// `delacruz`: iteration cap of each fixed-point loop (default 100).
    #[serde(default)]
    pub max_iterations: Option<u32>,
}

/// What to compute beyond peaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputsConfig {
    /// Accumulate the energies (default true).
    #[serde(default = "default_true")]
    pub energies: bool,
    /// Store time histories (default false).
    #[serde(default)]
    pub histories: bool,
}

impl Default for OutputsConfig {
    fn default() -> Self {
        OutputsConfig {
            energies: true,
            histories: false,
        }
    }
}

/// Command-line overrides; each `Some` wins over the file.
#[derive(Debug, Clone, Default)]
pub struct SceneOverrides {
    /// Record file (replaces the scene's excitation record).
    pub record: Option<PathBuf>,
    /// Units of that record.
    pub units: Option<Units>,
    /// Scale to this PGA, g.
    pub scale_pga_g: Option<f64>,
    /// Window (start, duration), s: replaces the scene's record window and applies to
    /// whichever ground motion the scene has (record, `record` above, or synthetic).
    pub window: Option<(f64, f64)>,
    /// Method.
    pub method: Option<MethodName>,
    /// Time step, s.
    pub dt: Option<f64>,
    /// Duration, s.
    pub duration: Option<f64>,
    /// Store histories.
    pub histories: Option<bool>,
    /// Accumulate energies.
    pub energies: Option<bool>,
    /// The scene is compiled to be explained, not run: with no ground motion and no
    /// duration it is planned over one bare-frame period T₁ (and a note says so) instead
    /// of being refused.
    pub plan_only: bool,
}

/// A harmonic floor force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Harmonic {
    /// Floor index from 0.
    pub floor: usize,
    /// Amplitude, N.
    pub amplitude: f64,
    /// ω, rad/s.
    pub omega: f64,
    /// Phase, rad.
    pub phase: f64,
}

impl Harmonic {
    /// P(t), N.
    #[inline]
    pub fn force(&self, t: f64) -> f64 {
        self.amplitude * (self.omega * t + self.phase).sin()
    }
}

/// Initial state, SI, one entry per floor.
#[derive(Debug, Clone, PartialEq)]
pub struct InitialState {
    /// Floor displacements, m.
    pub floor_displacement: Vec<f64>,
    /// Floor velocities, m/s.
    pub floor_velocity: Vec<f64>,
    /// Dissipator displacements, m.
    pub dissipator_displacement: Vec<f64>,
    /// Dissipator velocities, m/s.
    pub dissipator_velocity: Vec<f64>,
}

impl InitialState {
    /// At rest.
    pub fn rest(n: usize) -> Self {
        InitialState {
            floor_displacement: vec![0.0; n],
            floor_velocity: vec![0.0; n],
            dissipator_displacement: vec![0.0; n],
            dissipator_velocity: vec![0.0; n],
        }
    }
    /// True when everything is zero.
    pub fn is_rest(&self) -> bool {
        [
            &self.floor_displacement,
            &self.floor_velocity,
            &self.dissipator_displacement,
            &self.dissipator_velocity,
        ]
        .iter()
        .all(|v| v.iter().all(|x| *x == 0.0))
    }
}

/// Method and settings, resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MethodSettings {
    /// Method.
    pub name: MethodName,
    /// Time step, s (resolved).
    pub dt: f64,
    /// HHT α (0 for Newmark).
    pub alpha: f64,
    /// `delacruz` acceleration tolerance, m/s² (`None`: |a_g|max/10⁵).
    pub eps_a: Option<f64>,
    /// `delacruz` friction-force tolerance, N (`None`: μN/10⁵ per damper).
    pub eps_f: Option<f64>,
    /// `delacruz` iteration cap per loop (`None`: 100).
    pub max_iterations: Option<u32>,
}

/// A resolved scene, ready to compile into a plan.
#[derive(Debug, Clone)]
pub struct Scene {
    /// Name.
    pub name: String,
    /// The building.
    pub building: Building,
    /// Ground acceleration record, m/s².
    pub record: Option<Arc<Record>>,
    /// Harmonic floor force.
    pub harmonic: Option<Harmonic>,
    /// Initial state.
    pub initial: InitialState,
    /// Simulated time, s.
    pub duration: f64,
    /// Method.
    pub method: MethodSettings,
    /// What to compute.
    pub outputs: OutputsConfig,
    /// Compile into a reduced plan.
    pub reduce: bool,
    /// What the scene decided that the user should hear about (a window or duration
    /// past the record's end, a nominal duration for `explain`), one sentence each.
    pub notes: Vec<String>,
}

/// Default time step of `method`: T₁/400 of the bare frame (the paper's own T₁/200 for
/// `delacruz`), rounded down so that it divides the record's sample interval (the record is
/// then sampled at steps, not between them, and never more coarsely than it was recorded)
/// — or, without a record, so that it divides the duration (the run ends exactly at it).
///
/// T₁/400 because the step-by-step methods must stay within 1 % of `exact` on every
/// storey's peak drift at their default: over the embedded synthetic suite (10 records,
/// 15 s, 0.4 g) `newmark` at T₁/200 was up to 1.4 % off on the benchmark building and 4.3 %
/// on the ten-storey one (higher modes and the stiff braced state carry the error, not T₁);
/// at T₁/400, 0.40 % and 0.90 % (`scripts/accuracy-study.sh`, results/accuracy/).
pub fn default_dt(method: MethodName, t1: f64, record_dt: Option<f64>, duration: f64) -> f64 {
    let per_period = match method {
        MethodName::Delacruz => 200.0,
        _ => DEFAULT_STEPS_PER_PERIOD,
    };
    let target = t1 / per_period;
    let divide = |span: f64| span / (span / target).ceil().max(1.0);
    match record_dt {
        Some(rdt) => divide(rdt),
        None => divide(duration),
    }
}

/// A step-by-step method (every method but `exact`) samples the ground motion once per
/// step: a step longer than the record's sample interval skips samples, and with them
/// the peaks of the input, so it is refused ([`SimError::StepTooLong`]). `exact`
/// integrates every sample whatever its output step. (The accuracy study sets coarser
/// steps on purpose, on compiled scenes, to measure exactly that error.)
pub fn check_step_against_record(
    method: MethodName,
    dt: f64,
    record: &Record,
) -> Result<(), SimError> {
    let rdt = record.dt();
    if method != MethodName::Exact && dt > rdt * (1.0 + 1e-9) {
        return Err(SimError::StepTooLong {
            dt,
            what: format!("the sample interval of record {}", record.name()),
            span: rdt,
            consequence: format!(
                "{} samples the ground motion once per step and would skip record samples (and the peaks among them); give a step of at most {rdt} s, or none for the default (T1/400 rounded down to divide the sample interval); `exact` integrates every sample at any step",
                method.as_str()
            ),
        });
    }
    Ok(())
}

/// The benchmark building (`configs/benchmark-3story.json`), embedded so that every
/// front (the command line, the Python package) runs with no files.
pub const BENCHMARK_BUILDING: &str = include_str!("../../../configs/benchmark-3story.json");

/// How errors and relative paths name the embedded benchmark building.
pub const BENCHMARK_ORIGIN: &str = "configs/benchmark-3story.json (embedded)";

/// The default scene of every front: the embedded benchmark building under the first
/// record of the embedded synthetic suite, the default method and outputs.
pub fn benchmark_scene_config() -> Result<SceneConfig, SimError> {
    let building: BuildingConfig =
        serde_json::from_str(BENCHMARK_BUILDING).map_err(|source| SimError::Json {
            path: PathBuf::from(BENCHMARK_ORIGIN),
            source,
        })?;
    Ok(SceneConfig {
        name: Some("benchmark-3story, synthetic record 0".into()),
        description: None,
        building: BuildingRef::Inline(Box::new(building)),
        excitation: ExcitationConfig {
            synthetic: Some(SyntheticConfig::default()),
            ..Default::default()
        },
        duration: None,
        method: Default::default(),
        outputs: Default::default(),
        reduce: true,
    })
}

/// Most iterations of each `delacruz` fixed-point loop a scene may ask for
/// (`method.max_iterations`): the loops converge in a handful when they converge at all.
pub const MAX_LOOP_ITERATIONS: u32 = 10_000;

/// The band of a target peak ground acceleration, g (`scale_pga_g`, a synthetic record's
/// `pga_g`, `--scale-pga-g`): from about the threshold of perceptible shaking (below it
/// no damper slips and every response is the bare frame's at a scale no study needs, a
/// units slip) to the largest ground acceleration any record holds
/// ([`slipload_motion::MAX_ABS_ACCEL_G`]).
pub const TARGET_PGA_BAND_G: (f64, f64) = (1e-3, slipload_motion::MAX_ABS_ACCEL_G);

/// Whether `pga_g` lies in [`TARGET_PGA_BAND_G`].
pub fn target_pga_in_band(pga_g: f64) -> bool {
    pga_g.is_finite() && (TARGET_PGA_BAND_G.0..=TARGET_PGA_BAND_G.1).contains(&pga_g)
}

/// What [`TARGET_PGA_BAND_G`] asks for, for error messages.
fn target_pga_expected(pga_g: f64) -> String {
    format!(
        "must be positive and finite, within {} … {} g (perceptible shaking to the strongest ground motion recorded), got {} g",
        TARGET_PGA_BAND_G.0,
        TARGET_PGA_BAND_G.1,
        slipload_motion::readable(pga_g)
    )
}

/// Steps per bare-frame fundamental period of the default time step ([`default_dt`]).
pub const DEFAULT_STEPS_PER_PERIOD: f64 = 400.0;

/// The record a [`SyntheticConfig`] names, scaled to its PGA (the override's first).
fn synthetic_record(
    syn: &SyntheticConfig,
    path: &Path,
    over: &SceneOverrides,
) -> Result<Record, SimError> {
    let field = "excitation.synthetic";
    let pga_g = over
        .scale_pga_g
        .or(syn.pga_g)
        .unwrap_or(slipload_motion::DEFAULT_SUITE_PGA_G);
    if !target_pga_in_band(pga_g) {
        return Err(SimError::invalid(
            path,
            format!("{field}.pga_g"),
            target_pga_expected(pga_g),
        ));
    }
    let record = match (syn.index, syn.seed) {
        (Some(_), Some(_)) => {
            return Err(SimError::invalid(
                path,
                field,
                "give either index (a member of the embedded suite) or seed, not both",
            ));
        }
        (_, Some(seed)) => {
            let mut params = slipload_motion::Synthetic::default();
            if let Some(d) = syn.duration {
                params.duration_s = d.0;
            }
            if let Some(dt) = syn.dt {
                params.dt_s = dt.0;
            }
            params
                .validate()
                .map_err(|e| SimError::invalid(path, field, e.to_string()))?;
            params.generate(seed, &format!("synthetic seed {seed}"))?
        }
        (index, None) => {
            if syn.duration.is_some() || syn.dt.is_some() {
                return Err(SimError::invalid(
                    path,
                    field,
                    "duration and dt apply to a seeded record: give seed too",
                ));
            }
            let index = index.unwrap_or(0);
            let mut suite = slipload_motion::default_suite();
            if index >= suite.len() {
                return Err(SimError::invalid(
                    path,
                    format!("{field}.index"),
                    format!(
                        "the embedded suite has {} records (0..{}), got {index}",
                        suite.len(),
                        suite.len() - 1
                    ),
                ));
            }
            suite.swap_remove(index)
        }
    };
    Ok(record.scaled_to_pga(pga_g * G)?)
}

/// Largest |initial displacement| (m) or |initial velocity| (m/s) of a floor or
/// dissipator: no structure moves a kilometre or at a kilometre per second.
pub const MAX_INITIAL_STATE: f64 = 1e3;

fn vec_or_zero(
    path: &Path,
    field: &str,
    v: Option<Vec<f64>>,
    n: usize,
) -> Result<Vec<f64>, SimError> {
    match v {
        None => Ok(vec![0.0; n]),
        Some(v) if v.len() != n => Err(SimError::invalid(
            path,
            field,
            format!("has {} values, expected {n} (one per floor)", v.len()),
        )),
        Some(v) => match v.iter().position(|x| !x.is_finite()) {
            Some(i) => Err(SimError::invalid(
                path,
                format!("{field}[{i}]"),
                "must be finite",
            )),
            None => match v.iter().position(|x| x.abs() > MAX_INITIAL_STATE) {
                Some(i) => Err(SimError::invalid(
                    path,
                    format!("{field}[{i}]"),
                    format!(
                        "{:e} is beyond any structure's motion (at most {MAX_INITIAL_STATE:e} m or m/s; check the units)",
                        v[i]
                    ),
                )),
                None => Ok(v),
            },
        },
    }
}

impl SceneConfig {
    /// Parses a scene file's text — or a building file's, which is a scene with no
    /// excitation. `path` names it in errors.
    pub fn from_json(text: &str, path: &Path) -> Result<SceneConfig, SimError> {
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|source| SimError::Json {
                path: path.to_path_buf(),
                source,
            })?;
        let is_scene = value
            .as_object()
            .is_some_and(|o| o.contains_key("building"));
        Ok(if is_scene {
            crate::kind::parse::<SceneConfig>(text, path, Expected::SceneOrBuilding)?
        } else {
            let b: BuildingConfig = crate::kind::parse(text, path, Expected::SceneOrBuilding)?;
            SceneConfig {
                name: b.name.clone(),
                description: None,
                building: BuildingRef::Inline(Box::new(b)),
                excitation: ExcitationConfig::default(),
                duration: None,
                method: MethodConfig::default(),
                outputs: OutputsConfig::default(),
                reduce: true,
            }
        })
    }
}

impl Scene {
    /// Loads a scene file — or a building file, which is a scene with no excitation.
    pub fn load(path: &Path, over: &SceneOverrides) -> Result<Scene, SimError> {
        let text = slipload_motion::limits::read_input_text(
            path,
            "scene",
            slipload_motion::limits::MAX_CONFIG_BYTES,
        )?;
        Scene::from_json(&text, path, over)
    }

    /// Parses a scene (or building) from JSON text; `path` names it in errors and anchors
    /// relative paths.
    pub fn from_json(text: &str, path: &Path, over: &SceneOverrides) -> Result<Scene, SimError> {
        Scene::from_config(SceneConfig::from_json(text, path)?, path, over)
    }

    /// Resolves a config: loads the building and the record, applies overrides, validates.
    pub fn from_config(
        cfg: SceneConfig,
        path: &Path,
        over: &SceneOverrides,
    ) -> Result<Scene, SimError> {
        Scene::from_config_with_record(cfg, path, over, None)
    }

    /// As [`Scene::from_config`], with a ground motion already in memory (a record a
    /// notebook built from an array, say): when given, it replaces the scene's excitation
    /// record or synthetic motion as an `over.record` file would, and goes through the
    /// same rules — the window, `over.scale_pga_g`, the default step from its Δt, the
    /// duration from its length.
    pub fn from_config_with_record(
        cfg: SceneConfig,
        path: &Path,
        over: &SceneOverrides,
        given: Option<Arc<Record>>,
    ) -> Result<Scene, SimError> {
        if let Some(pga) = over.scale_pga_g
            && !target_pga_in_band(pga)
        {
            return Err(SimError::Scene(format!(
                "--scale-pga-g {}",
                target_pga_expected(pga)
            )));
        }
        if let Some(d) = over.duration
            && !is_positive(d)
        {
            return Err(SimError::Scene(format!(
                "--duration: the simulated time must be positive, got {d} (give a finite number of seconds)"
            )));
        }
        if let Some(dt) = over.dt
            && !is_positive(dt)
        {
            return Err(SimError::Scene(format!(
                "--dt: time step {dt} s must be positive and finite"
            )));
        }
        let base = path.parent().unwrap_or(Path::new("."));
        let building = match &cfg.building {
            BuildingRef::Path(p) => Building::load(&base.join(p))?,
            BuildingRef::Inline(b) => Building::from_config(b, path)?,
        };
        let n = building.floors();
        if cfg.excitation.record.is_some() && cfg.excitation.synthetic.is_some() {
            return Err(SimError::invalid(
                path,
                "excitation.synthetic",
                "give either record (a ground-motion file) or synthetic (a generated ground motion), not both",
            ));
        }
        if let Some(rc) = &cfg.excitation.record
            && rc.scale.is_some()
            && rc.scale_pga_g.is_some()
        {
            return Err(SimError::invalid(
                path,
                "excitation.record.scale",
                "give either scale or scale_pga_g, not both",
            ));
        }
        // The window in force: `--window` replaces the scene's record window.
        let scene_window = cfg
            .excitation
            .record
            .as_ref()
            .and_then(|rc| rc.window)
            .map(|[s, d]| (s.0, d.0));
        let window: Option<(f64, f64, String)> = match (over.window, scene_window) {
            (Some((s, d)), _) => Some((s, d, "--window".to_string())),
            (None, Some((s, d))) if over.record.is_none() && given.is_none() => Some((
                s,
                d,
                format!("{}: field `excitation.record.window`", path.display()),
            )),
            _ => None,
        };
        // Set when the window reaches past the record's end: the run then lasts the
        // window's duration, padded with the ground at rest. (A window inside the record
        // lasts what it keeps: whole sample intervals from its start.)
        let past_end = std::cell::Cell::new(false);
        let cut = |r: Record| -> Result<Record, SimError> {
            match &window {
                Some((s, d, what)) => {
                    past_end.set(s + d > r.duration() + 1e-9 * r.dt());
                    apply_window(&r, (*s, *d), what)
                }
                None => Ok(r),
            }
        };
        // Ground motion: the one given in memory, else the override's file, else the scene's
        // record, else its synthetic one.
        let record = if let Some(r) = given {
            let mut r = match &window {
                Some(_) => Arc::new(cut(Record::clone(&r))?),
                None => r,
            };
            if let Some(pga) = over.scale_pga_g {
                r = Arc::new(r.scaled_to_pga(pga * G)?);
            }
            Some(r)
        } else if let Some(file) = &over.record {
            let mut r = cut(slipload_motion::read_record(file, over.units, None)?)?;
            if let Some(pga) = over.scale_pga_g {
                r = r.scaled_to_pga(pga * G)?;
            }
            Some(Arc::new(r))
        } else if let Some(rc) = &cfg.excitation.record {
            let units = match &rc.units {
                None => over.units,
                Some(u) => Some(u.parse::<Units>().map_err(|e| {
                    SimError::invalid(path, "excitation.record.units", e.to_string())
                })?),
            };
            let mut r = cut(slipload_motion::read_record(
                &base.join(&rc.file),
                units,
                rc.dt.map(|d| d.0),
            )?)?;
            if let Some(f) = rc.scale {
                if !f.is_finite() {
                    return Err(SimError::invalid(
                        path,
                        "excitation.record.scale",
                        "must be finite",
                    ));
                }
                r = r.try_scaled(f)?;
            }
            match over.scale_pga_g.or(rc.scale_pga_g) {
                Some(pga) if !target_pga_in_band(pga) => {
                    return Err(SimError::invalid(
                        path,
                        "excitation.record.scale_pga_g",
                        target_pga_expected(pga),
                    ));
                }
                Some(pga) => r = r.scaled_to_pga(pga * G)?,
                None => {}
            }
            Some(Arc::new(r))
        } else if let Some(syn) = &cfg.excitation.synthetic {
            // windowed before scaling, as a record is: the PGA is the window's
            let r = synthetic_record(syn, path, over)?;
            let r = match &window {
                Some(_) => {
                    let pga = r.pga();
                    cut(r)?.scaled_to_pga(pga)?
                }
                None => r,
            };
            Some(Arc::new(r))
        } else {
            if window.is_some() {
                return Err(SimError::Scene(format!(
                    "--window: {} has no ground motion to window; give a record (--record) or a duration (--duration)",
                    path.display()
                )));
            }
            None
        };
        let harmonic = match &cfg.excitation.harmonic {
            None => None,
            Some(h) => {
                if h.floor == 0 || h.floor > n {
                    return Err(SimError::invalid(
                        path,
                        "excitation.harmonic.floor",
                        format!("must be a floor from 1 to {n}, got {}", h.floor),
                    ));
                }
                if !h.amplitude.0.is_finite() || !h.omega.0.is_finite() || !h.phase.0.is_finite() {
                    return Err(SimError::invalid(
                        path,
                        "excitation.harmonic",
                        "amplitude, omega and phase must be finite",
                    ));
                }
                let weight = building.mass.sum() * G;
                let limit = crate::building::MAX_HARMONIC_FORCE_PER_WEIGHT * weight;
                if h.amplitude.0.abs() > limit {
                    return Err(SimError::invalid(
                        path,
                        "excitation.harmonic.amplitude",
                        format!(
                            "{:e} N is more than {} × the building's weight ({weight:.4e} N): no shaker or load comes near it (check the units)",
                            h.amplitude.0,
                            crate::building::MAX_HARMONIC_FORCE_PER_WEIGHT
                        ),
                    ));
                }
                Some(Harmonic {
                    floor: h.floor - 1,
                    amplitude: h.amplitude.0,
                    omega: h.omega.0,
                    phase: h.phase.0,
                })
            }
        };
        let initial = match cfg.excitation.initial.clone() {
            None => InitialState::rest(n),
            Some(ic) => InitialState {
                floor_displacement: vec_or_zero(
                    path,
                    "excitation.initial.floor_displacement",
                    ic.floor_displacement
                        .map(|v| v.iter().map(|x| x.0).collect()),
                    n,
                )?,
                floor_velocity: vec_or_zero(
                    path,
                    "excitation.initial.floor_velocity",
                    ic.floor_velocity.map(|v| v.iter().map(|x| x.0).collect()),
                    n,
                )?,
                dissipator_displacement: vec_or_zero(
                    path,
                    "excitation.initial.dissipator_displacement",
                    ic.dissipator_displacement
                        .map(|v| v.iter().map(|x| x.0).collect()),
                    n,
                )?,
                dissipator_velocity: vec_or_zero(
                    path,
                    "excitation.initial.dissipator_velocity",
                    ic.dissipator_velocity
                        .map(|v| v.iter().map(|x| x.0).collect()),
                    n,
                )?,
            },
        };
        let mut notes = Vec::new();
        let duration = match over.duration.or(cfg.duration.map(|d| d.0)) {
            Some(d) if !is_positive(d) => {
                return Err(SimError::invalid(
                    path,
                    "duration",
                    format!("must be positive, got {d}"),
                ));
            }
            Some(d) => d,
            None => match (&record, &window) {
                (Some(_), Some((_, d, _))) if past_end.get() => *d,
                (Some(r), _) if r.len() < 2 => {
                    return Err(SimError::Scene(format!(
                        "{}: record {} holds a single sample, which lasts 0 s: give a record of at least two samples, or a duration (--duration) to run free vibration past it",
                        path.display(),
                        r.name()
                    )));
                }
                (Some(r), _) => r.duration(),
                (None, _) if over.plan_only => {
                    let t1 = building.t1();
                    notes.push(format!(
                        "no ground motion and no duration: the steps are planned over one bare-frame period T1 = {t1:.6} s; give a record (--record) or a duration (--duration) to plan a run"
                    ));
                    t1
                }
                (None, _) => {
                    return Err(SimError::Scene(format!(
                        "{}: no record and no duration: give a record (--record) or a duration (--duration)",
                        path.display()
                    )));
                }
            },
        };
        if let Some(r) = &record
            && let Some(note) = pad_note(
                r,
                duration,
                window.as_ref().map(|(s, d, what)| (*s, *d, what.as_str())),
            )
        {
            notes.push(note);
        }
        let name = over.method.unwrap_or(cfg.method.name);
        check_method_options(&cfg.method, name, over.method.is_some(), path)?;
        let alpha = match name {
            MethodName::Newmark
            | MethodName::Bilinear
            | MethodName::Delacruz
            | MethodName::Exact => 0.0,
            MethodName::Hht => cfg.method.alpha.unwrap_or(-0.05),
        };
        if !(-1.0 / 3.0..=0.0).contains(&alpha) {
            return Err(SimError::invalid(
                path,
                "method.alpha",
                format!("HHT α must be in [-1/3, 0], got {alpha}"),
            ));
        }
        let dt = over.dt.or(cfg.method.dt.map(|d| d.0)).unwrap_or_else(|| {
            default_dt(
                name,
                building.t1(),
                record.as_ref().map(|r| r.dt()),
                duration,
            )
        });
        if !is_positive(dt) {
            return Err(SimError::BadTimeStep { dt });
        }
        if let Some(r) = &record {
            check_step_against_record(name, dt, r)?;
        }
        // A step of half the forcing period or more samples sin(ωt) at the same phase or
        // aliases it to a slower force: the run would answer a different load.
        if let Some(h) = &harmonic
            && name != MethodName::Exact
            && h.omega.abs() * dt >= std::f64::consts::PI
        {
            return Err(SimError::invalid(
                path,
                "excitation.harmonic.omega",
                format!(
                    "{omega:e} rad/s has a period of {period:e} s, at most twice the time step {dt:e} s: {method} would sample the force fewer than twice per period and answer a different load; give a physical frequency (check the units: rad/s, or \"Hz\") or a step below half the period",
                    omega = h.omega,
                    period = 2.0 * std::f64::consts::PI / h.omega.abs(),
                    method = name.as_str(),
                ),
            ));
        }
        for (field, v) in [
            ("method.eps_a", cfg.method.eps_a),
            ("method.eps_f", cfg.method.eps_f),
        ] {
            if let Some(v) = v
                && !is_positive(v)
            {
                return Err(SimError::invalid(
                    path,
                    field,
                    format!("tolerance must be positive and finite, got {v}"),
                ));
            }
        }
        if let Some(cap) = cfg.method.max_iterations
            && cap > MAX_LOOP_ITERATIONS
            && !crate::limits::allow_large()
        {
            return Err(SimError::invalid(
                path,
                "method.max_iterations",
                format!(
                    "{cap} iterations per loop per step is more than any converging loop needs (limit {MAX_LOOP_ITERATIONS}; the default is 100): a loop that does not converge would run for days; {}",
                    crate::limits::OVERRIDE_HINT
                ),
            ));
        }
        if cfg.method.max_iterations == Some(0) {
            return Err(SimError::invalid(
                path,
                "method.max_iterations",
                "must be at least 1, got 0",
            ));
        }
        let mut outputs = cfg.outputs;
        if let Some(h) = over.histories {
            outputs.histories = h;
        }
        if let Some(e) = over.energies {
            outputs.energies = e;
        }
        Ok(Scene {
            name: cfg.name.clone().unwrap_or_else(|| building.name.clone()),
            building,
            record,
            harmonic,
            initial,
            duration,
            method: MethodSettings {
                name,
                dt,
                alpha,
                eps_a: cfg.method.eps_a,
                eps_f: cfg.method.eps_f,
                max_iterations: cfg.method.max_iterations,
            },
            outputs,
            reduce: cfg.reduce,
            notes,
        })
    }

    /// Ground acceleration at `t`, m/s² (zero without a record and after its end).
    #[inline]
    pub fn ground_accel(&self, t: f64) -> f64 {
        self.record.as_ref().map_or(0.0, |r| r.accel_at(t))
    }

    /// Number of steps: enough to reach the duration (the last step ends at or just after
    /// it; a relative slack of 1e-9 absorbs the round-off of duration/dt), at least one.
    pub fn steps(&self) -> usize {
        ((self.duration / self.method.dt * (1.0 - 1e-9)).ceil() as usize).max(1)
    }
}
