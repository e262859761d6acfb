//! Contract: one study folder, one writer. While a command holds a folder's lock
//! (`.slipload.lock`, an OS file lock), a second `sweep`, `optimize`, `rank` or `merge`
//! into it is refused at once with a message that says the folder is in use — and
//! `--fresh` removes nothing — and `merge` refuses a shard folder still being written.
//! The first run's files stay intact, and once the lock is released (as the OS does when
//! a run dies, `kill -9` included) the folder takes the next command.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use std::path::Path;

mod common;
use common::{slipload_within, tiny_study as study, utf8 as s};

/// Seconds a refused command may take at most: it must not wait for the lock.
const T: u64 = 60;

/// Every file of `dir` with its bytes, sorted by name.
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.file_type().unwrap().is_file())
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    v.sort();
    v
}

fn ok(args: &[&str]) {
    let o = slipload_within(T * 5, args);
    assert!(
        o.status.success(),
        "slipload {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Refused at once, saying the folder is in use.
fn refused_busy(args: &[&str], dir: &Path) {
    let o = slipload_within(T, args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "slipload {args:?} ran: {err}");
    assert!(
        err.contains(&format!(
            "{} is in use by another slipload command",
            dir.display()
        )),
        "slipload {args:?}: {err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

/// Holds the lock of `dir` as a running command does.
fn hold(dir: &Path) -> std::fs::File {
    let f = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(dir.join(".slipload.lock"))
        .unwrap();
    f.try_lock().unwrap();
    f
}

#[test]
fn a_second_command_into_a_folder_in_use_is_refused_and_the_first_is_intact() {
    let dir = common::scratch("lock", "busy");
    let st = study(&dir);
    let out = dir.join("out");
    ok(&["sweep", s(&st), "--out", s(&out), "--quiet"]);
    let before = snapshot(&out);
    assert!(before.iter().any(|(n, _)| n == "responses.csv"));
    let lock = hold(&out);
    refused_busy(
        &["sweep", s(&st), "--out", s(&out), "--fresh", "--quiet"],
        &out,
    );
    refused_busy(
        &["sweep", s(&st), "--out", s(&out), "--resume", "--quiet"],
        &out,
    );
    refused_busy(&["optimize", s(&st), "--out", s(&out), "--quiet"], &out);
    let cands = dir.join("cands.json");
    std::fs::write(
        &cands,
        r#"[{"name": "a", "slip_loads_kn": [100, 100, 100]}]"#,
    )
    .unwrap();
    refused_busy(
        &[
            "rank",
            s(&st),
            "--designs",
            s(&cands),
            "--out",
            s(&out),
            "--quiet",
        ],
        &out,
    );
    assert!(snapshot(&out) == before, "the first run's files are intact");
    // a shard folder still being written is not merged
    let merged = dir.join("merged");
    refused_busy(&["merge", "--out", s(&merged), s(&out)], &out);
    assert!(!merged.join("responses.csv").exists());
    // released (as when the holder ends, however it ends): the folder takes the next run
    drop(lock);
    ok(&["sweep", s(&st), "--out", s(&out), "--resume", "--quiet"]);
    ok(&["merge", "--out", s(&merged), s(&out)]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Two processes sweeping into one folder: while the first runs (it holds the lock), the
/// second is refused at once, and the first finishes with the bytes of a sweep that ran
/// alone.
#[test]
fn two_processes_one_folder_the_second_is_refused_and_the_first_finishes() {
    use std::process::{Command, Stdio};
    let dir = common::scratch("lock", "two");
    // the tiny study with enough designs that the first run is still going when the
    // second starts (its lock is watched, not its time)
    let st = study(&dir);
    let text = std::fs::read_to_string(&st)
        .unwrap()
        .replace("\"points\": 2", "\"points\": 2000");
    std::fs::write(&st, text).unwrap();
    let out = dir.join("out");
    let mut first = Command::new(env!("CARGO_BIN_EXE_slipload"))
        .args([
            "sweep",
            s(&st),
            "--out",
            s(&out),
            "--quiet",
            "--threads",
            "1",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // wait until the first holds the folder's lock
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(T * 5);
    loop {
        let held = std::fs::File::open(out.join(".slipload.lock"))
            .map(|f| matches!(f.try_lock_shared(), Err(std::fs::TryLockError::WouldBlock)))
            .unwrap_or(false);
        if held {
            break;
        }
        assert!(
            first.try_wait().unwrap().is_none(),
            "the first sweep ended before its lock was seen"
        );
        assert!(std::time::Instant::now() < deadline, "no lock taken");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    refused_busy(&["sweep", s(&st), "--out", s(&out), "--quiet"], &out);
    let done = first.wait_with_output().unwrap();
    assert!(
        done.status.success(),
        "the first sweep finishes: {}",
        String::from_utf8_lossy(&done.stderr)
    );
    let alone = dir.join("alone");
    ok(&["sweep", s(&st), "--out", s(&alone), "--quiet"]);
    let files = |d: &Path| -> Vec<(String, Vec<u8>)> {
        snapshot(d)
            .into_iter()
            .filter(|(n, _)| n != ".slipload.lock" && n != "journal.jsonl")
            .collect()
    };
    assert!(
        files(&out) == files(&alone),
        "the first run's files are those of a sweep that ran alone"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
