//! The scene rules from the command line (module docs of `slipload_sim::scene`):
//! `--window` replaces the scene's window and, past the record's end, is padded with the
//! ground at rest as a longer `--duration` is, with a note on stderr; times take units on
//! every flag (`--window 2s,10s`, `--duration 10s`, `--dt 5ms`); `explain` refuses what
//! `simulate` refuses (same checks, same words) and explains a building file alone;
//! `rank` refuses candidate files with a name twice. Each refusal exits non-zero, names
//! the file or flag, and writes nothing to stdout.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{scratch, slipload_within, stderr};
use std::process::Output;

const B: &str = "configs/benchmark-3story.json";
const SYL: &str = "records/SYL090.AT2";
/// Seconds any of these runs may take (a few seconds of ground motion each).
const T: u64 = 120;

fn run(args: &[&str]) -> Output {
    slipload_within(T, args)
}

fn ok(args: &[&str]) -> Output {
    let o = run(args);
    assert!(o.status.success(), "slipload {args:?}: {}", stderr(&o));
    assert!(!stderr(&o).contains("panicked"));
    o
}

fn refused(args: &[&str], needles: &[&str]) -> String {
    let o = run(args);
    let err = stderr(&o);
    assert!(!o.status.success(), "slipload {args:?} succeeded: {err}");
    assert!(o.stdout.is_empty(), "no answer on stdout: {args:?}");
    assert!(!err.contains("panicked"), "{err}");
    for n in needles {
        assert!(err.contains(n), "slipload {args:?}: {n:?} not in: {err}");
    }
    err
}

/// The responses of a `--format json` run, without the timing.
fn responses(o: &Output) -> serde_json::Value {
    let mut v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    v.as_object_mut().unwrap().remove("cpu_seconds");
    v
}

fn simulate_json(extra: &[&str]) -> (serde_json::Value, String) {
    let mut args = vec!["simulate", B, "--record", SYL, "--format", "json"];
    args.extend_from_slice(extra);
    let o = ok(&args);
    (responses(&o), stderr(&o))
}

#[test]
fn times_take_units_on_every_flag() {
    let (plain, _) = simulate_json(&["--window", "2,3", "--dt", "0.005"]);
    for (window, dt) in [
        ("2s,3s", "5ms"),
        ("2 s, 3 s", "5 ms"),
        ("2000ms,3", "0.005s"),
    ] {
        let (units, _) = simulate_json(&["--window", window, "--dt", dt]);
        assert_eq!(units, plain, "--window {window} --dt {dt}");
    }
    let (plain, _) = simulate_json(&["--duration", "3"]);
    let (units, _) = simulate_json(&["--duration", "3s"]);
    assert_eq!(units, plain);
    // the wrong dimension or garbage names the flag and what was expected
    for (flag, value) in [
        ("--duration", "3 kg"),
        ("--dt", "5 m"),
        ("--window", "2 kN,3"),
        ("--window", "2,three"),
    ] {
        refused(
            &["simulate", B, "--record", SYL, flag, value],
            &[flag, "a time in s"],
        );
    }
    // accuracy's --duration is a time too
    refused(
        &[
            "accuracy",
            "configs/paper-1story-harmonic.json",
            "--duration",
            "1 kg",
        ],
        &["--duration", "a time in s"],
    );
}

#[test]
fn a_window_past_the_record_end_is_padded_like_a_long_duration_and_says_so() {
    // SYL090 lasts 39.98 s: [38, 5] has 1.98 s of it, then 3.02 s of ground at rest
    let (padded, note) = simulate_json(&["--window", "38,5"]);
    assert!(
        note.contains("note: --window [38 s, 5 s] runs past the end of"),
        "{note}"
    );
    assert!(
        note.contains("at rest for the last 3.02 s of the 5 s run"),
        "{note}"
    );
    // the same run as the in-range window made longer by --duration
    let (by_duration, note) = simulate_json(&["--window", "38,1.98", "--duration", "5"]);
    assert!(note.contains("at rest for the last 3.02 s"), "{note}");
    assert_eq!(padded, by_duration);
    assert_eq!(padded["steps"], 2000); // 5 s at the default 2.5 ms
    // --duration past the record's end alone says so too
    let o = ok(&[
        "simulate",
        B,
        "--record",
        SYL,
        "--duration",
        "41",
        "--dt",
        "0.01",
    ]);
    assert!(
        stderr(&o).contains("note: the run lasts 41 s but the ground motion"),
        "{}",
        stderr(&o)
    );
    // within the record: no note
    let (_, quiet) = simulate_json(&["--window", "2,3"]);
    assert!(!quiet.contains("note:"), "{quiet}");
    // a window that starts past the end is refused
    refused(
        &["simulate", B, "--record", SYL, "--window", "40s,5s"],
        &["--window", "the window starts at 40 s", "39.98 s long"],
    );
}

#[test]
fn the_window_flag_replaces_the_scene_window() {
    let dir = scratch("scene-rules", "replace");
    let scene = dir.join("s.json");
    let building = common::root().join(B);
    let record = common::root().join(SYL);
    std::fs::write(
        &scene,
        format!(
            r#"{{ "building": {:?}, "excitation": {{ "record": {{ "file": {:?}, "window": ["5 s", "10 s"] }} }} }}"#,
            building.display().to_string(),
            record.display().to_string()
        ),
    )
    .unwrap();
    let s = scene.to_str().unwrap();
    let flag = responses(&ok(&["simulate", s, "--window", "1,2", "--format", "json"]));
    let (direct, _) = simulate_json(&["--window", "1,2"]);
    assert_eq!(flag, direct);
    // the scene's own window is [5, 15] of the record: 10 s
    let own = responses(&ok(&["simulate", s, "--format", "json"]));
    let (direct, _) = simulate_json(&["--window", "5,10"]);
    assert_eq!(own, direct);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn explain_refuses_what_simulate_refuses_in_the_same_words() {
    let dir = scratch("scene-rules", "explain");
    let unused = dir.join("unused.json");
    std::fs::write(
        &unused,
        format!(
            r#"{{ "building": {:?}, "duration": 1, "method": {{ "name": "newmark", "alpha": -0.1 }} }}"#,
            common::root().join(B).display().to_string()
        ),
    )
    .unwrap();
    let u = unused.to_str().unwrap();
    for (args, needle) in [
        (
            vec![
                "configs/ten-story-yielding.json",
                "--method",
                "delacruz",
                "--duration",
                "1",
            ],
            "delacruz does not model yielding storeys",
        ),
        (vec![u], "method newmark does not use alpha"),
    ] {
        let mut sim = vec!["simulate"];
        sim.extend_from_slice(&args);
        let mut exp = vec!["explain"];
        exp.extend_from_slice(&args);
        let by_sim = refused(&sim, &[needle]);
        let by_explain = refused(&exp, &[needle]);
        // the same cause, word for word (the context before it names the command's step)
        let tail = |e: &str| e[e.find(needle).unwrap()..].trim().to_string();
        assert_eq!(tail(&by_sim), tail(&by_explain));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn explain_works_on_a_building_file_alone() {
    let o = ok(&["explain", B]);
    let out = String::from_utf8_lossy(&o.stdout);
    for want in [
        // the bare frame's periods (docs/MODEL.md: 1.008/0.327/0.172 s) and modes
        "periods (s) [1.0080, 0.3270, 0.1715]",
        "mode 1: T = 1.0080 s, shape [",
        "mode 3: T = 0.1715 s",
        // the plan
        "plan for benchmark-3story",
        "6 DOFs (3 floors + 3 dissipators)",
        "ground motion: none",
        "no ground motion and no duration: the steps are planned over one bare-frame period",
    ] {
        assert!(out.contains(want), "{want:?} not in\n{out}");
    }
    // simulate still needs a ground motion or a duration
    refused(&["simulate", B], &["no record and no duration"]);
}

#[test]
fn rank_refuses_a_candidate_name_given_twice() {
    let dir = scratch("scene-rules", "rank");
    let designs = dir.join("designs.json");
    std::fs::write(
        &designs,
        r#"[ { "name": "a", "slip_loads_kn": [100, 100, 100] },
             { "name": "b", "slip_loads_kn": [200, 200, 200] },
             { "name": "a", "slip_loads_kn": [300, 300, 300] } ]"#,
    )
    .unwrap();
    let out = dir.join("out");
    refused(
        &[
            "rank",
            "configs/study-benchmark.json",
            "--designs",
            designs.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        &[
            "designs.json",
            "designs[2]",
            "\"a\"",
            "already the name of designs[0]",
        ],
    );
    assert!(!out.exists(), "no output for a refused ranking");
    std::fs::remove_dir_all(&dir).unwrap();
}
