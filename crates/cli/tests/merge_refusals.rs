//! Contract: `merge` writes into a folder of its own. It refuses an output folder that
//! is one of its shard folders, lies inside one or holds one, and one that holds another
//! study's sweep — each before writing anything, the shards' journals untouched — and a
//! merge it does run drops no task.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use std::path::{Path, PathBuf};

mod common;
use common::{root, slipload_within};

const T: u64 = 300;

/// The benchmark building on two 2-s synthetic records at `pga` g, two Halton points.
fn study(dir: &Path, name: &str, pga: f64) -> PathBuf {
    let building = root().join("configs/benchmark-3story.json");
    let text = format!(
        r#"{{ "building": {building:?},
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": 2, "seed": 11, "pga_g": {pga}, "duration_s": 2 }} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn ok(args: &[&str]) {
    let o = slipload_within(T, args);
    assert!(
        o.status.success(),
        "slipload {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

fn refused(args: &[&str], needles: &[&str]) {
    let o = slipload_within(T, args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "slipload {args:?} ran: {err}");
    for n in needles {
        assert!(err.contains(n), "slipload {args:?}: {n:?} not in {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
}

fn journal(dir: &Path) -> Vec<u8> {
    std::fs::read(dir.join("journal.jsonl")).unwrap()
}

#[test]
fn merge_refuses_its_own_shards_and_another_studys_folder() {
    let dir = common::scratch("merge", "refusals");
    let st = study(&dir, "a.json", 0.4);
    let shards = dir.join("shards");
    let (a, b) = (shards.join("a"), shards.join("b"));
    ok(&["sweep", s(&st), "--out", s(&a), "--shard", "0/2", "--quiet"]);
    ok(&["sweep", s(&st), "--out", s(&b), "--shard", "1/2", "--quiet"]);
    let (ja, jb) = (journal(&a), journal(&b));
    // the output is a shard folder, lies inside one, or holds them
    refused(
        &["merge", "--out", s(&a), s(&a), s(&b)],
        &[
            "is the output folder itself",
            "--out outside every shard folder",
        ],
    );
    refused(
        &["merge", "--out", s(&a.join("m")), s(&a), s(&b)],
        &["holds the output folder"],
    );
    refused(
        &["merge", "--out", s(&shards), s(&a), s(&b)],
        &["lies inside the output folder"],
    );
    assert!(!a.join("m").exists());
    assert!(!shards.join("responses.csv").exists() && !a.join("responses.csv").exists());
    // a folder holding another study's sweep
    let other = dir.join("other");
    let st_b = study(&dir, "b.json", 0.8);
    ok(&["sweep", s(&st_b), "--out", s(&other), "--quiet"]);
    let other_csv = std::fs::read(other.join("responses.csv")).unwrap();
    refused(
        &["merge", "--out", s(&other), s(&a), s(&b)],
        &["holds the sweep of another study", "record 1 samples"],
    );
    assert!(std::fs::read(other.join("responses.csv")).unwrap() == other_csv);
    assert!(
        journal(&a) == ja && journal(&b) == jb,
        "the shards are untouched"
    );
    // a merge into its own folder drops no task: 4 designs x 2 records
    let merged = dir.join("merged");
    ok(&["merge", "--out", s(&merged), s(&a), s(&b)]);
    let text = String::from_utf8(journal(&merged)).unwrap();
    assert_eq!(text.lines().count(), 1 + 4 * 2, "{text}");
    let one = dir.join("one");
    ok(&["sweep", s(&st), "--out", s(&one), "--quiet"]);
    for f in ["manifest.json", "responses.csv", "designs.csv"] {
        assert!(
            std::fs::read(one.join(f)).unwrap() == std::fs::read(merged.join(f)).unwrap(),
            "{f}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A `manifest.json` that is a FIFO — in a shard folder or in the output folder — is
/// refused by kind, never opened for reading (which would block the merge for ever).
#[test]
fn a_manifest_that_is_a_fifo_is_refused_without_blocking() {
    let dir = common::scratch("merge", "fifo");
    let shard = dir.join("shard-0");
    std::fs::create_dir_all(&shard).unwrap();
    let fifo = shard.join("manifest.json");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    // 60 s: a blocking read would hang until the guard kills it
    let o = slipload_within(60, &["merge", s(&shard), "--out", s(&dir.join("merged"))]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "merge ran: {err}");
    assert!(
        err.contains("FIFO") && err.contains("manifest.json"),
        "{err}"
    );
    // the same FIFO in the output folder, with a real shard to merge
    let st = study(&dir, "a.json", 0.4);
    let real = dir.join("real-shard");
    ok(&["sweep", s(&st), "--out", s(&real), "--quiet"]);
    let o = slipload_within(60, &["merge", s(&real), "--out", s(&shard)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "merge ran: {err}");
    assert!(err.contains("FIFO"), "{err}");
}
