//! Every input a user controls is bounded before it is used: a record, scene, building or
//! study path that is a FIFO, a device or a folder is refused by its kind without blocking
//! on it; counts (`record synth --count`, `accuracy --synthetic`/`--repeats`,
//! `simulate --repeat`, study refine counts) are refused beyond their limits naming the
//! flag or field and `--allow-large`; an AT2 header with an absurd DT or NPTS and a
//! building with absurd magnitudes are refused naming the file and field; `--duration
//! inf` blames the flag; an output folder flag naming an existing file says so. Every
//! case ends within the guard's time, with a non-zero status, no panic and no output.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{refused, root, scratch};
use std::path::{Path, PathBuf};

const B: &str = "configs/benchmark-3story.json";
const STUDY: &str = "configs/study-benchmark.json";

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn fifo(dir: &Path, name: &str) -> PathBuf {
    let p = dir.join(name);
    assert!(
        std::process::Command::new("mkfifo")
            .arg(&p)
            .status()
            .unwrap()
            .success()
    );
    p
}

#[test]
fn a_record_that_is_a_fifo_a_device_or_a_folder_is_refused_by_kind() {
    let dir = scratch("bounded", "record-kinds");
    let f = fifo(&dir, "r.AT2");
    for (path, kind) in [
        (s(&f), "named pipe (FIFO)"),
        ("/dev/zero", "character device"),
        (s(&dir), "a folder"),
    ] {
        let err = refused(&["simulate", B, "--record", path], &[path, kind]);
        assert!(err.contains("not a regular file"), "{err}");
    }
    // record info reads a folder as its AT2 files, but a FIFO or a device by kind
    refused(&["record", "info", s(&f)], &["named pipe (FIFO)"]);
    refused(&["record", "info", "/dev/zero"], &["character device"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_scene_or_study_that_is_a_fifo_or_a_device_is_refused_by_kind() {
    let dir = scratch("bounded", "config-kinds");
    let f = fifo(&dir, "scene.json");
    refused(&["simulate", s(&f)], &["scene file", "named pipe (FIFO)"]);
    refused(
        &["simulate", "/dev/zero"],
        &["scene file", "character device"],
    );
    refused(&["explain", s(&f)], &["named pipe (FIFO)"]);
    refused(
        &["accuracy", s(&f), "--synthetic", "1"],
        &["named pipe (FIFO)"],
    );
    let out = dir.join("out");
    refused(
        &["sweep", "/dev/zero", "--out", s(&out)],
        &["study file", "character device"],
    );
    refused(
        &["optimize", s(&f), "--out", s(&out)],
        &["study file", "named pipe (FIFO)"],
    );
    assert!(!out.exists(), "no output folder for a refused study");
    // a scene naming a building file that is a FIFO
    let scene = dir.join("s.json");
    let bf = fifo(&dir, "b.json");
    std::fs::write(&scene, r#"{ "building": "b.json", "duration": 1 }"#).unwrap();
    refused(
        &["simulate", s(&scene)],
        &["building file", "named pipe (FIFO)"],
    );
    let _ = bf;
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_record_larger_than_any_real_one_is_refused_with_its_size_and_the_limit() {
    let dir = scratch("bounded", "huge");
    let path = dir.join("huge.AT2");
    // sparse: no disk written; reading it would allocate 1 GiB
    std::fs::File::create(&path)
        .unwrap()
        .set_len(1 << 30)
        .unwrap();
    refused(
        &["simulate", B, "--record", s(&path)],
        &["huge.AT2", "1.0 GiB", "limit 64.0 MiB", "--allow-large"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_at2_header_with_an_absurd_dt_or_npts_is_refused() {
    let dir = scratch("bounded", "headers");
    for (name, text, needles) in [
        (
            "slow.AT2",
            "TITLE\nNPTS= 10, DT= 100 SEC\n0.1 0.1 0.1 0.1 0.1\n0.1 0.1 0.1 0.1 0.1\n",
            vec!["slow.AT2", "longer than any accelerograph"],
        ),
        (
            "many.AT2",
            "TITLE\nNPTS= 999999999999, DT= .01 SEC\n0.1\n",
            vec!["many.AT2:2", "NPTS = 999999999999", "can hold at most"],
        ),
    ] {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        refused(&["simulate", B, "--record", s(&p)], &needles);
        refused(&["record", "info", s(&p)], &needles);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn counts_beyond_their_limits_are_refused_naming_the_flag() {
    let dir = scratch("bounded", "counts");
    let out = dir.join("synth");
    refused(
        &["record", "synth", "--count", "1000000000", "--out", s(&out)],
        &["--count 1000000000", "limit 10000", "--allow-large"],
    );
    assert!(!out.exists());
    refused(
        &["accuracy", B, "--synthetic", "1000000000", "--out", s(&out)],
        &["--synthetic 1000000000", "embedded suite has 10 records"],
    );
    refused(
        &["accuracy", B, "--repeats", "1000000000", "--out", s(&out)],
        &["--repeats 1000000000", "--allow-large"],
    );
    refused(
        &["simulate", B, "--repeat", "4000000000", "--duration", "0.1"],
        &["--repeat 4000000000", "--allow-large"],
    );
    refused(
        &["record", "spectrum", "--synthetic", "1000000000"],
        &["--synthetic 1000000000", "embedded suite has 10 records"],
    );
    // a study's refine counts
    let study = dir.join("study.json");
    let text = std::fs::read_to_string(root().join(STUDY)).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["building"] = serde_json::Value::String(s(&root().join(B)).into());
    v["refine"]["max_evaluations"] = 1_000_000_000_000u64.into();
    std::fs::write(&study, v.to_string()).unwrap();
    refused(
        &["optimize", s(&study), "--out", s(&out)],
        &["field `refine.max_evaluations`", "--allow-large"],
    );
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn absurd_building_magnitudes_are_refused_never_a_1e256_energy() {
    let dir = scratch("bounded", "magnitudes");
    let text = std::fs::read_to_string(root().join(B)).unwrap();
    let base: serde_json::Value = serde_json::from_str(&text).unwrap();
    for (edit, field) in [
        (
            "/dissipators/0/brace_stiffness",
            "dissipators[0].brace_stiffness",
        ),
        ("/dissipators/0/slip_load", "dissipators[0].slip_load"),
        (
            "/dissipators/0/brace_damping",
            "dissipators[0].brace_damping",
        ),
    ] {
        let mut v = base.clone();
        *v.pointer_mut(edit).unwrap() = 1e300.into();
        let p = dir.join("b.json");
        std::fs::write(&p, v.to_string()).unwrap();
        refused(
            &["simulate", s(&p), "--duration", "1", "--format", "json"],
            &["b.json", field],
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_non_finite_or_negative_duration_blames_the_flag() {
    for d in ["inf", "NaN", "-1"] {
        let err = refused(&["simulate", "--duration", d], &["--duration"]);
        assert!(!err.contains("field `duration`"), "{d}: {err}");
        assert!(!err.contains("benchmark-3story.json"), "{d}: {err}");
    }
}

#[test]
fn an_output_folder_flag_naming_an_existing_file_says_so() {
    let dir = scratch("bounded", "out-file");
    let file = dir.join("taken");
    std::fs::write(&file, "keep").unwrap();
    refused(
        &["simulate", B, "--duration", "0.1", "--plot", s(&file)],
        &["--plot", "is an existing file, not a folder"],
    );
    refused(
        &["accuracy", B, "--synthetic", "1", "--out", s(&file)],
        &["--out", "is an existing file, not a folder"],
    );
    refused(
        &["sweep", STUDY, "--out", s(&file)],
        &["--out", "is an existing file, not a folder"],
    );
    refused(
        &["record", "synth", "--count", "2", "--out", s(&file)],
        &["--out", "is an existing file, not a folder"],
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn fresh_is_not_suggested_when_fresh_was_given() {
    let dir = scratch("bounded", "fresh");
    let out = dir.join("out");
    // a folder under a journal's name: --fresh cannot discard it and says so
    std::fs::create_dir_all(out.join("journal.jsonl")).unwrap();
    let err = refused(
        &["sweep", STUDY, "--out", s(&out), "--fresh"],
        &["journal.jsonl", "a folder", "remove it by hand"],
    );
    assert!(!err.contains("pass --fresh"), "{err}");
    std::fs::remove_dir_all(out.join("journal.jsonl")).unwrap();
    // a FIFO under a journal's name is refused by kind, without blocking, with or
    // without --fresh
    fifo(&out, "journal.jsonl");
    let err = refused(
        &["sweep", STUDY, "--out", s(&out), "--fresh"],
        &["journal.jsonl", "not a regular file"],
    );
    assert!(!err.contains("pass --fresh"), "{err}");
    refused(
        &["sweep", STUDY, "--out", s(&out)],
        &["journal.jsonl", "not a regular file"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_study_slip_load_bound_of_1e300_is_refused_naming_the_field() {
    let dir = scratch("bounded", "space");
    let study = dir.join("study.json");
    let out = dir.join("out");
    let text = std::fs::read_to_string(root().join(STUDY)).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["building"] = serde_json::Value::String(s(&root().join(B)).into());
    v["space"]["free"]["upper_kn"][2] = 1e300.into();
    std::fs::write(&study, v.to_string()).unwrap();
    refused(
        &["sweep", s(&study), "--out", s(&out)],
        &["field `space.free.upper_kn[2]`", "weight", "\"locked\""],
    );
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn absurd_scales_and_spectrum_settings_are_refused_naming_the_flag() {
    let dir = scratch("bounded", "scales");
    let out = dir.join("out");
    refused(
        &["table", "--period-scales", "1e300", "--out", s(&out)],
        &["--period-scales 1e300", "periods"],
    );
    assert!(!out.exists());
    let syl = root().join("records/SYL090.AT2");
    refused(
        &["record", "spectrum", s(&syl), "--damping", "1e300"],
        &["damping ratio = 1e300 is invalid", "at most 10"],
    );
    refused(
        &["record", "spectrum", s(&syl), "--periods", "1e300"],
        &["period (s) = 1e300 is invalid", "at most 1e4 s"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
