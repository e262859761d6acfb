//! Issue 16, `simulate` (and the flags every command shares) under hostile input: work
//! and memory are estimated before anything runs and refused with the estimate and the
//! override; a step longer than the duration or the record's sampling is an error;
//! non-finite or overflowing numbers are errors; negative numbers reach validation;
//! output never replaces a FIFO; a missing file's cause is printed once. Every case ends
//! quickly with a non-zero status and no output file.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{refused, scratch, slipload_within, stderr};
use std::path::Path;

const B: &str = "configs/benchmark-3story.json";
const SYL: &str = "records/SYL090.AT2";
/// Seconds any refusal may take (they are all up-front; this is generous).
const T: u64 = 60;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `simulate` of the benchmark under a record file `name` holding `text` (written to a
/// scratch folder), with `extra` arguments: refused, its message holding `needles`.
fn record_refused(name: &str, text: &str, extra: &[&str], needles: &[&str]) {
    let dir = scratch("bad-sim", name);
    let f = dir.join(name);
    std::fs::write(&f, text).unwrap();
    let mut args = vec!["simulate", B, "--record", s(&f)];
    args.extend_from_slice(extra);
    refused(&args, needles);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_tiny_step_is_refused_with_the_estimate_and_the_override() {
    refused(
        &["simulate", B, "--dt", "1e-12", "--duration", "2"],
        &["2.000e12 integration steps", "limit", "--allow-large"],
    );
    // and through the environment override the limit is lifted (not run here: the
    // message names it)
}

#[test]
fn a_huge_duration_is_refused() {
    refused(
        &["simulate", B, "--duration", "1e12"],
        &["steps", "--allow-large"],
    );
}

#[test]
fn a_record_sampled_at_1e_12_s_is_refused() {
    let mut text = String::from("TITLE\nNPTS= 4000, DT= 1e-12 SEC\n");
    for k in 0..4000 {
        text.push_str(&format!("{}\n", 0.1 * (k as f64 * 0.01).sin()));
    }
    record_refused(
        "fast.AT2",
        &text,
        &["--duration", "2"],
        &["fast.AT2", "shorter than any accelerograph"],
    );
}

#[test]
fn history_memory_is_estimated_before_allocating() {
    let dir = scratch("bad-sim", "hist");
    let h = dir.join("h.csv");
    // 2e7 steps (within the step limit) x 22 columns: about 10 GiB of history
    refused(
        &[
            "simulate",
            B,
            "--record",
            SYL,
            "--dt",
            "2e-6",
            "--history",
            s(&h),
        ],
        &["time histories", "GiB", "--allow-large"],
    );
    assert!(!h.exists());
    refused(
        &[
            "simulate",
            B,
            "--record",
            SYL,
            "--dt",
            "1e-9",
            "--history",
            s(&h),
        ],
        &["steps", "--allow-large"],
    );
    assert!(!h.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_step_longer_than_the_duration_is_an_error_not_a_small_drift() {
    refused(
        &["simulate", B, "--dt", "10", "--duration", "2"],
        &["time step 10 s is longer than the simulated duration (2 s)"],
    );
}

#[test]
fn a_step_longer_than_the_record_interval_is_an_error_for_step_methods() {
    let err = refused(
        &[
            "simulate",
            B,
            "--record",
            SYL,
            "--dt",
            "0.05",
            "--duration",
            "2",
        ],
        &["0.05", "0.02", "SYL090.AT2", "skip record samples"],
    );
    assert!(err.contains("newmark"), "{err}");
    // exact integrates every sample whatever its output step
    let o = slipload_within(
        T,
        &[
            "simulate",
            B,
            "--record",
            SYL,
            "--dt",
            "0.05",
            "--duration",
            "1",
            "--method",
            "exact",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn negative_numbers_reach_validation() {
    for (flag, value, needle) in [
        ("--dt", "-0.001", "time step -0.001 s must be positive"),
        ("--duration", "-2", "must be positive, got -2"),
        ("--scale-pga-g", "-0.5", "-0.5"),
        ("--window", "-1,2", "a start >= 0 s"),
    ] {
        let mut args = vec!["simulate", B, flag, value];
        match flag {
            "--dt" => args.extend(["--duration", "1"]),
            "--duration" => {}
            _ => args.extend(["--record", SYL]),
        }
        let err = refused(&args, &[needle]);
        assert!(!err.contains("unexpected argument"), "{flag}: {err}");
    }
}

#[test]
fn a_sample_of_1e300_is_refused_naming_file_line_and_physics() {
    for format in ["json", "table"] {
        record_refused(
            "huge.AT2",
            "TITLE\nNPTS= 5, DT= .0100 SEC\n0.0 0.1 1e300\n0.1 0.0\n",
            &["--format", format],
            &["huge.AT2:3", "beyond any physical record", "4-5 g"],
        );
    }
}

#[test]
fn an_overflowing_response_is_an_error_not_null() {
    // a finite harmonic force so large that the energies would overflow: refused up front
    // (bounded by the building's weight), for every method; the overflow checks behind it
    // are exercised in slipload-sim's bad_inputs_scene
    let dir = scratch("bad-sim", "overflow");
    let scene = dir.join("scene.json");
    let building = common::root().join(B);
    std::fs::write(
        &scene,
        format!(
            r#"{{ "building": {building:?}, "duration": 1,
                 "excitation": {{ "harmonic": {{ "floor": 1, "amplitude": 1e300, "omega": 6 }} }} }}"#
        ),
    )
    .unwrap();
    for method in ["newmark", "hht", "bilinear", "delacruz", "exact"] {
        let err = refused(
            &[
                "simulate",
                s(&scene),
                "--method",
                method,
                "--format",
                "json",
            ],
            &[],
        );
        assert!(
            err.contains("field `excitation.harmonic.amplitude`") && err.contains("weight"),
            "{method}: {err}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_at2_whose_npts_disagrees_with_its_values_is_refused() {
    record_refused(
        "n.AT2",
        "TITLE\nNPTS= 4, DT= .0100 SEC\n0.1 0.2 0.3\n0.1 0.2 0.3\n",
        &[],
        &["NPTS = 4", "holds 6"],
    );
}

#[cfg(unix)]
#[test]
fn history_never_replaces_a_fifo_nor_writes_through_a_symlink() {
    let dir = scratch("bad-sim", "fifo");
    let fifo = dir.join("pipe");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        refused(
            &["simulate", B, "--duration", "0.5", "--history", s(&fifo)],
            &["FIFO", "refusing to replace"],
        );
        use std::os::unix::fs::FileTypeExt;
        assert!(
            std::fs::symlink_metadata(&fifo)
                .unwrap()
                .file_type()
                .is_fifo()
        );
    }
    let target = dir.join("target.csv");
    std::fs::write(&target, "old").unwrap();
    let link = dir.join("link.csv");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    // a symbolic link is never written through: refused, the link and its target kept
    refused(
        &["simulate", B, "--duration", "0.5", "--history", s(&link)],
        &["symbolic link", "refusing to write through it"],
    );
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(
        std::fs::read_to_string(&target).unwrap(),
        "old",
        "the link's target is untouched"
    );
    // a folder is refused too
    refused(
        &["simulate", B, "--duration", "0.5", "--history", s(&dir)],
        &["a folder"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_missing_file_is_named_and_its_cause_printed_once() {
    for args in [
        vec!["simulate", "no-such-scene.json"],
        vec!["simulate", B, "--record", "no-such-record.AT2"],
        vec![
            "sweep",
            "no-such-study.json",
            "--out",
            "/tmp/slipload-never",
        ],
    ] {
        let err = refused(&args, &["No such file or directory"]);
        assert_eq!(
            err.matches("No such file or directory").count(),
            1,
            "{args:?}: {err}"
        );
    }
}

#[test]
fn absurd_thread_counts_are_refused_not_started() {
    refused(
        &["--threads", "100000", "simulate", B, "--duration", "0.1"],
        &["--threads 100000", "at most"],
    );
}
