//! A reduced plan gives the same answers as the full 2N model (docs/MODEL.md § Scenes and
//! plans), to round-off:
//! - massless dissipators condensed into elastic–perfectly plastic elements vs the
//!   same dissipators kept as zero-mass DOFs;
//! - zero slip loads dropped vs kept (massless, so the dropped brace carries nothing);
//! - dampers on only some floors.
//!
//! The condensation is exact for a brace with a dashpot (c′ > 0), whose dissipator DOF
//! has a velocity of its own: both plans then impose the friction law on the slip rate
//! at the step's end, so the first two checks give the braces a small dashpot. Without
//! one (c′ = 0) the condensed element is algebraic and `newmark` imposes the law on the
//! step's slip (the return mapping), which a zero-mass DOF does not:
//! tests/epp_return_mapping.rs checks that scheme against an independent one.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_sim::{Plan, Response, SceneOverrides, run_plan};

fn run(building: &str, reduce: bool, record: &str, pga_g: f64) -> (Response, usize) {
    let json = format!(
        r#"{{ "building": {building}, "excitation": {{ "record": {{ "file": "../records/{record}", "scale_pga_g": {pga_g} }} }},
             "duration": 8, "reduce": {reduce} }}"#
    );
    let scene = scene_json(&json, &SceneOverrides::default());
    let plan = Plan::compile(&scene).unwrap();
    let dofs = plan.dofs();
    (run_plan(&plan).unwrap().response, dofs)
}

/// Relative differences of every response array; round-off of a few thousand steps of a
/// well-conditioned linear solve is ~1e-12, the tolerance 1e-9 leaves room for the
/// different (but algebraically equal) operation order of the condensed element.
fn assert_same(a: &Response, b: &Response) {
    assert_peaks_close("reduced vs full", a, b, 1e-9);
    let (ea, eb) = (a.energy.unwrap(), b.energy.unwrap());
    for (p, q) in [
        (ea.input, eb.input),
        (ea.friction, eb.friction),
        (ea.viscous, eb.viscous),
    ] {
        assert!((p - q).abs() <= 1e-9 * ea.input.abs(), "energy {p} vs {q}");
    }
    // Transition counts are fragile (docs/MODEL.md): a grazing stick may flip in round-off.
    for (p, q) in a.transitions.iter().zip(&b.transitions) {
        assert!(p.abs_diff(*q) <= 2, "transitions {p} vs {q}");
    }
}

const TEN: &str = "ten-story.json";

/// The building with a brace dashpot c′ = 10⁵ N·s/m on every dissipator (under 1 % of
/// critical for the benchmark braces and floors), so its massless dissipator DOFs have a
/// velocity of their own.
fn with_brace_dashpots(building: &str) -> String {
    let out = building.replace("\"brace_damping\": 0", "\"brace_damping\": 1e5");
    assert_ne!(out, building, "the building must have braces to damp");
    out
}

#[test]
fn massless_dissipators_as_epp_elements_equal_zero_mass_dofs() {
    let building = with_brace_dashpots(&std::fs::read_to_string(configs().join(TEN)).unwrap());
    let (reduced, n_red) = run(&building, true, "I-ELC180.AT2", 0.4);
    let (full, n_full) = run(&building, false, "I-ELC180.AT2", 0.4);
    assert_eq!((n_red, n_full), (10, 20), "EPP elements carry no DOF");
    assert!(
        reduced.transitions.iter().sum::<u64>() > 10,
        "the dampers must actually slip for this test to mean something"
    );
    assert_same(&reduced, &full);
}

#[test]
fn zero_slip_loads_drop_the_brace_exactly() {
    // A shear-building version of the benchmark frame (storey springs fitted to its
    // periods), massless dampers: floor 2 with μN = 0, floors 1 and 3 active.
    let building = r#"{ "floor_masses": [4.78e5, 4.78e5, 5.18e5],
      "storey_stiffness": [6.8913163e7, 2.71262264e8, 1.21340205e8],
      "damping": { "rayleigh": { "alpha": 0.213, "beta": 9.33e-4 } },
      "dissipators": [ { "floor": 1, "brace_stiffness": 4.4812e8, "brace_damping": 1e5, "slip_load": 4e5 },
                       { "floor": 2, "brace_stiffness": 4.4812e8, "brace_damping": 1e5, "slip_load": 0 },
                       { "floor": 3, "brace_stiffness": 4.4812e8, "brace_damping": 1e5, "slip_load": 2e5 } ] }"#;
    let (reduced, n_red) = run(building, true, "SYL090.AT2", 0.6);
    let (mut full, n_full) = run(building, false, "SYL090.AT2", 0.6);
    assert_eq!((n_red, n_full), (3, 6));
    assert_eq!(reduced.peak_slip[1], 0.0, "no damper on the bare storey");
    // In the full model the force-free massless dissipator rides on the floor below, so
    // its stroke is the storey drift; the reduced plan has no damper there (slip 0).
    assert!((full.peak_slip[1] - full.peak_drift[1]).abs() <= 1e-12 * full.peak_drift[1]);
    full.peak_slip[1] = 0.0;
    assert_same(&reduced, &full);
}

#[test]
fn dampers_on_some_floors_only() {
    // Massive dissipators on floors 1 and 3 only: the plan has 5 DOFs; without
    // reduction it is the same model (nothing to reduce), so the answers are identical.
    let building = r#"{ "floor_masses": [4.78e5, 4.78e5, 5.18e5],
      "storey_stiffness": [6.8913163e7, 2.71262264e8, 1.21340205e8],
      "damping": { "rayleigh": { "alpha": 0.213, "beta": 9.33e-4 } },
      "dissipators": [ { "floor": 1, "brace_stiffness": 4.4812e8, "mass": 350.11, "slip_load": 8.34e5 },
                       { "floor": 3, "brace_stiffness": 4.4812e8, "mass": 350.11, "slip_load": 4.37e5 } ] }"#;
    let (reduced, n_red) = run(building, true, "SYL090.AT2", 0.6);
    let (full, _) = run(building, false, "SYL090.AT2", 0.6);
    assert_eq!(n_red, 5);
    assert_eq!(reduced.peak_slip[1], 0.0);
    assert_same(&reduced, &full);
}

#[test]
fn bilinear_equals_the_full_model_with_massless_dissipators() {
    // `bilinear` ignores m′: on the benchmark it must equal the full 2N model whose
    // dissipators are massless (zero-mass DOFs), at the same Δt, to round-off (with brace
    // dashpots: see the module's note).
    let bench = with_brace_dashpots(
        &std::fs::read_to_string(configs().join("benchmark-3story.json")).unwrap(),
    );
    let massless = bench.replace("\"350.11 kg\"", "0");
    assert_ne!(bench, massless);
    let run_with = |building: &str, method: &str, reduce: bool| {
        let json = format!(
            r#"{{ "building": {building}, "excitation": {{ "record": {{ "file": "../records/SYL090.AT2" }} }},
                 "duration": 10, "method": {{ "name": "{method}" }}, "reduce": {reduce} }}"#
        );
        slipload_sim::simulate(&scene_json(&json, &SceneOverrides::default()))
            .unwrap()
            .response
    };
    let bilinear = run_with(&bench, "bilinear", true);
    let full = run_with(&massless, "newmark", false);
    assert_eq!(bilinear.method, "bilinear");
    assert_same(&bilinear, &full);
    // With the real m′ = 350 kg the full model differs: bilinear is an approximation there.
    let newmark = run_with(&bench, "newmark", true);
    assert!(
        newmark
            .peak_drift
            .iter()
            .zip(&bilinear.peak_drift)
            .any(|(a, b)| a != b)
    );
}

#[test]
fn bilinear_puts_an_overstressed_initial_brace_on_its_slip_load() {
    // paper-1story-free: x′₀ = 0.10 m on k′ = 2597.01 kN/m is 259.7 kN, far above
    // μN = 39.325 kN. With m′ ignored the dissipator slides at once until k′x′ = μN.
    let over = SceneOverrides {
        method: Some(slipload_sim::MethodName::Bilinear),
        ..Default::default()
    };
    let scene = scene_file("paper-1story-free.json", &over);
    let plan = Plan::compile(&scene).unwrap();
    let (k, slip) = (2597.01e3, 39.325e3);
    assert!(
        (plan.contact_x0[0].0 - slip / k).abs() < 1e-15,
        "x'0 = {}",
        plan.contact_x0[0].0
    );
    assert!(plan.explain().contains("instant slide"));
    let out = run_plan(&plan).unwrap();
    let e = out.response.energy.unwrap();
    assert!(e.balance_error.abs() < 1e-10 * out.diagnostics.initial_energy);
    // The full model starts with the same floor but a charged brace: more energy to dissipate.
    let full = slipload_sim::simulate(&scene_file(
        "paper-1story-free.json",
        &SceneOverrides::default(),
    ))
    .unwrap();
    assert!(full.diagnostics.initial_energy > out.diagnostics.initial_energy);
}
