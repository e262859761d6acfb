//! Contract (issue 45 §4): `frame_strength` checks each storey's yield shear against the
//! study's fraction of the equivalent-lateral-force storey shear of the frame without
//! dampers (ASCE 7-16 §18.2.1.1 with §12.8: C_s from S_DS, S_D1, T_L, R and I_e, bounded
//! by Eq. 12.8-3 to 12.8-5; V = C_s W; F_x ∝ w_x h_x^k), computed here again by hand from
//! the building file's numbers; the compliance matrix states the least ratio.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::phases::compliance::{Status, matrix};
use slipload_opt::phases::strength::FrameStrength;
use std::path::Path;

/// The ten-storey yielding frame (350 t floors, 280 t roof, 3.5 m storeys, yield at
/// 26.25 mm of drift) over the RSN records scaled to S_DS = 1.0 g, S_D1 = 0.6 g;
/// `strength`: the `frame_strength` members.
fn study(strength: &str) -> Study {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/ten-story-yielding.json", "frame_strength": {{ {strength} }},
  "suites": [ {{ "name": "code", "records": ["records/RSN*.AT2"],
                 "scale": {{ "code_spectrum": {{ "sds_g": 1.0, "sd1_g": 0.6, "tl_s": 8 }} }},
                 "limits": {{ "criteria": [ {{ "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.02 }} ] }} }} ],
  "space": {{ "profile": {{ "shape": "uniform", "scale_kn": [0, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    Study::from_json(&text, &root.join("study.json")).unwrap()
}

/// The storey shears (kN) of the equivalent lateral force V (kN) at exponent k, by hand.
fn shears(v: f64, k: f64) -> Vec<f64> {
    let w: Vec<f64> = (0..10).map(|i| if i < 9 { 350.0 } else { 280.0 }).collect();
    let whk: Vec<f64> = (0..10)
        .map(|i| w[i] * (3.5 * (i + 1) as f64).powf(k))
        .collect();
    let total: f64 = whk.iter().sum();
    (0..10)
        .map(|x| v * whk[x..].iter().sum::<f64>() / total)
        .collect()
}

#[test]
fn the_frame_without_dampers_against_the_equivalent_lateral_force() {
    let g = 9.80665;
    let weight = (9.0 * 350.0 + 280.0) * g; // kN
    let yield_kn = [
        494.0, 466.6, 439.1, 411.7, 384.2, 356.8, 329.3, 301.9, 274.4, 247.0,
    ]
    .map(|k| k * 26.25); // MN/m × mm = kN
    // R = 8 at T = 1.2 s: C_s = min(1.0/8, 0.6/(1.2 × 8)) = 0.0625; k = 1 + 0.7/2
    let f = FrameStrength::of(&study(r#""response_modification": 8, "period_s": 1.2"#)).unwrap();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
    assert!(close(f.cs, 0.0625), "{}", f.cs);
    assert!(close(f.k, 1.35) && close(f.weight_kn, weight), "{f:?}");
    for (st, (v, y)) in f
        .storeys
        .iter()
        .zip(shears(0.0625 * weight, 1.35).iter().zip(yield_kn))
    {
        assert!(close(st.required_kn, 0.75 * v), "{st:?} vs {v}");
        assert!(close(st.strength_kn.unwrap(), y), "{st:?} vs {y}");
    }
    let rows = matrix(
        &study(r#""response_modification": 8, "period_s": 1.2"#),
        &Default::default(),
        &[],
    );
    let row = rows.iter().find(|r| r.clause == "§18.2.1.1").unwrap();
    assert_eq!(row.status, Status::Pass);
    // R = 1, all of the demand: C_s = min(1/1, 0.6/1.2) = 0.5, more than the frame has
    let st = study(r#""response_modification": 1, "fraction": 1.0, "period_s": 1.2"#);
    let f = FrameStrength::of(&st).unwrap();
    assert!(close(f.cs, 0.5), "{}", f.cs);
    let by_hand = shears(weight / 2.0, 1.35);
    let (least, at) = f.least().unwrap();
    let (want, want_at) = (0..10)
        .map(|i| (yield_kn[i] / by_hand[i], i + 1))
        .fold((f64::INFINITY, 0), |m, x| if x.0 < m.0 { x } else { m });
    assert!(
        close(least, want) && at == want_at,
        "{least} at {at}, by hand {want} at {want_at}"
    );
    assert!(least < 1.0, "{least}");
    let row = matrix(&st, &Default::default(), &[])
        .into_iter()
        .find(|r| r.clause == "§18.2.1.1")
        .unwrap();
    assert_eq!(row.status, Status::Fail);
    assert_eq!(
        row.value,
        format!("yield shear / required {least:.2} at storey {at}, the least")
    );
    // the minimum C_s governs a long period: 0.044 S_DS I_e at T = 6 s, R = 8
    let f = FrameStrength::of(&study(r#""response_modification": 8, "period_s": 6"#)).unwrap();
    assert!(close(f.cs, 0.044) && close(f.k, 2.0), "{f:?}");
}

#[test]
fn a_bad_frame_strength_names_its_field() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let load = |strength: &str, suite: &str| {
        let text = format!(
            r#"{{ "building": "configs/ten-story-yielding.json", "frame_strength": {{ {strength} }},
  "suites": [ {{ "name": "s", {suite} }} ],
  "space": {{ "profile": {{ "shape": "uniform", "scale_kn": [0, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }} }}"#
        );
        Study::from_json(&text, &root.join("study.json"))
            .unwrap_err()
            .to_string()
    };
    let err = load(
        r#""response_modification": 8"#,
        r#""synthetic": { "count": 2 }"#,
    );
    assert!(
        err.contains("frame_strength.response_modification") && err.contains("code_spectrum"),
        "{err}"
    );
    let code = r#""records": ["records/RSN*.AT2"], "scale": { "code_spectrum": { "sds_g": 1.0, "sd1_g": 0.6, "tl_s": 8 } }"#;
    for (bad, field) in [
        (
            r#""response_modification": 0.5"#,
            "frame_strength.response_modification",
        ),
        (
            r#""response_modification": 8, "importance": 2"#,
            "frame_strength.importance",
        ),
        (
            r#""response_modification": 8, "fraction": 0"#,
            "frame_strength.fraction",
        ),
        (
            r#""response_modification": 8, "period_s": -1"#,
            "frame_strength.period_s",
        ),
    ] {
        let err = load(bad, code);
        assert!(err.contains(field), "{bad}: {err}");
    }
}
