//! Contract: a study's fingerprint covers the frame's yield laws, P-Δ loads and collapse
//! limit (a journal of the elastic frame must not serve a yielding one), and an elastic
//! building keeps the fingerprint it had before those fields existed (its journals stay
//! valid).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::model::fingerprint::of_study;
use std::path::Path;

fn study(building_extra: Option<(&str, serde_json::Value)>) -> Study {
    let configs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs");
    let path = configs.join("study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let mut b: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(configs.join("benchmark-3story.json")).unwrap(),
    )
    .unwrap();
    b["storey_heights"] = serde_json::json!([3.0, 3.0, 3.0]);
    if let Some((key, value)) = building_extra {
        b[key] = value;
    }
    v["building"] = b;
    Study::from_json(&v.to_string(), &path).unwrap()
}

#[test]
fn yield_laws_p_delta_and_collapse_limits_are_part_of_the_fingerprint() {
    let elastic = of_study(&study(None), &[]);
    assert_eq!(elastic, of_study(&study(None), &[]), "deterministic");
    let variants = [
        (
            "storey_yield",
            serde_json::json!([{ "storey": 1, "yield_shear": "2 MN", "stiffness": "100 MN/m" }]),
        ),
        (
            "storey_yield",
            serde_json::json!([{ "storey": 1, "yield_shear": "3 MN", "stiffness": "100 MN/m" }]),
        ),
        ("p_delta", serde_json::json!({})),
        ("collapse_drift_ratio", serde_json::json!(0.05)),
    ];
    let mut seen = vec![elastic.clone()];
    for (key, value) in variants {
        let f = of_study(&study(Some((key, value.clone()))), &[]);
        assert!(
            !seen.contains(&f),
            "{key} = {value} leaves the fingerprint unchanged"
        );
        assert_eq!(f.changes_from(&elastic), vec!["building".to_string()]);
        seen.push(f);
    }
}

#[test]
fn a_study_sets_its_own_collapse_limit() {
    let configs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs");
    let path = configs.join("study-ten-story-mce.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let default = Study::from_json(&v.to_string(), &path).unwrap();
    // the building's default: 10 % of the 3.5 m storeys
    let limit = default.building.collapse_drift.clone().unwrap();
    assert!(
        limit.len() == 10 && limit.iter().all(|d| (d - 0.35).abs() < 1e-12),
        "{limit:?}"
    );
    v["collapse_drift_ratio"] = serde_json::json!(0.04);
    let own = Study::from_json(&v.to_string(), &path).unwrap();
    let limit = own.building.collapse_drift.clone().unwrap();
    assert!(limit.iter().all(|d| (d - 0.14).abs() < 1e-12), "{limit:?}");
    assert_eq!(
        of_study(&own, &[]).changes_from(&of_study(&default, &[])),
        vec!["building".to_string()]
    );
    v["collapse_drift_ratio"] = serde_json::json!(-1.0);
    let err = Study::from_json(&v.to_string(), &path)
        .unwrap_err()
        .to_string();
    assert!(err.contains("collapse_drift_ratio"), "{err}");
}
