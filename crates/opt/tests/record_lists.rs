//! Record lists as engineers give them: a pattern's `.AT2` matches `.at2` too (PEER files
//! come with either), and a record scaled far from the rest of its suite is named among
//! the study's warnings — while the shipped examples warn about nothing.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use std::path::Path;

/// A study of the benchmark building over one suite of `records` (paths from configs/),
/// scaled by `scale` (a JSON object).
fn study(records: &[&str], scale: &str) -> Result<Study, String> {
    let list: Vec<String> = records.iter().map(|r| format!("\"{r}\"")).collect();
    let text = format!(
        r#"{{ "name": "lists", "building": "benchmark-3story.json",
  "suites": [ {{ "name": "s", "records": [{}], "scale": {scale} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark", "check_method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 1 }} }}"#,
        list.join(", ")
    );
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/lists.json");
    Study::from_json(&text, &path).map_err(|e| e.to_string())
}

#[test]
fn a_patterns_at2_takes_the_lower_case_files_too() {
    // records/ARL360.at2 is the one file of records/ named in lower case
    let s = study(&["../records/ARL*.AT2"], r#"{ "pga_g": 0.4 }"#).unwrap();
    assert_eq!(s.records.len(), 1);
    assert!(
        s.records[0].name().ends_with("ARL360.at2"),
        "{}",
        s.records[0].name()
    );
    // the rest of the name is as written
    let e = study(&["../records/arl*.AT2"], r#"{ "pga_g": 0.4 }"#).unwrap_err();
    assert!(e.contains("matches no file"), "{e}");
}

#[test]
fn a_record_scaled_far_from_its_suite_is_named() {
    // PGAs 0.17, 0.13, 0.24, 0.25 and 1.22 g, one factor: San Fernando's Pacoima record
    // at 5 x the suite's median
    let records = [
        "../records/WON185.AT2",
        "../records/RSN1148_KOCAELI_ARE090.AT2",
        "../records/RSN900_LANDERS_YER270.AT2",
        "../records/RSN777_LOMAP_HCH090.AT2",
        "../records/RSN77_SFERN_PUL164.AT2",
    ];
    let s = study(&records, r#"{ "factor": 1.0 }"#).unwrap();
    let w: Vec<String> = s
        .warnings()
        .into_iter()
        .filter(|w| w.contains("median PGA"))
        .collect();
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].contains("RSN77_SFERN_PUL164.AT2") && w[0].contains("x the suite's median"),
        "{}",
        w[0]
    );
    // the same records each scaled to one PGA: nothing to name
    let s = study(&records, r#"{ "pga_g": 0.4 }"#).unwrap();
    assert!(!s.warnings().iter().any(|w| w.contains("median PGA")));
}

#[test]
fn the_shipped_code_scaled_examples_warn_about_nothing() {
    for name in [
        "study-ten-story-check.json",
        "study-ten-story-least-slip-load.json",
    ] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../configs")
            .join(name);
        let s = Study::load(&path).unwrap();
        assert!(s.warnings().is_empty(), "{name}: {:?}", s.warnings());
    }
}

/// What the model cannot show that a check counts is said: the elastic benchmark frame
/// checked at MCE_R, and a count of unacceptable responses on a frame that cannot collapse
/// with no per-record limit (0 whatever the design) — in the study's warnings and in the
/// code check.
#[test]
fn what_the_model_cannot_show_is_named() {
    let text = r#"{ "name": "elastic-mce", "building": "benchmark-3story.json",
  "suites": [ { "name": "mce", "records": ["../records/RSN*.AT2"],
                "scale": { "code_spectrum": { "sds_g": 0.5, "sd1_g": 0.3, "tl_s": 8, "hazard": "mce_r" } },
                "limits": { "criteria": [ { "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.03 } ],
                            "unacceptable": { "max_count": 1 } } } ],
  "space": { "free": { "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] } },
  "objective": { "terms": [ { "metric": "peak_drift_ratio", "statistic": "mean" } ] },
  "fidelity": { "method": "newmark", "check_method": "newmark" },
  "sweep": { "sampler": "halton", "points": 2, "seed": 1 } }"#;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/elastic-mce.json");
    let s = Study::from_json(text, &path).unwrap();
    let m = s.model_limits();
    assert_eq!(m.len(), 2, "{m:?}");
    assert!(
        m[0].contains("checked at MCE_R on an elastic frame"),
        "{}",
        m[0]
    );
    assert!(m[1].contains("the count is 0 for every design"), "{}", m[1]);
    // both are among the warnings the fronts print
    let w = s.warnings();
    assert!(m.iter().all(|x| w.contains(x)), "{w:?}");
    // a per-record limit makes the count count: only the elastic frame is left
    let with_record_limit = text.replace(
        r#""unacceptable": { "max_count": 1 }"#,
        r#""unacceptable": { "max_count": 1, "record_limits": [ { "metric": "peak_drift_ratio", "max": 0.05 } ] }"#,
    );
    let s = Study::from_json(&with_record_limit, &path).unwrap();
    assert_eq!(s.model_limits().len(), 1, "{:?}", s.model_limits());
    // a count the study does not write (the default allowance) is not one it is told of
    let unwritten = text.replace(
        r#",
                            "unacceptable": { "max_count": 1 }"#,
        "",
    );
    assert_ne!(unwritten, text);
    let s = Study::from_json(&unwritten, &path).unwrap();
    assert_eq!(s.model_limits().len(), 1, "{:?}", s.model_limits());
    assert!(s.model_limits()[0].contains("elastic frame"));
}

/// A record shorter than the bare frame's first period is a pulse to the frame, not
/// shaking it goes through: named among the warnings, with its length and the period.
#[test]
fn a_record_shorter_than_the_first_period_is_named() {
    let with = |duration: f64| {
        let text = format!(
            r#"{{ "name": "short", "building": "ten-story.json",
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": 2, "seed": 7, "pga_g": 0.3, "duration_s": {duration} }} }} ],
  "space": {{ "profile": {{ "shape": "uniform", "scale_kn": [0, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark", "check_method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 1 }} }}"#
        );
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/short.json");
        Study::from_json(&text, &path).unwrap()
    };
    let s = with(1.0);
    let t1 = s.building.t1();
    assert!(t1 > 1.0, "the ten-storey frame's T1 = {t1} s");
    let w: Vec<String> = s
        .warnings()
        .into_iter()
        .filter(|w| w.contains("shorter than the bare frame's first period"))
        .collect();
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(
        w[0].starts_with("suite syn: record ") && w[0].contains("lasts 1 s"),
        "{}",
        w[0]
    );
    // ten periods long: nothing to name
    let s = with(10.0 * t1);
    assert!(
        !s.warnings().iter().any(|w| w.contains("first period")),
        "{:?}",
        s.warnings()
    );
}
