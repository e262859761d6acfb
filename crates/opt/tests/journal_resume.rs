//! Contract: the journal tolerates a torn last line (and cuts it off before appending),
//! refuses a corrupt line elsewhere, and a journal of a changed study is recognised; a
//! sweep over pools of 1, 2 and 3 threads gives bit-identical responses.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::phases::sweep::{self, Manifest};
use slipload_opt::store::journal::{Journal, read};
use slipload_opt::{Shard, Study};
use std::io::Write;
use std::path::{Path, PathBuf};

mod common;
use common::open_folder;

fn study(points: usize) -> Study {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["suites"][0]["synthetic"]["count"] = 2.into();
    v["suites"][0]["synthetic"]["duration_s"] = 4.0.into();
    v["sweep"]["points"] = points.into();
    Study::from_json(&v.to_string(), &path).unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slipload-journal-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn torn_last_line_is_dropped_and_cut_off() {
    let dir = scratch("torn");
    let st = study(3);
    sweep::run(&st, &open_folder(&dir), Shard::ALL, false, &|| {}).unwrap();
    let j = dir.join("journal.jsonl");
    let (entries, len) = read(&j).unwrap();
    assert_eq!(entries.len(), 5 * 2);
    assert_eq!(len, std::fs::metadata(&j).unwrap().len());
    std::fs::OpenOptions::new()
        .append(true)
        .open(&j)
        .unwrap()
        .write_all(b"{\"design\":1,\"reco")
        .unwrap();
    let (again, good) = read(&j).unwrap();
    assert_eq!(again, entries);
    assert_eq!(good, len);
    // opening for resume cuts the torn bytes, so the next line starts on its own
    let (journal, back) = Journal::open(&j, &Manifest::of(&st).fingerprint, true).unwrap();
    assert_eq!(back.len(), 10);
    drop(journal);
    assert_eq!(std::fs::metadata(&j).unwrap().len(), len);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn corrupt_middle_line_and_changed_study_are_errors() {
    let dir = scratch("corrupt");
    let st = study(3);
    sweep::run(&st, &open_folder(&dir), Shard::ALL, false, &|| {}).unwrap();
    let j = dir.join("journal.jsonl");
    let text = std::fs::read_to_string(&j).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    lines[2] = "garbage";
    std::fs::write(&j, lines.join("\n") + "\n").unwrap();
    let e = read(&j).unwrap_err().to_string();
    assert!(e.contains("line 3"), "{e}");
    // a changed sample (another seed) under the same journal
    std::fs::write(&j, &text).unwrap();
    let mut other = study(3);
    other.config.sweep.seed = 99;
    let e = sweep::run(&other, &open_folder(&dir), Shard::ALL, true, &|| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("study changed"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn pools_of_one_two_three_threads_give_the_same_bits() {
    let st = study(6);
    let mut outs = Vec::new();
    for threads in [1, 2, 3] {
        let dir = scratch(&format!("pool{threads}"));
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let rows = pool
            .install(|| sweep::run(&st, &open_folder(&dir), Shard::ALL, false, &|| {}))
            .unwrap()
            .rows
            .unwrap();
        let m = Manifest::of(&st);
        let obj: Vec<u64> = m
            .objectives(&rows)
            .unwrap()
            .iter()
            .map(|o| o.0.to_bits())
            .collect();
        outs.push((std::fs::read(dir.join("responses.csv")).unwrap(), obj));
        std::fs::remove_dir_all(&dir).unwrap();
    }
    assert!(outs[0] == outs[1] && outs[1] == outs[2]);
}
