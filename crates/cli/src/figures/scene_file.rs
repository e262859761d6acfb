//! The scene a `simulate --plot DIR` run ran, kept in `DIR/scene.json`: the scene (or
//! building) file with the command line's overrides applied, the building inlined, the
//! record's path written relative to DIR (as a scene file's paths resolve), and the
//! method, time step and duration written out as resolved. `slipload simulate
//! DIR/scene.json` runs it again from anywhere, and the folder can move with the records
//! beside it (a clone's `results/` and `records/`); the report of the folder reads its
//! building, record and scaling from it.

use crate::cmd::scene_args::{BENCHMARK_BUILDING, SceneArgs};
use anyhow::Context;
use serde_json::{Map, Value, json};
use slipload_sim::Scene;
use std::path::{Path, PathBuf};

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

/// The object at `key` of `obj`, created empty when absent or null.
fn object_at<'a>(obj: &'a mut Map<String, Value>, key: &str) -> &'a mut Map<String, Value> {
    let slot = obj.entry(key).or_insert_with(|| Value::Object(Map::new()));
    if !slot.is_object() {
        *slot = Value::Object(Map::new());
    }
    match slot {
        Value::Object(m) => m,
        _ => unreachable!("just made an object"),
    }
}

/// The resolved scene of `args` as JSON (see the module's doc), to be written into the
/// folder `dir`; `scene` is what it resolved to (its name, method, time step and duration
/// are written out).
pub fn resolved(args: &SceneArgs, scene: &Scene, dir: &Path) -> anyhow::Result<Value> {
    let (mut root, base) = match &args.scene {
        Some(path) => {
            let v = read_json(path)?;
            let base = absolute(path)
                .parent()
                .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
            let is_scene = v.as_object().is_some_and(|o| o.contains_key("building"));
            let v = if is_scene {
                v
            } else {
                // a building file alone: the scene of that building
                let name = v.get("name").cloned();
                let mut m = Map::new();
                if let Some(n) = name {
                    m.insert("name".into(), n);
                }
                m.insert("building".into(), v);
                Value::Object(m)
            };
            (v, base)
        }
        None => {
            let building: Value =
                serde_json::from_str(BENCHMARK_BUILDING).context("embedded benchmark building")?;
            (
                json!({
                    "building": building,
                    "excitation": { "synthetic": {} }
                }),
                PathBuf::from("."),
            )
        }
    };
    let Some(obj) = root.as_object_mut() else {
        anyhow::bail!("the scene is not a JSON object");
    };
    obj.insert("name".into(), Value::String(scene.name.clone()));
    // the building inline, so the folder holds everything but the record
    if let Some(Value::String(p)) = obj.get("building") {
        let path = base.join(p);
        let b = read_json(&path)?;
        obj.insert("building".into(), b);
    }
    let excitation = object_at(obj, "excitation");
    if let Some(file) = &args.record {
        // --record replaces the scene's ground motion
        let mut r = Map::new();
        r.insert(
            "file".into(),
            Value::String(relative_to(file, dir).to_string_lossy().into_owned()),
        );
        if let Some(u) = args.units {
            r.insert("units".into(), Value::String(u.to_string()));
        }
        if let Some((s, d)) = args.window {
            r.insert("window".into(), json!([s, d]));
        }
        if let Some(p) = args.scale_pga_g {
            r.insert("scale_pga_g".into(), json!(p));
        }
        excitation.remove("synthetic");
        excitation.insert("record".into(), Value::Object(r));
    } else if let Some(Value::Object(r)) = excitation.get_mut("record") {
        if let Some(Value::String(f)) = r.get("file") {
            let rel = relative_to(&base.join(f), dir);
            r.insert(
                "file".into(),
                Value::String(rel.to_string_lossy().into_owned()),
            );
        }
        if r.get("units").is_none_or(Value::is_null)
            && let Some(u) = args.units
        {
            r.insert("units".into(), Value::String(u.to_string()));
        }
        if let Some((s, d)) = args.window {
            // --window replaces the scene's window (docs/MODEL.md, scenes and plans)
            r.insert("window".into(), json!([s, d]));
        }
        if let Some(p) = args.scale_pga_g {
            r.remove("scale");
            r.insert("scale_pga_g".into(), json!(p));
        }
    } else if let Some(Value::Object(syn)) = excitation.get_mut("synthetic")
        && let Some(p) = args.scale_pga_g
    {
        syn.insert("pga_g".into(), json!(p));
    }
    if excitation.is_empty() {
        obj.remove("excitation");
    }
    obj.insert("duration".into(), json!(scene.duration));
    let method = object_at(obj, "method");
    method.insert("name".into(), json!(scene.method.name.as_str()));
    method.insert("dt".into(), json!(scene.method.dt));
    Ok(root)
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
            window: None,
            method: None,
            dt: None,
            duration: None,
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
}
