//! Asking for energies must not change the peaks: a peaks-only `newmark` run takes the
//! fixed-size step loop (compile-time DOF and contact counts, friction answered from its
//! stick/slip pattern), a run with energies the general loop, and both solve the same
//! equations exactly. Their answers may differ only by round-off.
//!
//! Covers every branch of the fixed loop: dissipators with mass (contacts with DOF),
//! massless ones condensed into elastic–perfectly plastic elements (first floor against
//! the ground, upper floors against the floor below), the ten-storey building in both
//! forms, HHT-α (friction memory), a harmonic floor force, asymmetric friction bounds,
//! dampers on some floors only, and a bare frame; and a DOF count without a fixed loop,
//! where both runs take the general loop.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_sim::{Plan, Response, SceneOverrides, run_plan};

/// Runs `scene_json` twice, peaks only and with energies; returns both responses and the
/// plan's (DOFs, contacts).
fn both(scene_json: &str) -> (Response, Response, (usize, usize)) {
    let mut scene = scene_json_checked(scene_json);
    scene.outputs.energies = false;
    scene.outputs.histories = false;
    let fast = Plan::compile(&scene).unwrap();
    let dims = (fast.dofs(), fast.contacts.len());
    let a = run_plan(&fast).unwrap().response;
    scene.outputs.energies = true;
    let b = run_plan(&Plan::compile(&scene).unwrap()).unwrap().response;
    assert!(a.energy.is_none() && b.energy.is_some());
    (a, b, dims)
}

fn scene_json_checked(text: &str) -> slipload_sim::Scene {
    scene_json(text, &SceneOverrides::default())
}

/// Every peak to 1e-9 of its array's largest value: both loops run the same arithmetic
/// up to the order of a few sums and the friction solve (explicit inverse of the free
/// block vs a Cholesky factor), ~1e-15 per step, over a few thousand steps of a
/// non-expansive (dissipative) map. Transition counts are fragile (a grazing contact may
/// stick for one step in one run and not the other): within 2 or 1 %.
fn assert_same(name: &str, a: &Response, b: &Response) {
    assert_peaks_close(name, a, b, 1e-9);
    for (i, (p, q)) in a.transitions.iter().zip(&b.transitions).enumerate() {
        let allowed = 2u64.max(q / 100);
        assert!(
            p.abs_diff(*q) <= allowed,
            "{name}: transitions[{i}] {p} vs {q}"
        );
    }
    assert_eq!(a.steps, b.steps);
}

fn record_scene(building: &str, record: &str, pga_g: f64, duration: f64, extra: &str) -> String {
    format!(
        r#"{{ "building": {building},
             "excitation": {{ "record": {{ "file": "../../shared/records/{record}", "scale_pga_g": {pga_g} }} }},
             "duration": {duration} {extra} }}"#
    )
}

#[test]
fn dissipators_with_mass() {
    let s = record_scene(r#""benchmark-3story.json""#, "SYL090.AT2", 0.6, 10.0, "");
    let (a, b, dims) = both(&s);
    assert_eq!(dims, (6, 3));
    assert!(
        a.transitions.iter().sum::<u64>() > 100,
        "the case must slip and stick"
    );
    assert_same("benchmark", &a, &b);
}

#[test]
fn massless_dissipators_as_epp_elements() {
    let s = record_scene(
        r#""benchmark-3story-massless.json""#,
        "SYL090.AT2",
        0.6,
        10.0,
        "",
    );
    let (a, b, dims) = both(&s);
    assert_eq!(dims, (3, 3));
    assert_same("benchmark massless", &a, &b);
}

#[test]
fn ten_storeys_reduced_and_full() {
    for (reduce, dims) in [(true, (10, 10)), (false, (20, 10))] {
        let extra = format!(r#", "reduce": {reduce}"#);
        let s = record_scene(r#""ten-story.json""#, "I-ELC180.AT2", 0.4, 8.0, &extra);
        let (a, b, got) = both(&s);
        assert_eq!(got, dims);
        assert_same(&format!("ten-story reduce={reduce}"), &a, &b);
    }
}

#[test]
fn hht_alpha_keeps_its_friction_memory() {
    let s = record_scene(
        r#""benchmark-3story.json""#,
        "SYL090.AT2",
        0.6,
        6.0,
        r#", "method": { "name": "hht", "alpha": -0.1 }"#,
    );
    let (a, b, _) = both(&s);
    assert_same("benchmark hht", &a, &b);
}

#[test]
fn harmonic_floor_force() {
    let s = r#"{ "building": "paper-1story.json",
                 "excitation": { "harmonic": { "floor": 1, "amplitude": "127.491 kN", "omega": 15.9781 } },
                 "duration": 5 }"#;
    let (a, b, dims) = both(s);
    assert_eq!(dims.1, 1);
    assert!(a.transitions[0] > 0);
    assert_same("one storey harmonic", &a, &b);
}

#[test]
fn asymmetric_bounds_and_some_floors_without_dampers() {
    let building = r#"{
        "floor_masses": ["4.78e5 kg", "4.78e5 kg", "5.18e5 kg"],
        "storey_stiffness": ["68913.163 kN/m", "271262.264 kN/m", "121340.205 kN/m"],
        "damping": { "rayleigh": { "alpha": 0.213, "beta": 9.33e-4 } },
        "dissipators": [
          { "floor": 1, "brace_stiffness": "448.12 MN/m", "mass": "350.11 kg", "brace_damping": 0,
            "bounds": ["-500 kN", "900 kN"] },
          { "floor": 3, "brace_stiffness": "448.12 MN/m", "mass": 0, "brace_damping": 0,
            "bounds": ["-300 kN", "200 kN"] }
        ] }"#;
    let s = record_scene(building, "SYL090.AT2", 0.6, 8.0, "");
    let (a, b, dims) = both(&s);
    assert_eq!(dims, (4, 2));
    assert_same("asymmetric, floors 1 and 3", &a, &b);
}

#[test]
fn bare_frame_and_sizes_without_a_fixed_loop() {
    let bare = r#"{
        "floor_masses": ["4.78e5 kg", "4.78e5 kg", "5.18e5 kg"],
        "storey_stiffness": ["68913.163 kN/m", "271262.264 kN/m", "121340.205 kN/m"],
        "damping": { "rayleigh": { "alpha": 0.213, "beta": 9.33e-4 } } }"#;
    let (a, b, dims) = both(&record_scene(bare, "SYL090.AT2", 0.6, 8.0, ""));
    assert_eq!(dims, (3, 0));
    assert_same("bare frame", &a, &b);
    // Nine storeys with massless dampers: no fixed loop for (9, 9); both take the
    // general loop.
    let masses: Vec<String> = (0..9).map(|_| "\"5e5 kg\"".into()).collect();
    let ks: Vec<String> = (0..9).map(|_| "\"4e8 N/m\"".into()).collect();
    let ds: Vec<String> = (1..=9)
        .map(|f| {
            format!(
                r#"{{ "floor": {f}, "brace_stiffness": "8e8 N/m", "mass": 0, "brace_damping": 0, "slip_load": "{} kN" }}"#,
                100 * (10 - f)
            )
        })
        .collect();
    let nine = format!(
        r#"{{ "floor_masses": [{}], "storey_stiffness": [{}], "damping": {{ "modal": {{ "ratio": 0.02 }} }}, "dissipators": [{}] }}"#,
        masses.join(","),
        ks.join(","),
        ds.join(",")
    );
    let (a, b, dims) = both(&record_scene(&nine, "I-ELC180.AT2", 0.4, 6.0, ""));
    assert_eq!(dims, (9, 9));
    assert_same("nine storeys", &a, &b);
}
