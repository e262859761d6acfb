//! Contract: every journal line carries a CRC-32 of its JSON; a line that fails it is
//! not trusted and its task is run again on `--resume` (the result files keep the bytes
//! of an intact run); a line without a checksum (an older slipload's) is recomputed the
//! same way; a line that is no entry at all, other than the last, is refused with how
//! to recover.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::phases::sweep;
use slipload_opt::store::journal::{checked_line, crc32, read};
use slipload_opt::{Shard, Study};
use std::path::{Path, PathBuf};

mod common;
use common::open_folder;

fn study() -> Study {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["suites"][0]["synthetic"]["count"] = 2.into();
    v["suites"][0]["synthetic"]["duration_s"] = 2.0.into();
    v["sweep"]["points"] = 2.into();
    Study::from_json(&v.to_string(), &path).unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slipload-crc-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A fresh sweep into `name`: (folder, journal text, responses.csv).
fn swept(st: &Study, name: &str) -> (PathBuf, String, Vec<u8>) {
    let dir = scratch(name);
    sweep::run(st, &open_folder(&dir), Shard::ALL, false, &|| {}).unwrap();
    let j = std::fs::read_to_string(dir.join("journal.jsonl")).unwrap();
    let csv = std::fs::read(dir.join("responses.csv")).unwrap();
    (dir, j, csv)
}

#[test]
fn crc32_matches_the_reference_value() {
    // the IEEE CRC-32 check value
    assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    let line = checked_line(&serde_json::json!({"a": 1})).unwrap();
    assert_eq!(
        line,
        format!(r#"{{"a":1,"crc32":"{:08x}"}}"#, crc32(br#"{"a":1}"#))
    );
}

#[test]
fn a_line_that_fails_its_checksum_is_run_again() {
    let st = study();
    let (dir, text, csv) = swept(&st, "flip");
    let j = dir.join("journal.jsonl");
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    // change one digit of one response of the task on line 3: still valid JSON
    let l = &mut lines[2];
    let at = l.find("\"drift_ratio\":[0.").unwrap() + "\"drift_ratio\":[0.".len();
    let d = l.as_bytes()[at];
    let flipped = if d == b'9' { '1' } else { (d + 1) as char };
    l.replace_range(at..at + 1, &flipped.to_string());
    std::fs::write(&j, lines.join("\n") + "\n").unwrap();
    let (entries, _) = read(&j).unwrap();
    assert_eq!(entries.len(), 4 * 2 - 1, "the damaged line is not trusted");
    let r = sweep::run(&st, &open_folder(&dir), Shard::ALL, true, &|| {}).unwrap();
    assert_eq!((r.resumed, r.ran), (7, 1), "exactly its task runs again");
    assert_eq!(r.distrusted, 1, "the run says one line was not trusted");
    assert!(std::fs::read(dir.join("responses.csv")).unwrap() == csv);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_older_journal_without_checksums_is_recomputed() {
    let st = study();
    let (dir, text, csv) = swept(&st, "old");
    let j = dir.join("journal.jsonl");
    // the lines as an older slipload wrote them: no crc32 field
    let old: String = text
        .lines()
        .map(|l| {
            let at = l.rfind(",\"crc32\":\"").unwrap();
            format!("{}}}\n", &l[..at])
        })
        .collect();
    std::fs::write(&j, old).unwrap();
    let r = sweep::run(&st, &open_folder(&dir), Shard::ALL, true, &|| {}).unwrap();
    assert_eq!((r.resumed, r.ran), (0, 8), "none of its lines is trusted");
    assert_eq!(r.distrusted, 8);
    assert!(std::fs::read(dir.join("responses.csv")).unwrap() == csv);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_line_that_is_no_entry_is_refused_with_how_to_recover() {
    let st = study();
    let (dir, text, _) = swept(&st, "garbage");
    let j = dir.join("journal.jsonl");
    let mut lines: Vec<&str> = text.lines().collect();
    lines[3] = "garbage";
    std::fs::write(&j, lines.join("\n") + "\n").unwrap();
    let e = sweep::run(&st, &open_folder(&dir), Shard::ALL, true, &|| {}).unwrap_err();
    let mut chain = e.to_string();
    let mut src = std::error::Error::source(&e);
    while let Some(s) = src {
        chain.push_str(&format!(": {s}"));
        src = s.source();
    }
    for needle in ["line 4", "delete line 4", "--resume", "--fresh"] {
        assert!(chain.contains(needle), "{needle}: {chain}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
