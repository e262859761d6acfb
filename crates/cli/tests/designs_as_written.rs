//! Contract: the commands evaluate the building file's design as written. With a
//! `locked` damper on floor 2, `optimize` sweeps it locked (designs.csv says `locked`),
//! its summary and design table name the friction law, `candidates.json` carries it, and
//! `rank` reads those candidates and runs it.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use std::path::{Path, PathBuf};

mod common;
use common::{root, slipload_within};

const T: u64 = 300;

/// The benchmark building with floor 2's damper locked, on two 2-s synthetic records.
fn study(dir: &Path) -> PathBuf {
    let mut b: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root().join("configs/benchmark-3story.json")).unwrap(),
    )
    .unwrap();
    b["dissipators"][1]["slip_load"] = "locked".into();
    let text = format!(
        r#"{{ "building": {b},
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": 2, "seed": 11, "pga_g": 0.4, "duration_s": 2 }} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark", "check_method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 4, "seed": 5 }},
  "refine": {{ "method": "nelder-mead", "starts": 1, "max_evaluations": 6, "finalists": 2 }} }}"#
    );
    let p = dir.join("study.json");
    std::fs::write(&p, text).unwrap();
    p
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn a_locked_file_damper_stays_locked_through_optimize_and_rank() {
    let dir = common::scratch("written", "locked");
    let st = study(&dir);
    let out = dir.join("o");
    let o = slipload_within(T, &["optimize", s(&st), "--out", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains(
            "building file's design (friction law -834.095..834.095 / locked / -437.51..437.51 kN)"
        ),
        "{stdout}"
    );
    let designs = std::fs::read_to_string(out.join("designs.csv")).unwrap();
    let file = designs.lines().nth(2).unwrap();
    assert!(
        file.starts_with("1,file,-834.095..834.095,locked,-437.51..437.51,"),
        "{file}"
    );
    let md = std::fs::read_to_string(out.join("design-table.md")).unwrap();
    assert!(md.contains("| 2 | locked | locked | locked |"), "{md}");
    let cands = std::fs::read_to_string(out.join("candidates.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&cands).unwrap();
    let file = v
        .as_array()
        .unwrap()
        .iter()
        .find(|d| d["name"] == "file")
        .unwrap();
    assert_eq!(file["friction_kn"][1], "locked", "{cands}");
    assert_eq!(
        file["friction_kn"][0]["bounds"],
        serde_json::json!([-834.095, 834.095])
    );
    let ranked = dir.join("r");
    let o = slipload_within(
        T,
        &[
            "rank",
            s(&st),
            "--designs",
            s(&out.join("candidates.json")),
            "--out",
            s(&ranked),
            "--bootstrap",
            "5",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let _ = std::fs::remove_dir_all(&dir);
}
