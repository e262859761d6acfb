//! A scene file as written ([`SceneConfig`] and its parts: serde structs, unknown fields
//! rejected, quantities as numbers or strings with units), the command line's
//! [`SceneOverrides`], and the embedded benchmark scene. Nothing here is validated beyond
//! the schema; `check` and `build` resolve it into a [`Scene`](super::resolved::Scene).

use super::method::MethodName;
use crate::building::BuildingConfig;
use crate::error::SimError;
use crate::kind::Expected;
use crate::units::{Angle, AngularFrequency, Force, Length, Time, Velocity};
use serde::{Deserialize, Serialize};
use slipload_motion::Units;
use std::path::{Path, PathBuf};

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

/// Method and accuracy settings, as written.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MethodConfig {
    /// Method (default newmark).
    #[serde(default)]
    pub name: MethodName,
    /// Time step (s); default T₁/400 (`delacruz` T₁/200) rounded to divide the record's dt
    /// ([`default_dt`](super::method::default_dt)).
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

impl MethodConfig {
    /// The option fields that are set, by name.
    pub(super) fn given(&self) -> Vec<&'static str> {
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
    /// Per-damper demands: slip each way, peak slip velocity, cumulative travel, slip
    /// excursions and cycles, peak friction force and dissipated energy per damper
    /// (`Response::dampers`; default false: not computed, and not written back).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub dampers: bool,
    /// The derivatives of the peak responses with respect to each damper's slip load
    /// (`Response::sensitivity`; `newmark` only; default false: not computed). The run then
    /// steps on the general dense loop, which carries the tangent of its state.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub sensitivities: bool,
}

impl Default for OutputsConfig {
    fn default() -> Self {
        OutputsConfig {
            energies: true,
            histories: false,
            dampers: false,
            sensitivities: false,
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
    /// Multiply the ground motion by this factor (in place of a record's own `scale` or
    /// `scale_pga_g`; not with `scale_pga_g`): a suite's scale factor.
    pub scale: Option<f64>,
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
    /// Per-damper demands.
    pub dampers: Option<bool>,
    /// The scene is compiled to be explained, not run: with no ground motion and no
    /// duration it is planned over one bare-frame period T₁ (and a note says so) instead
    /// of being refused.
    pub plan_only: bool,
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

/// The benchmark building (`configs/benchmark-3story.json`), embedded so that every
/// front (the command line, the Python package) runs with no files.
pub const BENCHMARK_BUILDING: &str = include_str!("../../../../configs/benchmark-3story.json");

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
