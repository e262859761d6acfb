//! Issue 40 §2, plausibility: a slip load far below its floor's weight (kN written as a
//! bare number, which a building file reads in N) and a time step that runs past the
//! duration are warnings the library returns as data, for a front to print.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_sim::building::{
    MIN_PLAUSIBLE_SLIP_LOAD_PER_FLOOR_WEIGHT, Plausibility, plausibility,
};
use slipload_sim::{Building, SceneOverrides};
use std::path::Path;

fn benchmark() -> Building {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    Building::load(&root.join("configs/benchmark-3story.json")).unwrap()
}

#[test]
fn the_benchmark_as_written_is_plausible() {
    let b = benchmark();
    assert_eq!(plausibility(&b, 0.01, 10.0, 1000), vec![]);
}

#[test]
fn a_slip_load_in_kn_written_as_newtons_is_warned_about_per_floor() {
    let b = benchmark();
    let w1 = b.mass[(0, 0)] * slipload_motion::G;
    // floor 1 far below the threshold, floor 2 just above it, floor 3 free (the bare frame)
    let tiny = 0.5 * MIN_PLAUSIBLE_SLIP_LOAD_PER_FLOOR_WEIGHT * w1;
    let w2 = b.mass[(1, 1)] * slipload_motion::G;
    let fine = 1.01 * MIN_PLAUSIBLE_SLIP_LOAD_PER_FLOOR_WEIGHT * w2;
    let b = b.with_slip_loads(&[Some(tiny), Some(fine), Some(0.0)]);
    let w = plausibility(&b, 0.01, 10.0, 1000);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        matches!(w[0], Plausibility::TinySlipLoad { floor: 1, slip_load_n, .. } if slip_load_n == tiny),
        "{w:?}"
    );
    let text = w[0].to_string();
    assert!(text.starts_with("floor 1: the slip load"), "{text}");
    assert!(text.contains("did you mean kN"), "{text}");
    assert!(text.contains("0.1 % of the floor's weight"), "{text}");
}

#[test]
fn a_step_that_does_not_divide_the_duration_is_said_with_where_the_run_ends() {
    let b = benchmark();
    let w = plausibility(&b, 0.003, 1.0, 334);
    assert_eq!(
        w,
        vec![Plausibility::PastDuration {
            dt_s: 0.003,
            duration_s: 1.0,
            steps: 334
        }]
    );
    assert!(
        w[0].to_string().starts_with(
            "dt = 0.003 s does not divide the duration 1 s: the run takes 334 steps and ends at t = 1.002 s, 0.002 s past it"
        ),
        "{}",
        w[0]
    );
    // a step that divides it up to round-off is not
    assert_eq!(plausibility(&b, 0.1, 0.3, 3), vec![]);
}

#[test]
fn the_step_count_the_warning_uses_is_the_scenes() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let over = SceneOverrides {
        dt: Some(0.003),
        duration: Some(1.0),
        ..SceneOverrides::default()
    };
    let scene =
        slipload_sim::Scene::load(&root.join("configs/benchmark-3story.json"), &over).unwrap();
    let w = plausibility(
        &scene.building,
        scene.method.dt,
        scene.duration,
        scene.steps(),
    );
    assert!(
        matches!(
            w.as_slice(),
            [Plausibility::PastDuration { steps: 334, .. }]
        ),
        "{w:?}"
    );
}
