//! `slipload accuracy` as a user runs it: one record or several (per record and median),
//! CSV + JSON + Markdown written, and a clear error without partial files for bad input.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::slipload;
use std::path::PathBuf;

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slipload-acc-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn two_records_give_per_record_entries_and_their_median() {
    let out_dir = tmp("two");
    let out = slipload(&[
        "accuracy",
        "configs/benchmark-3story-massless.json",
        "--record",
        "records/SYL090.AT2",
        "records/I-ELC180.AT2",
        "--duration",
        "2",
        "--methods",
        "newmark,exact",
        "--dts",
        "T1/100,0.0025",
        "--repeats",
        "1",
        "--out",
        out_dir.to_str().unwrap(),
        "--name",
        "t",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(out_dir.join("t.csv")).unwrap();
    // header + (median + 2 records) × 2 methods × 2 steps
    assert_eq!(csv.lines().count(), 1 + 3 * 4, "{csv}");
    assert!(csv.contains("median over 2 records"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("t.json")).unwrap()).unwrap();
    assert_eq!(json["records"].as_array().unwrap().len(), 2);
    assert!(json["median"]["entries"].is_array());
    let md = std::fs::read_to_string(out_dir.join("t.md")).unwrap();
    assert!(md.contains("| newmark | T1/100 |") && md.contains("| exact | 0.0025 |"));
    let _ = std::fs::remove_dir_all(&out_dir);
}

#[test]
fn bad_time_step_is_a_clear_error_and_writes_nothing() {
    let out_dir = tmp("bad");
    let out = slipload(&[
        "accuracy",
        "configs/paper-1story-harmonic.json",
        "--dts",
        "T1/0",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("T1/k"), "{err}");
    assert!(!out_dir.exists());
}
