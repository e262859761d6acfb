//! A scene in plan: a [`FloorPlan`], the ground's horizontal components (each a record at
//! an angle to the plan's x axis), the duration, the method and the outputs. As written
//! ([`FloorPlanSceneConfig`]) and resolved ([`FloorPlanScene`]).

use super::config::FloorPlanConfig;
use super::model::FloorPlan;
use crate::error::SimError;
use crate::scene::{
    MethodConfig, MethodName, MethodSettings, OutputsConfig, RecordConfig, TARGET_PGA_BAND_G,
    check_step_against_record, default_dt, target_pga_in_band,
};
use crate::units::{Time, is_positive};
use serde::{Deserialize, Serialize};
use slipload_motion::{Record, Units};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Standard gravity, m/s² (scaling to a PGA in g).
const G: f64 = 9.806_65;

/// A scene in plan, as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FloorPlanSceneConfig {
    /// Short name.
    #[serde(default)]
    pub name: Option<String>,
    /// Free text.
    #[serde(default)]
    pub description: Option<String>,
    /// The building in plan: a path (relative to this file) or an inline object.
    pub building: FloorPlanRef,
    /// The ground's horizontal components (none, one, or two applied together).
    #[serde(default)]
    pub ground: Vec<GroundConfig>,
    /// Simulated time (s); default the longest component's duration.
    #[serde(default)]
    pub duration: Option<Time>,
    /// Integration method and its accuracy settings.
    #[serde(default)]
    pub method: MethodConfig,
    /// What to compute beyond peak responses.
    #[serde(default)]
    pub outputs: OutputsConfig,
}

/// A building in plan given by path or inline.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum FloorPlanRef {
    /// Path relative to the scene file.
    Path(PathBuf),
    /// The building itself.
    Inline(Box<FloorPlanConfig>),
}

/// A string is a path, an object an inline building in plan, read by
/// [`FloorPlanConfig`]'s own deserializer so its errors surface as in a building file.
impl<'de> Deserialize<'de> for FloorPlanRef {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = FloorPlanRef;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(
                    "a building-in-plan file's path (a string) or a building-in-plan object",
                )
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<FloorPlanRef, E> {
                Ok(FloorPlanRef::Path(PathBuf::from(v)))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<FloorPlanRef, A::Error> {
                FloorPlanConfig::deserialize(serde::de::value::MapAccessDeserializer::new(map))
                    .map(|b| FloorPlanRef::Inline(Box::new(b)))
            }
        }
        d.deserialize_any(Visitor)
    }
}

/// One horizontal ground component, as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroundConfig {
    /// The record and its scaling (a window is not taken here).
    pub record: RecordConfig,
    /// Direction of the component from the plan's x axis, degrees counter-clockwise
    /// (default 0: along x).
    #[serde(default)]
    pub angle_deg: Option<f64>,
}

/// One horizontal ground component, resolved: its record (m/s²) and direction.
#[derive(Debug, Clone)]
pub struct GroundComponent {
    /// The record, m/s².
    pub record: Arc<Record>,
    /// Direction from the plan's x axis, rad.
    pub angle: f64,
}

/// A resolved scene in plan.
#[derive(Debug, Clone)]
pub struct FloorPlanScene {
    /// Name.
    pub name: String,
    /// The building.
    pub building: Arc<FloorPlan>,
    /// The ground components (at most two).
    pub ground: Vec<GroundComponent>,
    /// Simulated time, s.
    pub duration: f64,
    /// Method and step.
    pub method: MethodSettings,
    /// What to compute.
    pub outputs: OutputsConfig,
}

impl FloorPlanScene {
    /// A scene of `building` under `ground` for `duration` s with `method` at its default
    /// step (T1/400, or a divisor of the records' step) and `outputs`.
    pub fn new(
        building: Arc<FloorPlan>,
        ground: Vec<GroundComponent>,
        duration: f64,
        method: MethodName,
        outputs: OutputsConfig,
    ) -> FloorPlanScene {
        let record_dt = ground.iter().map(|g| g.record.dt()).min_by(f64::total_cmp);
        let dt = default_dt(method, building.t1(), record_dt, duration);
        FloorPlanScene {
            name: building.name.clone(),
            building,
            ground,
            duration,
            method: MethodSettings {
                name: method,
                dt,
                alpha: if method == MethodName::Hht {
                    -0.05
                } else {
                    0.0
                },
                eps_a: None,
                eps_f: None,
                max_iterations: None,
            },
            outputs,
        }
    }

    /// Applies the command line's overrides: another method (its default step unless
    /// `dt` is given), a step, a duration, histories.
    pub fn override_with(
        &mut self,
        method: Option<MethodName>,
        dt: Option<f64>,
        duration: Option<f64>,
        histories: bool,
    ) -> Result<(), SimError> {
        if let Some(d) = duration {
            if !is_positive(d) {
                return Err(SimError::Scene(format!("--duration {d}: must be positive")));
            }
            self.duration = d;
        }
        if let Some(m) = method {
            let again = FloorPlanScene::new(
                self.building.clone(),
                self.ground.clone(),
                self.duration,
                m,
                self.outputs,
            );
            self.method = again.method;
        }
        if let Some(dt) = dt {
            if !is_positive(dt) {
                return Err(SimError::BadTimeStep { dt });
            }
            self.method.dt = dt;
        }
        for g in &self.ground {
            check_step_against_record(self.method.name, self.method.dt, &g.record)?;
        }
        self.outputs.histories |= histories;
        Ok(())
    }

    /// Number of steps.
    pub fn steps(&self) -> usize {
        ((self.duration / self.method.dt * (1.0 - 1e-9)).ceil() as usize).max(1)
    }

    /// The files a scene in plan at `path` reads: itself, its building's file and its
    /// records (as far as the file can be parsed; loading it says what is wrong).
    pub fn input_files(path: &Path) -> Vec<PathBuf> {
        let mut files = vec![path.to_path_buf()];
        let base = path.parent().unwrap_or(Path::new("."));
        let cfg = slipload_motion::limits::read_input_text(
            path,
            "scene in plan",
            slipload_motion::limits::MAX_CONFIG_BYTES,
        )
        .ok()
        .and_then(|t| serde_json::from_str::<FloorPlanSceneConfig>(&t).ok());
        if let Some(cfg) = cfg {
            if let FloorPlanRef::Path(p) = &cfg.building {
                files.push(base.join(p));
            }
            files.extend(cfg.ground.iter().map(|g| base.join(&g.record.file)));
        }
        files
    }

    /// Reads and resolves a scene-in-plan JSON file.
    pub fn load(path: &Path) -> Result<FloorPlanScene, SimError> {
        let text = slipload_motion::limits::read_input_text(
            path,
            "scene in plan",
            slipload_motion::limits::MAX_CONFIG_BYTES,
        )?;
        if let Ok(serde_json::Value::Object(o)) = serde_json::from_str::<serde_json::Value>(&text)
            && o.contains_key("lines")
            && o.contains_key("floors")
        {
            return Err(SimError::Scene(format!(
                "{} is a building in plan; a run needs a scene that names it with its ground motion: {{\"building\": \"{}\", \"ground\": [{{\"record\": {{\"file\": \"RECORD.AT2\"}}, \"angle_deg\": 0}}]}}",
                path.display(),
                path.file_name()
                    .map_or_else(String::new, |f| f.to_string_lossy().into_owned())
            )));
        }
        let cfg: FloorPlanSceneConfig =
            serde_json::from_str(&text).map_err(|source| SimError::Json {
                path: path.to_path_buf(),
                source,
            })?;
        FloorPlanScene::from_config(&cfg, path)
    }

    /// Resolves a config; `path` names it in errors and anchors relative paths.
    pub fn from_config(
        cfg: &FloorPlanSceneConfig,
        path: &Path,
    ) -> Result<FloorPlanScene, SimError> {
        let base = path.parent().unwrap_or(Path::new("."));
        let building = match &cfg.building {
            FloorPlanRef::Path(p) => FloorPlan::load(&base.join(p))?,
            FloorPlanRef::Inline(b) => FloorPlan::from_config(b, path)?,
        };
        if cfg.ground.len() > 2 {
            return Err(SimError::invalid(
                path,
                "ground",
                format!(
                    "has {} components: a scene takes at most the two horizontal ones",
                    cfg.ground.len()
                ),
            ));
        }
        let mut ground = Vec::new();
        for (i, g) in cfg.ground.iter().enumerate() {
            let field = |name: &str| format!("ground[{i}].{name}");
            let rc = &g.record;
            if rc.window.is_some() {
                return Err(SimError::invalid(
                    path,
                    field("record.window"),
                    "a scene in plan runs its records whole: cut a window with `slipload record` first",
                ));
            }
            let units =
                match &rc.units {
                    None => None,
                    Some(u) => Some(u.parse::<Units>().map_err(|e| {
                        SimError::invalid(path, field("record.units"), e.to_string())
                    })?),
                };
            if rc.scale.is_some() && rc.scale_pga_g.is_some() {
                return Err(SimError::invalid(
                    path,
                    field("record.scale_pga_g"),
                    "give either scale or scale_pga_g, not both",
                ));
            }
            let mut r =
                slipload_motion::read_record(&base.join(&rc.file), units, rc.dt.map(|d| d.0))?;
            if let Some(f) = rc.scale {
                if !f.is_finite() {
                    return Err(SimError::invalid(
                        path,
                        field("record.scale"),
                        "must be finite",
                    ));
                }
                r = r.try_scaled(f)?;
            }
            if let Some(pga) = rc.scale_pga_g {
                if !target_pga_in_band(pga) {
                    return Err(SimError::invalid(
                        path,
                        field("record.scale_pga_g"),
                        format!(
                            "a target PGA in g within [{}, {}], got {pga}",
                            TARGET_PGA_BAND_G.0, TARGET_PGA_BAND_G.1
                        ),
                    ));
                }
                r = r.scaled_to_pga(pga * G)?;
            }
            let angle = g.angle_deg.unwrap_or(0.0);
            if !angle.is_finite() {
                return Err(SimError::invalid(
                    path,
                    field("angle_deg"),
                    "must be finite",
                ));
            }
            ground.push(GroundComponent {
                record: Arc::new(r),
                angle: angle.to_radians(),
            });
        }
        let duration = match cfg.duration.map(|d| d.0) {
            Some(d) if !is_positive(d) => {
                return Err(SimError::invalid(
                    path,
                    "duration",
                    format!("must be positive, got {d}"),
                ));
            }
            Some(d) => d,
            None => ground
                .iter()
                .map(|g| g.record.duration())
                .max_by(f64::total_cmp)
                .filter(|d| *d > 0.0)
                .ok_or_else(|| {
                    SimError::invalid(
                        path,
                        "duration",
                        "missing: no ground motion to take it from",
                    )
                })?,
        };
        let mut scene = FloorPlanScene::new(
            Arc::new(building),
            ground,
            duration,
            cfg.method.name,
            cfg.outputs,
        );
        if let Some(n) = &cfg.name {
            scene.name = n.clone();
        }
        if let Some(alpha) = cfg.method.alpha {
            if cfg.method.name != MethodName::Hht || !(-1.0 / 3.0..=0.0).contains(&alpha) {
                return Err(SimError::invalid(
                    path,
                    "method.alpha",
                    format!("HHT's alpha in [-1/3, 0] (method hht only), got {alpha}"),
                ));
            }
            scene.method.alpha = alpha;
        }
        if let Some(dt) = cfg.method.dt.map(|d| d.0) {
            if !is_positive(dt) {
                return Err(SimError::BadTimeStep { dt });
            }
            scene.method.dt = dt;
        }
        for g in &scene.ground {
            check_step_against_record(scene.method.name, scene.method.dt, &g.record)?;
        }
        Ok(scene)
    }
}
