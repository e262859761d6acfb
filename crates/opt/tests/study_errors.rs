//! Contract: a bad study (unknown field, empty suite, reversed bounds, infeasible
//! constraints, bad settings) is an error that names the file and the field, raised while
//! loading — before any simulation can run.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use std::path::{Path, PathBuf};

fn configs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs")
}

/// The benchmark study with `edit` applied to its JSON value.
fn study_with(edit: impl FnOnce(&mut serde_json::Value)) -> Result<Study, String> {
    let path = configs().join("study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    edit(&mut v);
    Study::from_json(&v.to_string(), &path).map_err(|e| e.to_string())
}

fn err(edit: impl FnOnce(&mut serde_json::Value)) -> String {
    match study_with(edit) {
        Ok(_) => panic!("the study should be rejected"),
        Err(e) => {
            assert!(e.contains("study-benchmark.json"), "names the file: {e}");
            e
        }
    }
}

#[test]
fn shipped_studies_load() {
    for name in ["study-benchmark.json", "study-ten-story.json"] {
        let s = Study::load(&configs().join(name)).unwrap();
        assert!(!s.records.is_empty());
        assert!(s.space.is_feasible(&vec![0.0; s.space.dim()]));
    }
}

#[test]
fn unknown_fields_are_named() {
    let e = err(|v| v["sweep"]["pionts"] = 3.into());
    assert!(e.contains("unknown field `pionts`"), "{e}");
    let e = err(|v| v["objectve"] = 1.into());
    assert!(e.contains("unknown field `objectve`"), "{e}");
    let e = err(|v| v["objective"]["terms"][0]["metric"] = "drift".into());
    assert!(e.contains("unknown variant `drift`"), "{e}");
}

#[test]
fn empty_suites_are_rejected() {
    let e = err(|v| v["suites"] = serde_json::json!([]));
    assert!(
        e.contains("`suites`") && e.contains("at least one suite"),
        "{e}"
    );
    let e = err(|v| v["suites"] = serde_json::json!([{ "name": "none" }]));
    assert!(
        e.contains("`suites[0].records`") && e.contains("empty"),
        "{e}"
    );
    let e = err(|v| v["suites"][0]["synthetic"]["count"] = 0.into());
    assert!(e.contains("`suites[0].synthetic.count`"), "{e}");
    let e = err(|v| {
        v["suites"] = serde_json::json!([{ "name": "x", "records": ["../records/NOPE*.AT2"] }])
    });
    assert!(
        e.contains("`suites[0].records[0]`") && e.contains("matches no file"),
        "{e}"
    );
}

#[test]
fn reversed_bounds_are_rejected() {
    let e = err(|v| v["space"]["free"]["upper_kn"][2] = (-5.0).into());
    assert!(e.contains("`space.free.upper_kn[2]`"), "{e}");
    let e = err(|v| v["space"]["free"]["lower_kn"] = serde_json::json!([0, 3000, 0]));
    assert!(
        e.contains("`space.free.upper_kn[1]`") && e.contains("reversed"),
        "{e}"
    );
    let e = err(|v| v["space"]["free"]["lower_kn"] = serde_json::json!([0, 0]));
    assert!(
        e.contains("`space.free.lower_kn`") && e.contains("expected 3"),
        "{e}"
    );
    let e = err(|v| {
        v["space"] =
            serde_json::json!({ "profile": { "shape": "uniform", "scale_kn": [500, 100] } })
    });
    assert!(e.contains("`space.profile.scale_kn`"), "{e}");
}

#[test]
fn infeasible_constraints_are_rejected() {
    // lower bounds alone need 3 × 500 kN > 1000 kN
    let e = err(|v| {
        v["space"]["free"]["lower_kn"] = serde_json::json!([500, 500, 500]);
        v["constraints"] = serde_json::json!({ "budget_kn": 1000 });
    });
    assert!(
        e.contains("`constraints.budget_kn`") && e.contains("infeasible"),
        "{e}"
    );
    // a top floor that must carry 800 kN forces floors below to 800 kN: 2400 > 2000
    let e = err(|v| {
        v["space"]["free"]["lower_kn"] = serde_json::json!([0, 0, 800]);
        v["constraints"] = serde_json::json!({ "budget_kn": 2000, "non_increasing": true });
    });
    assert!(
        e.contains("`constraints.budget_kn`") && e.contains("non-increasing"),
        "{e}"
    );
    // floor 1 capped at 300 kN below floor 3's minimum of 800 kN
    let e = err(|v| {
        v["space"]["free"]["lower_kn"] = serde_json::json!([0, 0, 800]);
        v["space"]["free"]["upper_kn"] = serde_json::json!([300, 2000, 2000]);
        v["constraints"] = serde_json::json!({ "non_increasing": true });
    });
    assert!(e.contains("`constraints.non_increasing`"), "{e}");
    // the same constraints with room to spare are accepted
    study_with(|v| {
        v["space"]["free"]["lower_kn"] = serde_json::json!([0, 0, 800]);
        v["constraints"] = serde_json::json!({ "budget_kn": 2400, "non_increasing": true });
    })
    .unwrap();
}

#[test]
fn bad_settings_are_rejected() {
    let e = err(|v| v["objective"]["terms"] = serde_json::json!([]));
    assert!(e.contains("`objective.terms`"), "{e}");
    let e = err(|v| v["objective"]["terms"][0]["weight"] = (-1.0).into());
    assert!(e.contains("`objective.terms[0].weight`"), "{e}");
    let e = err(|v| v["fidelity"]["check_dt_factor"] = 2.0.into());
    assert!(e.contains("`fidelity.check_dt_factor`"), "{e}");
    let e = err(|v| v["sweep"] = serde_json::json!({ "sampler": "grid", "levels": 1 }));
    assert!(e.contains("`sweep.levels`"), "{e}");
    let e = err(|v| v["refine"]["tolerance"] = 0.0.into());
    assert!(e.contains("`refine.tolerance`"), "{e}");
}

#[test]
fn an_empty_list_of_table_scales_is_refused_naming_it() {
    use slipload_opt::phases::family::check_scales;
    let study = study_with(|_| {}).unwrap();
    let one = [1.0];
    for (p, i, name) in [
        (&[][..], &one[..], "--period-scales"),
        (&one[..], &[][..], "--intensity-scales"),
    ] {
        let e = check_scales(&study, p, i).unwrap_err().to_string();
        assert!(e.starts_with(name), "names the list: {e}");
        assert!(e.contains("empty list"), "{e}");
    }
    assert!(check_scales(&study, &one, &one).is_ok());
}
