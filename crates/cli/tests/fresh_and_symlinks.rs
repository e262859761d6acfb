//! Contract: `--fresh` removes every file a previous run of any slipload command wrote
//! in the output folder (journals, tables, figures, rankings, the report, a temporary
//! file an interrupted write left), so no stale figure shows up in the next report; it
//! names what it removes and keeps, and never removes another file. An output path that
//! is a symbolic link is never written through: the command is refused before it runs,
//! the link and its target untouched.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{slipload_within, tiny_study as study, utf8 as s};

const T: u64 = 300;

fn run(args: &[&str]) -> (bool, String) {
    let o = slipload_within(T, args);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!err.contains("panicked"), "{err}");
    (o.status.success(), err)
}

#[test]
fn fresh_removes_every_file_slipload_wrote_and_names_what_it_keeps() {
    let dir = common::scratch("fresh", "all");
    let st = study(&dir);
    let out = dir.join("out");
    let (ok, err) = run(&["sweep", s(&st), "--out", s(&out), "--quiet"]);
    assert!(ok, "{err}");
    let fresh_bytes = std::fs::read(out.join("responses.csv")).unwrap();
    // what other commands left here: optimize's figures and tables, a ranking, a
    // family table, the report, a temporary file of an interrupted write — each named in
    // the folder's list of the files slipload wrote there (the lock file), as those
    // commands name them
    let stale = [
        "convergence.svg",
        "convergence.csv",
        "objective-map.png",
        "design-table.md",
        "optimum.json",
        "refine-trust-region.jsonl",
        "check.jsonl",
        "rank.md",
        "family.csv",
        "report.html",
        ".designs.csv.tmp",
    ];
    let mut list = std::fs::read_to_string(out.join(".slipload.lock")).unwrap();
    for f in stale {
        std::fs::write(out.join(f), "stale").unwrap();
        if !f.ends_with(".tmp") {
            list.push_str(f);
            list.push('\n');
        }
    }
    std::fs::write(out.join(".slipload.lock"), list).unwrap();
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let (ok, err) = run(&["sweep", s(&st), "--out", s(&out), "--fresh", "--quiet"]);
    assert!(ok, "{err}");
    for f in stale {
        assert!(!out.join(f).exists(), "{f} survived --fresh");
        assert!(
            err.contains(f),
            "--fresh does not say it removed {f}: {err}"
        );
    }
    assert!(err.contains("--fresh: removed"), "{err}");
    assert!(
        err.contains("--fresh: kept notes.txt"),
        "it names what it keeps: {err}"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "mine"
    );
    assert!(std::fs::read(out.join("responses.csv")).unwrap() == fresh_bytes);
    let _ = std::fs::remove_dir_all(&dir);
}

#[cfg(unix)]
#[test]
fn an_output_that_is_a_symlink_is_refused_and_its_target_untouched() {
    let dir = common::scratch("fresh", "symlink");
    let st = study(&dir);
    let target = dir.join("elsewhere.csv");
    std::fs::write(&target, "precious").unwrap();
    for name in ["responses.csv", "journal.jsonl"] {
        let out = dir.join(format!("out-{name}"));
        std::fs::create_dir_all(&out).unwrap();
        let link = out.join(name);
        std::os::unix::fs::symlink(&target, &link).unwrap();
        let (ok, err) = run(&["sweep", s(&st), "--out", s(&out), "--quiet"]);
        assert!(!ok, "{name}: ran through a symlink");
        assert!(
            err.contains("is a symbolic link") && err.contains("refusing to write through it"),
            "{name}: {err}"
        );
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "precious");
        // refused before anything ran: no journal, no table
        assert!(!out.join("manifest.json").exists(), "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--fresh` removes the files slipload wrote and nothing else: a user's own files in
/// the folder — under any name, one of slipload's output names included — are kept and
/// named, and a file under an output name that slipload did not write is never
/// overwritten: the run is refused before it starts, naming it.
#[test]
fn a_users_files_are_kept_and_never_overwritten() {
    let dir = common::scratch("fresh", "users");
    let st = study(&dir);
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    // the user's own table, under the name the sweep writes, in a folder slipload never
    // wrote into
    std::fs::write(out.join("designs.csv"), "my designs").unwrap();
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    for extra in [&[][..], &["--fresh"][..]] {
        let mut args = vec!["sweep", s(&st), "--out", s(&out), "--quiet"];
        args.extend_from_slice(extra);
        let (ok, err) = run(&args);
        assert!(
            !ok,
            "sweep {extra:?} over a user's designs.csv must be refused"
        );
        assert!(
            err.contains("designs.csv") && err.contains("did not write"),
            "the refusal names the file and why: {err}"
        );
        assert_eq!(
            std::fs::read_to_string(out.join("designs.csv")).unwrap(),
            "my designs"
        );
        assert!(!out.join("journal.jsonl").exists(), "nothing ran: {err}");
    }
    // moved away, the sweep runs; --fresh then removes its files and keeps the user's
    std::fs::rename(out.join("designs.csv"), dir.join("my-designs.csv")).unwrap();
    let (ok, err) = run(&["sweep", s(&st), "--out", s(&out), "--quiet"]);
    assert!(ok, "{err}");
    std::fs::write(out.join("my-plot.png"), "mine too").unwrap();
    let (ok, err) = run(&["sweep", s(&st), "--out", s(&out), "--fresh", "--quiet"]);
    assert!(ok, "{err}");
    assert!(
        err.contains("--fresh: kept my-plot.png, notes.txt"),
        "it names what it keeps: {err}"
    );
    assert!(
        err.contains("journal.jsonl"),
        "it names what it removed: {err}"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "mine"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("my-plot.png")).unwrap(),
        "mine too"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A user's own code check or device table put into a folder slipload already wrote in
/// (names the check and the device table take) is never overwritten: a run, a resume and
/// a `--fresh` run are refused before they start, naming the file; the earlier run's own
/// files are still slipload's and rewritten.
#[test]
fn a_users_code_check_or_device_table_in_a_study_folder_is_never_overwritten() {
    let dir = common::scratch("fresh", "check-files");
    let st = study(&dir);
    let out = dir.join("out");
    let (ok, err) = run(&["sweep", s(&st), "--out", s(&out), "--quiet"]);
    assert!(ok, "{err}");
    for mine in [
        "code-check.md",
        "code-check.csv",
        "code-check.json",
        "device-table.csv",
        "device-table.md",
        "device-table.json",
    ] {
        std::fs::write(out.join(mine), "my own").unwrap();
        for extra in [&[][..], &["--resume"][..], &["--fresh"][..]] {
            let mut args = vec!["sweep", s(&st), "--out", s(&out), "--quiet"];
            args.extend_from_slice(extra);
            let (ok, err) = run(&args);
            assert!(!ok, "sweep {extra:?} over a user's {mine} must be refused");
            assert!(
                err.contains(mine) && err.contains("did not write"),
                "the refusal names {mine} and why: {err}"
            );
            assert_eq!(std::fs::read_to_string(out.join(mine)).unwrap(), "my own");
            assert!(
                out.join("journal.jsonl").exists(),
                "--fresh removed nothing"
            );
        }
        std::fs::remove_file(out.join(mine)).unwrap();
    }
    // without them, the folder's own files are rewritten as before
    let (ok, err) = run(&["sweep", s(&st), "--out", s(&out), "--resume", "--quiet"]);
    assert!(ok, "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
