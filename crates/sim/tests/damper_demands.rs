//! Per-damper demands (`outputs.dampers`, docs/MODEL.md § Per-damper demands).
//!
//! - Energy balance: Σ per-damper energy = `energy.friction`. For Newmark's average
//!   acceleration the slip of a step is Δt times its mean slip rate (an identity of the
//!   method; an algebraic element's rate is its slip / Δt), so each damper's term
//!   ½(F₀+F₁)Δs is the accumulator's ½(F₀+F₁)w̄Δt up to the rounding of the state update;
//!   the two sums differ only by that and by summation order: at most a few ε per step of
//!   Σ|terms| (bounded here by 8·steps·ε·Σ peak_force·(travel + peak slip)).
//! - Closed form: Coulomb free vibration of a rigid-plastic damper on an undamped
//!   oscillator (amplitude down by 2F/k each half cycle until |x| ≤ F/k), with `exact` and
//!   `newmark` at the same Δt.
//! - Invariants, a damper that never slips, outputs unchanged when not asked,
//!   determinism.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_sim::bench_scenes::{ShearDamping, shear_building_damped};
use slipload_sim::response::DamperDemand;
use slipload_sim::{MethodName, Outcome, Scene, SceneOverrides, simulate};

fn with_dampers(mut scene: Scene) -> Scene {
    scene.outputs.dampers = true;
    scene
}

fn shipped(name: &str, method: MethodName, duration: f64) -> Scene {
    let over = SceneOverrides {
        record: Some(records().join("I-ELC180.AT2")),
        duration: Some(duration),
        method: Some(method),
        // delacruz is conditionally stable: its default step is too long here
        dt: (method == MethodName::Delacruz).then_some(5e-4),
        ..Default::default()
    };
    with_dampers(scene_file(name, &over))
}

fn demands(out: &Outcome) -> &[DamperDemand] {
    out.response.dampers.as_deref().unwrap()
}

/// |Σ energy_j − energy.friction| and the round-off bound of the module docs.
fn energy_gap(out: &Outcome) -> (f64, f64) {
    let d = demands(out);
    let sum: f64 = d.iter().map(|x| x.energy_j).sum();
    let friction = out.response.energy.unwrap().friction;
    let scale: f64 = d
        .iter()
        .zip(&out.response.peak_slip)
        .map(|(x, s)| x.peak_force_n * (x.cumulative_travel_m + s))
        .sum();
    let bound = 8.0 * out.response.steps as f64 * f64::EPSILON * scale;
    ((sum - friction).abs(), bound)
}

fn check_invariants(what: &str, out: &Outcome, slip_loads: &[f64]) {
    let r = &out.response;
    let d = demands(out);
    assert_eq!(d.len(), r.peak_drift.len(), "{what}");
    for (i, x) in d.iter().enumerate() {
        let travel = x.cumulative_travel_m;
        assert!(
            travel >= (x.slip_max_pos_m + x.slip_max_neg_m) * (1.0 - 1e-12),
            "{what} storey {}: {x:?}",
            i + 1
        );
        if r.peak_slip[i] > 1e-9 && slip_loads[i] > 0.0 {
            assert!(x.slip_excursions >= 1, "{what} storey {}: {x:?}", i + 1);
        }
        assert!(
            x.peak_force_n <= slip_loads[i] * (1.0 + 1e-12),
            "{what} storey {}: {x:?} vs {}",
            i + 1,
            slip_loads[i]
        );
        assert_eq!(x.cycles, x.slip_excursions as f64 / 2.0);
        assert!(
            x.energy_j >= -1e-9 * x.peak_force_n * travel.max(1e-12),
            "{x:?}"
        );
    }
}

fn slip_loads(scene: &Scene) -> Vec<f64> {
    let plan = slipload_sim::Plan::compile(scene).unwrap();
    let mut loads = vec![0.0; plan.floors];
    for c in &plan.contacts {
        loads[c.floor] = c.upper.abs().max(c.lower.abs());
    }
    loads
}

#[test]
fn per_damper_energies_sum_to_the_friction_energy() {
    // dense loop with dissipator DOFs, with algebraic elements, and the banded O(N) loop
    let banded = shear_building_damped(12, ShearDamping::Rayleigh);
    let banded = format!(
        r#"{{ "building": {banded}, "excitation": {{ "synthetic": {{ "index": 0 }} }},
              "duration": 8, "outputs": {{ "dampers": true }} }}"#
    );
    let scenes = [
        (
            "benchmark-3story",
            shipped("benchmark-3story.json", MethodName::Newmark, 10.0),
        ),
        (
            "benchmark-3story-massless",
            shipped("benchmark-3story-massless.json", MethodName::Newmark, 10.0),
        ),
        (
            "ten-story",
            shipped("ten-story.json", MethodName::Newmark, 10.0),
        ),
        (
            "banded shear building",
            scene_json(&banded, &SceneOverrides::default()),
        ),
    ];
    for (what, scene) in scenes {
        let out = simulate(&scene).unwrap();
        let (gap, bound) = energy_gap(&out);
        let friction = out.response.energy.unwrap().friction;
        assert!(friction > 0.0, "{what}");
        assert!(
            gap <= bound,
            "{what}: |Σ − friction| = {gap:e} > {bound:e} (friction {friction:e})"
        );
        check_invariants(what, &out, &slip_loads(&scene));
    }
}

#[test]
fn other_methods_keep_the_invariants_and_the_energy_to_their_accuracy() {
    // hht (the friction energy is its trapezoid in time, not in the slip), exact (∫F·w dt
    // by quadrature between events; the per-damper trapezoid between output steps misses
    // part of a step in which a damper starts slipping) and delacruz.
    for (method, rel) in [
        (MethodName::Hht, 1e-2),
        (MethodName::Exact, 1e-3),
        (MethodName::Delacruz, 1e-2),
    ] {
        let scene = shipped("benchmark-3story.json", method, 4.0);
        let out = simulate(&scene).unwrap();
        let d = demands(&out);
        let sum: f64 = d.iter().map(|x| x.energy_j).sum();
        let friction = out.response.energy.unwrap().friction;
        assert!(
            (sum - friction).abs() <= rel * friction,
            "{method:?}: Σ {sum} vs friction {friction}"
        );
        check_invariants(&format!("{method:?}"), &out, &slip_loads(&scene));
    }
}

/// One storey, m = 1000 kg, k = 1e5 N/m (ω = 10 rad/s), a rigid-plastic friction damper of
/// 500 N (brace 1e6 times the storey), x₀ = 0.1037 m.
fn coulomb(method: &str, dt: f64) -> Outcome {
    let json = format!(
        r#"{{ "building": {{ "floor_masses": [1000], "storey_stiffness": [1e5],
              "dissipators": [ {{ "floor": 1, "brace_stiffness": 1e11, "mass": 0, "slip_load": 500 }} ] }},
             "excitation": {{ "initial": {{ "floor_displacement": [0.1037] }} }},
             "duration": 4.0, "method": {{ "name": "{method}", "dt": {dt} }},
             "outputs": {{ "dampers": true }} }}"#
    );
    simulate(&scene_json(&json, &SceneOverrides::default())).unwrap()
}

#[test]
fn coulomb_free_vibration_demands_match_the_closed_form() {
    let (k, f, x0, omega) = (1e5, 500.0, 0.1037, 10.0);
    // Amplitudes a_j = x0 − 2jF/k while a_j > F/k: ten half cycles, ending at 0.0037 m.
    let amps: Vec<f64> = (0..=10).map(|j| x0 - 2.0 * j as f64 * f / k).collect();
    let travel: f64 = amps.windows(2).map(|w| w[0] + w[1]).sum();
    let want = DamperDemand {
        slip_max_pos_m: 0.0,
        slip_max_neg_m: amps[0] + amps[1],
        peak_slip_velocity_m_s: omega * (x0 - f / k),
        cumulative_travel_m: travel,
        // ten half cycles, and at the stop the stiff brace rings (the force swings from
        // −F towards F + 2k·a₁₀ > F) and the slider slips back by ~(F + k·a₁₀)/k′ ≈ 9e-9 m:
        // a real, tiny, eleventh episode of the elastic–plastic model, in both methods
        slip_excursions: 11,
        cycles: 5.5,
        peak_force_n: f,
        energy_j: 0.5 * k * (x0 * x0 - amps[10] * amps[10]),
    };
    assert!((want.energy_j - f * travel).abs() < 1e-9 * want.energy_j);
    let dt = 1e-4; // ωΔt = 1e-3
    let exact = coulomb("exact", dt);
    let newmark = coulomb("newmark", dt);
    for (what, out, rel) in [
        // sampled at the output steps: a reversal's extreme is missed by ~(ωΔt)²/2
        ("exact", &exact, 1e-6),
        // plus Newmark's own error at ωΔt = 1e-3 over ten half cycles
        ("newmark", &newmark, 1e-5),
    ] {
        let got = demands(out)[0];
        for ((name, g), (_, w)) in got.values().into_iter().zip(want.values()) {
            let tol = rel * w.abs().max(x0 * 1e-3);
            assert!((g - w).abs() <= tol, "{what} {name}: {g} vs {w}");
        }
        assert_eq!(got.slip_excursions, 11, "{what}");
    }
    // exact and newmark agree on every figure at the same Δt
    let (a, b) = (demands(&exact)[0], demands(&newmark)[0]);
    for ((name, x), (_, y)) in a.values().into_iter().zip(b.values()) {
        assert!(
            (x - y).abs() <= 1e-5 * x.abs().max(1e-4),
            "{name}: {x} vs {y}"
        );
    }
}

#[test]
fn a_damper_that_never_slips_reports_no_excursion() {
    let json = r#"{ "building": { "floor_masses": [1000], "storey_stiffness": [1e5],
          "dissipators": [ { "floor": 1, "brace_stiffness": 1e5, "mass": 0, "slip_load": 1e12 } ] },
         "excitation": { "synthetic": { "index": 0 } }, "duration": 5,
         "outputs": { "dampers": true } }"#;
    for method in ["newmark", "exact"] {
        let json = json.replace(
            r#""duration": 5"#,
            &format!(r#""duration": 5, "method": {{ "name": "{method}" }}"#),
        );
        let out = simulate(&scene_json(&json, &SceneOverrides::default())).unwrap();
        let d = demands(&out)[0];
        assert_eq!(d.slip_excursions, 0, "{method}: {d:?}");
        assert!(d.cumulative_travel_m < 1e-12, "{method}: {d:?}");
        assert!(
            d.peak_force_n > 0.0 && d.peak_force_n < 1e12,
            "{method}: {d:?}"
        );
        assert!(d.energy_j.abs() < 1e-9, "{method}: {d:?}");
    }
}

#[test]
fn without_the_key_nothing_changes() {
    for name in ["benchmark-3story.json", "benchmark-3story-massless.json"] {
        let over = SceneOverrides {
            record: Some(records().join("I-ELC180.AT2")),
            duration: Some(5.0),
            ..Default::default()
        };
        let off = scene_file(name, &over);
        assert!(!off.outputs.dampers);
        let on = with_dampers(off.clone());
        let a = simulate(&off).unwrap().response;
        let mut b = simulate(&on).unwrap().response;
        assert!(a.dampers.is_none() && b.dampers.is_some());
        let json = serde_json::to_string(&a).unwrap();
        assert!(!json.contains("dampers"), "{json}");
        // the other outputs with the demands on: a scene the fixed-size loop runs moves to
        // the general loop, which sums in another order (the same answers to round-off)
        assert_peaks_close(name, &a, &b, 1e-12);
        assert_eq!(a.transitions, b.transitions);
        let (ea, eb) = (a.energy.unwrap(), b.energy.unwrap());
        assert!((ea.friction - eb.friction).abs() <= 1e-12 * ea.friction);
        assert!(a.dampers.is_none() && b.dampers.take().is_some());
    }
    // a run the general loop takes either way (histories asked) is the same to the bit
    let over = SceneOverrides {
        record: Some(records().join("I-ELC180.AT2")),
        duration: Some(5.0),
        histories: Some(true),
        ..Default::default()
    };
    let off = scene_file("benchmark-3story.json", &over);
    let mut a = simulate(&off).unwrap().response;
    let mut b = simulate(&with_dampers(off)).unwrap().response;
    (a.cpu_seconds, b.cpu_seconds, b.dampers) = (0.0, 0.0, None);
    assert_eq!(
        serde_json::to_string(&a).unwrap(),
        serde_json::to_string(&b).unwrap()
    );
    // a scene without the key writes none back
    let cfg = slipload_sim::scene::benchmark_scene_config().unwrap();
    let text = serde_json::to_string(&cfg).unwrap();
    assert!(!text.contains("dampers"), "{text}");
}

#[test]
fn demands_are_deterministic() {
    for method in [MethodName::Newmark, MethodName::Exact] {
        let scene = shipped("benchmark-3story.json", method, 3.0);
        let a = simulate(&scene).unwrap();
        let b = simulate(&scene).unwrap();
        assert_eq!(demands(&a), demands(&b), "{method:?}");
    }
}
