//! Contract (issue 48 §3): a study keeps the building it ran in its folder —
//! `building.json`, a building file that loads back into the very building the study ran
//! (to the bit: masses, stiffnesses, damping, heights, dampers, yield laws, P-Δ loads,
//! collapse limit), with the damping as the file gives it; and `building.md`, the report's
//! first page, whose tables state every input in the report's units with the numbers of
//! the building the library loads (six significant digits; slip loads to 0.1 kN).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::phases::building::BuildingPage;
use slipload_sim::Building;
use slipload_sim::building::storey_stiffness;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

fn configs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs")
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slipload-building-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The yielding ten-storey frame with P-Δ (its file's yield drifts, default gravity loads
/// and default collapse limit), the study's own collapse limit of 8 % and chevron braces
/// at 40° (a device table needs limits: one on the mean drift), on two 2-s synthetic
/// records.
fn yielding_study() -> Study {
    let text = r#"{ "building": "ten-story-yielding.json",
      "suites": [ { "name": "s", "synthetic": { "count": 2, "seed": 3, "pga_g": 0.3, "duration_s": 2 },
                    "limits": { "criteria": [ { "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.03 } ] } } ],
      "collapse_drift_ratio": 0.08,
      "devices": { "brace_angle_deg": 40, "braces_per_damper": 2 },
      "space": { "profile": { "shape": "uniform", "scale_kn": [0, 2000] } },
      "objective": { "terms": [ { "metric": "peak_drift_ratio", "statistic": "mean" } ] },
      "fidelity": { "method": "newmark" },
      "sweep": { "sampler": "halton", "points": 2, "seed": 1 } }"#;
    Study::from_json(text, &configs().join("study-building-page.json")).unwrap()
}

/// The benchmark building inlined, its damping given as Rayleigh ratios at modes 1 and 3,
/// the second damper with asymmetric bounds and the third locked.
fn benchmark_study() -> Study {
    let mut b: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(configs().join("benchmark-3story.json")).unwrap(),
    )
    .unwrap();
    b["damping"] = serde_json::json!({ "rayleigh": { "ratio": 0.05, "modes": [1, 3] } });
    b["dissipators"][1]["slip_load"] = serde_json::Value::Null;
    b["dissipators"][1]["bounds"] = serde_json::json!(["-300 kN", "412.5 kN"]);
    b["dissipators"][2]["slip_load"] = "locked".into();
    let path = configs().join("study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["building"] = b;
    v["suites"][0]["synthetic"]["count"] = 2.into();
    v["suites"][0]["synthetic"]["duration_s"] = 2.0.into();
    v["sweep"]["points"] = 2.into();
    v["fidelity"]["method"] = "newmark".into();
    Study::from_json(&v.to_string(), &path).unwrap()
}

/// `building.json` loads back into the building the study ran, to the bit.
fn loads_back(study: &Study, page: &BuildingPage, name: &str) -> serde_json::Value {
    let dir = scratch(name);
    let file = dir.join("building.json");
    std::fs::write(&file, &page.json).unwrap();
    let b2 = Building::load(&file).unwrap();
    let b = &study.building;
    assert_eq!(b2.name, b.name);
    assert_eq!(b2.mass, b.mass);
    assert_eq!(b2.stiffness, b.stiffness);
    assert_eq!(b2.damping, b.damping);
    assert_eq!(b2.storey_heights, b.storey_heights);
    assert_eq!(b2.dissipators, b.dissipators);
    assert_eq!(b2.storey_yield, b.storey_yield);
    assert_eq!(b2.gravity_loads, b.gravity_loads);
    assert_eq!(b2.collapse_drift, b.collapse_drift);
    std::fs::remove_dir_all(&dir).unwrap();
    serde_json::from_str(&page.json).unwrap()
}

/// The rows of the Markdown table under `## HEADING`, each a map from column title to
/// cell text.
fn table(md: &str, heading: &str) -> Vec<HashMap<String, String>> {
    let start = md
        .find(&format!("## {heading}\n"))
        .unwrap_or_else(|| panic!("no {heading} in\n{md}"));
    let cells = |l: &str| -> Vec<String> {
        l.trim()
            .trim_matches('|')
            .split(" | ")
            .map(|c| c.trim().to_string())
            .collect()
    };
    let mut lines = md[start..]
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'));
    let head = cells(lines.next().unwrap());
    lines.next(); // the alignment row
    lines
        .map(|l| head.iter().cloned().zip(cells(l)).collect())
        .collect()
}

/// The cell of `row` under `column` is `want` to its six significant digits.
fn close(row: &HashMap<String, String>, column: &str, want: f64) {
    let cell = row
        .get(column)
        .unwrap_or_else(|| panic!("no column {column:?} in {row:?}"));
    let shown: f64 = cell
        .parse()
        .unwrap_or_else(|_| panic!("{column}: {cell:?}"));
    // six significant digits: at most half a unit of the sixth digit
    assert!(
        (shown - want).abs() <= 5e-6 * want.abs() + 1e-12,
        "{column}: shown {shown}, building {want}"
    );
}

#[test]
fn a_yielding_frame_is_stated_as_it_ran() {
    let study = yielding_study();
    let page = BuildingPage::of(&study).unwrap();
    let json = loads_back(&study, &page, "yielding");
    let b = &study.building;
    let n = b.floors();
    // what the file left to defaults, and the study's override, made explicit
    assert_eq!(json["collapse_drift_ratio"], 0.08);
    assert_eq!(json["storey_yield"].as_array().unwrap().len(), n);
    assert!(json["storey_yield"][0]["yield_shear"].is_number());
    assert_eq!(
        json["p_delta"]["gravity_loads"].as_array().unwrap().len(),
        n
    );
    assert_eq!(
        json["damping"],
        serde_json::json!({ "modal": { "ratio": 0.02 } })
    );

    let md = &page.markdown;
    assert!(
        md.starts_with("# Building: ten\\-story\\-yielding\n"),
        "{md}"
    );
    let frame = table(md, "Frame");
    assert_eq!(frame.len(), n);
    let cfg = &study.building_config;
    for (i, r) in frame.iter().enumerate() {
        assert_eq!(r["storey"], (i + 1).to_string());
        close(r, "height (m)", b.storey_heights.as_ref().unwrap()[i]);
        close(r, "floor mass (t)", b.mass[(i, i)] / 1e3);
        close(
            r,
            "storey stiffness (kN/m)",
            cfg.storey_stiffness.as_ref().unwrap()[i].0 / 1e3,
        );
        let y = b.storey_yield[i].unwrap();
        close(r, "yield stiffness k (kN/m)", y.stiffness / 1e3);
        close(r, "yield shear F_y (kN)", y.yield_shear / 1e3);
        close(r, "yield drift (mm)", y.yield_drift() * 1e3);
        close(r, "post-yield ratio α", y.post_yield_ratio);
        close(
            r,
            "P-Δ gravity load P (kN)",
            b.gravity_loads.as_ref().unwrap()[i] / 1e3,
        );
    }
    // the file's yield drift (26.25 mm) is what the table shows
    assert_eq!(frame[0]["yield drift (mm)"], "26.25");
    assert!(
        md.contains("**Inherent damping:** modal, 2 % of critical in every mode."),
        "{md}"
    );
    assert!(
        md.contains("**Collapse:** a run stops when a storey drifts past 8 % of its height (the study's `collapse_drift_ratio`)."),
        "{md}"
    );
    assert!(md.contains("the gravity load of the table (g = 9.80665 m/s² times the mass at and above the storey, the default)"), "{md}");
    // modal damping: every mode listed at 2 %
    assert_eq!(md.matches(", ζ = 2.00 %").count(), 6, "{md}");

    let dampers = table(md, "Dampers");
    let floors: Vec<usize> = (0..n).filter(|&f| b.dissipators[f].is_some()).collect();
    assert_eq!(dampers.len(), floors.len());
    let c = 40f64.to_radians().cos();
    for (r, &f) in dampers.iter().zip(&floors) {
        let d = b.dissipators[f].unwrap();
        assert_eq!(r["floor"], (f + 1).to_string());
        close(
            r,
            "brace stiffness k′ (kN/m, horizontal)",
            d.brace_stiffness / 1e3,
        );
        close(
            r,
            "axial stiffness per brace (kN/m)",
            d.brace_stiffness / (2.0 * c * c) / 1e3,
        );
        close(r, "dissipator mass m′ (kg)", d.mass);
        let shown: f64 = r["slip load in the building file (kN)"].parse().unwrap();
        assert!((shown - d.upper / 1e3).abs() <= 0.05 + 1e-9, "{r:?}");
    }
    assert!(
        md.contains("2 braces at 40 ° to the horizontal per damper"),
        "{md}"
    );
}

#[test]
fn a_frame_given_by_matrices_and_rayleigh_ratios_is_stated_as_given() {
    let study = benchmark_study();
    let page = BuildingPage::of(&study).unwrap();
    let json = loads_back(&study, &page, "matrices");
    let b = &study.building;
    // Rayleigh stays as given (its ratios and modes), not as α and β
    assert_eq!(
        json["damping"],
        serde_json::json!({ "rayleigh": { "ratio": 0.05, "modes": [1, 3] } })
    );
    assert_eq!(json["dissipators"][1]["bounds"][0], -300e3);
    assert_eq!(json["dissipators"][2]["slip_load"], "locked");
    assert!(json.get("collapse_drift_ratio").is_none() && json.get("p_delta").is_none());

    let md = &page.markdown;
    let frame = table(md, "Frame");
    for (i, r) in frame.iter().enumerate() {
        close(r, "floor mass (t)", b.mass[(i, i)] / 1e3);
        close(
            r,
            "storey stiffness (kN/m; of the frame's stiffness matrix, shear over drift)",
            storey_stiffness(&b.stiffness, i).unwrap() / 1e3,
        );
        assert!(!r.contains_key("yield shear F_y (kN)"), "an elastic frame");
    }
    assert!(
        md.contains("gives the frame's `stiffness_matrix` as a matrix"),
        "{md}"
    );
    assert!(
        md.contains(
            "**Inherent damping:** Rayleigh, 5 % of critical at the bare frame's modes 1 and 3."
        ),
        "{md}"
    );
    // the ratios hold at the two modes named (5.00 %), and mode 2 lies below them
    assert!(md.contains("mode 1: T = "), "{md}");
    let zeta = |k: usize| -> f64 {
        let at = md.find(&format!("mode {k}: T = ")).unwrap();
        md[at..].split("ζ = ").nth(1).unwrap()[..4].parse().unwrap()
    };
    assert_eq!((zeta(1), zeta(3)), (5.0, 5.0));
    assert!(zeta(2) < 5.0);
    assert!(md.contains("**Collapse:** no limit"), "{md}");
    let dampers = table(md, "Dampers");
    assert_eq!(dampers.len(), 3);
    assert_eq!(dampers[0]["slip load in the building file (kN)"], "834.1");
    assert_eq!(
        dampers[1]["slip load in the building file (kN)"],
        "-300.0..412.5"
    );
    assert_eq!(dampers[2]["slip load in the building file (kN)"], "locked");
    assert!(
        md.contains("The study states no brace configuration"),
        "{md}"
    );
}
