//! Contract (issue 45 §4): the study's `wind` (one design wind shear per storey) holds the
//! design space to slip loads no wind slips — the space's least slip load of each damper,
//! at the lower property bound, at least `factor` (1.3) × its storey's wind shear, else the
//! study is refused naming the bound to raise and the load it needs — and the compliance
//! matrix states the design's least margin.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::phases::compliance::{Status, matrix, wind_margin};
use std::path::Path;

fn study(lower: &str, wind: &str) -> Result<Study, slipload_opt::OptError> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/benchmark-3story.json", "wind": {{ {wind} }},
  "suites": [ {{ "name": "s", "synthetic": {{ "count": 2 }},
                 "limits": {{ "criteria": [ {{ "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.02 }} ] }} }} ],
  "property_bounds": {{ "slip_load": {{ "lower": 0.8, "upper": 1.25 }} }},
  "space": {{ "free": {{ "lower_kn": [{lower}], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }} }}"#
    );
    Study::from_json(&text, &root.join("study.json"))
}

const WIND: &str = r#""storey_shears_kn": [100, 80, 40]"#;

#[test]
fn the_design_wind_bounds_the_space_and_the_check_states_the_margin() {
    // 1.3 × 100 kN / 0.8 = 162.5 kN at the base: a space from 150 kN is refused
    let err = study("150, 200, 100", WIND).unwrap_err().to_string();
    assert!(err.contains("space.free.lower_kn[0]"), "{err}");
    assert!(err.contains("needs at least 162.5 kN"), "{err}");
    // the top floor: 1.3 × 40 / 0.8 = 65 kN
    let err = study("200, 200, 60", WIND).unwrap_err().to_string();
    assert!(
        err.contains("space.free.lower_kn[2]") && err.contains("65"),
        "{err}"
    );
    // a factor the study gives: 1.0 × 100 / 0.8 = 125 kN, so 150 kN stands
    assert!(study("150, 200, 100", &format!("{WIND}, \"factor\": 1.0")).is_ok());
    let err = study("200, 200, 100", r#""storey_shears_kn": [100, 80]"#)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("wind.storey_shears_kn") && err.contains("3 storeys"),
        "{err}"
    );
    let err = study("200, 200, 100", r#""storey_shears_kn": [100, -1, 40]"#)
        .unwrap_err()
        .to_string();
    assert!(err.contains("wind.storey_shears_kn[1]"), "{err}");
    // a design of the space: its least margin λ_min F / V, by hand
    let st = study("200, 200, 100", WIND).unwrap();
    let loads = [400e3, 200e3, 100e3];
    let by_hand = [0.8 * 400.0 / 100.0, 0.8 * 200.0 / 80.0, 0.8 * 100.0 / 40.0];
    let (least, floor) = wind_margin(&st, &loads).unwrap();
    assert_eq!((least, floor), (2.0, 2), "{by_hand:?}");
    let row = |loads: &[f64]| {
        matrix(&st, &Default::default(), loads)
            .into_iter()
            .find(|r| r.clause == "design practice")
            .unwrap()
    };
    let r = row(&loads);
    assert_eq!((r.status, r.limit.as_str()), (Status::Pass, "≥ 1.3"));
    assert_eq!(r.value, "slip load / wind shear 2.00 at floor 2, the least");
    // a design below the margin (the building file's, say) fails the row
    assert_eq!(row(&[150e3, 200e3, 100e3]).status, Status::Fail);
}
