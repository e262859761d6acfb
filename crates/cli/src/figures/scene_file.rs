//! The scene a `simulate --plot DIR` run ran, kept in `DIR/scene.json`: the scene (or
//! building) file with the command line's overrides applied, the building inlined, the
//! record's path written relative to DIR (as a scene file's paths resolve), and the
//! method, time step and duration written out as resolved. `slipload simulate
//! DIR/scene.json` runs it again from anywhere, and the folder can move with the records
//! beside it (a clone's `results/` and `records/`); the report of the folder reads its
//! building, record and scaling from it.
//!
//! The file is a typed value, [`SceneAsRun`]: what the command line resolved (name,
//! duration, method and time step, the flags' record, window and scaling) as numbers and
//! strings, and every other field as the scene file wrote it (a JSON value, `null`
//! included), so a field it left out stays out. Its keys are in alphabetical order, at
//! every level, as the file has always had them: the fields are declared in that order,
//! and what passes through as written is a JSON value, whose keys are sorted.

use crate::cmd::scene_args::{BENCHMARK_BUILDING, SceneArgs};
use anyhow::Context;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use serde_json::Value;
use slipload_sim::Scene;
use std::path::{Path, PathBuf};

/// A field of `scene.json`: left out (as the scene file left it out), as the scene file
/// wrote it (any JSON, `null` included), or as the run resolved it.
#[derive(Debug, Clone, Default, PartialEq)]
pub enum Field<T> {
    /// Not in the file.
    #[default]
    Absent,
    /// As written.
    Written(Value),
    /// As resolved.
    Resolved(T),
}

impl<T> Field<T> {
    /// Whether the field is left out (it is then not written).
    pub fn is_absent(&self) -> bool {
        matches!(self, Field::Absent)
    }
}

impl<T: Serialize> Serialize for Field<T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Field::Absent => s.serialize_none(),
            Field::Written(v) => v.serialize(s),
            Field::Resolved(t) => t.serialize(s),
        }
    }
}

/// A field in the file is read as written.
impl<'de, T> Deserialize<'de> for Field<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Value::deserialize(d).map(Field::Written)
    }
}

impl<T: Clone + DeserializeOwned> Field<T> {
    /// The object the field holds, to be edited: as resolved, or as written when the file
    /// wrote an object (`None` when left out, `null` or any other value).
    fn object(&self) -> anyhow::Result<Option<T>> {
        match self {
            Field::Resolved(t) => Ok(Some(t.clone())),
            Field::Written(v) if v.is_object() => Ok(Some(T::deserialize(v)?)),
            _ => Ok(None),
        }
    }
}

/// `DIR/scene.json` (see the module's doc). Fields in alphabetical order; the name,
/// duration, method and time step are always resolved.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SceneAsRun {
    /// The building, inline: the building file's JSON.
    building: Value,
    #[serde(skip_serializing_if = "Field::is_absent")]
    description: Field<Value>,
    /// The simulated time, s.
    #[serde(skip_serializing_if = "Field::is_absent")]
    duration: Field<f64>,
    #[serde(skip_serializing_if = "Excitation::is_empty")]
    excitation: Excitation,
    method: Method,
    #[serde(skip_serializing_if = "Field::is_absent")]
    name: Field<String>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    outputs: Field<Value>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    reduce: Field<Value>,
}

/// The scene's `excitation`. Fields in alphabetical order.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct Excitation {
    #[serde(skip_serializing_if = "Field::is_absent")]
    harmonic: Field<Value>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    initial: Field<Value>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    record: Field<RecordAsRun>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    synthetic: Field<SyntheticAsRun>,
}

impl Excitation {
    /// No field at all (the excitation is then not written).
    fn is_empty(&self) -> bool {
        self.harmonic.is_absent()
            && self.initial.is_absent()
            && self.record.is_absent()
            && self.synthetic.is_absent()
    }
}

/// A record of the excitation. Fields in alphabetical order.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct RecordAsRun {
    #[serde(skip_serializing_if = "Field::is_absent")]
    dt: Field<Value>,
    /// The record file, relative to the folder of `scene.json`.
    #[serde(skip_serializing_if = "Field::is_absent")]
    file: Field<String>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    scale: Field<Value>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    scale_pga_g: Field<f64>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    units: Field<String>,
    /// `[start, duration]`, s.
    #[serde(skip_serializing_if = "Field::is_absent")]
    window: Field<[f64; 2]>,
}

/// A synthetic record of the excitation. Fields in alphabetical order.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct SyntheticAsRun {
    #[serde(skip_serializing_if = "Field::is_absent")]
    dt: Field<Value>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    duration: Field<Value>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    index: Field<Value>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    pga_g: Field<f64>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    seed: Field<Value>,
}

/// The scene's `method`. Fields in alphabetical order.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
struct Method {
    #[serde(skip_serializing_if = "Field::is_absent")]
    alpha: Field<Value>,
    /// The time step, s.
    #[serde(skip_serializing_if = "Field::is_absent")]
    dt: Field<f64>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    eps_a: Field<Value>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    eps_f: Field<Value>,
    #[serde(skip_serializing_if = "Field::is_absent")]
    max_iterations: Field<Value>,
    /// The method's name.
    #[serde(skip_serializing_if = "Field::is_absent")]
    name: Field<String>,
}

/// `p` made absolute (against the working folder), symbolic links resolved when it exists.
fn absolute(p: &Path) -> PathBuf {
    p.canonicalize().unwrap_or_else(|_| {
        std::env::current_dir()
            .map(|d| d.join(p))
            .unwrap_or_else(|_| p.to_path_buf())
    })
}

/// `target` as a path relative to the folder `from` (both made absolute first): `..` up
/// to their common ancestor, then down. Absolute when they share no root.
fn relative_to(target: &Path, from: &Path) -> PathBuf {
    use std::path::Component;
    let (t, f) = (absolute(target), absolute(from));
    let tc: Vec<Component> = t.components().collect();
    let fc: Vec<Component> = f.components().collect();
    let common = tc.iter().zip(&fc).take_while(|(a, b)| a == b).count();
    if common == 0 {
        return t;
    }
    let mut out = PathBuf::new();
    for _ in common..fc.len() {
        out.push("..");
    }
    for c in &tc[common..] {
        out.push(c.as_os_str());
    }
    out
}

fn read_json(path: &Path) -> anyhow::Result<Value> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    serde_json::from_str(&text).with_context(|| format!("parsing {}", path.display()))
}

/// The resolved scene of `args` (see the module's doc), to be written into the folder
/// `dir`; `scene` is what it resolved to (its name, method, time step and duration are
/// written out).
pub fn resolved(args: &SceneArgs, scene: &Scene, dir: &Path) -> anyhow::Result<SceneAsRun> {
    let (mut run, base) = match &args.scene {
        Some(path) => {
            let v = read_json(path)?;
            let base = absolute(path)
                .parent()
                .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
            let is_scene = v.as_object().is_some_and(|o| o.contains_key("building"));
            let run = if is_scene {
                SceneAsRun::deserialize(v).with_context(|| format!("reading {}", path.display()))?
            } else {
                // a building file alone: the scene of that building
                SceneAsRun {
                    building: v,
                    ..SceneAsRun::default()
                }
            };
            (run, base)
        }
        None => {
            let building: Value =
                serde_json::from_str(BENCHMARK_BUILDING).context("embedded benchmark building")?;
            let excitation = Excitation {
                synthetic: Field::Resolved(SyntheticAsRun::default()),
                ..Excitation::default()
            };
            let run = SceneAsRun {
                building,
                excitation,
                ..SceneAsRun::default()
            };
            (run, PathBuf::from("."))
        }
    };
    run.name = Field::Resolved(scene.name.clone());
    // the building inline, so the folder holds everything but the record
    if let Value::String(p) = &run.building {
        run.building = read_json(&base.join(p))?;
    }
    let excitation = &mut run.excitation;
    if let Some(file) = &args.record {
        // --record replaces the scene's ground motion
        let mut record = RecordAsRun {
            file: Field::Resolved(relative_to(file, dir).to_string_lossy().into_owned()),
            ..RecordAsRun::default()
        };
        if let Some(u) = args.units {
            record.units = Field::Resolved(u.to_string());
        }
        if let Some((s, d)) = args.window {
            record.window = Field::Resolved([s, d]);
        }
        if let Some(p) = args.scale_pga_g {
            record.scale_pga_g = Field::Resolved(p);
        }
        if let Some(f) = args.scale {
            record.scale = Field::Resolved(Value::from(f));
        }
        excitation.synthetic = Field::Absent;
        excitation.record = Field::Resolved(record);
    } else if let Some(mut r) = excitation.record.object()? {
        if let Field::Written(Value::String(f)) = &r.file {
            let rel = relative_to(&base.join(f), dir);
            r.file = Field::Resolved(rel.to_string_lossy().into_owned());
        }
        if matches!(r.units, Field::Absent | Field::Written(Value::Null))
            && let Some(u) = args.units
        {
            r.units = Field::Resolved(u.to_string());
        }
        if let Some((s, d)) = args.window {
            // --window replaces the scene's window (docs/MODEL.md, scenes and plans)
            r.window = Field::Resolved([s, d]);
        }
        if let Some(p) = args.scale_pga_g {
            r.scale = Field::Absent;
            r.scale_pga_g = Field::Resolved(p);
        }
        if let Some(f) = args.scale {
            // --scale replaces the scene's own scaling
            r.scale_pga_g = Field::Absent;
            r.scale = Field::Resolved(Value::from(f));
        }
        excitation.record = Field::Resolved(r);
    } else if let Some(mut syn) = excitation.synthetic.object()? {
        // a synthetic motion is generated at its PGA: --scale-pga-g is that PGA, and
        // --scale makes it the scaled motion's (the same motion to round-off)
        let pga = match (args.scale_pga_g, args.scale, &scene.record) {
            (Some(p), _, _) => Some(p),
            (None, Some(_), Some(r)) => Some(r.pga() / slipload_motion::G),
            _ => None,
        };
        if let Some(p) = pga {
            syn.pga_g = Field::Resolved(p);
            excitation.synthetic = Field::Resolved(syn);
        }
    }
    run.duration = Field::Resolved(scene.duration);
    run.method.name = Field::Resolved(scene.method.name.as_str().to_string());
    run.method.dt = Field::Resolved(scene.method.dt);
    Ok(run)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
    use super::*;

    /// The repository root, without `..` in it (so relative paths come out the same on
    /// any machine).
    fn root() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .canonicalize()
            .unwrap()
    }

    fn args(scene: Option<PathBuf>) -> SceneArgs {
        SceneArgs {
            scene,
            record: None,
            units: None,
            scale_pga_g: None,
            scale: None,
            window: None,
            method: None,
            dt: None,
            duration: None,
            study: None,
            designs: None,
            design: "optimum".into(),
            run: None,
            suite: None,
        }
    }

    /// `DIR/scene.json` as `simulate --plot DIR` writes it for `args`, with its inline
    /// building (its first key) shortened to `{…}` once it is checked to be `building`
    /// (the building file's JSON).
    fn written(args: &SceneArgs, dir: &Path, building: &str) -> String {
        let scene = args.load(true).unwrap();
        let mut text = serde_json::to_string_pretty(&resolved(args, &scene, dir).unwrap()).unwrap();
        text.push('\n');
        let back: Value = serde_json::from_str(&text).unwrap();
        let file: Value = serde_json::from_str(building).unwrap();
        assert_eq!(
            back["building"], file,
            "the building inline, as its file has it"
        );
        let start = text.find("\"building\": {").unwrap();
        let end = start + text[start..].find("\n  },\n").unwrap() + 5;
        text.replace_range(start..end, "\"building\": {…},");
        text
    }

    fn config(name: &str) -> String {
        std::fs::read_to_string(root().join("configs").join(name)).unwrap()
    }

    /// A scene file with overrides: the building inlined, the record's path relative to
    /// the folder, the window and scaling replaced, method, Δt and duration resolved,
    /// every other field as the file wrote it; keys in the order the file has always had
    /// them (alphabetical).
    #[test]
    fn a_scene_with_overrides_is_written_as_it_ran() {
        let root = root();
        let mut a = args(Some(root.join("configs/paper-benchmark-sylmar.json")));
        a.duration = Some(5.0);
        a.scale_pga_g = Some(0.3);
        a.window = Some((1.0, 4.5));
        a.method = Some(crate::cmd::scene_args::MethodArg::Hht);
        a.dt = Some(0.0025);
        let text = written(
            &a,
            &root.join("a-plot-folder"),
            &config("benchmark-3story.json"),
        );
        assert_eq!(
            text,
            r#"{
  "building": {…},
  "description": "The paper's benchmark three-storey building (De la Cruz, Lopez-Almansa & Oller 2007, Figs. 12-13) under Sylmar 1994, 90 degree component, first 10 s, unscaled.",
  "duration": 5.0,
  "excitation": {
    "record": {
      "file": "../records/SYL090.AT2",
      "scale_pga_g": 0.3,
      "window": [
        1.0,
        4.5
      ]
    }
  },
  "method": {
    "dt": 0.0025,
    "name": "hht"
  },
  "name": "paper-benchmark-sylmar",
  "outputs": {
    "energies": true,
    "histories": false
  }
}
"#
        );
    }

    /// A building file alone with `--record`: the record comes from the flags.
    #[test]
    fn a_building_with_a_record_flag_is_written_as_it_ran() {
        let root = root();
        let mut a = args(Some(root.join("configs/benchmark-3story.json")));
        a.record = Some(root.join("records/SYL090.AT2"));
        a.units = Some(slipload_motion::Units::G);
        a.window = Some((0.0, 2.0));
        a.scale_pga_g = Some(0.2);
        let text = written(
            &a,
            &root.join("results/a-plot-folder"),
            &config("benchmark-3story.json"),
        );
        assert_eq!(
            text,
            r#"{
  "building": {…},
  "duration": 2.0,
  "excitation": {
    "record": {
      "file": "../../records/SYL090.AT2",
      "scale_pga_g": 0.2,
      "units": "g",
      "window": [
        0.0,
        2.0
      ]
    }
  },
  "method": {
    "dt": 0.0025,
    "name": "newmark"
  },
  "name": "benchmark-3story"
}
"#
        );
    }

    /// The embedded default, scaled: a synthetic record with its PGA.
    #[test]
    fn the_embedded_scene_is_written_as_it_ran() {
        let mut a = args(None);
        a.scale_pga_g = Some(0.25);
        a.duration = Some(3.0);
        let text = written(&a, &root().join("a-plot-folder"), BENCHMARK_BUILDING);
        assert_eq!(
            text,
            r#"{
  "building": {…},
  "duration": 3.0,
  "excitation": {
    "synthetic": {
      "pga_g": 0.25
    }
  },
  "method": {
    "dt": 0.0025,
    "name": "newmark"
  },
  "name": "benchmark-3story, synthetic record 0"
}
"#
        );
    }

    /// A scene whose fields the flags fill in or replace, beside fields written as
    /// `null`, a description, outputs and `reduce`, which pass through as written.
    #[test]
    fn fields_written_as_null_and_the_rest_pass_through() {
        let dir = std::env::temp_dir().join(format!("slipload-scene-file-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("plot")).unwrap();
        let mut csv = String::from("time_s,accel_m_s2\n");
        for k in 0..=400 {
            let t = k as f64 * 0.01;
            csv.push_str(&format!("{t},{}\n", (6.0 * t).sin()));
        }
        std::fs::write(dir.join("rec.csv"), csv).unwrap();
        std::fs::write(
            dir.join("scene.json"),
            r#"{
  "description": "a test",
  "building": "building.json",
  "excitation": {
    "record": { "file": "rec.csv", "units": null, "scale": 2, "dt": "10 ms" },
    "synthetic": null,
    "harmonic": null
  },
  "method": { "name": "exact", "dt": "5 ms", "max_iterations": null },
  "outputs": { "histories": true },
  "reduce": false
}"#,
        )
        .unwrap();
        let building = config("paper-1story.json");
        std::fs::write(dir.join("building.json"), &building).unwrap();
        let mut a = args(Some(dir.join("scene.json")));
        a.units = Some(slipload_motion::Units::MPerS2);
        a.scale_pga_g = Some(0.1);
        a.method = Some(crate::cmd::scene_args::MethodArg::Newmark);
        let text = written(&a, &dir.join("plot"), &building);
        let _ = std::fs::remove_dir_all(&dir);
        assert_eq!(
            text,
            r#"{
  "building": {…},
  "description": "a test",
  "duration": 4.0,
  "excitation": {
    "harmonic": null,
    "record": {
      "dt": "10 ms",
      "file": "../rec.csv",
      "scale_pga_g": 0.1,
      "units": "m/s2"
    },
    "synthetic": null
  },
  "method": {
    "dt": 0.005,
    "max_iterations": null,
    "name": "newmark"
  },
  "name": "paper-1story",
  "outputs": {
    "histories": true
  },
  "reduce": false
}
"#
        );
    }

    /// Every field a scene file may hold passes through [`SceneAsRun`] as written: a
    /// scene config of the library with every field given (a field added there and not
    /// here fails to build or fails this test, not a user's run).
    #[test]
    fn every_field_of_a_scene_file_passes_through() {
        use slipload_sim::MethodName;
        use slipload_sim::scene::{
            BuildingRef, ExcitationConfig, HarmonicConfig, InitialConfig, MethodConfig,
            OutputsConfig, RecordConfig, SceneConfig, SyntheticConfig,
        };
        use slipload_sim::units::{Angle, AngularFrequency, Force, Length, Time, Velocity};
        let cfg = SceneConfig {
            name: Some("n".into()),
            description: Some("d".into()),
            building: BuildingRef::Path("b.json".into()),
            excitation: ExcitationConfig {
                record: Some(RecordConfig {
                    file: "r.csv".into(),
                    units: Some("g".into()),
                    dt: Some(Time(0.01)),
                    scale: Some(2.0),
                    scale_pga_g: Some(0.3),
                    window: Some([Time(0.5), Time(1.5)]),
                }),
                synthetic: Some(SyntheticConfig {
                    index: Some(1),
                    seed: Some(2),
                    pga_g: Some(0.4),
                    duration: Some(Time(5.0)),
                    dt: Some(Time(0.02)),
                }),
                harmonic: Some(HarmonicConfig {
                    floor: 1,
                    amplitude: Force(1e3),
                    omega: AngularFrequency(2.0),
                    phase: Angle(0.25),
                }),
                initial: Some(InitialConfig {
                    floor_displacement: Some(vec![Length(0.01)]),
                    floor_velocity: Some(vec![Velocity(0.02)]),
                    dissipator_displacement: Some(vec![Length(0.03)]),
                    dissipator_velocity: Some(vec![Velocity(0.04)]),
                }),
            },
            duration: Some(Time(3.0)),
            method: MethodConfig {
                name: MethodName::Delacruz,
                dt: Some(Time(0.001)),
                alpha: Some(-0.05),
                eps_a: Some(1e-6),
                eps_f: Some(1e-3),
                max_iterations: Some(50),
            },
            outputs: OutputsConfig {
                energies: false,
                histories: true,
                dampers: false,
                sensitivities: false,
            },
            reduce: false,
        };
        let written = serde_json::to_value(&cfg).unwrap();
        let run = SceneAsRun::deserialize(&written).unwrap();
        assert_eq!(
            serde_json::to_string_pretty(&run).unwrap(),
            serde_json::to_string_pretty(&written).unwrap()
        );
    }
}
