//! Contract (issue 38): `slipload optimize` of a study with property bounds and limits
//! ends its summary with the verdict and writes the code check and the device table; a
//! study whose limits no design can meet still writes every file, names the governing
//! limit and the closest design on stderr, and exits with code 3 — not 0 (success), 1
//! (an error) or 2 (a usage error) — so a script can tell "ran, no acceptable design"
//! from a crash.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use std::path::{Path, PathBuf};
mod common;
use common::{root, slipload_in as run_in};

fn study(dir: &Path, drift: f64) -> PathBuf {
    study_with(dir, drift, r#""brace_angle_deg": 40"#)
}

/// The study with `devices` holding `devices` (JSON members).
fn study_with(dir: &Path, drift: f64, devices: &str) -> PathBuf {
    let text = format!(
        r#"{{ "name": "check-cli", "building": "{building}",
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": 2, "seed": 2007, "pga_g": 0.4, "duration_s": 4.0 }},
                 "limits": {{ "criteria": [ {{ "metric": "peak_drift_ratio", "statistic": "mean", "max": {drift} }} ],
                              "unacceptable": {{ "max_count": 0 }} }} }} ],
  "property_bounds": {{ "slip_load": {{ "lower": 0.8, "upper": 1.25 }} }},
  "devices": {{ {devices} }},
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark", "check_method": "newmark", "check_dt_factor": 0.5 }},
  "sweep": {{ "sampler": "halton", "points": 6, "seed": 2007 }},
  "refine": {{ "method": "trust-region", "starts": 1, "max_evaluations": 4, "finalists": 2 }} }}"#,
        building = root().join("configs/benchmark-3story.json").display()
    );
    std::fs::create_dir_all(dir).unwrap();
    let p = dir.join("study.json");
    std::fs::write(&p, text).unwrap();
    p
}

/// `slipload --quiet optimize STUDY --out o` in `dir`, which must exit with `code`.
fn optimize(dir: &Path, study: &Path, code: i32) -> std::process::Output {
    let out = run_in(
        dir,
        &["--quiet", "optimize", study.to_str().unwrap(), "--out", "o"],
    );
    assert_eq!(
        out.status.code(),
        Some(code),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

const FILES: [&str; 6] = [
    "code-check.csv",
    "code-check.md",
    "code-check.json",
    "device-table.csv",
    "device-table.md",
    "device-table.json",
];

#[test]
fn a_passing_design_ends_with_its_verdict() {
    let dir = common::scratch("check", "pass");
    let s = study(&dir, 0.012);
    let out = optimize(&dir, &s, 0);
    let text = String::from_utf8_lossy(&out.stdout);
    let last = text.lines().last().unwrap();
    assert!(last.starts_with("verdict: PASS (governing: "), "{last}");
    // whether the bare frame and the file's design met the limits already, as the
    // optimum.json says it
    let optimum: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("o/optimum.json")).unwrap())
            .unwrap();
    let says = |key: &str| {
        if optimum[key].as_bool().unwrap() {
            "meets every limit"
        } else {
            "misses a limit"
        }
    };
    let line = format!(
        "limits: the bare frame {}, the building file's design {}",
        says("bare_passes"),
        says("file_passes")
    );
    assert!(text.contains(&line), "{line:?} not in\n{text}");
    assert!(text.contains("devices to specify"), "{text}");
    assert!(
        text.contains("lower properties (slip loads × 0.8"),
        "{text}"
    );
    for f in FILES {
        assert!(dir.join("o").join(f).is_file(), "{f}");
    }
    assert_eq!(optimum["objective_value_is"], "objective");
}

#[test]
fn no_acceptable_design_exits_3_after_writing_its_files() {
    let dir = common::scratch("check", "fail");
    let s = study(&dir, 0.001);
    let out = optimize(&dir, &s, 3);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no evaluated design meets the study's limits")
            && err.contains("governing limit")
            && err.contains("misses by"),
        "{err}"
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.lines().last().unwrap().starts_with("verdict: FAIL"),
        "{text}"
    );
    for f in FILES {
        assert!(dir.join("o").join(f).is_file(), "{f}");
    }
    // optimum.json says which number it gives: the closest design's sum of exceedances
    let optimum: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("o/optimum.json")).unwrap())
            .unwrap();
    assert_eq!(optimum["objective_value_is"], "sum_of_exceedances");
    assert!(
        optimum["objective_value"].as_f64().unwrap() > 0.0,
        "{optimum}"
    );
    // run again: everything from the journals, the same verdict and exit code
    optimize(&dir, &s, 3);
}

/// `devices.stroke_capacity_mm`: the device table states each damper's stroke against
/// it, and the check counts a run past it as an unacceptable response (the check's
/// arithmetic is tested in `model::check`); a capacity that is no stroke is refused.
#[test]
fn a_stated_stroke_capacity_is_in_the_device_table_and_a_bad_one_is_refused() {
    let dir = common::scratch("check", "stroke");
    let s = study_with(
        &dir,
        0.012,
        r#""brace_angle_deg": 40, "stroke_capacity_mm": 500"#,
    );
    optimize(&dir, &s, 0);
    let md = std::fs::read_to_string(dir.join("o/device-table.md")).unwrap();
    assert!(
        md.contains("Stroke capacity 500.0 mm each way (`devices.stroke_capacity_mm`)"),
        "{md}"
    );
    let table: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("o/device-table.json")).unwrap())
            .unwrap();
    assert_eq!(table["stroke_capacity_mm"], 500.0);
    // the code check says what its count of unacceptable responses counts
    let check = std::fs::read_to_string(dir.join("o/code-check.md")).unwrap();
    assert!(
        check.contains("a damper travels past the devices' stroke capacity of 500.0 mm each way"),
        "{check}"
    );
    // every damper of the passing design within it; each suite's mean stroke names the
    // property case it is taken at, in the JSON and beside the number in the Markdown
    for d in table["dampers"].as_array().unwrap() {
        for s in d["stroke_mm"].as_array().unwrap() {
            assert!(s.as_f64().unwrap() <= 500.0, "{d}");
        }
        for st in d["stroke_by_suite"].as_array().unwrap() {
            let case = st["mean_case"].as_str().unwrap();
            assert!(["nominal", "lower", "upper"].contains(&case), "{st}");
            let shown = format!(
                "{:.1} ({case}) / {:.1}",
                st["mean_mm"].as_f64().unwrap(),
                st["max_mm"].as_f64().unwrap()
            );
            assert!(md.contains(&shown), "{shown} not in {md}");
        }
    }
    // a number that is no stroke names the field; a text names the line (a JSON type)
    for (bad, says) in [
        ("0", "devices.stroke_capacity_mm"),
        ("-5", "devices.stroke_capacity_mm"),
        (r#""50 mm""#, "expected f64 at line 6"),
    ] {
        let d = dir.join(format!("bad{}", bad.len()));
        let s = study_with(&d, 0.012, &format!(r#""stroke_capacity_mm": {bad}"#));
        let out = optimize(&d, &s, 1);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{bad}: {err}");
        assert!(!d.join("o").exists());
    }
}

/// `devices.test_protocol`: the device table's protocol takes each damper's amplitude from
/// the table's own mean stroke of the suite (the only suite here, not at MCE_R, which it
/// says), its force range from the property bounds, the loop energy 4FA and the velocity
/// 2πA/T_1M; counts and bands out of range name their field and write nothing.
#[test]
fn a_test_protocol_is_computed_from_the_device_tables_strokes() {
    let dir = common::scratch("check", "protocol");
    let s = study_with(
        &dir,
        0.012,
        r#""brace_angle_deg": 40, "test_protocol": { "cycles": 5, "band_percent": 15, "production_cycles": 3, "displacement_factor": 1.2 }"#,
    );
    optimize(&dir, &s, 0);
    let md = std::fs::read_to_string(dir.join("o/device-table.md")).unwrap();
    for says in [
        "## Test protocol",
        "5 fully reversed sinusoidal cycles",
        "within ±15 % of their averages",
        "no suite is at MCE_R",
        "times the study's displacement factor 1.2",
        "**Production test**, every unit: 3 cycles",
        "the study claims the exemption",
    ] {
        assert!(md.contains(says), "{says} not in {md}");
    }
    let table: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("o/device-table.json")).unwrap())
            .unwrap();
    let p = &table["test_protocol"];
    assert_eq!(p["suite"], "syn");
    assert_eq!(p["at_mce_r"], false);
    let t1m = p["t1m_s"].as_f64().unwrap();
    // the dampers stiffen the bare frame until they slip: T_1M below the bare T1
    assert!(t1m > 0.0 && t1m < p["t1_s"].as_f64().unwrap(), "{p}");
    let rel = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-300);
    let rows = table["dampers"].as_array().unwrap();
    let tests = p["dampers"].as_array().unwrap();
    assert_eq!(rows.len(), tests.len());
    for (r, t) in rows.iter().zip(tests) {
        let stroke = r["stroke_by_suite"][0]["mean_mm"].as_f64().unwrap();
        let a = t["amplitude_mm"].as_f64().unwrap();
        assert!(rel(a, 1.2 * stroke), "{t} vs {r}");
        let f = t["force_kn"].as_array().unwrap();
        let range = r["slip_load_range_kn"].as_array().unwrap();
        for (got, want) in f.iter().zip([&r["slip_load_kn"], &range[0], &range[1]]) {
            assert_eq!(got, want, "{t}");
        }
        for (e, f) in t["loop_energy_kj"].as_array().unwrap().iter().zip(f) {
            assert!(
                rel(e.as_f64().unwrap(), 4.0 * f.as_f64().unwrap() * a / 1e3),
                "{t}"
            );
        }
        let v = t["velocity_mm_s"].as_f64().unwrap();
        assert!(rel(v, 2.0 * std::f64::consts::PI * a / t1m), "{t}");
    }
    for (bad, says) in [
        (
            r#""cycles": 0, "band_percent": 15"#,
            "devices.test_protocol.cycles",
        ),
        (
            r#""cycles": 5, "band_percent": 0"#,
            "devices.test_protocol.band_percent",
        ),
        (
            r#""cycles": 5, "band_percent": 15, "displacement_factor": 0.5"#,
            "devices.test_protocol.displacement_factor",
        ),
    ] {
        let d = dir.join(format!("bad{}", bad.len()));
        let s = study_with(&d, 0.012, &format!(r#""test_protocol": {{ {bad} }}"#));
        let out = optimize(&d, &s, 1);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{bad}: {err}");
        assert!(!d.join("o").exists());
    }
}

/// A suite with a residual limit and `free_vibration_s`: the code check says where the
/// residual is read and names every run whose residual alone exceeds the limit (each
/// named run past it, as many as the runs past it in the suite's responses).
#[test]
fn the_code_check_names_the_runs_past_a_residual_limit_after_the_free_vibration() {
    let dir = common::scratch("check", "residual-tail");
    let text = format!(
        r#"{{ "name": "tail", "building": "{building}",
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": 3, "seed": 11, "pga_g": 0.5, "duration_s": 6.0 }},
                 "free_vibration_s": 20,
                 "limits": {{ "criteria": [ {{ "metric": "residual_drift_ratio", "statistic": "mean", "max": 0.5 }},
                                           {{ "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.05 }} ] }} }} ],
  "property_bounds": {{ "slip_load": {{ "lower": 0.8, "upper": 1.25 }} }},
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [300, 300, 300] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark", "check_method": "newmark", "check_dt_factor": 0.5 }},
  "sweep": {{ "sampler": "halton", "points": 4, "seed": 2007 }},
  "refine": {{ "method": "trust-region", "starts": 1, "max_evaluations": 2, "finalists": 1 }} }}"#,
        building = root().join("configs/benchmark-3story.json").display()
    );
    std::fs::create_dir_all(&dir).unwrap();
    let s = dir.join("study.json");
    // a limit of 0.5 (50 %) no run reaches
    std::fs::write(&s, &text).unwrap();
    optimize(&dir, &s, 0);
    let md = std::fs::read_to_string(dir.join("o/code-check.md")).unwrap();
    assert!(
        md.contains("Residual drift (the largest storey drift ratio left when the run ends) read after 20 s of free vibration; runs whose residual alone exceeds 50.00 %: none."),
        "{md}"
    );
    // a limit of 1e-5 most runs pass: every run named is past it, with its value
    let d2 = dir.join("tight");
    std::fs::create_dir_all(&d2).unwrap();
    let s2 = d2.join("study.json");
    std::fs::write(&s2, text.replace(r#""max": 0.5 }"#, r#""max": 0.00001 }"#)).unwrap();
    optimize(&d2, &s2, 3);
    let check: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d2.join("o/code-check.json")).unwrap())
            .unwrap();
    let tail = &check["residual_tails"][0];
    assert_eq!(tail["free_vibration_s"], 20.0);
    let runs = tail["runs"].as_array().unwrap();
    assert!(!runs.is_empty(), "{tail}");
    for r in runs {
        assert!(r[1].as_f64().unwrap() > 1e-5, "{r}");
    }
    let md = std::fs::read_to_string(d2.join("o/code-check.md")).unwrap();
    // named as Markdown text (punctuation escaped: a record's name is a file name)
    let name = runs[0][0].as_str().unwrap();
    let escaped: String = name
        .chars()
        .flat_map(|c| {
            let esc = c.is_ascii_punctuation().then_some('\\');
            esc.into_iter().chain(std::iter::once(c))
        })
        .collect();
    assert!(md.contains(&escaped), "{escaped} not in {md}");
}
