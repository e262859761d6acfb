//! Contract (issue 45 §3): with `devices.redundancy` the device table gives each device's
//! design values — its force, the storey's slip load at the upper bound over the devices
//! the storey's damper stands for; its design displacement, each suite's mean stroke at
//! its governing case; its design velocity, the largest slip velocity — and with fewer
//! devices than the rule's minimum (4 per storey, 2 on each side of the centre of
//! rigidity, unless the study gives others) the displacement and velocity are × 1.3 (or
//! the study's factor), as are the test protocol's amplitudes. Bad keys name their field.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::eval::evaluate::run_one;
use slipload_opt::model::fidelity::Fidelity;
use slipload_opt::phases::devices::DeviceTable;
use slipload_opt::{RecordMetrics, Study};
use std::path::Path;

/// The benchmark three-storey frame under two short records, property bounds 0.85/1.15,
/// a drift limit (so the check records the dampers' demands), `devices` as given.
fn study(devices: &str) -> Result<Study, slipload_opt::OptError> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/benchmark-3story.json",
  "suites": [ {{ "name": "two", "records": ["records/SYL090.AT2", "records/RSN900_LANDERS_YER270.AT2"],
                 "limits": {{ "criteria": [ {{ "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.05 }} ] }} }} ],
  "property_bounds": {{ "slip_load": {{ "lower": 0.85, "upper": 1.15 }} }},
  "devices": {{ {devices} }},
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    Study::from_json(&text, &root.join("study.json"))
}

fn table(devices: &str) -> DeviceTable {
    let st = study(devices).unwrap();
    let fid = Fidelity::check(&st);
    let design = [300e3, 250e3, 150e3];
    let runs: Vec<RecordMetrics> = (0..st.runs())
        .map(|r| run_one(&st, &design, r, &fid, "d").unwrap())
        .collect();
    DeviceTable::of(&st, &design, &runs, "check".into()).unwrap()
}

#[test]
fn few_devices_raise_the_design_values_and_the_test_amplitudes() {
    let protocol =
        r#""test_protocol": { "cycles": 5, "band_percent": 15, "production_cycles": 3 }"#;
    let plain = table(protocol);
    assert!(plain.redundancy.is_none());
    let two = table(&format!(
        r#"{protocol}, "redundancy": {{ "devices_per_storey": 2 }}"#
    ));
    let six = table(&format!(
        r#"{protocol}, "redundancy": {{ "devices_per_storey": 6, "devices_per_side": 3 }}"#
    ));
    let one_side = table(&format!(
        r#"{protocol}, "redundancy": {{ "devices_per_storey": 6, "devices_per_side": 1, "factor": 1.5 }}"#
    ));
    let (r2, r6, r1) = (
        two.redundancy.as_ref().unwrap(),
        six.redundancy.as_ref().unwrap(),
        one_side.redundancy.as_ref().unwrap(),
    );
    assert!(r2.applies && r2.why.contains("fewer than 4"), "{}", r2.why);
    assert_eq!(r2.factor, 1.3);
    assert!(!r6.applies);
    assert_eq!(r6.factor, 1.0);
    assert!(r1.applies && r1.why.contains("fewer than 2"), "{}", r1.why);
    assert_eq!(r1.factor, 1.5);
    for (k, row) in plain.dampers.iter().enumerate() {
        // the force is shared, the stroke is each device's
        let f2 = r2.devices[k].device_force_kn;
        assert!((f2 - row.slip_load_range_kn[1] / 2.0).abs() <= 1e-12 * f2);
        let f6 = r6.devices[k].device_force_kn;
        assert!((f6 - row.slip_load_range_kn[1] / 6.0).abs() <= 1e-12 * f6);
        for (j, st) in row.stroke_by_suite.iter().enumerate() {
            assert_eq!(r2.devices[k].design_stroke_mm[j], 1.3 * st.mean_mm);
            assert_eq!(r6.devices[k].design_stroke_mm[j], st.mean_mm);
            assert_eq!(r1.devices[k].design_stroke_mm[j], 1.5 * st.mean_mm);
        }
        assert_eq!(
            r2.devices[k].design_velocity_mm_s,
            1.3 * row.peak_velocity_mm_s
        );
    }
    // the protocol tests the raised displacement: the amplitudes scale by the factor
    let (p, q) = (
        plain.test_protocol.as_ref().unwrap(),
        two.test_protocol.as_ref().unwrap(),
    );
    assert_eq!(p.dampers.len(), 3);
    for (a, b) in p.dampers.iter().zip(&q.dampers) {
        let (a, b) = (a.figures.amplitude_mm, b.figures.amplitude_mm);
        assert!((b - 1.3 * a).abs() <= 1e-12 * b, "{a} {b}");
    }
    let md = two.to_markdown();
    assert!(md.contains("## Devices and the redundancy rule"));
    assert!(md.contains("× 1.3"));
}

#[test]
fn bad_redundancy_keys_name_their_field() {
    for (devices, field) in [
        (
            r#""redundancy": { "devices_per_storey": 0 }"#,
            "devices.redundancy.devices_per_storey",
        ),
        (
            r#""redundancy": { "devices_per_storey": 4, "devices_per_side": 3 }"#,
            "devices.redundancy.devices_per_side",
        ),
        (
            r#""redundancy": { "devices_per_storey": 4, "factor": 0.5 }"#,
            "devices.redundancy.factor",
        ),
    ] {
        let e = study(devices).unwrap_err().to_string();
        assert!(e.contains(field), "{field}: {e}");
    }
}
