//! The `sqp` refiner in a study: a design's derivatives (`phases::gradient`, through the
//! runs' sensitivities and the study's own statistics) are those of its objective, by
//! central differences of plain runs; the refinement takes the same path to the bit on
//! pools of one and two threads; a study it cannot differentiate is refused naming the
//! field; the default refiner `auto` becomes it where the study can be differentiated.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;

use slipload_opt::Study;
use slipload_opt::eval::evaluate::run_designs;
use slipload_opt::model::fidelity::Fidelity;
use slipload_opt::phases::gradient::gradient;
use std::path::{Path, PathBuf};

/// The benchmark study (three storeys) on 2 synthetic records of 4 s, 2 Halton designs,
/// the sqp refiner with `evals` evaluations and 2 finalists; `edit` changes the JSON.
fn study(evals: usize, edit: impl Fn(&mut serde_json::Value)) -> Result<Study, String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["suites"][0]["synthetic"]["count"] = 2.into();
    v["suites"][0]["synthetic"]["duration_s"] = 4.0.into();
    v["sweep"]["points"] = 2.into();
    v["refine"]["method"] = "sqp".into();
    v["refine"]["starts"] = 1.into();
    v["refine"]["max_evaluations"] = evals.into();
    v["refine"]["finalists"] = 2.into();
    edit(&mut v);
    Study::from_json(&v.to_string(), &path).map_err(|e| e.to_string())
}

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("slipload-sqp-{}-{name}", std::process::id()))
}

/// ∂f/∂z of the study's objective from one run with sensitivities, against central
/// differences of plain runs (±1e-6 of the range: the objective is piecewise smooth, and
/// the difference over so short a step is the derivative of its piece to O(δ²) — the
/// tolerance, 1e-5 of the largest component, is the round-off of the runs, 1e-16/1e-6,
/// with room for a stick/slip change inside ±δ in a few of the steps).
#[test]
fn a_designs_derivatives_are_those_of_its_objective() {
    let st = study(4, |_| {}).unwrap();
    let plain = Fidelity::sweep(&st);
    let sens = Fidelity {
        sensitivities: true,
        ..plain
    };
    let z = vec![0.3, 0.45, 0.2];
    let loads = st.space.slip_loads(&z);
    let bare = run_designs(&st, &[vec![0.0; 3]], &plain, &|| {})
        .unwrap()
        .remove(0);
    let rows = run_designs(&st, std::slice::from_ref(&loads), &sens, &|| {})
        .unwrap()
        .remove(0);
    let g = gradient(&st, &rows, &bare, &loads, false).unwrap().unwrap();
    // one case (no property bounds): its objective is the study's
    assert_eq!(g.cases.len(), 1);
    assert_eq!(
        g.cases[0].to_bits(),
        st.objective_value(&rows, &bare, &loads).unwrap().to_bits()
    );
    let f = |z: &[f64]| {
        let l = st.space.slip_loads(z);
        let r = run_designs(&st, std::slice::from_ref(&l), &plain, &|| {})
            .unwrap()
            .remove(0);
        st.objective_value(&r, &bare, &l).unwrap()
    };
    let h = 1e-6;
    let mut worst = 0.0f64;
    let scale = g.case_grads[0].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0);
    for i in 0..3 {
        let (mut a, mut b) = (z.clone(), z.clone());
        a[i] += h;
        b[i] -= h;
        let fd = (f(&a) - f(&b)) / (2.0 * h);
        worst = worst.max((fd - g.case_grads[0][i]).abs());
    }
    assert!(worst <= 1e-5 * scale, "{worst:e} against {scale:e}");
}

/// The refinement on pools of one and two threads: the same evaluations, the same
/// optimum, to the bit.
#[test]
fn pools_of_one_and_two_threads_take_the_same_path() {
    let st = study(5, |_| {}).unwrap();
    let mut out = Vec::new();
    for threads in [1, 2] {
        let dir = scratch(&format!("pool{threads}"));
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let run = pool.install(|| common::optimize_fresh(&st, &dir));
        let r = &run.report.refine;
        // every refinement design carries its derivatives, within the budget; the
        // post-check's moves after them (those the derivatives flag) do not
        let refined = r
            .log
            .iter()
            .take_while(|p| p.limits.as_ref().is_some_and(|l| l.gradient.is_some()))
            .count();
        assert!((1..=5).contains(&refined), "{refined} evaluations");
        let s = r.stationarity.as_ref().unwrap();
        let checked = if s.polls == 0 { 0 } else { s.moves };
        assert_eq!(r.log.len(), refined + checked, "{s:?}");
        assert!(
            r.log[refined..]
                .iter()
                .all(|p| p.limits.as_ref().is_none_or(|l| l.gradient.is_none())),
            "{:?}",
            &r.log[refined..]
        );
        out.push((
            r.log
                .iter()
                .map(|p| {
                    (
                        p.z.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                        p.f.to_bits(),
                    )
                })
                .collect::<Vec<_>>(),
            std::fs::read(dir.join("optimum.json")).unwrap(),
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
    assert!(out[0] == out[1]);
}

#[test]
fn a_study_the_sqp_refiner_cannot_differentiate_is_refused_naming_the_field() {
    let e = study(4, |v| {
        v["objective"]["terms"][0]["metric"] = "energy_ratio".into();
    })
    .unwrap_err();
    assert!(
        e.contains("objective.terms[0].metric") && e.contains("energy_ratio"),
        "{e}"
    );
    let e = study(4, |v| {
        v["fidelity"]["method"] = "exact".into();
    })
    .unwrap_err();
    assert!(e.contains("fidelity.method") && e.contains("exact"), "{e}");
    // a refiner named on the command line is held to the same
    let st = study(4, |v| {
        v["refine"]["method"] = "model".into();
        v["objective"]["terms"][0]["metric"] = "energy_ratio".into();
    })
    .unwrap();
    let e = st
        .check_refiner(slipload_opt::model::config::RefineMethod::Sqp)
        .unwrap_err()
        .to_string();
    assert!(e.contains("objective.terms[0].metric"), "{e}");
    assert!(
        st.check_refiner(slipload_opt::model::config::RefineMethod::Model)
            .is_ok()
    );
}

/// The default refiner, `auto`: the study resolves it when it loads — `sqp` for an
/// objective it can differentiate, `model` for an energy objective or an `exact` sweep —
/// and `--refine auto` asks the same of a loaded study.
#[test]
fn the_default_refiner_is_sqp_where_the_study_can_be_differentiated() {
    use slipload_opt::model::config::RefineMethod;
    let unnamed = |edit: &dyn Fn(&mut serde_json::Value)| {
        study(4, |v| {
            v["refine"].as_object_mut().unwrap().remove("method");
            edit(v);
        })
        .unwrap()
    };
    let st = unnamed(&|_| {});
    assert_eq!(st.config.refine.method, RefineMethod::Sqp);
    assert_eq!(
        st.check_refiner(RefineMethod::Auto).unwrap(),
        RefineMethod::Sqp
    );
    let energy = unnamed(&|v| v["objective"]["terms"][0]["metric"] = "energy_ratio".into());
    assert_eq!(energy.config.refine.method, RefineMethod::Model);
    assert_eq!(
        energy.check_refiner(RefineMethod::Auto).unwrap(),
        RefineMethod::Model
    );
    let exact = unnamed(&|v| v["fidelity"]["method"] = "exact".into());
    assert_eq!(exact.config.refine.method, RefineMethod::Model);
    // a refiner the study names is kept
    let named = study(4, |v| v["refine"]["method"] = "trust-region".into()).unwrap();
    assert_eq!(named.config.refine.method, RefineMethod::TrustRegion);
}
