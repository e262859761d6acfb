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
