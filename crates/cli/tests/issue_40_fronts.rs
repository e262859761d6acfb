//! Issue 40 §2–§4 on the command line: no command writes over its inputs or over a file it
//! was not told it may replace (`record synth --out`, `simulate --history`); `record
//! synth` writes only records `record info` reads (steps of 1 µs … 1 s); a negative number
//! to a numeric flag is refused naming the flag and what it expects, not as an
//! "unexpected argument"; `--threads` is listed only by the commands that use threads and
//! checked by the library's rule; and `simulate` warns about a slip load that looks like
//! kN written as N.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch, slipload, stderr};

const B: &str = "configs/benchmark-3story.json";

fn path(p: &std::path::Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn record_synth_refuses_an_existing_out_unless_forced() {
    let d = scratch("fronts", "synth-out");
    let out = d.join("mine.csv");
    std::fs::write(&out, "time_s,accel_m_s2\n0,0\n0.01,1\n").unwrap();
    let o = slipload(&["record", "synth", "--duration", "2", "--out", path(&out)]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(err.contains(path(&out)) && err.contains("--force"), "{err}");
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        "time_s,accel_m_s2\n0,0\n0.01,1\n",
        "the user's file is untouched"
    );
    // through a symlink too
    #[cfg(unix)]
    {
        let link = d.join("link.csv");
        std::os::unix::fs::symlink(&out, &link).unwrap();
        let o = slipload(&["record", "synth", "--duration", "2", "--out", path(&link)]);
        assert!(!o.status.success(), "{}", stderr(&o));
    }
    let o = slipload(&[
        "record",
        "synth",
        "--duration",
        "2",
        "--out",
        path(&out),
        "--force",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::read_to_string(&out).unwrap().lines().count() > 100);
    // a folder of records (--count): a record already there is not replaced either
    let folder = d.join("suite");
    let args = |force: bool| {
        let mut a = vec![
            "record",
            "synth",
            "--duration",
            "2",
            "--count",
            "2",
            "--seed",
            "9",
            "--out",
            path(&folder),
        ];
        if force {
            a.push("--force");
        }
        a.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let run = |force| {
        let a = args(force);
        slipload(&a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    assert!(run(false).status.success());
    let o = run(false);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("synthetic-9-000.csv"), "{}", stderr(&o));
    assert!(run(true).status.success());
}

#[test]
fn record_synth_writes_only_steps_record_info_reads() {
    let d = scratch("fronts", "synth-dt");
    for dt in ["5", "1.5", "5e-7", "0", "-0.01"] {
        let out = d.join(format!("dt{dt}.csv"));
        let o = slipload(&[
            "record",
            "synth",
            "--dt",
            dt,
            "--duration",
            "20",
            "--out",
            path(&out),
        ]);
        assert!(!o.status.success(), "--dt {dt}");
        let err = stderr(&o);
        assert!(err.contains("--dt"), "{err}");
        assert!(!out.exists(), "--dt {dt}: nothing written");
    }
    // the band's ends: written, and read back by record info
    for (dt, duration) in [("1", "30"), ("1e-3", "0.5")] {
        let out = d.join(format!("ok{dt}.csv"));
        let o = slipload(&[
            "record",
            "synth",
            "--dt",
            dt,
            "--duration",
            duration,
            "--out",
            path(&out),
        ]);
        assert!(o.status.success(), "--dt {dt}: {}", stderr(&o));
        let o = slipload(&["record", "info", path(&out)]);
        assert!(o.status.success(), "--dt {dt}: {}", stderr(&o));
    }
}

#[test]
fn simulate_history_refuses_the_files_being_run() {
    let d = scratch("fronts", "history");
    let record = d.join("rec.AT2");
    std::fs::copy(root().join("records/SYL090.AT2"), &record).unwrap();
    let building = d.join("building.json");
    std::fs::copy(root().join(B), &building).unwrap();
    let scene = d.join("scene.json");
    std::fs::write(
        &scene,
        r#"{"building": "building.json", "excitation": {"record": {"file": "rec.AT2"}}, "duration": 0.5}"#,
    )
    .unwrap();
    let before = |p: &std::path::Path| std::fs::read(p).unwrap();
    let (rec0, bld0, scn0) = (before(&record), before(&building), before(&scene));
    let link = d.join("link.AT2");
    #[cfg(unix)]
    std::os::unix::fs::symlink(&record, &link).unwrap();
    let dotted = d.join(".").join("rec.AT2");
    let mut cases: Vec<(Vec<&str>, &std::path::Path)> = vec![
        // --record's file
        (
            vec![
                "simulate",
                B,
                "--record",
                path(&record),
                "--duration",
                "0.5",
            ],
            &record,
        ),
        (
            vec![
                "simulate",
                B,
                "--record",
                path(&record),
                "--duration",
                "0.5",
            ],
            &dotted,
        ),
        // the building file being run
        (
            vec!["simulate", path(&building), "--duration", "0.5"],
            &building,
        ),
        // a scene, the building it names and the record it names
        (vec!["simulate", path(&scene)], &scene),
        (vec!["simulate", path(&scene)], &building),
        (vec!["simulate", path(&scene)], &record),
    ];
    // the record read through a symlink, written to by its own name (writing through a
    // symlink is refused as such by every output)
    #[cfg(unix)]
    cases.push((
        vec!["simulate", B, "--record", path(&link), "--duration", "0.5"],
        &record,
    ));
    for (args, history) in cases {
        let mut a = args.clone();
        a.extend(["--history", path(history)]);
        let o = slipload(&a);
        assert!(!o.status.success(), "{a:?}");
        let err = stderr(&o);
        assert!(
            err.contains("--history") && err.contains("input of this run"),
            "{a:?}: {err}"
        );
    }
    assert_eq!(before(&record), rec0);
    assert_eq!(before(&building), bld0);
    assert_eq!(before(&scene), scn0);
    // another file is written
    let h = d.join("h.csv");
    let o = slipload(&["simulate", path(&scene), "--history", path(&h)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(h.is_file());
}

#[test]
fn a_negative_number_to_a_numeric_flag_names_the_flag_and_what_it_expects() {
    for (args, want) in [
        (vec!["--threads", "-1", "simulate"], "--threads"),
        (vec!["sweep", "s.json", "--threads", "-1"], "--threads"),
        (vec!["simulate", "--threads", "-1"], "--threads"),
        (vec!["simulate", "--dt", "-0.01", "--duration", "1"], "--dt"),
        (
            vec!["record", "synth", "--dt", "-0.01", "--out", "x.csv"],
            "--dt",
        ),
        (
            vec!["record", "synth", "--count", "-1", "--out", "x"],
            "--count",
        ),
        (vec!["report", "d", "--max-rows", "-1"], "--max-rows"),
        (vec!["table", "--period-scales", "-1,1"], "--period-scales"),
        (vec!["simulate", "--repeat", "-3"], "--repeat"),
    ] {
        let o = slipload(&args);
        assert!(!o.status.success(), "{args:?}");
        let err = stderr(&o);
        assert!(!err.contains("unexpected argument"), "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
        assert!(
            err.contains("expected") || err.contains("must be") || err.contains("give at least"),
            "{args:?}: says what is expected: {err}"
        );
    }
}

#[test]
fn threads_is_listed_only_by_the_commands_that_use_threads_and_checked_alike() {
    for (cmd, listed) in [
        (&["simulate"][..], false),
        (&["explain"], false),
        (&["record", "synth"], false),
        (&["accuracy"], false),
        (&["report"], false),
        (&["opensees"], false),
        (&["bench"], false),
        (&["merge"], false),
        (&["sweep"], true),
        (&["optimize"], true),
        (&["rank"], true),
        (&["table"], true),
    ] {
        let mut a = cmd.to_vec();
        a.push("--help");
        let o = slipload(&a);
        assert!(o.status.success(), "{a:?}");
        let help = String::from_utf8_lossy(&o.stdout);
        assert_eq!(help.contains("--threads"), listed, "{a:?}: {help}");
    }
    // 0 is refused, after a command's name as before it
    for args in [
        vec!["--threads", "0", "simulate", "--duration", "0.1"],
        vec!["table", "--threads", "0"],
    ] {
        let o = slipload(&args);
        assert!(!o.status.success(), "{args:?}");
        assert!(
            stderr(&o).contains("--threads 0: no worker thread"),
            "{}",
            stderr(&o)
        );
    }
}

#[test]
fn a_slip_load_that_looks_like_kn_written_as_newtons_is_warned_about() {
    let d = scratch("fronts", "kn");
    let text = std::fs::read_to_string(root().join(B)).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["dissipators"][0]["slip_load"] = serde_json::json!(834.095);
    let b = d.join("bare-number.json");
    std::fs::write(&b, v.to_string()).unwrap();
    let o = slipload(&["simulate", path(&b), "--duration", "0.5"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("warning: floor 1: the slip load 834.095 N")
            && err.contains("did you mean kN"),
        "{err}"
    );
    assert!(!err.contains("floor 2"), "{err}");
    // the file as written: nothing to warn about
    let o = slipload(&["simulate", B, "--duration", "0.5"]);
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
}
