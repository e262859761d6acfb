//! Contract (issue 45 §3): a brace is a force-controlled element, and the most a friction
//! damper can put into it is its slip load at the upper property bound: with
//! `devices.brace_capacity_kn` no design of the space may exceed a brace's strength,
//! λ_max F / (n cos θ) ≤ capacity (a space that could is refused naming the bound and the
//! largest slip load allowed), and the compliance matrix states the design's largest ratio.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::phases::compliance::{Status, brace_ratio, matrix};
use std::path::Path;

fn study(devices: &str) -> Result<Study, slipload_opt::OptError> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/benchmark-3story.json", "devices": {{ {devices} }},
  "suites": [ {{ "name": "s", "synthetic": {{ "count": 2 }},
                 "limits": {{ "criteria": [ {{ "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.02 }} ] }} }} ],
  "property_bounds": {{ "slip_load": {{ "lower": 0.8, "upper": 1.25 }} }},
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }} }}"#
    );
    Study::from_json(&text, &root.join("study.json"))
}

#[test]
fn a_brace_strength_bounds_the_space_and_the_check_states_the_ratio() {
    let cos = 40f64.to_radians().cos();
    // 1.25 × 2000 kN / cos 40° = 3263.5 kN: a 3000 kN brace is refused at the first floor,
    // whose slip load may be at most 3000 cos 40° / 1.25 = 1838.5 kN
    let err = study(r#""brace_angle_deg": 40, "brace_capacity_kn": [3000, 3300, 3300]"#)
        .unwrap_err()
        .to_string();
    assert!(err.contains("space.free.upper_kn[0]"), "{err}");
    assert!((3000.0 * cos / 1.25 - 1838.5).abs() < 0.1, "{cos}");
    assert!(
        err.contains("the slip load may be at most 1839 kN"),
        "{err}"
    );
    assert!(
        err.contains("the brace carries 3264 kN against its 3000 kN"),
        "{err}"
    );
    // a chevron shares it between two braces: 1631.8 kN each, within 3000 kN
    let st = study(
        r#""brace_angle_deg": 40, "braces_per_damper": 2, "brace_capacity_kn": [3000, 3000, 3000]"#,
    )
    .unwrap();
    let loads = [1000e3, 800e3, 500e3];
    let (ratio, floor) = brace_ratio(&st, &loads).unwrap();
    let by_hand = 1.25 * 1000.0 / (2.0 * cos) / 3000.0;
    assert!(
        (ratio - by_hand).abs() < 1e-12 && floor == 1,
        "{ratio} at {floor}"
    );
    let rows = matrix(&st, &Default::default(), &loads);
    let row = rows
        .iter()
        .find(|r| r.clause == "Ch. 18 (force-controlled)")
        .unwrap();
    assert_eq!(row.status, Status::Pass);
    assert_eq!(
        row.value,
        format!("brace force / strength {by_hand:.2} at floor 1, the largest")
    );
    // a slip load beyond it (a design outside the space, the building file's say) fails
    let over = matrix(&st, &Default::default(), &[6000e3, 800e3, 500e3]);
    let row = over
        .iter()
        .find(|r| r.clause == "Ch. 18 (force-controlled)")
        .unwrap();
    assert_eq!(row.status, Status::Fail);
    // without the angle, or with a capacity per damper missing, the field is named
    let err = study(r#""brace_capacity_kn": [3000, 3000, 3000]"#)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("devices.brace_capacity_kn") && err.contains("brace_angle_deg"),
        "{err}"
    );
    let err = study(r#""brace_angle_deg": 40, "brace_capacity_kn": [3000, 3000]"#)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("devices.brace_capacity_kn") && err.contains("3 dampers"),
        "{err}"
    );
    let err = study(r#""brace_angle_deg": 40, "brace_capacity_kn": [3000, 0, 3000]"#)
        .unwrap_err()
        .to_string();
    assert!(err.contains("devices.brace_capacity_kn[1]"), "{err}");
}
