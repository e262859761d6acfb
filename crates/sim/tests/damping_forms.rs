//! Damping as engineers state it: Rayleigh damping by its ratios at two modes or two
//! periods (Chopra, Dynamics of Structures, §11.4: ζ = α/(2ω) + βω/2), the damping ratio
//! of every mode, and the periods with the dampers stuck (closed form on one storey).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_sim::{Building, BuildingConfig};
use std::path::Path;

const BENCHMARK: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../configs/benchmark-3story.json"
);

/// The benchmark building with its `damping` replaced by `damping`.
fn benchmark_with(damping: serde_json::Value) -> Result<Building, String> {
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(BENCHMARK).unwrap()).unwrap();
    v["damping"] = damping;
    let cfg: BuildingConfig = serde_json::from_value(v).map_err(|e| e.to_string())?;
    Building::from_config(&cfg, Path::new("b.json")).map_err(|e| e.to_string())
}

/// Round-off of the eigen solve and of ΦᵀCΦ on a three-storey frame: far below 1e-10 of
/// a ratio.
const TOL: f64 = 1e-10;

#[test]
fn rayleigh_by_ratios_at_two_modes_gives_those_ratios_and_the_rayleigh_curve_between() {
    let b = benchmark_with(
        serde_json::json!({ "rayleigh": { "ratios": [0.02, 0.05], "modes": [1, 3] } }),
    )
    .unwrap();
    let z = b.dynamics().damping_ratios;
    assert!((z[0] - 0.02).abs() < TOL, "{z:?}");
    assert!((z[2] - 0.05).abs() < TOL, "{z:?}");
    // mode 2 lies on the Rayleigh curve through the two: α, β from the closed form
    let w = &b.modes.omega;
    let d = w[2] * w[2] - w[0] * w[0];
    let alpha = 2.0 * w[0] * w[2] * (0.02 * w[2] - 0.05 * w[0]) / d;
    let beta = 2.0 * (0.05 * w[2] - 0.02 * w[0]) / d;
    let z2 = alpha / (2.0 * w[1]) + beta * w[1] / 2.0;
    assert!((z[1] - z2).abs() < TOL, "{} vs {z2}", z[1]);
    assert!(b.dynamics().classical);
}

#[test]
fn rayleigh_by_periods_equals_rayleigh_by_the_modes_of_those_periods() {
    let by_modes =
        benchmark_with(serde_json::json!({ "rayleigh": { "ratio": 0.03, "modes": [1, 2] } }))
            .unwrap();
    let t = by_modes.modes.periods();
    let by_periods = benchmark_with(serde_json::json!({
        "rayleigh": { "ratio": 0.03, "periods": [format!("{} s", t[0]), format!("{} s", t[1])] }
    }))
    .unwrap();
    let scale = by_modes.damping.norm();
    assert!((&by_modes.damping - &by_periods.damping).norm() < 1e-12 * scale);
    // and the coefficients as written give the same matrix as the ratios they imply
    let w = &by_modes.modes.omega;
    let (alpha, beta) = (
        2.0 * 0.03 * w[0] * w[1] / (w[0] + w[1]),
        2.0 * 0.03 / (w[0] + w[1]),
    );
    let given = benchmark_with(serde_json::json!({ "rayleigh": { "alpha": alpha, "beta": beta } }))
        .unwrap();
    assert!((&by_modes.damping - &given.damping).norm() < 1e-12 * scale);
}

#[test]
fn rayleigh_forms_that_cannot_hold_are_refused_naming_the_field() {
    for (damping, field, words) in [
        // a ratio rising this fast between the modes needs α < 0
        (
            serde_json::json!({ "rayleigh": { "ratios": [0.01, 0.2], "modes": [1, 3] } }),
            "damping.rayleigh.ratios",
            "negative",
        ),
        (
            serde_json::json!({ "rayleigh": { "ratio": 0.05, "modes": [1, 1] } }),
            "damping.rayleigh.modes",
            "must differ",
        ),
        (
            serde_json::json!({ "rayleigh": { "ratio": 0.05, "modes": [1, 4] } }),
            "damping.rayleigh.modes",
            "modes 1 to 3",
        ),
        (
            serde_json::json!({ "rayleigh": { "ratio": 0.05, "periods": ["1 s"] } }),
            "damping.rayleigh.periods",
            "two periods",
        ),
        (
            serde_json::json!({ "rayleigh": { "ratio": 0.05, "periods": ["1 s", "-0.2 s"] } }),
            "damping.rayleigh.periods",
            "> 0",
        ),
        (
            serde_json::json!({ "rayleigh": { "ratio": 1.5, "modes": [1, 2] } }),
            "damping.rayleigh.ratio",
            "[0, 1)",
        ),
        (
            serde_json::json!({ "rayleigh": { "ratio": 0.05 } }),
            "damping.rayleigh.modes",
            "exactly one of `modes`",
        ),
        (
            serde_json::json!({ "rayleigh": { "alpha": 0.2, "ratio": 0.05, "modes": [1, 2] } }),
            "damping.rayleigh",
            "give `alpha` and `beta`",
        ),
        (
            serde_json::json!({ "rayleigh": { "alpha": 0.2 } }),
            "damping.rayleigh",
            "give `alpha` and `beta`",
        ),
        (
            serde_json::json!({ "rayleigh": { "alpha": -0.2, "beta": 0.001 } }),
            "damping.rayleigh.alpha",
            "≥ 0",
        ),
    ] {
        let e = benchmark_with(damping.clone()).unwrap_err();
        assert!(e.contains(field) && e.contains(words), "{damping}: {e}");
    }
}

/// One storey: stuck, the brace k′ works beside the storey k and the dissipator's mass m′
/// rides on the floor, T = 2π √((m + m′)/(k + k′)); a free contact (slip load 0) never
/// sticks.
#[test]
fn stuck_periods_on_one_storey_are_the_closed_form() {
    let (m, k, kb, mb): (f64, f64, f64, f64) = (2.0e5, 8.0e7, 1.2e8, 500.0);
    let building = |slip: &str| {
        let cfg: BuildingConfig = serde_json::from_value(serde_json::json!({
            "name": "one",
            "floor_masses": [m],
            "storey_stiffness": [k],
            "damping": { "storey": [1.0e5] },
            "dissipators": [{ "floor": 1, "brace_stiffness": kb, "mass": mb, "slip_load": slip }]
        }))
        .unwrap();
        Building::from_config(&cfg, Path::new("one.json")).unwrap()
    };
    let b = building("100 kN");
    let stuck = b.dynamics().stuck.unwrap().periods()[0];
    let want = 2.0 * std::f64::consts::PI * ((m + mb) / (k + kb)).sqrt();
    assert!((stuck - want).abs() < 1e-12 * want, "{stuck} vs {want}");
    // one storey: its one mode's ratio is c/(2 m ω), the damping is classical
    let z = b.dynamics().damping_ratios[0];
    let zw = 1.0e5 / (2.0 * m * (k / m).sqrt());
    assert!((z - zw).abs() < 1e-12, "{z} vs {zw}");
    assert!(building("0 kN").dynamics().stuck.is_none());
    let text = b.describe_modes();
    assert!(text.contains("dampers stuck"), "{text}");
    assert!(text.contains(&format!("[{want:.4}]")), "{text}");
}

/// Storey dashpots not proportional to the storey stiffnesses couple the modes: the
/// ratios are the diagonal's, and the text says so.
#[test]
fn non_classical_damping_is_named() {
    let cfg: BuildingConfig = serde_json::from_value(serde_json::json!({
        "name": "two",
        "floor_masses": [1.0e5, 1.0e5],
        "storey_stiffness": [5.0e7, 5.0e7],
        "damping": { "storey": [4.0e5, 1.0e3] }
    }))
    .unwrap();
    let b = Building::from_config(&cfg, Path::new("two.json")).unwrap();
    assert!(!b.dynamics().classical);
    assert!(b.describe_modes().contains("not classical"));
}
