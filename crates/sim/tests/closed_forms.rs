//! Closed forms and linear limits (docs/MODEL.md § The model, "Limits that must come out right").
//!
//! - Coulomb-damped free vibration: a rigid-plastic friction damper on an undamped
//!   oscillator loses 4F/k of amplitude per cycle and stops inside |x| ≤ F/k.
//! - μN = 0 is the bare frame; a locked damper (μN = ∞) gives the braced frame: both
//!   against the exact (matrix-exponential) solution, with Newmark's observed order ≈ 2.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_sim::{Plan, SceneOverrides, simulate};

/// One storey, m = 1000 kg, k = 1e5 N/m (ω = 10 rad/s), friction 500 N through a brace
/// 1e6 times stiffer than the storey (rigid-plastic up to F/k′ = 5e-9 m), x₀ = 0.1037 m.
fn coulomb_scene(dt: f64) -> slipload_sim::Scene {
    let json = format!(
        r#"{{ "building": {{ "floor_masses": [1000], "storey_stiffness": [1e5],
              "dissipators": [ {{ "floor": 1, "brace_stiffness": 1e11, "mass": 0, "slip_load": 500 }} ] }},
             "excitation": {{ "initial": {{ "floor_displacement": [0.1037] }} }},
             "duration": 4.0, "method": {{ "dt": {dt} }}, "outputs": {{ "histories": true }} }}"#
    );
    scene_json(&json, &SceneOverrides::default())
}

#[test]
fn coulomb_free_vibration_loses_4f_over_k_per_cycle_and_stops_in_band() {
    let (k, f, x0) = (1e5, 500.0, 0.1037);
    let dt = 1e-4; // ωΔt = 1e-3
    let out = simulate(&coulomb_scene(dt)).unwrap();
    let h = out.history.unwrap();
    let x = h.column("x1_m").unwrap();
    // Extrema: points where the motion reverses (strict sign change of the increment)
    // outside the stick band. Once stuck, the floor rings elastically on the stiff brace
    // with an amplitude of order F/k′ = 5e-9 m: real motion, but no friction reversal.
    let mut extrema = Vec::new();
    let mut last_dir = 0.0f64;
    for i in 1..x.len() {
        let d = x[i] - x[i - 1];
        if d != 0.0 {
            if last_dir != 0.0 && d.signum() != last_dir.signum() && x[i - 1].abs() > f / k {
                extrema.push(x[i - 1]);
            }
            last_dir = d;
        }
    }
    // Closed form: |x_j| = x0 − 2jF/k while |x_{j−1}| > F/k, alternating sign.
    let mut expected = Vec::new();
    let mut amp = x0;
    let mut sign = -1.0;
    while amp > f / k {
        amp -= 2.0 * f / k;
        expected.push(sign * amp);
        sign = -sign;
    }
    let last = expected.pop().expect("several half-cycles"); // the rest position, not a reversal
    // Tolerance: sampled extrema and switching instants are off by O((ωΔt)²)·x0 = 1e-7 m;
    // the brace adds F/k′ = 5e-9 m. 2e-6 m is 20× that budget.
    let tol = 2e-6;
    assert_eq!(
        extrema.len(),
        expected.len(),
        "extrema {extrema:?} vs closed form {expected:?}"
    );
    for (j, (got, want)) in extrema.iter().zip(&expected).enumerate() {
        assert!(
            (got - want).abs() < tol,
            "extremum {j}: {got} vs closed form {want}"
        );
    }
    // Per full cycle the amplitude falls 4F/k.
    for w in extrema.windows(3) {
        assert!(((w[0].abs() - w[2].abs()) - 4.0 * f / k).abs() < 2.0 * tol);
    }
    let x_end = *x.last().unwrap();
    assert!(
        x_end.abs() <= f / k + tol,
        "stops inside the band |x| <= F/k: {x_end}"
    );
    assert!(
        (x_end - last).abs() < tol,
        "rest position {x_end} vs closed form {last}"
    );
}

fn roof_errors(json_building: &str, locked: bool, dts: &[f64]) -> Vec<f64> {
    // Harmonic force on the roof: smooth, so Newmark's order 2 shows (STYLE.md).
    let slip = if locked { r#""locked""# } else { "0" };
    let building = json_building.replace("SLIP", slip);
    let mut errs = Vec::new();
    for &dt in dts {
        let json = format!(
            r#"{{ "building": {building}, "excitation": {{ "harmonic": {{ "floor": 3, "amplitude": 1e6, "omega": 9.0 }} }},
                 "duration": 2.125, "method": {{ "dt": {dt} }}, "outputs": {{ "histories": true, "energies": false }} }}"#
        );
        let scene = scene_json(&json, &SceneOverrides::default());
        let plan = Plan::compile(&scene).unwrap();
        let out = slipload_sim::run_plan(&plan).unwrap();
        let roof = out.history.unwrap().column("x3_m").unwrap();
        // Reference on the coarsest grid: the plan's own M, C, K (bare or braced).
        let h = dts[0];
        let stride = (h / dt).round() as usize;
        let steps = (2.125 / h).round() as usize;
        let exact = exact_linear(
            &plan.mass,
            &plan.damping,
            &plan.stiffness,
            Load::Harmonic {
                floor: 2,
                amplitude: 1e6,
                omega: 9.0,
            },
            h,
            steps,
        );
        errs.push(max_error(&roof, &exact, 2, stride));
    }
    errs
}

const BUILDING: &str = r#"{ "floor_masses": [4.78e5, 4.78e5, 5.18e5],
  "storey_stiffness": [6.8913163e7, 2.71262264e8, 1.21340205e8],
  "damping": { "rayleigh": { "alpha": 0.213, "beta": 9.33e-4 } },
  "dissipators": [ { "floor": 1, "brace_stiffness": 4.4812e8, "mass": 350.11, "slip_load": SLIP },
                   { "floor": 2, "brace_stiffness": 4.4812e8, "mass": 350.11, "slip_load": SLIP },
                   { "floor": 3, "brace_stiffness": 4.4812e8, "mass": 350.11, "slip_load": SLIP } ] }"#;

fn assert_second_order(errs: &[f64]) {
    let orders: Vec<f64> = errs.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
    eprintln!("errors {errs:?}, observed orders {orders:?}");
    // Newmark average acceleration is second order (its period error ∝ Δt²); the band
    // allows the pre-asymptotic drift of the first halvings, not a different order.
    assert!(
        orders.iter().all(|p| (p - 2.0).abs() < 0.15),
        "orders {orders:?}, errors {errs:?}"
    );
}

#[test]
fn zero_slip_load_is_the_bare_frame_second_order() {
    let dts = [1.0 / 128.0, 1.0 / 256.0, 1.0 / 512.0, 1.0 / 1024.0];
    let errs = roof_errors(BUILDING, false, &dts);
    assert_second_order(&errs);
    // And the plan really is the bare frame: 3 DOFs, no contacts.
    let scene = scene_json(
        &format!(
            r#"{{"building": {}, "duration": 1}}"#,
            BUILDING.replace("SLIP", "0")
        ),
        &SceneOverrides::default(),
    );
    let plan = Plan::compile(&scene).unwrap();
    assert_eq!((plan.dofs(), plan.contacts.len()), (3, 0));
}

#[test]
fn locked_dampers_are_the_braced_frame_second_order() {
    let dts = [1.0 / 256.0, 1.0 / 512.0, 1.0 / 1024.0, 1.0 / 2048.0];
    let errs = roof_errors(BUILDING, true, &dts);
    assert_second_order(&errs);
}

#[test]
fn huge_slip_load_matches_the_braced_frame() {
    // μN = 1e15 N through the full model with dissipator DOFs must equal the merged
    // braced frame: the contacts never slip, so only round-off separates them.
    let run = |slip: &str, reduce: bool| {
        let json = format!(
            r#"{{ "building": {}, "excitation": {{ "record": {{ "file": "../records/elCentro.AT2" }} }},
                 "duration": 5, "method": {{ "dt": 0.005 }}, "reduce": {reduce} }}"#,
            BUILDING.replace("SLIP", slip)
        );
        simulate(&scene_json(&json, &SceneOverrides::default()))
            .unwrap()
            .response
    };
    let full = run("1e15", false);
    let locked = run(r#""locked""#, true);
    for i in 0..3 {
        let rel = (full.peak_drift[i] - locked.peak_drift[i]).abs() / locked.peak_drift[i];
        // Round-off: the stuck contacts satisfy w = 0 to ~1e-16 relative per step.
        assert!(
            rel < 1e-9,
            "storey {i}: {} vs {}",
            full.peak_drift[i],
            locked.peak_drift[i]
        );
        assert_eq!(full.transitions[i], 0);
    }
}
