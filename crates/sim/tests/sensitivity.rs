//! The derivatives of the peaks with respect to the slip loads (`outputs.sensitivities`,
//! the tangent of the `newmark` step) against central differences of the runs
//! themselves. The step is a projection, continuous and piecewise smooth in the slip
//! loads: a difference over ±δ agrees with the tangent to O(δ²) on the run's piece, and a
//! pattern change inside ±δ moves it by at most the Lipschitz jump of the slope times the
//! share of δ it covers. With δ = 1e-6 F the differences carry round-off of about
//! 1e-16/1e-6 = 1e-10 of the response; the tolerance, 1e-5 of the largest derivative of
//! the kind, leaves room for a pattern change in a few of the ten thousand steps and
//! nothing for a wrong term (a dropped column, a sign, the Delassus coupling, each of which
//! moves the derivatives by their own size).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use slipload_sim::response::Sensitivity;
use slipload_sim::{Scene, SceneOverrides, simulate};

/// A four-storey yielding frame with a damper on each floor: massless on a brace without
/// dashpot (floors 1 and 3, the return mapping), massless with a brace dashpot (floor 2)
/// and with mass (floor 4, a dissipator DOF); `method` its method object.
fn scene(method: &str) -> Scene {
    scene_with(method, ("2e5", "\"2000 kg\""))
}

/// The same frame with every damper massless on a brace without dashpot (every contact an
/// algebraic elastic–perfectly plastic element: the tangent's lane loop).
fn algebraic_scene(method: &str) -> Scene {
    scene_with(method, ("0", "0"))
}

/// The frame with floor 2's brace dashpot and floor 4's damper mass as given.
fn scene_with(method: &str, (dashpot, mass): (&str, &str)) -> Scene {
    let text = format!(
        r#"{{ "name": "sensitivity",
             "building": {{ "name": "four", "floor_masses": ["4e5 kg", "4e5 kg", "4e5 kg", "3e5 kg"],
                           "storey_stiffness": ["3e8 N/m", "2.6e8 N/m", "2.2e8 N/m", "1.8e8 N/m"],
                           "storey_heights": ["3.5 m", "3.5 m", "3.5 m", "3.5 m"],
                           "damping": {{ "rayleigh": {{ "alpha": 0.3, "beta": 0.002 }} }},
                           "dissipators": [
                             {{ "floor": 1, "brace_stiffness": "3e8 N/m", "mass": 0, "slip_load": "300 kN" }},
                             {{ "floor": 2, "brace_stiffness": "2.5e8 N/m", "mass": 0, "brace_damping": {dashpot}, "slip_load": "250 kN" }},
                             {{ "floor": 3, "brace_stiffness": "2e8 N/m", "mass": 0, "slip_load": "200 kN" }},
                             {{ "floor": 4, "brace_stiffness": "1.5e8 N/m", "mass": {mass}, "slip_load": "120 kN" }} ],
                           "storey_yield": [ {{ "storey": 1, "yield_drift": "0.02 m", "post_yield_ratio": 0.1 }},
                                             {{ "storey": 2, "yield_drift": "0.018 m", "post_yield_ratio": 0.05 }} ] }},
             "excitation": {{ "synthetic": {{ "seed": 7, "duration": 12, "dt": 0.01, "pga_g": 0.4 }} }},
             "method": {method},
             "outputs": {{ "energies": false, "histories": false, "sensitivities": true }} }}"#
    );
    common::scene_json(&text, &SceneOverrides::default())
}

/// The scene with damper `q`'s slip load times (1 + `rel`).
fn scaled(s: &Scene, q: usize, rel: f64) -> Scene {
    let mut s = s.clone();
    let d = s.building.dissipators.iter_mut().flatten().nth(q).unwrap();
    d.lower *= 1.0 + rel;
    d.upper *= 1.0 + rel;
    s
}

fn slip_load(s: &Scene, q: usize) -> f64 {
    s.building
        .dissipators
        .iter()
        .flatten()
        .nth(q)
        .unwrap()
        .upper
}

/// Tangent against central differences of every peak (drift, residual drift,
/// displacement, absolute acceleration, base shear) for every damper.
fn check(s: &Scene) {
    let out = simulate(s).unwrap();
    let sens: Sensitivity = out.response.sensitivity.clone().unwrap();
    assert_eq!(sens.dampers, vec![0, 1, 2, 3]);
    let rel = 1e-6;
    let mut worst = [0.0f64; 5];
    let mut scale = [0.0f64; 5];
    for q in 0..4 {
        let f = slip_load(s, q);
        let (hi, lo) = (
            simulate(&scaled(s, q, rel)).unwrap().response,
            simulate(&scaled(s, q, -rel)).unwrap().response,
        );
        let fd = |a: &[f64], b: &[f64]| -> Vec<f64> {
            a.iter()
                .zip(b)
                .map(|(x, y)| (x - y) / (2.0 * rel * f))
                .collect()
        };
        let kinds: [(Vec<f64>, Vec<f64>); 5] = [
            (
                fd(&hi.peak_drift, &lo.peak_drift),
                sens.peak_drift.iter().map(|r| r[q]).collect(),
            ),
            (
                fd(&hi.residual_drift, &lo.residual_drift),
                sens.residual_drift.iter().map(|r| r[q]).collect(),
            ),
            (
                fd(&hi.peak_displacement, &lo.peak_displacement),
                sens.peak_displacement.iter().map(|r| r[q]).collect(),
            ),
            (
                fd(&hi.peak_abs_acceleration, &lo.peak_abs_acceleration),
                sens.peak_abs_acceleration.iter().map(|r| r[q]).collect(),
            ),
            (
                fd(&[hi.peak_base_shear], &[lo.peak_base_shear]),
                vec![sens.peak_base_shear[q]],
            ),
        ];
        for (k, (d, t)) in kinds.iter().enumerate() {
            for (x, y) in d.iter().zip(t) {
                worst[k] = worst[k].max((x - y).abs());
                scale[k] = scale[k].max(x.abs()).max(y.abs());
            }
        }
    }
    let names = [
        "peak drift",
        "residual drift",
        "peak displacement",
        "peak acceleration",
        "base shear",
    ];
    for k in 0..5 {
        assert!(scale[k] > 0.0, "{}: every derivative is zero", names[k]);
        assert!(
            worst[k] <= 1e-5 * scale[k],
            "{}: tangent and central difference differ by {:.3e} (largest derivative {:.3e})",
            names[k],
            worst[k],
            scale[k]
        );
    }
}

#[test]
fn newmark_tangent_matches_central_differences() {
    check(&scene(r#"{ "name": "newmark", "dt": 0.005 }"#));
}

#[test]
fn the_algebraic_lane_loop_matches_central_differences() {
    check(&algebraic_scene(r#"{ "name": "newmark", "dt": 0.005 }"#));
    check(&algebraic_scene(
        r#"{ "name": "hht", "alpha": -0.1, "dt": 0.005 }"#,
    ));
}

#[test]
fn hht_tangent_matches_central_differences() {
    check(&scene(r#"{ "name": "hht", "alpha": -0.1, "dt": 0.005 }"#));
}

/// The sensitivities ride on the run without changing it: the peaks are those of the run
/// without them to round-off (the general loop against the fixed-size one), and a method
/// that cannot carry them is refused, naming the field.
#[test]
fn sensitivities_leave_the_run_and_are_refused_by_other_methods() {
    let s = scene(r#"{ "name": "newmark", "dt": 0.005 }"#);
    let with = simulate(&s).unwrap().response;
    let mut plain = s.clone();
    plain.outputs.sensitivities = false;
    let without = simulate(&plain).unwrap().response;
    assert!(without.sensitivity.is_none());
    for (a, b) in with.peak_drift.iter().zip(&without.peak_drift) {
        assert!((a - b).abs() <= 1e-9 * b.abs(), "{a} vs {b}");
    }
    let exact = scene(r#"{ "name": "exact" }"#);
    let err = simulate(&exact).unwrap_err().to_string();
    assert!(
        err.contains("outputs.sensitivities") && err.contains("exact"),
        "{err}"
    );
}

/// A damper at zero slip load stays a contact (zero bounds) and its derivative is the
/// one-sided one of a damper that starts to slip: against the forward difference F = 0 →
/// δ (δ = 1e-3 N, far below any force of the run). The difference carries the run's
/// accumulated round-off (about 1e-16 m over a change of δ × 5e-9 m/N: 2e-5 of it) and
/// its own first-order error (a damper of slip load δ sticks for a moment at each
/// reversal, which the derivative at F = 0 does not see): measured 2.5e-4 of the largest
/// derivative; the bound is 1e-3 (a wrong side or a dropped column is off by its size).
#[test]
fn a_damper_at_zero_slip_load_has_its_one_sided_derivative() {
    let mut s = algebraic_scene(r#"{ "name": "newmark", "dt": 0.005 }"#);
    let d = s.building.dissipators.iter_mut().flatten().nth(2).unwrap();
    (d.lower, d.upper) = (0.0, 0.0);
    let out = simulate(&s).unwrap();
    let sens = out.response.sensitivity.unwrap();
    assert_eq!(
        sens.dampers,
        vec![0, 1, 2, 3],
        "the zero-load damper stays a column"
    );
    let mut moved = s.clone();
    let d = moved
        .building
        .dissipators
        .iter_mut()
        .flatten()
        .nth(2)
        .unwrap();
    let delta = 1e-3;
    (d.lower, d.upper) = (-delta, delta);
    let hi = simulate(&moved).unwrap().response;
    let scale = sens
        .peak_drift
        .iter()
        .map(|r| r[2].abs())
        .fold(0.0f64, f64::max);
    assert!(scale > 0.0, "a slipping damper changes the drifts");
    for (i, row) in sens.peak_drift.iter().enumerate() {
        let fd = (hi.peak_drift[i] - out.response.peak_drift[i]) / delta;
        assert!(
            (fd - row[2]).abs() <= 1e-3 * scale,
            "storey {}: forward difference {fd:e}, tangent {:e}",
            i + 1,
            row[2]
        );
    }
}
