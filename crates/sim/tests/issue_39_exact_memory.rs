//! Issue 39 (tall buildings): `exact` keeps its stick/slip mode sets within a byte budget,
//! and the budget changes its time, never its answer.
//!
//! - A run within the least budget it accepts (its working set: two mode sets and the
//!   scratch of forming one) gives every output bit of an unbounded run — responses,
//!   diagnostics, histories, energies — on scenes that meet many mode sets (massless and
//!   massive dissipators; every output step observed, and peaks only on record intervals),
//!   while its cache stays within that budget and the unbounded run's holds several times
//!   more (so mode sets were evicted and formed again).
//! - A budget below the working set is refused before the first step with
//!   `SimError::ExactMemory`, which gives both figures and the alternative (`newmark` at a
//!   small step); the default budget refuses a frame too tall for its cap, and
//!   `simulate::check` (what `explain` runs) refuses it with the same words.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_sim::bench_scenes::{ShearDamping, shear_building_damped};
use slipload_sim::integrator::exact::{MemoryBudget, working_set_bytes};
use slipload_sim::response::Outcome;
use slipload_sim::{Exact, Integrator, Plan, SceneOverrides, SimError};

/// Every bit of an outcome but the cache's own figure, as text (`{:?}` prints each f64 as
/// its shortest round-trip form: equal text, equal bits).
fn bits(out: &Outcome) -> String {
    let mut o = out.clone();
    o.diagnostics.cache_peak_bytes = 0;
    format!("{o:?}")
}

/// The shear building of `storeys` (a massless damper on every floor) under 10 s of
/// Sylmar, with energies and histories as given.
fn shear_plan(storeys: usize, energies: bool, histories: bool) -> Plan {
    let building = shear_building_damped(storeys, ShearDamping::Rayleigh);
    let json = format!(
        r#"{{ "building": {building},
             "excitation": {{ "record": {{ "file": "../records/SYL090.AT2", "window": [0, 10] }} }},
             "method": {{ "name": "exact" }},
             "outputs": {{ "energies": {energies}, "histories": {histories} }} }}"#
    );
    Plan::compile(&scene_json(&json, &SceneOverrides::default())).unwrap()
}

/// Runs `plan` within its working set and unbounded, and checks the answers are the same
/// bits while the small cache stayed small.
fn same_bits_within_the_least_budget(plan: &Plan) {
    let least = MemoryBudget {
        bytes: working_set_bytes(plan),
    };
    let small = Exact.run_within(plan, least).unwrap();
    let full = Exact.run_within(plan, MemoryBudget::unbounded()).unwrap();
    assert!(
        small.diagnostics.events > 20,
        "the scene meets many mode sets: {} events",
        small.diagnostics.events
    );
    assert!(
        small.diagnostics.cache_peak_bytes <= least.bytes,
        "cache peak {} within the budget {}",
        small.diagnostics.cache_peak_bytes,
        least.bytes
    );
    assert!(
        full.diagnostics.cache_peak_bytes > 3 * least.bytes,
        "the unbounded run keeps more than the small one could ({} vs {})",
        full.diagnostics.cache_peak_bytes,
        least.bytes
    );
    assert_eq!(bits(&small), bits(&full));
    // and again after the unbounded run filled the thread's cache: the budget brings it
    // down, and the bits stay
    let again = Exact.run_within(plan, least).unwrap();
    assert!(again.diagnostics.cache_peak_bytes <= least.bytes);
    assert_eq!(bits(&again), bits(&full));
}

#[test]
fn massless_dampers_every_step_observed_same_bits_within_the_least_budget() {
    same_bits_within_the_least_budget(&shear_plan(10, true, true));
}

#[test]
fn massless_dampers_peaks_only_same_bits_within_the_least_budget() {
    same_bits_within_the_least_budget(&shear_plan(10, false, false));
}

#[test]
fn massive_dampers_same_bits_within_the_least_budget() {
    let over = SceneOverrides {
        method: Some(slipload_sim::MethodName::Exact),
        histories: Some(true),
        ..SceneOverrides::default()
    };
    let plan = Plan::compile(&scene_file("paper-benchmark-sylmar.json", &over)).unwrap();
    same_bits_within_the_least_budget(&plan);
}

#[test]
fn a_budget_below_the_working_set_is_refused_before_the_first_step() {
    let plan = shear_plan(10, false, false);
    let needed = working_set_bytes(&plan);
    let err = Exact
        .run_within(&plan, MemoryBudget { bytes: needed - 1 })
        .unwrap_err();
    match &err {
        SimError::ExactMemory {
            needed: n,
            budget,
            suggested_dt,
        } => {
            assert_eq!((*n, *budget), (needed, needed - 1));
            assert_eq!(*suggested_dt, plan.method.dt / 4.0);
        }
        other => panic!("expected ExactMemory, got {other}"),
    }
    let msg = err.to_string();
    assert!(
        msg.contains("memory budget") && msg.contains("newmark"),
        "{msg}"
    );
}

#[test]
fn the_default_budget_refuses_a_frame_too_tall_and_explain_says_the_same() {
    // 600 storeys: two mode sets with their propagators exceed the 1.5 GiB cap
    let building = shear_building_damped(600, ShearDamping::Rayleigh);
    let json = format!(
        r#"{{ "building": {building},
             "excitation": {{ "record": {{ "file": "../records/SYL090.AT2", "window": [0, 2] }} }},
             "method": {{ "name": "exact" }},
             "outputs": {{ "energies": false, "histories": false }} }}"#
    );
    let plan = Plan::compile(&scene_json(&json, &SceneOverrides::default())).unwrap();
    let budget = MemoryBudget::for_plan(&plan);
    assert_eq!(budget.bytes, slipload_sim::integrator::exact::MEMORY_CAP);
    assert!(working_set_bytes(&plan) > budget.bytes);
    let by_run = Exact.run(&plan).unwrap_err();
    assert!(
        matches!(by_run, SimError::ExactMemory { .. }),
        "expected ExactMemory, got {by_run}"
    );
    let by_check = slipload_sim::simulate::check(&plan).unwrap_err();
    assert_eq!(by_check.to_string(), by_run.to_string());
}

#[test]
fn the_default_budget_is_within_the_issues_targets() {
    // peak RSS targets of issue 39: 256 MiB at 60 storeys, 2 GiB at 120, whatever the
    // record; the mode sets' budget leaves room for the rest of the process
    for (storeys, target) in [(60, 256u64 << 20), (120, 2u64 << 30)] {
        for energies in [false, true] {
            let plan = shear_plan(storeys, energies, false);
            let budget = MemoryBudget::for_plan(&plan).bytes;
            assert!(
                budget <= target * 5 / 8,
                "{storeys} storeys: budget {budget} B against a target of {target} B"
            );
            assert!(working_set_bytes(&plan) <= budget);
        }
    }
}
