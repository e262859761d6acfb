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
        let mut s = one_storey(
            r#", "duration": 0.5, "excitation": { "harmonic": { "floor": 1, "amplitude": 1e300, "omega": 6 } }"#,
        );
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
