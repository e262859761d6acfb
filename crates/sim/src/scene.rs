//! Scenes: a building, an excitation, what is asked for, and a method with its settings.
//!
//! A scene file names a building (inline or by path relative to the scene file) and may
//! name a record, a member of the embedded synthetic suite, a harmonic floor force and an
//! initial state. A building file alone is a valid scene (no excitation: give a record or
//! a duration through [`SceneOverrides`]). Overrides (the CLI's flags) win over the file.

use crate::building::{Building, BuildingConfig};
use crate::error::SimError;
use crate::kind::Expected;
use crate::units::{Force, Length, Time, is_positive};
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
    /// Simulated time (s); default: the record's duration.
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
    pub dt: Option<f64>,
    /// Scale factor on the accelerations.
    #[serde(default)]
    pub scale: Option<f64>,
    /// Scale to this peak ground acceleration, in g.
    #[serde(default)]
    pub scale_pga_g: Option<f64>,
    /// Window [start, duration] in s.
    #[serde(default)]
    pub window: Option<[f64; 2]>,
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
    /// Circular frequency ω, rad/s.
    pub omega: f64,
    /// Phase, rad (default 0).
    #[serde(default)]
    pub phase: f64,
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
    pub floor_velocity: Option<Vec<f64>>,
    /// Dissipator displacements x′₀ (m); floors without a dissipator ignore theirs.
    #[serde(default)]
    pub dissipator_displacement: Option<Vec<Length>>,
    /// Dissipator velocities (m/s).
    #[serde(default)]
    pub dissipator_velocity: Option<Vec<f64>>,
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
    /// Window (start, duration), s.
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

/// Most iterations of each `delacruz` fixed-point loop a scene may ask for
/// (`method.max_iterations`): the loops converge in a handful when they converge at all.
pub const MAX_LOOP_ITERATIONS: u32 = 10_000;

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
    if !is_positive(pga_g) {
        return Err(SimError::invalid(
            path,
            format!("{field}.pga_g"),
            format!("must be positive, got {pga_g}"),
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
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|source| SimError::Json {
                path: path.to_path_buf(),
                source,
            })?;
        let is_scene = value
            .as_object()
            .is_some_and(|o| o.contains_key("building"));
        let cfg = if is_scene {
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
        };
        Scene::from_config(cfg, path, over)
    }

    /// Resolves a config: loads the building and the record, applies overrides, validates.
    pub fn from_config(
        cfg: SceneConfig,
        path: &Path,
        over: &SceneOverrides,
    ) -> Result<Scene, SimError> {
        if let Some(pga) = over.scale_pga_g
            && !is_positive(pga)
        {
            return Err(SimError::Scene(format!(
                "--scale-pga-g must be positive and finite, got {pga}"
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
        // Ground motion: the override's file, else the scene's record, else its synthetic member.
        let record = if let Some(file) = &over.record {
            let mut r = slipload_motion::read_record(file, over.units, None)?;
            if let Some((s, d)) = over.window {
                r = r.window(s, d)?;
            }
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
            let mut r = slipload_motion::read_record(&base.join(&rc.file), units, rc.dt)?;
            if let Some([s, d]) = rc.window {
                r = r.window(s, d)?;
            }
            if let Some((s, d)) = over.window {
                r = r.window(s, d)?;
            }
            if rc.scale.is_some() && rc.scale_pga_g.is_some() {
                return Err(SimError::invalid(
                    path,
                    "excitation.record.scale",
                    "give either scale or scale_pga_g, not both",
                ));
            }
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
                Some(pga) if !is_positive(pga) => {
                    return Err(SimError::invalid(
                        path,
                        "excitation.record.scale_pga_g",
                        format!("must be positive, got {pga}"),
                    ));
                }
                Some(pga) => r = r.scaled_to_pga(pga * G)?,
                None => {}
            }
            Some(Arc::new(r))
        } else if let Some(syn) = &cfg.excitation.synthetic {
            Some(Arc::new(synthetic_record(syn, path, over)?))
        } else {
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
                if !h.amplitude.0.is_finite() || !h.omega.is_finite() || !h.phase.is_finite() {
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
                    omega: h.omega,
                    phase: h.phase,
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
                    ic.floor_velocity,
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
                    ic.dissipator_velocity,
                    n,
                )?,
            },
        };
        let duration = match over.duration.or(cfg.duration.map(|d| d.0)) {
            Some(d) if !is_positive(d) => {
                return Err(SimError::invalid(
                    path,
                    "duration",
                    format!("must be positive, got {d}"),
                ));
            }
            Some(d) => d,
            None => match &record {
                Some(r) => r.duration(),
                None => {
                    return Err(SimError::Scene(format!(
                        "{}: no record and no duration: give a record (--record) or a duration (--duration)",
                        path.display()
                    )));
                }
            },
        };
        let name = over.method.unwrap_or(cfg.method.name);
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
