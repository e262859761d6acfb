//! Contract: [`Building::scaling_periods`] gives the first period with the dampers slipping
//! (the bare frame) and stuck (each brace a storey spring, each damper's mass on its
//! floor), and how many modes make up 90 % of the mass. Checked against a one-storey
//! closed form and against the modes of the plan a locked-damper scene compiles (the
//! braced frame the integrators run), for the shipped ten-storey frame.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_sim::modes::Modes;
use slipload_sim::{Building, Plan, SceneOverrides};
use std::f64::consts::PI;

#[test]
fn one_storey_stuck_and_slipping_periods_are_the_closed_forms() {
    // m = 1000 kg, k = 1e5 N/m, a massless brace k′ = 3e5 N/m: T = 2π√(m/k), 2π√(m/(k+k′))
    let json = r#"{ "floor_masses": [1000], "storey_stiffness": [1e5],
      "dissipators": [ { "floor": 1, "brace_stiffness": 3e5, "slip_load": 100 } ] }"#;
    let cfg: slipload_sim::BuildingConfig = serde_json::from_str(json).unwrap();
    let b = Building::from_config(&cfg, &configs().join("inline.json")).unwrap();
    let p = b.scaling_periods().unwrap();
    let (bare, stuck) = (
        2.0 * PI * (1000.0f64 / 1e5).sqrt(),
        2.0 * PI * (1000.0f64 / 4e5).sqrt(),
    );
    // eigen-solver round-off only
    assert!((p.bare_t1_s / bare - 1.0).abs() < 1e-12, "{p:?}");
    assert!((p.stuck_t1_s / stuck - 1.0).abs() < 1e-12, "{p:?}");
    // one mode is all the mass
    assert_eq!((p.bare_modes_90, p.stuck_modes_90), (1, 1));
    assert_eq!(p.mass_90_period_s, p.stuck_t1_s);
}

#[test]
fn ten_storey_braced_period_is_the_locked_plans() {
    let b = Building::load(&configs().join("ten-story.json")).unwrap();
    let p = b.scaling_periods().unwrap();
    // the README's building table: bare T₁ = 1.20 s, locked T₁ = 0.85 s
    assert!((p.bare_t1_s - 1.20).abs() < 0.005, "{p:?}");
    assert!((p.stuck_t1_s - 0.85).abs() < 0.005, "{p:?}");
    // the plan of the same frame with every damper locked: its M and K are the braced
    // frame the integrators run
    let text = std::fs::read_to_string(configs().join("ten-story.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    for d in v["dissipators"].as_array_mut().unwrap() {
        d["slip_load"] = serde_json::json!("locked");
    }
    let json = format!(
        r#"{{ "building": {v}, "excitation": {{ "harmonic": {{ "floor": 1, "amplitude": 1.0, "omega": 1.0 }} }},
             "duration": 0.1, "method": {{ "dt": 0.01 }} }}"#
    );
    let plan = Plan::compile(&scene_json(&json, &SceneOverrides::default())).unwrap();
    let modes = Modes::compute(&plan.mass, &plan.stiffness).unwrap();
    let t1 = 2.0 * PI / modes.omega[0];
    assert!(
        (p.stuck_t1_s / t1 - 1.0).abs() < 1e-9,
        "{} vs {t1}",
        p.stuck_t1_s
    );
    // a shear building's first mode carries most but not 90 % of the mass; ten storeys
    // need two or three modes, and the range's lower end reaches them
    assert!((2..=3).contains(&p.stuck_modes_90), "{p:?}");
    assert!(p.mass_90_period_s < 0.5 * p.stuck_t1_s, "{p:?}");
}
