//! Contract: `slipload sweep` writes the same bytes (manifest.json, responses.csv,
//! designs.csv) whatever the thread count, whether run whole or as three shards joined
//! by `slipload merge` (which writes every file a single run writes, figures included),
//! and when killed (`kill -9`) mid-way and continued with `--resume` — which repeats no
//! finished task.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod common;
use common::root;

fn scratch(name: &str) -> PathBuf {
    common::scratch("sweep", name)
}

const FILES: [&str; 3] = ["manifest.json", "responses.csv", "designs.csv"];

/// A study of the benchmark building over `count` synthetic records of `secs` seconds
/// with `points` Halton designs.
fn study(dir: &Path, count: usize, secs: f64, points: usize) -> PathBuf {
    let building = root().join("configs/benchmark-3story.json");
    let text = format!(
        r#"{{
  "building": {building:?},
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": {count}, "seed": 11, "pga_g": 0.4, "duration_s": {secs} }} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }}, {{ "metric": "rpi", "statistic": "p84", "weight": 0.01 }} ] }},
  "sweep": {{ "sampler": "halton", "points": {points}, "seed": 5 }}
}}"#
    );
    let p = dir.join("study.json");
    std::fs::write(&p, text).unwrap();
    p
}

fn slipload(args: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_slipload"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "slipload {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The names of the files in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// `merged` holds exactly the files of the single run `one`, byte for byte; the journal
/// (appended in finishing order by a run, sorted by key by merge) holds the same lines.
fn assert_merge_writes_what_one_run_writes(one: &Path, merged: &Path) {
    let names = listing(one);
    assert_eq!(
        names,
        listing(merged),
        "merge writes the files one run writes"
    );
    for f in [
        "drift-profiles.csv",
        "drift-profiles.svg",
        "drift-profiles.png",
        "records-scatter.csv",
    ] {
        assert!(
            names.iter().any(|n| n == f),
            "a sweep writes {f}: {names:?}"
        );
    }
    for f in &names {
        let (x, y) = (
            std::fs::read(one.join(f)).unwrap(),
            std::fs::read(merged.join(f)).unwrap(),
        );
        if f == "journal.jsonl" {
            let sorted = |b: &[u8]| {
                let mut l: Vec<String> = String::from_utf8_lossy(b)
                    .lines()
                    .map(str::to_string)
                    .collect();
                l.sort();
                l
            };
            assert_eq!(sorted(&x), sorted(&y), "the journals hold the same tasks");
        } else {
            assert!(
                x == y,
                "{f} differs between {} and {}",
                one.display(),
                merged.display()
            );
        }
    }
}

fn assert_same_files(a: &Path, b: &Path) {
    for f in FILES {
        let (x, y) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        assert!(
            x == y,
            "{f} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}

#[test]
fn threads_and_shards_give_identical_bytes() {
    let dir = scratch("threads");
    let st = study(&dir, 3, 4.0, 6);
    let one = dir.join("t1");
    let two = dir.join("t2");
    slipload(&[
        "--threads",
        "1",
        "sweep",
        s(&st),
        "--out",
        s(&one),
        "--quiet",
    ]);
    slipload(&[
        "--threads",
        "2",
        "sweep",
        s(&st),
        "--out",
        s(&two),
        "--quiet",
    ]);
    assert_same_files(&one, &two);
    // 8 designs (bare, file, 6 sampled) × 3 records, one header line
    let responses = std::fs::read_to_string(one.join("responses.csv")).unwrap();
    assert_eq!(responses.lines().count(), 1 + 8 * 3);
    let shards: Vec<PathBuf> = (0..3).map(|i| dir.join(format!("shard{i}"))).collect();
    for (i, sd) in shards.iter().enumerate() {
        let spec = format!("{i}/3");
        slipload(&[
            "--threads",
            "2",
            "sweep",
            s(&st),
            "--out",
            s(sd),
            "--shard",
            &spec,
            "--quiet",
        ]);
        assert!(
            !sd.join("responses.csv").exists(),
            "a shard writes no tables"
        );
    }
    // a merge with a shard missing fails and names the gap
    let partial = Command::new(env!("CARGO_BIN_EXE_slipload"))
        .args([
            "merge",
            s(&shards[0]),
            s(&shards[1]),
            "--out",
            s(&dir.join("bad")),
        ])
        .output()
        .unwrap();
    assert!(!partial.status.success());
    assert!(String::from_utf8_lossy(&partial.stderr).contains("in no journal"));
    let merged = dir.join("merged");
    slipload(&[
        "merge",
        s(&shards[0]),
        s(&shards[1]),
        s(&shards[2]),
        "--out",
        s(&merged),
    ]);
    assert_merge_writes_what_one_run_writes(&one, &merged);
    // the same through the job-array environment (Kubernetes indexed Job)
    let auto: Vec<PathBuf> = (0..3).map(|i| dir.join(format!("auto{i}"))).collect();
    for (i, sd) in auto.iter().enumerate() {
        let out = Command::new(env!("CARGO_BIN_EXE_slipload"))
            .args([
                "sweep",
                s(&st),
                "--out",
                s(sd),
                "--shard",
                "auto",
                "--quiet",
            ])
            .env("JOB_COMPLETION_INDEX", i.to_string())
            .env("SLIPLOAD_SHARDS", "3")
            .env_remove("SLURM_ARRAY_TASK_ID")
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let merged2 = dir.join("merged2");
    slipload(&[
        "merge",
        s(&auto[0]),
        s(&auto[1]),
        s(&auto[2]),
        "--out",
        s(&merged2),
    ]);
    assert_merge_writes_what_one_run_writes(&one, &merged2);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn killed_run_resumes_to_the_same_bytes_without_repeating_tasks() {
    let dir = scratch("kill");
    // 42 designs × 10 records of 20 s: long enough to be killed mid-way
    let st = study(&dir, 10, 20.0, 40);
    let total = 42 * 10;
    let out = dir.join("killed");
    let mut child = Command::new(env!("CARGO_BIN_EXE_slipload"))
        .args([
            "--threads",
            "2",
            "sweep",
            s(&st),
            "--out",
            s(&out),
            "--quiet",
        ])
        .spawn()
        .unwrap();
    let journal = out.join("journal.jsonl");
    // journal entries: the lines after the header line (the study's fingerprint)
    let lines = || {
        std::fs::read_to_string(&journal)
            .map(|t| t.lines().count().saturating_sub(1))
            .unwrap_or(0)
    };
    while lines() < 20 {
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before it could be killed"
        );
        std::thread::sleep(std::time::Duration::from_millis(1));
    }
    child.kill().unwrap(); // SIGKILL
    let status = child.wait().unwrap();
    assert!(!status.success(), "the run was killed, not finished");
    let before = lines();
    assert!(before < total, "killed before the end: {before} of {total}");
    assert!(
        !out.join("responses.csv").exists(),
        "no tables from an unfinished run"
    );
    // a torn last line, as a crash mid-write leaves it
    {
        use std::io::Write;
        let mut f = std::fs::OpenOptions::new()
            .append(true)
            .open(&journal)
            .unwrap();
        f.write_all(b"{\"design\":3,\"rec").unwrap();
    }
    // without --resume the old journal is refused
    let refused = Command::new(env!("CARGO_BIN_EXE_slipload"))
        .args(["sweep", s(&st), "--out", s(&out), "--quiet"])
        .output()
        .unwrap();
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("--resume"));
    let resumed = slipload(&[
        "--threads",
        "1",
        "sweep",
        s(&st),
        "--out",
        s(&out),
        "--resume",
        "--quiet",
    ]);
    let msg = String::from_utf8_lossy(&resumed.stderr);
    let done = before.to_string();
    assert!(
        msg.contains(&format!("({done} from the journal, {} run", total - before)),
        "resume ran only the rest: {msg}"
    );
    assert_eq!(lines(), total, "every task journalled exactly once");
    let fresh = dir.join("fresh");
    slipload(&[
        "--threads",
        "2",
        "sweep",
        s(&st),
        "--out",
        s(&fresh),
        "--quiet",
    ]);
    assert_same_files(&fresh, &out);
    std::fs::remove_dir_all(&dir).unwrap();
}
