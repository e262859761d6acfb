//! Issue 16, compiled scenes: work and memory are estimated before anything runs and
//! refused beyond the limits ([`slipload_sim::limits`]); a step longer than the duration
//! is an error; a response that overflows is a typed error for every method, never an
//! `Ok` holding NaN or infinity.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_sim::{MethodName, Plan, Scene, SceneOverrides, SimError, simulate};

fn one_storey(extra: &str) -> Scene {
    let json = format!(
        r#"{{ "building": {{ "floor_masses": [1000], "storey_stiffness": [1e5],
               "dissipators": [ {{ "floor": 1, "brace_stiffness": 1e6, "mass": 10, "slip_load": 500 }} ] }}{extra} }}"#
    );
    Scene::from_json(&json, &configs().join("t.json"), &SceneOverrides::default()).unwrap()
}

#[test]
fn steps_beyond_the_limit_are_refused_before_compiling() {
    let mut s = one_storey(r#", "duration": 2"#);
    s.method.dt = 1e-12;
    match Plan::compile(&s) {
        Err(SimError::TooLarge { estimate, .. }) => {
            assert!(estimate.contains("2.000e12"), "{estimate}")
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn histories_beyond_the_memory_limit_are_refused() {
    let mut s = one_storey(r#", "duration": 90, "outputs": { "histories": true }"#);
    // 9e7 steps (within the step limit) x 11 columns x 25 B: 23 GiB
    s.method.dt = 1e-6;
    let e = Plan::compile(&s).unwrap_err();
    assert!(matches!(e, SimError::TooLarge { .. }), "{e}");
    assert!(e.to_string().contains("GiB"), "{e}");
}

#[test]
fn a_step_longer_than_the_duration_is_an_error() {
    let mut s = one_storey(r#", "duration": 2"#);
    s.method.dt = 10.0;
    assert!(matches!(
        Plan::compile(&s),
        Err(SimError::StepTooLong { .. })
    ));
    // at the duration itself it is one step, as asked
    s.method.dt = 2.0;
    assert!(Plan::compile(&s).is_ok());
}

#[test]
fn an_overflowing_response_is_an_error_for_every_method() {
    for method in [
        MethodName::Newmark,
        MethodName::Hht,
        MethodName::Bilinear,
        MethodName::Delacruz,
        MethodName::Exact,
    ] {
        // a scene file refuses so absurd a force (excitation.harmonic.amplitude is
        // bounded by the weight); set on the compiled scene, it exercises the overflow
        // checks every method must still have
        let mut s = one_storey(
            r#", "duration": 0.5, "excitation": { "harmonic": { "floor": 1, "amplitude": 1e3, "omega": 6 } }"#,
        );
        s.harmonic.as_mut().unwrap().amplitude = 1e300;
        s.method.name = method;
        s.method.dt = 1e-3;
        match simulate(&s) {
            Ok(out) => panic!("{method:?} answered {:?}", out.response.first_non_finite()),
            Err(e) => assert!(
                matches!(
                    e,
                    SimError::NonFiniteResponse { .. }
                        | SimError::NonFinite { .. }
                        | SimError::DelaCruzNotConverged { .. }
                        | SimError::ExactBudget { .. }
                ),
                "{method:?}: {e}"
            ),
        }
    }
}

// ---- Absurd magnitudes, inline buildings, override flags, input paths ----
// A building's values must be physical, not only finite and signed: the bare frame's
// and the braced frame's periods lie in slipload_sim::building::PERIOD_BAND_S, floor
// masses, damping ratios and slip loads in their bands; each refusal names the field.

/// A one-storey building (1000 kg, 1e5 N/m) with the members `frame` added and one
/// dissipator on floor 1 holding `dissipator` (k′ = 1e6 N/m unless given), loaded as a
/// building file: its error.
fn building_error(frame: &str, dissipator: &str) -> String {
    let brace = if dissipator.contains("brace_stiffness") {
        ""
    } else {
        r#""brace_stiffness": 1e6,"#
    };
    let json = format!(
        r#"{{ "floor_masses": [1000], "storey_stiffness": [1e5], {frame}
              "dissipators": [ {{ "floor": 1, {brace} {dissipator} }} ] }}"#
    );
    match Scene::from_json(&json, &configs().join("b.json"), &SceneOverrides::default()) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("accepted: {json}"),
    }
}

#[test]
fn a_stiffness_of_1e300_is_refused_naming_the_field_and_the_period_band() {
    let json = r#"{ "floor_masses": [1000], "storey_stiffness": [1e300] }"#;
    let e = Scene::from_json(
        json,
        &configs().join("b.json"),
        &SceneOverrides {
            duration: Some(1.0),
            ..Default::default()
        },
    )
    .unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("b.json: field `storey_stiffness`"), "{msg}");
    assert!(msg.contains("natural periods"), "{msg}");
    assert!(msg.contains("within 1e-4 … 1e4 s"), "{msg}");
}

#[test]
fn a_floor_mass_of_1e_300_is_refused_naming_the_floor() {
    let json = r#"{ "floor_masses": [1000, 1e-300], "storey_stiffness": [1e5, 1e5] }"#;
    let e = Scene::from_json(
        json,
        &configs().join("b.json"),
        &SceneOverrides {
            duration: Some(1.0),
            ..Default::default()
        },
    )
    .unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("field `floor_masses[1]`"), "{msg}");
    assert!(msg.contains("physical band"), "{msg}");
}

#[test]
fn a_brace_of_1e300_n_per_m_is_refused_naming_the_dissipator() {
    let msg = building_error("", r#""brace_stiffness": 1e300, "slip_load": 500"#);
    assert!(msg.contains("dissipators[0].brace_stiffness"), "{msg}");
    assert!(msg.contains("braces locked"), "{msg}");
}

#[test]
fn a_dissipator_mass_of_1e_300_is_refused_with_the_massless_advice() {
    let json = r#"{ "floor_masses": [1000], "storey_stiffness": [1e5],
          "dissipators": [ { "floor": 1, "brace_stiffness": 1e6, "mass": 1e-300, "slip_load": 500 } ] }"#;
    let msg = Scene::from_json(json, &configs().join("b.json"), &SceneOverrides::default())
        .unwrap_err()
        .to_string();
    assert!(msg.contains("dissipators[0].mass"), "{msg}");
    assert!(msg.contains("m′ = 0 for a massless dissipator"), "{msg}");
}

#[test]
fn damping_of_1e300_is_refused_with_the_damping_ratio() {
    let msg = building_error(
        r#""damping": { "storey": [1e300] },"#,
        r#""mass": 10, "slip_load": 500"#,
    );
    assert!(msg.contains("field `damping`"), "{msg}");
    assert!(msg.contains("damping ratio"), "{msg}");
    let msg = building_error(
        "",
        r#""mass": 10, "slip_load": 500, "brace_damping": 1e300"#,
    );
    assert!(msg.contains("dissipators[0].brace_damping"), "{msg}");
    assert!(msg.contains("critical"), "{msg}");
}

#[test]
fn a_slip_load_of_1e300_is_refused_with_the_weight_and_locked_advice() {
    let msg = building_error("", r#""slip_load": 1e300"#);
    assert!(msg.contains("dissipators[0].slip_load"), "{msg}");
    assert!(msg.contains("weight"), "{msg}");
    assert!(msg.contains("\"locked\""), "{msg}");
    let msg = building_error("", r#""bounds": [-1e300, 10]"#);
    assert!(msg.contains("dissipators[0].bounds[0]"), "{msg}");
}

#[test]
fn physical_extremes_are_accepted() {
    // a stiff light dissipator (the benchmark's m′ on its brace: 5.6 ms) and a slip load
    // of the whole weight are real designs
    let json = r#"{ "floor_masses": [4.78e5], "storey_stiffness": [4.36e8],
          "damping": { "modal": { "ratio": 0.05 } },
          "dissipators": [ { "floor": 1, "brace_stiffness": 4.4812e8, "mass": 350.11,
                             "slip_load": 4.7e6 } ] }"#;
    Scene::from_json(
        json,
        &configs().join("b.json"),
        &SceneOverrides {
            duration: Some(0.5),
            ..Default::default()
        },
    )
    .unwrap();
}

#[test]
fn an_inline_building_error_names_the_field_as_a_building_file_does() {
    let json = r#"{ "building": { "floor_masses": [1000], "storey_stifness": [1e5] },
                    "duration": 1 }"#;
    let msg = Scene::from_json(json, &configs().join("s.json"), &SceneOverrides::default())
        .unwrap_err()
        .to_string();
    assert!(!msg.contains("untagged"), "{msg}");
    assert!(!msg.contains("did not match any variant"), "{msg}");
    assert!(msg.contains("unknown field `storey_stifness`"), "{msg}");
    assert!(msg.contains("line 1"), "{msg}");
    // a wrong type inside the inline building, likewise
    let json = r#"{ "building": { "floor_masses": "heavy", "storey_stiffness": [1e5] } }"#;
    let msg = Scene::from_json(json, &configs().join("s.json"), &SceneOverrides::default())
        .unwrap_err()
        .to_string();
    assert!(!msg.contains("did not match any variant"), "{msg}");
    assert!(msg.contains("invalid type"), "{msg}");
    // neither a path nor an object
    let json = r#"{ "building": 3, "duration": 1 }"#;
    let msg = Scene::from_json(json, &configs().join("s.json"), &SceneOverrides::default())
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("a building file's path (a string) or a building object"),
        "{msg}"
    );
}

#[test]
fn a_non_finite_duration_override_blames_the_flag_not_the_file() {
    for d in [f64::INFINITY, f64::NAN, -1.0] {
        let json = r#"{ "floor_masses": [1000], "storey_stiffness": [1e5] }"#;
        let msg = Scene::from_json(
            json,
            &configs().join("b.json"),
            &SceneOverrides {
                duration: Some(d),
                ..Default::default()
            },
        )
        .unwrap_err()
        .to_string();
        assert!(msg.contains("--duration: "), "{d}: {msg}");
        assert!(!msg.contains("b.json"), "{d}: {msg}");
    }
}

#[test]
fn a_scene_path_that_is_a_fifo_device_or_folder_is_refused_by_kind() {
    let dir = std::env::temp_dir().join(format!("slipload-bad-scene-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("scene.json");
    assert!(
        std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let (tx, rx) = std::sync::mpsc::channel();
    let paths = [fifo.clone(), "/dev/zero".into(), dir.clone()];
    std::thread::spawn(move || {
        let errors: Vec<String> = paths
            .iter()
            .map(|p| match Scene::load(p, &SceneOverrides::default()) {
                Err(e) => e.to_string(),
                Ok(_) => "accepted".into(),
            })
            .collect();
        let _ = tx.send(errors);
    });
    let errors = rx
        .recv_timeout(std::time::Duration::from_secs(20))
        .expect("loading blocked");
    assert!(errors[0].contains("named pipe (FIFO)"), "{}", errors[0]);
    assert!(errors[1].contains("character device"), "{}", errors[1]);
    assert!(errors[2].contains("is a folder"), "{}", errors[2]);
    for e in &errors {
        assert!(e.contains("scene file"), "{e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_iteration_cap_beyond_any_converging_loop_is_refused() {
    let json = r#"{ "building": { "floor_masses": [1000], "storey_stiffness": [1e5] },
                    "duration": 1, "method": { "name": "delacruz", "max_iterations": 4000000000 } }"#;
    let msg = Scene::from_json(json, &configs().join("s.json"), &SceneOverrides::default())
        .unwrap_err()
        .to_string();
    assert!(msg.contains("field `method.max_iterations`"), "{msg}");
    assert!(msg.contains("limit 10000"), "{msg}");
    assert!(msg.contains("--allow-large"), "{msg}");
}

#[test]
fn an_absurd_harmonic_force_or_initial_state_is_refused_naming_the_field() {
    let json = r#"{ "building": { "floor_masses": [1000], "storey_stiffness": [1e5] }, "duration": 1,
                    "excitation": { "harmonic": { "floor": 1, "amplitude": 1e150, "omega": 6 } } }"#;
    let msg = Scene::from_json(json, &configs().join("s.json"), &SceneOverrides::default())
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("field `excitation.harmonic.amplitude`"),
        "{msg}"
    );
    assert!(msg.contains("weight"), "{msg}");
    let json = r#"{ "building": { "floor_masses": [1000], "storey_stiffness": [1e5] }, "duration": 1,
                    "excitation": { "initial": { "floor_velocity": [1e200] } } }"#;
    let msg = Scene::from_json(json, &configs().join("s.json"), &SceneOverrides::default())
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("field `excitation.initial.floor_velocity[0]`"),
        "{msg}"
    );
}
