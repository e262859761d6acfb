//! Issue 16, the journals' identity: a study's fingerprint is stable (same study, same
//! bits), names the component that changed, and a journal without one or of another
//! study is refused; a task journal of the check is refused the same way.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::phases::sweep::{self, Manifest};
use slipload_opt::store::journal::{Journal, read};
use slipload_opt::{Shard, Study};
use std::path::{Path, PathBuf};

mod common;
use common::open_folder;

fn study_with(edit: impl Fn(&mut serde_json::Value)) -> Study {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["suites"][0]["synthetic"]["count"] = 2.into();
    v["suites"][0]["synthetic"]["duration_s"] = 2.0.into();
    v["sweep"]["points"] = 2.into();
    edit(&mut v);
    Study::from_json(&v.to_string(), &path).unwrap()
}

/// An edit of the study's JSON.
type Edit = dyn Fn(&mut serde_json::Value);

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slipload-badj-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn the_fingerprint_is_stable_and_names_what_changed() {
    let a = Manifest::of(&study_with(|_| {})).fingerprint;
    assert_eq!(a, Manifest::of(&study_with(|_| {})).fingerprint);
    let cases: [(&str, Box<Edit>); 4] = [
        (
            "method/step",
            Box::new(|v| v["fidelity"]["method"] = "hht".into()),
        ),
        (
            "method/step",
            Box::new(|v| v["fidelity"]["dt_s"] = 0.002.into()),
        ),
        (
            "record 1 samples",
            Box::new(|v| v["suites"][0]["synthetic"]["pga_g"] = 0.8.into()),
        ),
        (
            "objective",
            Box::new(|v| v["objective"]["terms"][0]["statistic"] = "max".into()),
        ),
    ];
    for (needle, edit) in cases {
        let b = Manifest::of(&study_with(edit)).fingerprint;
        assert_ne!(a.hash, b.hash, "{needle}");
        let ch = b.describe_changes(&a);
        assert!(ch.contains(needle), "{needle}: {ch}");
        assert!(!ch.contains("building"), "only what changed: {ch}");
    }
}

#[test]
fn a_journal_of_another_study_or_without_a_fingerprint_is_refused() {
    let dir = scratch("other");
    let a = study_with(|_| {});
    sweep::run(&a, &open_folder(&dir), Shard::ALL, false, &|| {}).unwrap();
    let j = dir.join("journal.jsonl");
    let (entries, _) = read(&j).unwrap();
    assert_eq!(entries.len(), 4 * 2);
    let b = study_with(|v| v["suites"][0]["synthetic"]["pga_g"] = 0.8.into());
    let e = sweep::run(&b, &open_folder(&dir), Shard::ALL, true, &|| {})
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("another study") && e.contains("record 1 samples"),
        "{e}"
    );
    assert!(e.contains("--fresh"), "{e}");
    // a journal without its header line (as an older slipload wrote it)
    let text = std::fs::read_to_string(&j).unwrap();
    let body: String = text.lines().skip(1).map(|l| format!("{l}\n")).collect();
    std::fs::write(&j, body).unwrap();
    let fp = Manifest::of(&a).fingerprint;
    let e = Journal::open(&j, &fp, true).unwrap_err().to_string();
    assert!(e.contains("no study fingerprint"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_torn_header_is_a_fresh_journal() {
    let dir = scratch("torn-header");
    let a = study_with(|_| {});
    let j = dir.join("journal.jsonl");
    std::fs::write(&j, "{\"journal\":\"sweep\",\"finger").unwrap();
    let r = sweep::run(&a, &open_folder(&dir), Shard::ALL, false, &|| {}).unwrap();
    assert_eq!((r.resumed, r.ran), (0, 8));
    let fresh = scratch("torn-header-fresh");
    sweep::run(&a, &open_folder(&fresh), Shard::ALL, false, &|| {}).unwrap();
    // the same header and entries (their order follows the threads)
    let sorted = |p: &Path| {
        let t = std::fs::read_to_string(p).unwrap();
        let mut l: Vec<String> = t.lines().map(String::from).collect();
        l[1..].sort();
        l
    };
    assert_eq!(sorted(&j), sorted(&fresh.join("journal.jsonl")));
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_dir_all(&fresh).unwrap();
}

/// Issue 40: a line pasted from another study's journal — the same design and record
/// under another record scaling — is not trusted: each entry's checksum runs over the
/// study's fingerprint, so the pasted line fails it and its task runs again, giving the
/// bytes of a run that never saw it.
#[test]
fn a_line_pasted_from_another_study_is_run_again() {
    let (da, db, dc) = (scratch("paste-a"), scratch("paste-b"), scratch("paste-c"));
    let a = study_with(|_| {});
    let b = study_with(|v| v["suites"][0]["synthetic"]["pga_g"] = 0.8.into());
    sweep::run(&a, &open_folder(&da), Shard::ALL, false, &|| {}).unwrap();
    sweep::run(&b, &open_folder(&db), Shard::ALL, false, &|| {}).unwrap();
    sweep::run(&a, &open_folder(&dc), Shard::ALL, false, &|| {}).unwrap();
    let ja = std::fs::read_to_string(da.join("journal.jsonl")).unwrap();
    let jb = std::fs::read_to_string(db.join("journal.jsonl")).unwrap();
    // the entry of design 2, record 0 in b's journal, in place of a's
    let key = "\"design\":2,\"record\":0,";
    let from_b = jb
        .lines()
        .find(|l| l.starts_with(&format!("{{{key}")))
        .unwrap();
    let pasted: String = ja
        .lines()
        .map(|l| {
            if l.starts_with(&format!("{{{key}")) {
                format!("{from_b}\n")
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    assert_ne!(pasted, ja, "the line was replaced");
    std::fs::write(da.join("journal.jsonl"), pasted).unwrap();
    let r = sweep::run(&a, &open_folder(&da), Shard::ALL, true, &|| {}).unwrap();
    assert_eq!((r.distrusted, r.ran), (1, 1));
    for f in ["responses.csv", "designs.csv"] {
        assert_eq!(
            std::fs::read(da.join(f)).unwrap(),
            std::fs::read(dc.join(f)).unwrap(),
            "{f}"
        );
    }
    for d in [da, db, dc] {
        std::fs::remove_dir_all(d).unwrap();
    }
}
