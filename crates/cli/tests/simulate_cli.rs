//! The `simulate` and `explain` commands as a user runs them: the JSON output contract,
//! the embedded default scene, history files, and clear errors with a non-zero exit.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::slipload;

#[test]
fn json_output_has_exactly_the_contract_keys() {
    let out = slipload(&[
        "simulate",
        "configs/benchmark-3story.json",
        "--record",
        "records/SYL090.AT2",
        "--duration",
        "10",
        "--format",
        "json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    keys.sort_unstable();
    let mut want = vec![
        "method",
        "dt",
        "steps",
        "cpu_seconds",
        "peak_drift",
        "peak_drift_ratio",
        "peak_displacement",
        "peak_abs_acceleration",
        "residual_drift",
        "peak_base_shear",
        "peak_slip",
        "transitions",
        "energy",
    ];
    want.sort_unstable();
    assert_eq!(keys, want);
    let mut ek: Vec<&str> = v["energy"]
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    ek.sort_unstable();
    assert_eq!(
        ek,
        [
            "balance_error",
            "friction",
            "input",
            "kinetic",
            "strain",
            "viscous"
        ]
    );
    assert_eq!(v["peak_drift"].as_array().unwrap().len(), 3);
    assert_eq!(v["method"], "newmark");
    assert_eq!(
        v["steps"], 4000,
        "10 s at T1/400 rounded to divide 0.02 s: dt = 0.0025 s"
    );
}

#[test]
fn embedded_default_runs_with_no_files() {
    let out = slipload(&["simulate"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("benchmark-3story") && text.contains("balance error"),
        "{text}"
    );
}

#[test]
fn explain_prints_the_reductions() {
    let out = slipload(&["explain", "configs/ten-story.json", "--duration", "1"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("elastic-perfectly plastic element"), "{text}");
    assert!(
        text.contains("10 DOFs (10 floors + 0 dissipators)"),
        "{text}"
    );
}

#[test]
fn history_file_is_written_whole() {
    let dir = std::env::temp_dir().join(format!("slipload-cli-{}", std::process::id()));
    let file = dir.join("free.csv");
    let out = slipload(&[
        "simulate",
        "configs/paper-1story-free.json",
        "--history",
        file.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(&file).unwrap();
    let mut lines = csv.lines();
    let header = lines.next().unwrap();
    assert!(
        header.starts_with("t_s,ag_m_s2,x1_m,xd1_m,drift1_m,F1_N,w1_m_s"),
        "{header}"
    );
    let rows: Vec<&str> = lines.collect();
    let t_last: f64 = rows
        .last()
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        (t_last - 2.0).abs() < 1e-9,
        "history reaches the 2 s duration: {t_last}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_config_fails_with_file_and_field() {
    let dir = std::env::temp_dir().join(format!("slipload-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.json");
    std::fs::write(&bad, r#"{ "floor_masses": [1000], "storey_stiffness": [1e5], "dissipators": [{ "floor": 1, "brace_stiffness": -2, "slip_load": 5 }] }"#).unwrap();
    let out = slipload(&["simulate", bad.to_str().unwrap(), "--duration", "1"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.json") && err.contains("dissipators[0].brace_stiffness"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    let missing = slipload(&["simulate", "no-such-file.json"]);
    assert!(!missing.status.success());
    assert!(String::from_utf8_lossy(&missing.stderr).contains("no-such-file.json"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A reader that stops early (`slipload simulate | head`) ends the program quietly: exit
/// status 0 and no panic message, instead of Rust's default panic on a broken pipe.
#[test]
fn closed_stdout_pipe_is_not_a_panic() {
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_slipload"))
        .args(["simulate", "--format", "json"])
        .current_dir(common::root())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Close the read end before the simulation has printed anything.
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(out.status.success(), "{:?}: {stderr}", out.status);
}

/// `--repeat N` (for timing scripts) runs the same simulation N times in one process: the
/// answers are those of one run, `cpu_seconds` is a positive median.
#[test]
fn repeat_reports_the_same_answers_with_a_median_time() {
    let json = |extra: &[&str]| {
        let mut args = vec!["simulate", "--format", "json", "--duration", "3"];
        args.extend_from_slice(extra);
        let out = slipload(&args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice::<serde_json::Value>(&out.stdout).unwrap()
    };
    let once = json(&[]);
    let thrice = json(&["--repeat", "3"]);
    assert_eq!(once["peak_drift"], thrice["peak_drift"]);
    assert_eq!(once["energy"], thrice["energy"]);
    assert!(thrice["cpu_seconds"].as_f64().unwrap() > 0.0);
    let bad = slipload(&["simulate", "--repeat", "0"]);
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--repeat"));
}
