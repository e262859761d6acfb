//! Contract (issue 45 §1): the count of unacceptable responses a suite allows follows the
//! study's `risk_category` and the suite's number of ground motions (ASCE 7-16 §16.4.1.1:
//! one for Risk Category I and II with at least 11, none otherwise); a count given above
//! that is refused naming its field; a study without a risk category allows 1, as before,
//! and serialises its checks as before (its fingerprint is unchanged).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use std::path::Path;

/// The ten-storey frame over `records` scaled to a design spectrum, with a drift limit;
/// `extra`: members of the study, `unacceptable`: the suite's `unacceptable` members.
fn study(records: &str, extra: &str, unacceptable: &str) -> Result<Study, slipload_opt::OptError> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/ten-story.json"{extra},
  "suites": [ {{ "name": "code", "records": [{records}],
                 "scale": {{ "code_spectrum": {{ "sds_g": 1.0, "sd1_g": 0.6, "tl_s": 8, "min_records": 7 }} }},
                 "limits": {{ "criteria": [ {{ "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.02 }} ],
                              "unacceptable": {{ {unacceptable} }} }} }} ],
  "space": {{ "profile": {{ "shape": "uniform", "scale_kn": [0, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    Study::from_json(&text, &root.join("study.json"))
}

const ALL: &str = r#""records/RSN*.AT2""#;

fn seven() -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../records");
    let mut names: Vec<String> = std::fs::read_dir(root)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("RSN") && n.ends_with(".AT2"))
        .collect();
    names.sort();
    names
        .iter()
        .take(7)
        .map(|n| format!(r#""records/{n}""#))
        .collect::<Vec<_>>()
        .join(", ")
}

fn allowed(st: &Study) -> usize {
    st.checks.limits[0].as_ref().unwrap().unacceptable.allowed()
}

#[test]
fn the_allowance_follows_the_risk_category_and_the_count() {
    let rc = |c: &str| format!(r#", "risk_category": "{c}""#);
    // at least 11 ground motions: one for I and II, none for III and IV
    let n = study(ALL, "", "").unwrap().suites[0].range.len();
    assert!(n >= 11, "{n}");
    for (c, want) in [("I", 1), ("II", 1), ("III", 0), ("IV", 0)] {
        assert_eq!(allowed(&study(ALL, &rc(c), "").unwrap()), want, "{c}");
    }
    // seven (the study's rule): none, whatever the category
    assert_eq!(allowed(&study(&seven(), &rc("II"), "").unwrap()), 0);
    // a count the category allows stands; one above it names the field and the allowance
    assert_eq!(
        allowed(&study(ALL, &rc("III"), r#""max_count": 0"#).unwrap()),
        0
    );
    let err = study(ALL, &rc("III"), r#""max_count": 1"#)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("suites[0].limits.unacceptable.max_count"),
        "{err}"
    );
    assert!(err.contains("Risk Category III allows a suite of"), "{err}");
    let err = study(ALL, r#", "risk_category": "V""#, "")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("unknown variant `V`, expected one of `I`, `II`, `III`, `IV` at line 1"),
        "{err}"
    );
    // without a category: 1, written into the checks as before
    let st = study(ALL, "", "").unwrap();
    assert_eq!(allowed(&st), 1);
    let json = serde_json::to_string(&st.checks).unwrap();
    assert!(
        json.contains(r#""unacceptable":{"max_count":1,"record_limits":[]}"#),
        "{json}"
    );
}

#[test]
fn the_allowance_and_its_check_line_agree() {
    use slipload_opt::model::check::RiskCategory;
    assert_eq!(RiskCategory::II.allowance(11), 1);
    assert_eq!(RiskCategory::II.allowance(10), 0);
    assert_eq!(RiskCategory::I.allowance(40), 1);
    assert_eq!(RiskCategory::IV.allowance(40), 0);
}
