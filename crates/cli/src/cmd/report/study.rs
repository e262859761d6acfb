//! A study folder on a report page: the optimum's key numbers, the bounds it sits on,
//! what it costs against the building file's slip loads and the bare frame, and the
//! trade-off of a study with objectives.

use super::tables::{f64_at, f64s_at, grid, kv_table};
use crate::html::escape;
use std::fmt::Write as _;

/// The trade-off of a study with objectives, from `pareto.json`: the objectives, the
/// front's size and cost, the knee and each objective's optimum with their slip loads and
/// objectives, and whether the front held at the check fidelity.
pub(super) fn pareto_section(p: &serde_json::Value) -> String {
    let text = |v: &serde_json::Value| v.as_str().unwrap_or("").to_string();
    let list = |v: &serde_json::Value, digits: usize| {
        v.as_array()
            .map(|a| {
                a.iter()
                    .map(|x| x.as_f64().map_or("—".into(), |f| format!("{f:.digits$}")))
                    .collect::<Vec<_>>()
                    .join(" / ")
            })
            .unwrap_or_default()
    };
    let names: Vec<String> = p["objectives"]
        .as_array()
        .map(|a| a.iter().map(text).collect())
        .unwrap_or_default();
    // each objective's value: a drift ratio in percent of the storey height, as every
    // drift a person reads; the others as pareto.json holds them
    let objectives = |v: &serde_json::Value| {
        v.as_array()
            .map(|a| {
                a.iter()
                    .enumerate()
                    .map(|(k, x)| match x.as_f64() {
                        None => "—".to_string(),
                        Some(f) if names.get(k).is_some_and(|n| n.ends_with("drift_ratio")) => {
                            format!("{:.3} %", 100.0 * f)
                        }
                        Some(f) => format!("{f:.5}"),
                    })
                    .collect::<Vec<_>>()
                    .join(" / ")
            })
            .unwrap_or_default()
    };
    let front = p["front"].as_array().cloned().unwrap_or_default();
    let entry = |label: &str| {
        front
            .iter()
            .find(|e| e["label"].as_str() == Some(label))
            .map(|e| {
                format!(
                    "{} — slip loads {} kN; objectives (sweep) {}; (check) {}",
                    label,
                    list(&e["slip_loads_kN"], 1),
                    objectives(&e["sweep"]),
                    objectives(&e["check"])
                )
            })
            .unwrap_or_else(|| label.to_string())
    };
    let mut rows = vec![
        ("objectives".to_string(), names.join(" vs ")),
        (
            "front".to_string(),
            format!(
                "{} designs non-dominated of {} evaluated ({} sweep-fidelity simulations)",
                front.len(),
                p["sweep_designs"].as_u64().unwrap_or(0)
                    + p["search_designs"].as_u64().unwrap_or(0),
                p["sweep_fidelity_simulations"].as_u64().unwrap_or(0)
            ),
        ),
        ("knee".to_string(), entry(&text(&p["knee"]))),
    ];
    if let Some(ext) = p["extremes"].as_array() {
        for e in ext {
            rows.push((format!("optimum of {}", text(&e[0])), entry(&text(&e[1]))));
        }
    }
    let dominated: Vec<String> = p["dominated_at_check"]
        .as_array()
        .map(|a| a.iter().map(|d| text(&d[0])).collect())
        .unwrap_or_default();
    rows.push((
        "at the check fidelity".to_string(),
        if dominated.is_empty() {
            "the front held: no design became dominated".to_string()
        } else {
            format!("dominated now: {}", dominated.join(", "))
        },
    ));
    rows.push((
        "hypervolume".to_string(),
        format!(
            "{:.6e} against the reference point {}",
            p["hypervolume"].as_f64().unwrap_or(f64::NAN),
            list(&p["reference_point"], 6)
        ),
    ));
    kv_table(&rows)
}

/// `optimum.json`'s `on_bound` entries as a sentence: "floor 2 at its upper bound
/// (2000.0 kN)"; a profile's scale names the floors it sets.
fn on_bound_text(o: &serde_json::Value) -> Option<String> {
    let entries = o.get("on_bound")?.as_array()?;
    if entries.is_empty() {
        return None;
    }
    let floors: Vec<u64> = o
        .get("damper_floors")
        .and_then(|v| v.as_array())
        .map(|a| a.iter().filter_map(serde_json::Value::as_u64).collect())
        .unwrap_or_default();
    let loads = f64s_at(o, "slip_loads_kN").unwrap_or_default();
    let load_of = |f: u64| {
        floors
            .iter()
            .position(|&x| x == f)
            .and_then(|k| loads.get(k))
            .map(|v| format!("{v:.1} kN"))
    };
    let parts: Vec<String> = entries
        .iter()
        .map(|b| {
            let fl: Vec<u64> = b
                .get("floors")
                .and_then(|v| v.as_array())
                .map(|a| a.iter().filter_map(serde_json::Value::as_u64).collect())
                .unwrap_or_default();
            let bound = b.get("bound").and_then(|v| v.as_str()).unwrap_or("?");
            let variable = b.get("variable").and_then(|v| v.as_str()).unwrap_or("?");
            let at: Vec<String> = fl.iter().filter_map(|&f| load_of(f)).collect();
            let names: Vec<String> = fl.iter().map(u64::to_string).collect();
            if fl.len() == 1 && variable.starts_with("floor") {
                format!("floor {} at its {bound} bound ({})", names[0], at.join(""))
            } else {
                format!(
                    "{variable} (floors {}) at its {bound} bound ({})",
                    names.join(", "),
                    at.join(" / ")
                )
            }
        })
        .collect();
    Some(parts.join("; "))
}

/// The property case a study's objective values are read at, from its manifest: `at the
/// worst properties` or `at nominal properties` where the study names property bounds
/// (a cost objective, the same in every case, and a study without bounds need none).
pub(super) fn objective_case(manifest: Option<&serde_json::Value>) -> Option<&'static str> {
    let m = manifest?;
    if m.get("objective").and_then(|o| o.get("cost")).is_some() {
        return None;
    }
    let bounds = m.get("checks")?.get("property_bounds")?;
    if bounds.is_null() {
        return None;
    }
    Some(
        match bounds.get("objective_reads").and_then(|r| r.as_str()) {
            Some("worst") => "at the worst properties",
            _ => "at nominal properties",
        },
    )
}

/// The optimum's key numbers as a table, the floors on a bound of the design space, and
/// what the optimum costs in base shear and floor acceleration against the building
/// file's slip loads and the bare frame (from `design-table.json`), rounded as the
/// design tables round them; with property bounds each objective value names the case
/// it was read at (from the study's `manifest`).
pub(super) fn key_results(
    o: &serde_json::Value,
    table: Option<&serde_json::Value>,
    manifest: Option<&serde_json::Value>,
) -> String {
    let num = |k: &str| f64_at(o, k);
    let case = objective_case(manifest).map_or(String::new(), |c| format!(" {c}"));
    let mut rows: Vec<(String, String)> = Vec::new();
    if let Some(s) = o.get("objective").and_then(|s| s.as_str()) {
        rows.push(("objective".into(), s.to_string()));
    }
    if let Some(loads) = f64s_at(o, "slip_loads_kN") {
        let floors: Vec<String> = o
            .get("damper_floors")
            .and_then(|v| v.as_array())
            .map(|a| a.iter().map(|f| f.to_string()).collect())
            .unwrap_or_default();
        let loads: Vec<String> = loads.iter().map(|v| format!("{v:.1}")).collect();
        rows.push((
            format!("optimal slip loads (kN), floors {}", floors.join(" / ")),
            loads.join(" / "),
        ));
    }
    if let Some(f) = num("objective_value") {
        rows.push((format!("objective at the optimum{case}"), format!("{f:.6}")));
    }
    let lower = |f: f64, b: f64| format!("{b:.6} (optimum {:.1} % lower)", 100.0 * (1.0 - f / b));
    if let (Some(f), Some(b)) = (num("objective_value"), num("bare_objective")) {
        rows.push((format!("bare frame{case}"), lower(f, b)));
    }
    if let (Some(f), Some(b)) = (num("objective_value"), num("file_objective")) {
        rows.push((format!("building file's slip loads{case}"), lower(f, b)));
    }
    if let Some(s) = o.get("refiner").and_then(|s| s.as_str()) {
        rows.push(("refiner".into(), s.to_string()));
    }
    let mut out = String::new();
    if let Some(t) = on_bound_text(o) {
        let _ = writeln!(
            out,
            "<p class=\"warn\"><strong>On a bound of the design space</strong> (the optimum may lie beyond it: widen the bound to see): {}</p>",
            escape(&t)
        );
    }
    if !rows.is_empty() {
        out.push_str(&kv_table(&rows));
    }
    if let Some(t) = table {
        out.push_str(&costs(t, &case));
    }
    out
}

/// What the optimum costs: mean peak base shear and floor acceleration of the optimum,
/// the building file's slip loads and the bare frame (rows of `design-table.json`).
fn costs(table: &serde_json::Value, case: &str) -> String {
    let Some(rows) = table.get("rows").and_then(|r| r.as_array()) else {
        return String::new();
    };
    let row = |name: &str| {
        rows.iter()
            .find(|r| r.get("design").and_then(|d| d.as_str()) == Some(name))
    };
    let mut body: Vec<Vec<String>> = Vec::new();
    for (name, label) in [
        ("optimum", "optimum"),
        ("file", "building file's slip loads"),
        ("bare", "bare frame"),
    ] {
        let Some(r) = row(name) else { continue };
        let loads = f64s_at(r, "slip_load_kn").unwrap_or_default();
        body.push(vec![
            label.to_string(),
            loads
                .iter()
                .map(|v| format!("{v:.1}"))
                .collect::<Vec<_>>()
                .join(" / "),
            f64_at(r, "objective").map_or("—".into(), |v| format!("{v:.5}")),
            f64_at(r, "base_shear_mean").map_or("—".into(), |v| format!("{:.2}", v / 1e6)),
            f64_at(r, "peak_floor_acceleration_mean").map_or("—".into(), |v| format!("{v:.2}")),
        ]);
    }
    if body.is_empty() {
        return String::new();
    }
    let fidelity = table.get("fidelity").and_then(|f| f.as_str()).unwrap_or("");
    format!(
        "<h3>What the optimum costs</h3>\n<p>Means over the records of each run's peak ({}).</p>\n{}",
        escape(fidelity),
        grid(
            &[
                "design".into(),
                "slip loads (kN)".into(),
                format!("objective{case}"),
                "peak base shear (MN)".into(),
                "peak floor acceleration (m/s²)".into(),
            ],
            &body,
        )
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_objective_value_names_its_case_where_the_study_has_bounds() {
        let optimum = serde_json::json!({
            "objective": "mean peak_drift_ratio",
            "objective_value": 0.0064,
            "bare_objective": 0.0113,
            "slip_loads_kN": [2746.856, 464.46],
            "damper_floors": [1, 2]
        });
        let bounds = |reads: &str| {
            serde_json::json!({
                "objective": { "terms": [] },
                "checks": { "property_bounds": { "slip_load": { "lower": 0.85, "upper": 1.15 }, "objective_reads": reads } }
            })
        };
        let worst = key_results(&optimum, None, Some(&bounds("worst")));
        assert!(
            worst.contains("objective at the optimum at the worst properties"),
            "{worst}"
        );
        assert!(
            worst.contains("bare frame at the worst properties"),
            "{worst}"
        );
        assert!(
            worst.contains("2746.9 / 464.5"),
            "slip loads to 0.1 kN: {worst}"
        );
        let nominal = key_results(&optimum, None, Some(&bounds("nominal")));
        assert!(nominal.contains("objective at the optimum at nominal properties"));
        // one case (no bounds), a cost objective: no label
        let none = serde_json::json!({ "objective": { "terms": [] }, "checks": {} });
        assert_eq!(objective_case(Some(&none)), None);
        let cost = serde_json::json!({
            "objective": { "terms": [], "cost": { "per_kn": 1.0 } },
            "checks": { "property_bounds": { "objective_reads": "worst" } }
        });
        assert_eq!(objective_case(Some(&cost)), None);
        assert!(key_results(&optimum, None, None).contains("<th>objective at the optimum</th>"));
    }
}
