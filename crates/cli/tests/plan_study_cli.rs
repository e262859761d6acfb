//! `slipload optimize` on a study in plan: it is recognised by its building, prints its
//! summary (the same text as `plan-summary.txt`) and names its files; a rerun replays the
//! journal and writes the same bytes; the options a study in plan does not take are
//! refused by name; a bad study names its field and writes nothing.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch, slipload};
use serde_json::json;

/// A short study of the shipped ten-storey plan: one pair, 4 s, one orientation.
fn study(dir: &std::path::Path, placement: &str) -> std::path::PathBuf {
    let r = root();
    let rec = |f: &str| r.join("records/pairs").join(f).display().to_string();
    let v = json!({
        "name": "short plan study",
        "building": r.join("configs/plan-ten-story.json").display().to_string(),
        "suites": [{
            "name": "newhall",
            "pairs": [[rec("RSN1044_NORTHR_NWH090.AT2"), rec("RSN1044_NORTHR_NWH360.AT2")]],
            "angles_deg": [90],
            "duration_s": 4
        }],
        "space": {"placement": placement, "slip_load_kn": [0, 4000]},
        "sweep": {"points": 3},
        "refine": {"max_evaluations": 4}
    });
    let p = dir.join("study.json");
    std::fs::write(&p, serde_json::to_string_pretty(&v).unwrap()).unwrap();
    p
}

#[test]
fn a_study_in_plan_runs_prints_its_summary_and_replays_to_the_same_bytes() {
    let dir = scratch("plan-study-cli", "run");
    let p = study(&dir, "lines");
    let out = dir.join("out");
    let args = [
        "optimize",
        p.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    let o = slipload(&args);
    assert!(o.status.success(), "{}", common::stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    let summary = std::fs::read_to_string(out.join("plan-summary.txt")).unwrap();
    assert!(text.starts_with(&summary), "{text}");
    assert!(summary.contains("10 storeys, 4 lines, 40 dampers (40 sized by 4 variable(s)"));
    assert!(summary.contains("planar split"));
    assert!(text.contains("plan-dampers.md") && text.contains("plan-view"));
    for f in [
        "plan-view.svg",
        "plan-view.png",
        "line-drift-profiles.csv",
        "plan-optimum.json",
    ] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let before = std::fs::read(out.join("plan-optimum.json")).unwrap();
    let again = slipload(&args);
    assert!(again.status.success(), "{}", common::stderr(&again));
    let text = String::from_utf8(again.stdout).unwrap();
    assert!(text.contains("taken from the journal"), "{text}");
    assert_eq!(
        std::fs::read(out.join("plan-optimum.json")).unwrap(),
        before
    );
    assert_eq!(
        std::fs::read_to_string(out.join("plan-summary.txt")).unwrap(),
        summary
    );
}

#[test]
fn options_a_study_in_plan_does_not_take_are_refused_by_name() {
    let dir = scratch("plan-study-cli", "options");
    let p = study(&dir, "directions");
    let out = dir.join("out");
    for (flag, needle) in [
        (vec!["--refine", "sqp"], "refines with `model`"),
        (vec!["--map"], "no objective map"),
    ] {
        let mut args = vec![
            "optimize",
            p.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend(flag);
        let o = slipload(&args);
        assert!(!o.status.success());
        let e = common::stderr(&o);
        assert!(e.contains(needle), "{e}");
        assert!(!out.exists(), "a refused run writes nothing");
    }
}

#[test]
fn a_bad_study_in_plan_names_its_field_and_writes_nothing() {
    let dir = scratch("plan-study-cli", "bad");
    let p = study(&dir, "edges");
    let out = dir.join("out");
    let o = slipload(&[
        "optimize",
        p.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let e = common::stderr(&o);
    assert!(e.contains("study.json") && e.contains("edges"), "{e}");
    assert!(!out.exists());
}
