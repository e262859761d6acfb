//! The fixed-size step loop of `newmark` (compile-time DOF and contact counts, friction
//! answered from its stick/slip pattern) runs peaks-only runs and runs with energies; a run
//! that also records histories takes the general loop. All three solve the same equations
//! exactly, so their answers may differ only by round-off: asking for energies or
//! histories must not change the peaks, and the fixed loop's energies must be the
//! general loop's.
//!
//! Covers every branch of the fixed loop: dissipators with mass (contacts with DOF),
//! massless ones condensed into elastic–perfectly plastic elements (first floor against
//! the ground, upper floors against the floor below), the ten-storey building in both
//! forms, HHT-α (friction memory), a harmonic floor force, asymmetric friction bounds,
//! dampers on some floors only, and a bare frame; and a DOF count without a fixed loop,
//! where every run takes the general loop.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_sim::{Outcome, Plan, SceneOverrides, run_plan};

/// The runs of one scene: peaks only, with energies, and with energies and histories (the
/// general loop).
struct Runs {
    peaks: Outcome,
    energies: Outcome,
    general: Outcome,
    /// The plan's (DOFs, contacts).
    dims: (usize, usize),
}

/// Runs `scene_json` peaks only, with energies, and with energies and histories.
fn both(scene_json: &str) -> Runs {
    let mut scene = scene_json_checked(scene_json);
    let mut run = |energies: bool, histories: bool| {
        scene.outputs.energies = energies;
        scene.outputs.histories = histories;
        let plan = Plan::compile(&scene).unwrap();
        (run_plan(&plan).unwrap(), (plan.dofs(), plan.contacts.len()))
    };
    let (peaks, dims) = run(false, false);
    let (energies, _) = run(true, false);
    let (general, _) = run(true, true);
    assert!(peaks.response.energy.is_none() && energies.response.energy.is_some());
    assert!(peaks.history.is_none() && energies.history.is_none());
    assert!(general.history.is_some(), "histories take the general loop");
    Runs {
        peaks,
        energies,
        general,
        dims,
    }
}

fn scene_json_checked(text: &str) -> slipload_sim::Scene {
    scene_json(text, &SceneOverrides::default())
}

/// Every peak to 1e-9 of its array's largest value: the loops run the same arithmetic
/// up to the order of a few sums and the friction solve (explicit inverse of the free
/// block vs a Cholesky factor), ~1e-15 per step, over a few thousand steps of a
/// non-expansive (dissipative) map. Transition counts are fragile (a grazing contact may
/// stick for one step in one run and not the other): within 2 or 1 %. The energies and
/// the strain-energy area to 1e-9 of the largest energy: the same trapezoidal sums over
/// those states, their quadratic forms summed in another order.
fn assert_same(name: &str, runs: &Runs) {
    let g = &runs.general;
    for (what, o) in [("peaks only", &runs.peaks), ("energies", &runs.energies)] {
        let (a, b) = (&o.response, &g.response);
        let name = format!("{name} ({what} vs general loop)");
        assert_peaks_close(&name, a, b, 1e-9);
        for (i, (p, q)) in a.transitions.iter().zip(&b.transitions).enumerate() {
            let allowed = 2u64.max(q / 100);
            assert!(
                p.abs_diff(*q) <= allowed,
                "{name}: transitions[{i}] {p} vs {q}"
            );
        }
        assert_eq!(a.steps, b.steps);
    }
    let (e, f) = (
        runs.energies.response.energy.as_ref().unwrap(),
        g.response.energy.as_ref().unwrap(),
    );
    let pairs = [
        ("input", e.input, f.input),
        ("kinetic", e.kinetic, f.kinetic),
        ("strain", e.strain, f.strain),
        ("viscous", e.viscous, f.viscous),
        ("friction", e.friction, f.friction),
        ("balance_error", e.balance_error, f.balance_error),
    ];
    let scale = pairs
        .iter()
        .fold(0.0f64, |m, (_, x, y)| m.max(x.abs()).max(y.abs()))
        .max(1e-30);
    for (what, x, y) in pairs {
        assert!(
            (x - y).abs() <= 1e-9 * scale,
            "{name}: energy {what}: {x} vs {y} (scale {scale})"
        );
    }
    let (sa, sb) = (
        runs.energies.diagnostics.strain_energy_area,
        g.diagnostics.strain_energy_area,
    );
    assert!(
        sa > 0.0 && (sa - sb).abs() <= 1e-9 * sb,
        "{name}: strain energy area {sa} vs {sb}"
    );
    assert_eq!(
        runs.energies.diagnostics.initial_energy, g.diagnostics.initial_energy,
        "{name}: initial energy"
    );
}

fn record_scene(building: &str, record: &str, pga_g: f64, duration: f64, extra: &str) -> String {
    format!(
        r#"{{ "building": {building},
             "excitation": {{ "record": {{ "file": "../records/{record}", "scale_pga_g": {pga_g} }} }},
             "duration": {duration} {extra} }}"#
    )
}

#[test]
fn dissipators_with_mass() {
    let s = record_scene(r#""benchmark-3story.json""#, "SYL090.AT2", 0.6, 10.0, "");
    let runs = both(&s);
    assert_eq!(runs.dims, (6, 3));
    assert!(
        runs.peaks.response.transitions.iter().sum::<u64>() > 100,
        "the case must slip and stick"
    );
    assert_same("benchmark", &runs);
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
    let runs = both(&s);
    assert_eq!(runs.dims, (3, 3));
    assert_same("benchmark massless", &runs);
}

#[test]
fn ten_storeys_reduced_and_full() {
    for (reduce, dims) in [(true, (10, 10)), (false, (20, 10))] {
        let extra = format!(r#", "reduce": {reduce}"#);
        let s = record_scene(r#""ten-story.json""#, "I-ELC180.AT2", 0.4, 8.0, &extra);
        let runs = both(&s);
        assert_eq!(runs.dims, dims);
        assert_same(&format!("ten-story reduce={reduce}"), &runs);
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
    let runs = both(&s);
    assert_same("benchmark hht", &runs);
}

#[test]
fn harmonic_floor_force() {
    let s = r#"{ "building": "paper-1story.json",
                 "excitation": { "harmonic": { "floor": 1, "amplitude": "127.491 kN", "omega": 15.9781 } },
                 "duration": 5 }"#;
    let runs = both(s);
    assert_eq!(runs.dims.1, 1);
    assert!(runs.peaks.response.transitions[0] > 0);
    assert_same("one storey harmonic", &runs);
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
    let runs = both(&s);
    assert_eq!(runs.dims, (4, 2));
    assert_same("asymmetric, floors 1 and 3", &runs);
}

#[test]
fn bare_frame_and_sizes_without_a_fixed_loop() {
    let bare = r#"{
        "floor_masses": ["4.78e5 kg", "4.78e5 kg", "5.18e5 kg"],
        "storey_stiffness": ["68913.163 kN/m", "271262.264 kN/m", "121340.205 kN/m"],
        "damping": { "rayleigh": { "alpha": 0.213, "beta": 9.33e-4 } } }"#;
    let runs = both(&record_scene(bare, "SYL090.AT2", 0.6, 8.0, ""));
    assert_eq!(runs.dims, (3, 0));
    assert_same("bare frame", &runs);
    // Nine storeys with massless dampers: no fixed loop for (9, 9); every run takes the
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
    let runs = both(&record_scene(&nine, "I-ELC180.AT2", 0.4, 6.0, ""));
    assert_eq!(runs.dims, (9, 9));
    assert_same("nine storeys", &runs);
}
