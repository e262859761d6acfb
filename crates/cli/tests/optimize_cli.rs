//! Contract: `slipload optimize` with no study runs the embedded benchmark study from any
//! folder and writes its files, the same bytes for 1 and 2 threads; `rank` ranks the candidates it writes; a bad study fails
//! with the field named, a non-zero exit and no output folder — before any simulation.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use std::path::PathBuf;
mod common;
use common::{root, slipload_in as run_in};

fn scratch(name: &str) -> PathBuf {
    common::scratch("opt", name)
}

#[test]
fn default_optimize_runs_the_embedded_benchmark() {
    let dir = scratch("default");
    let out = run_in(&dir, &["optimize", "--quiet"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("optimal slip loads, floors 1 / 2 / 3 (kN)"),
        "{text}"
    );
    let res = dir.join("out/optimize");
    for f in [
        "manifest.json",
        "designs.csv",
        "responses.csv",
        "refine.csv",
        "optimum.json",
        "candidates.json",
        "design-table.csv",
        "design-table.md",
        "design-table.json",
        "refine-trust-region.jsonl",
    ] {
        assert!(res.join(f).is_file(), "{f} written");
    }
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(res.join("optimum.json")).unwrap()).unwrap();
    let f = v["objective_value"].as_f64().unwrap();
    // the optimum beats the paper's slip loads, which beat the bare frame
    assert!(f < v["file_objective"].as_f64().unwrap());
    assert!(v["file_objective"].as_f64().unwrap() < v["bare_objective"].as_f64().unwrap());
    let loads = v["slip_loads_kN"].as_array().unwrap();
    assert_eq!(loads.len(), 3);
    assert!(
        loads
            .iter()
            .all(|x| (0.0..=2000.0).contains(&x.as_f64().unwrap()))
    );
    // A floor is listed on a bound of the space (0–2000 kN) exactly when its slip load is
    // there, and the summary names it.
    let on_bound = v["on_bound"].as_array().unwrap();
    for (i, x) in loads.iter().enumerate() {
        let kn = x.as_f64().unwrap();
        let at = if kn <= 2000.0 * 1e-6 {
            Some("lower")
        } else if kn >= 2000.0 * (1.0 - 1e-6) {
            Some("upper")
        } else {
            None
        };
        let listed = on_bound
            .iter()
            .find(|b| b["floors"] == serde_json::json!([i + 1]));
        assert_eq!(listed.map(|b| b["bound"].as_str().unwrap()), at, "{v:#}");
        if let Some(bound) = at {
            assert!(
                text.contains(&format!("floor {} at its {bound} bound", i + 1)),
                "{text}"
            );
        }
    }
    if on_bound.is_empty() {
        assert!(!text.contains("on a bound"), "{text}");
    }
    // The first run ran every sweep task and reused none.
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(res.join("manifest.json")).unwrap()).unwrap();
    let designs = manifest["designs"].as_array().unwrap().len();
    assert!(
        text.contains(&format!(
            "sweep: {designs} designs × 10 records, {} simulations run (0 reused from journal.jsonl)",
            designs * 10
        )),
        "{text}"
    );
    // interrupted refinement: keep 30 journalled points and a torn line; the second run
    // reuses the finished sweep, replays those 30 points and gives the same files
    let rj = res.join("refine-trust-region.jsonl");
    let text = std::fs::read_to_string(&rj).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert!(
        lines.len() > 30,
        "{} refinement points journalled",
        lines.len()
    );
    // (line 1 is the header: the study's fingerprint)
    std::fs::write(&rj, lines[..31].join("\n") + "\n{\"z\":[0.1,").unwrap();
    let refine_csv = std::fs::read(res.join("refine.csv")).unwrap();
    let table = std::fs::read(res.join("design-table.csv")).unwrap();
    let again = run_in(&dir, &["optimize", "--quiet"]);
    assert!(again.status.success());
    let msg = String::from_utf8_lossy(&again.stdout);
    // What was reused and what ran: no sweep task, only the refinement points after the
    // 30 replayed ones (10 records each); the check and the design table come from the
    // check journal, so none of their runs is repeated. (The refine journal's first line
    // is its header, so it holds n designs in n + 1 lines.)
    let n = lines.len() - 1;
    assert!(
        msg.contains(&format!(
            "0 simulations run ({} reused from journal.jsonl)",
            designs * 10
        )) && msg.contains(&format!(
            "{n} designs, {} run (30 replayed from refine-trust-region.jsonl)",
            n - 30
        )),
        "{msg}"
    );
    assert!(
        msg.contains(&format!(
            "sweep 0, refine {}, check 0, design table 0 (",
            (n - 30) * 10
        )) && msg.contains("design-table runs reused from check.jsonl)"),
        "{msg}"
    );
    assert_eq!(
        std::fs::read_to_string(&rj).unwrap().lines().count(),
        lines.len()
    );
    assert!(refine_csv == std::fs::read(res.join("refine.csv")).unwrap());
    assert!(table == std::fs::read(res.join("design-table.csv")).unwrap());
    let v2: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(res.join("optimum.json")).unwrap()).unwrap();
    assert_eq!(v, v2);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn rank_reads_the_candidates_of_optimize() {
    let dir = scratch("rank");
    let building = root().join("configs/benchmark-3story.json");
    let study = dir.join("study.json");
    std::fs::write(
        &study,
        format!(
            r#"{{ "building": {building:?},
  "suites": [ {{ "name": "a", "synthetic": {{ "count": 3, "seed": 1, "duration_s": 6 }} }},
              {{ "name": "b", "synthetic": {{ "count": 3, "seed": 2, "duration_s": 6 }} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "p84" }} ] }},
  "sweep": {{ "sampler": "lhs", "points": 10 }},
  "refine": {{ "max_evaluations": 10, "starts": 1 }} }}"#
        ),
    )
    .unwrap();
    let s = study.to_str().unwrap();
    let o = run_in(
        &dir,
        &[
            "--threads",
            "2",
            "optimize",
            s,
            "--out",
            "opt",
            "--refine",
            "nelder-mead",
            "--quiet",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // refinement and tables are as deterministic as the sweep: 1 and 2 threads agree
    let o1 = run_in(
        &dir,
        &[
            "--threads",
            "1",
            "optimize",
            s,
            "--out",
            "opt1",
            "--refine",
            "nelder-mead",
            "--quiet",
        ],
    );
    assert!(
        o1.status.success(),
        "{}",
        String::from_utf8_lossy(&o1.stderr)
    );
    for f in [
        "designs.csv",
        "refine.csv",
        "optimum.json",
        "candidates.json",
        "design-table.csv",
    ] {
        let a = std::fs::read(dir.join("opt").join(f)).unwrap();
        let b = std::fs::read(dir.join("opt1").join(f)).unwrap();
        assert!(a == b, "{f} differs between thread counts");
    }
    let r = run_in(
        &dir,
        &[
            "rank",
            s,
            "--designs",
            "opt/candidates.json",
            "--out",
            "rank",
            "--quiet",
        ],
    );
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    // rank.md says which study and objective it ranks by (the study is named by its stem)
    let md = std::fs::read_to_string(dir.join("rank/rank.md")).unwrap();
    assert!(
        md.starts_with("# Ranking of 5 designs: study\n")
            && md.contains("Objective: p84 peak_drift_ratio"),
        "{md}"
    );
    let csv = std::fs::read_to_string(dir.join("rank/rank.csv")).unwrap();
    // 5 candidates × (2 suites + all)
    assert_eq!(csv.lines().count(), 1 + 5 * 3);
    // the bare frame is last on every suite
    assert!(
        csv.lines()
            .filter(|l| l.contains(",bare,"))
            .all(|l| l.split(',').nth(3) == Some("5"))
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_study_fails_before_any_simulation() {
    let dir = scratch("bad");
    let building = root().join("configs/benchmark-3story.json");
    let study = dir.join("bad.json");
    std::fs::write(
        &study,
        format!(
            r#"{{ "building": {building:?},
  "suites": [ {{ "name": "a", "synthetic": {{ "count": 2 }} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 900, 0], "upper_kn": [2000, 500, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }} }}"#
        ),
    )
    .unwrap();
    for cmd in ["sweep", "optimize"] {
        let o = run_in(
            &dir,
            &[cmd, study.to_str().unwrap(), "--out", "o", "--quiet"],
        );
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("bad.json") && err.contains("`space.free.upper_kn[1]`"),
            "{err}"
        );
        assert!(
            !dir.join("o").exists(),
            "{cmd}: no output folder for a bad study"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
