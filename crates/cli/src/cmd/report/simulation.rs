//! A simulation folder on a report page: what ran (building, ground motion, scaling,
//! method, time step, from `scene.json` and `response.json`) and the responses per storey
//! and of the whole run in engineering units, the bare frame's beside them.

use super::tables::{f64_at, f64s_at, grid, kv_table};
use crate::html::sig;
use std::path::Path;

/// A length in mm: 0.01 mm below 10 mm, 0.1 mm below 1 m, whole mm beyond (a column
/// keeps its decimals, so its values line up).
fn mm(v_m: f64) -> String {
    let v = 1e3 * v_m;
    let s = if v.abs() < 10.0 {
        format!("{v:.2}")
    } else if v.abs() < 1000.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.0}")
    };
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        // round-off of nothing (a storey that never yielded): plainly 0
        "0".to_string()
    } else {
        s
    }
}

/// An energy in kJ: 4 significant digits, whole kJ from 1000 kJ on.
fn kj(v_j: f64) -> String {
    let v = v_j / 1e3;
    if v.abs() >= 1000.0 {
        format!("{v:.0}")
    } else {
        sig(v, 4)
    }
}

/// The floors (from 1) with a damper, from a scene's inline building.
fn damper_floors(scene: &serde_json::Value) -> Option<Vec<u64>> {
    let d = scene.get("building")?.get("dissipators")?.as_array()?;
    Some(
        d.iter()
            .filter_map(|x| x.get("floor").and_then(serde_json::Value::as_u64))
            .collect(),
    )
}

/// Per storey: peak drift (mm, % of the storey height), peak displacement, peak absolute
/// acceleration, residual drift, damper slip and stick↔slip transitions ("—" for a
/// storey without a damper), ductility and plastic drift for a yielding frame.
fn storey_table(r: &serde_json::Value, dampers: Option<&[u64]>) -> String {
    let drift = f64s_at(r, "peak_drift").unwrap_or_default();
    let n = drift.len();
    let col = |k: &str| f64s_at(r, k).filter(|v| v.len() == n);
    let ratio = col("peak_drift_ratio");
    let disp = col("peak_displacement");
    let acc = col("peak_abs_acceleration");
    let resid = col("residual_drift");
    let slip = col("peak_slip");
    let trans = col("transitions");
    let ductility: Option<Vec<Option<f64>>> = r
        .get("peak_ductility")
        .and_then(|v| v.as_array())
        .map(|a| a.iter().map(serde_json::Value::as_f64).collect());
    let plastic = col("peak_plastic_drift");
    let mut head: Vec<String> = vec![
        "storey".into(),
        "peak drift (mm)".into(),
        "drift ratio (%)".into(),
        "peak displacement (mm)".into(),
        "peak abs. acceleration (m/s²)".into(),
        "residual drift (mm)".into(),
        "damper slip (mm)".into(),
        "stick↔slip transitions".into(),
    ];
    if ductility.is_some() {
        head.push("ductility".into());
        head.push("plastic drift (mm)".into());
    }
    let dash = || "—".to_string();
    let at = |v: &Option<Vec<f64>>, i: usize, f: &dyn Fn(f64) -> String| {
        v.as_ref().map_or_else(dash, |v| f(v[i]))
    };
    let rows: Vec<Vec<String>> = (0..n)
        .map(|i| {
            let has_damper = dampers.is_none_or(|d| d.contains(&(i as u64 + 1)));
            let mut row = vec![
                (i + 1).to_string(),
                mm(drift[i]),
                at(&ratio, i, &|v| format!("{:.3}", 100.0 * v)),
                at(&disp, i, &mm),
                at(&acc, i, &|v| format!("{v:.2}")),
                at(&resid, i, &mm),
                if has_damper {
                    at(&slip, i, &mm)
                } else {
                    dash()
                },
                if has_damper {
                    at(&trans, i, &|v| format!("{v:.0}"))
                } else {
                    dash()
                },
            ];
            if let Some(d) = &ductility {
                row.push(
                    d.get(i)
                        .copied()
                        .flatten()
                        .map_or("elastic".into(), |m| format!("{m:.2}")),
                );
                // plastic drift below 1 µm is round-off of a storey that never yielded
                row.push(at(&plastic, i, &mm));
            }
            row
        })
        .collect();
    grid(&head, &rows)
}

/// Whole-run responses: peak base shear (kN) and the energies (kJ).
fn run_totals(r: &serde_json::Value) -> Vec<(String, String)> {
    let mut rows = Vec::new();
    if let Some(v) = f64_at(r, "peak_base_shear") {
        rows.push(("peak base shear (kN)".into(), format!("{:.0}", v / 1e3)));
    }
    if let Some(e) = r.get("energy") {
        for (k, label) in [
            ("input", "input energy (kJ)"),
            ("kinetic", "kinetic energy at the end (kJ)"),
            ("strain", "strain energy at the end (kJ)"),
            ("viscous", "viscous energy (kJ)"),
            ("friction", "friction energy (kJ)"),
            ("plastic", "plastic energy of the frame (kJ)"),
        ] {
            if let Some(v) = f64_at(e, k) {
                rows.push((label.into(), kj(v)));
            }
        }
        if let Some(v) = f64_at(e, "balance_error") {
            rows.push((
                "energy balance error (kJ)".into(),
                format!("{:.1e}", v / 1e3),
            ));
        }
    }
    if let Some(c) = r.get("collapse").filter(|c| !c.is_null()) {
        rows.push((
            "collapse".into(),
            format!(
                "storey {} past its drift limit at t = {} s (peaks up to then)",
                c.get("storey").map_or("?".into(), |v| v.to_string()),
                f64_at(c, "time").map_or("?".into(), |t| sig(t, 4))
            ),
        ));
    }
    rows
}

/// What a scene ran on: building, ground motion (or force), scaling, as the facts of
/// the page's run table.
fn scene_facts(scene: &serde_json::Value, floors: usize) -> Vec<(String, String)> {
    let mut rows = Vec::new();
    let b = scene.get("building");
    let bname = b
        .and_then(|b| b.get("name"))
        .and_then(|n| n.as_str())
        .unwrap_or("(unnamed)");
    let dampers = damper_floors(scene).unwrap_or_default();
    let damper_text = match dampers.len() {
        0 => "no dampers".to_string(),
        1 => format!("a damper on floor {}", dampers[0]),
        _ => format!(
            "dampers on floors {}",
            dampers
                .iter()
                .map(u64::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    rows.push((
        "building".into(),
        format!(
            "{bname}: {floors} {}, {damper_text}",
            if floors == 1 { "storey" } else { "storeys" }
        ),
    ));
    let ex = scene.get("excitation");
    let record = ex.and_then(|e| e.get("record")).filter(|r| !r.is_null());
    let synthetic = ex.and_then(|e| e.get("synthetic")).filter(|r| !r.is_null());
    let (motion, scaling) = if let Some(r) = record {
        let file = r.get("file").and_then(|f| f.as_str()).unwrap_or("?");
        let name = Path::new(file)
            .file_name()
            .map_or(file.to_string(), |n| n.to_string_lossy().into_owned());
        let window = f64s_at(r, "window")
            .filter(|w| w.len() == 2)
            .map_or(String::new(), |w| {
                format!(", window {} s from {} s", sig(w[1], 6), sig(w[0], 6))
            });
        let scaling = match (f64_at(r, "scale_pga_g"), f64_at(r, "scale")) {
            (Some(p), _) => format!("scaled to a PGA of {} g", sig(p, 6)),
            (None, Some(f)) => format!("× {}", sig(f, 6)),
            (None, None) => "none (as recorded)".to_string(),
        };
        (format!("{name}{window}"), scaling)
    } else if let Some(syn) = synthetic {
        let pga = f64_at(syn, "pga_g").unwrap_or(slipload_motion::DEFAULT_SUITE_PGA_G);
        let motion = match (
            syn.get("seed").and_then(serde_json::Value::as_u64),
            syn.get("index").and_then(serde_json::Value::as_u64),
        ) {
            (Some(seed), _) => format!("synthetic record, seed {seed}"),
            (None, i) => format!("synthetic record {} of the embedded suite", i.unwrap_or(0)),
        };
        (motion, format!("scaled to a PGA of {} g", sig(pga, 6)))
    } else {
        ("none".to_string(), "—".to_string())
    };
    rows.push(("ground motion".into(), motion));
    rows.push(("scaling".into(), scaling));
    if let Some(h) = ex.and_then(|e| e.get("harmonic")).filter(|h| !h.is_null()) {
        rows.push(("harmonic force".into(), h.to_string()));
    }
    rows
}

/// The run of a `simulate --plot` folder: what ran (from `scene.json`, which
/// `simulate --plot` writes, and `response.json`), then the per-storey table and the
/// whole-run numbers in engineering units, with the bare frame's when the folder has it.
pub(super) fn simulation_run(
    scene: Option<&serde_json::Value>,
    r: &serde_json::Value,
    bare: Option<&serde_json::Value>,
) -> String {
    let floors = f64s_at(r, "peak_drift").map_or(0, |v| v.len());
    let mut facts = match scene {
        Some(s) => scene_facts(s, floors),
        None => vec![(
            "scene".to_string(),
            "not in the folder (scene.json is written by simulate --plot)".to_string(),
        )],
    };
    if let Some(m) = r.get("method").and_then(|m| m.as_str()) {
        facts.push(("method".into(), m.to_string()));
    }
    if let Some(dt) = f64_at(r, "dt") {
        let steps = r.get("steps").and_then(serde_json::Value::as_u64);
        facts.push((
            "time step Δt".into(),
            match steps {
                Some(n) => format!(
                    "{} s, {n} steps ({} s simulated)",
                    sig(dt, 6),
                    sig(dt * n as f64, 6)
                ),
                None => format!("{} s", sig(dt, 6)),
            },
        ));
    }
    let dampers = scene.and_then(damper_floors);
    let mut out = kv_table(&facts);
    out.push_str("<h3>Peak responses per storey</h3>\n");
    out.push_str(&storey_table(r, dampers.as_deref()));
    let totals = run_totals(r);
    if !totals.is_empty() {
        out.push_str(&kv_table(&totals));
    }
    if let Some(b) = bare {
        out.push_str("<h3>Bare frame (no braces: every slip load 0)</h3>\n");
        out.push_str(&storey_table(b, Some(&[][..])));
        let totals = run_totals(b);
        if !totals.is_empty() {
            out.push_str(&kv_table(&totals));
        }
    }
    out
}
