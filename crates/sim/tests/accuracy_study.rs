//! The accuracy study measures errors against `exact`, fits orders, and records a method's
//! failure as data instead of aborting.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_sim::accuracy::{DtSpec, StudySettings, run_study};
use slipload_sim::{MethodName, SceneOverrides};

#[test]
fn newmark_converges_to_exact_and_exact_is_its_own_reference() {
    let over = SceneOverrides {
        duration: Some(2.0),
        ..Default::default()
    };
    let scene = scene_file("paper-1story-harmonic.json", &over);
    let settings = StudySettings {
        methods: vec![MethodName::Newmark, MethodName::Exact],
        dts: [200.0, 400.0, 800.0, 1600.0]
            .map(DtSpec::PeriodOver)
            .to_vec(),
        repeats: 1,
    };
    let r = run_study(&scene, &settings).unwrap();
    assert_eq!(r.entries.len(), 8);
    let nm: Vec<_> = r.entries[..4].iter().map(|e| e.errors.unwrap()).collect();
    // Newmark through stick-slip events converges at order 1-2 (STYLE.md): the finest step
    // is at least 4x better than the coarsest on every metric, and under 1e-3.
    for (a, b) in [
        (nm[0].peak_drift, nm[3].peak_drift),
        (nm[0].friction_energy, nm[3].friction_energy),
        (nm[0].roof_history, nm[3].roof_history),
    ] {
        assert!(b < a / 4.0 && b < 1e-3, "coarse {a:.3e} fine {b:.3e}");
    }
    let order = r.orders[0].roof_history.unwrap();
    assert!((0.8..2.5).contains(&order), "order {order}");
    // exact against exact: identical runs (deterministic), zero error, and events counted.
    for e in &r.entries[4..] {
        let x = e.errors.unwrap();
        assert_eq!(
            (x.peak_drift, x.friction_energy, x.roof_history),
            (0.0, 0.0, 0.0)
        );
        assert!(e.events > 0);
    }
    assert!(r.to_markdown().contains("| newmark | T1/200 |"));
    assert_eq!(r.to_csv().lines().count(), 9);
}

#[test]
fn a_failing_method_is_recorded_not_fatal() {
    // The benchmark's 350 kg dissipators on 448 MN/m braces: delacruz's sliding-damper
    // loop has gain k′Δt²/(6m′) ≈ 5 at T₁/200 and stops with its typed error, which the
    // study must record as a failure while the other methods still run.
    let scene = scene_file("paper-benchmark-sylmar.json", &SceneOverrides::default());
    let settings = StudySettings {
        methods: vec![MethodName::Delacruz, MethodName::Newmark],
        dts: vec![DtSpec::PeriodOver(200.0)],
        repeats: 1,
    };
    let r = run_study(&scene, &settings).unwrap();
    let d = &r.entries[0];
    assert!(d.errors.is_none() && d.cpu_seconds.is_none());
    assert!(
        d.failure.as_deref().unwrap().contains("did not converge"),
        "{d:?}"
    );
    assert!(r.entries[1].errors.is_some());
    assert!(r.to_markdown().contains("failed:"));
}
