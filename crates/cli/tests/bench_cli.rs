//! `slipload bench` as scripts use it: `--format json` prints a list of
//! `{case, metric, value, unit, target, met, status, note}` objects, every target with a
//! status (met, NOT MET, withdrawn) and every status but `met` pointing to where
//! it is explained; the plan reductions it times give
//! the same peak drifts as the full 2N model, and the energies it times balance to
//! round-off (properties, so asserted; its timings are not — they are benchmarks on a
//! shared machine, not tests).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, slipload};

/// A figure's target has a status, its status agrees with `met`, and every status but
/// `met` points to a file of the repository that explains it.
/// `slipload bench --quick ARGS --format json`, parsed (the run must succeed).
fn bench_json(args: &[&str]) -> serde_json::Value {
    let mut argv = vec!["bench", "--quick"];
    argv.extend_from_slice(args);
    argv.extend_from_slice(&["--format", "json"]);
    let out = slipload(&argv);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn check_status(f: &serde_json::Value) {
    let status = f["status"].as_str();
    if f["target"].is_null() {
        assert!(status.is_none() && f["met"].is_null(), "{f}");
        return;
    }
    let status = status.unwrap_or_else(|| panic!("a target without a status: {f}"));
    match status {
        "met" => assert!(f["met"] == true && f["note"].is_null(), "{f}"),
        "NOT MET" => assert_eq!(f["met"], false, "{f}"),
        "withdrawn" => assert!(f["met"].is_null(), "a withdrawn target is not judged: {f}"),
        other => panic!("unknown status {other:?}: {f}"),
    }
    if status != "met" {
        let note = f["note"].as_str().unwrap_or_else(|| panic!("{f}"));
        let file = note.trim_start_matches("see ");
        assert!(root().join(file).is_file(), "{note}: {f}");
    }
}

/// The benchmark's 5000/s newmark target is withdrawn (3500/s stays as a regression
/// guard); `exact`'s speed targets are withdrawn too and its rows are judged against
/// regression guards instead: each says so, and where it is explained.
#[test]
fn withdrawn_targets_and_guards_are_marked() {
    let v = bench_json(&[
        "--only",
        "benchmark-3story, 15 s synthetic",
        "--only",
        "benchmark-3story m'=0, 15 s synthetic, exact",
    ]);
    let figs = v.as_array().unwrap();
    for f in figs {
        check_status(f);
    }
    let rate = |case: &str, target: &str| {
        figs.iter()
            .find(|f| {
                f["case"].as_str().unwrap().starts_with(case)
                    && f["metric"] == "simulations per second per core"
                    && f["target"] == target
            })
            .unwrap_or_else(|| panic!("{case} {target}: {v:#}"))
    };
    let judged = |f: &serde_json::Value| f["status"] == "met" || f["status"] == "NOT MET";
    let newmark = "benchmark-3story, 15 s synthetic, newmark";
    assert_eq!(rate(newmark, ">= 5000")["status"], "withdrawn");
    assert!(judged(rate(newmark, ">= 3500")));
    let exact = "benchmark-3story, 15 s synthetic, exact";
    let exact0 = "benchmark-3story m'=0, 15 s synthetic, exact";
    assert_eq!(rate(exact, ">= 1000")["status"], "withdrawn");
    assert_eq!(rate(exact0, ">= 5000")["status"], "withdrawn");
    // the guards: 0.8x the slower machine's rate when the targets were withdrawn (52.95
    // and 361.3 per second), judged
    assert!(judged(rate(exact, ">= 42.4")));
    assert!(judged(rate(exact0, ">= 289")));
    let ratios: Vec<&serde_json::Value> = figs
        .iter()
        .filter(|f| f["metric"] == "time per simulation / newmark's at its default dt")
        .collect();
    let targets: Vec<(&str, &str)> = ratios
        .iter()
        .map(|f| (f["target"].as_str().unwrap(), f["status"].as_str().unwrap()))
        .collect();
    // 1.2x the larger ratio then (54.71 and 8.700) judged; the old 5x and 1.5x withdrawn
    assert_eq!(targets.len(), 4, "{v:#}");
    for (target, status) in targets {
        match target {
            "<= 65.7" | "<= 10.4" => assert!(status == "met" || status == "NOT MET"),
            "<= 5" | "<= 1.5" => assert_eq!(status, "withdrawn"),
            other => panic!("unexpected ratio target {other}: {v:#}"),
        }
    }
    // The table says the same, and where to read why.
    let out = slipload(&[
        "bench",
        "--quick",
        "--only",
        "benchmark-3story, 15 s synthetic, newmark",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("withdrawn: see results/performance/README.md"),
        "{text}"
    );
}

/// The locked m′ = 0 scene, which separates the stepping and output cost of `exact` from
/// its events, has none: its dampers never slip, and its only targets are the regression
/// guards of its rate and of its time against newmark's (no withdrawn target: it had none).
#[test]
fn the_locked_scene_has_no_events() {
    let v = bench_json(&[
        "--only",
        "benchmark-3story m'=0 locked, 15 s synthetic, exact",
    ]);
    let figs = v.as_array().unwrap();
    let events = figs
        .iter()
        .find(|f| f["metric"] == "stick-slip events")
        .unwrap_or_else(|| panic!("{v:#}"));
    assert_eq!(events["value"], 0.0, "{events}");
    assert!(
        figs.iter()
            .any(|f| f["metric"] == "time per simulation / newmark's at its default dt")
    );
    for f in figs {
        check_status(f);
        let guarded = f["metric"] == "simulations per second per core"
            || f["metric"] == "time per simulation / newmark's at its default dt";
        assert_eq!(f["target"].is_null(), !guarded, "{f}");
        if guarded {
            assert!(f["status"] == "met" || f["status"] == "NOT MET", "{f}");
        }
    }
}

#[test]
fn json_lists_figures_and_reductions_keep_answers() {
    let v = bench_json(&[
        "--only",
        "reductions",
        "--only",
        "memory",
        "--only",
        "outputs",
    ]);
    let figs = v.as_array().unwrap();
    assert!(figs.len() >= 8, "{v:#}");
    for f in figs {
        let mut keys: Vec<&str> = f.as_object().unwrap().keys().map(String::as_str).collect();
        keys.sort_unstable();
        assert_eq!(
            keys,
            [
                "case", "met", "metric", "note", "status", "target", "unit", "value"
            ]
        );
        assert!(f["value"].as_f64().unwrap().is_finite(), "{f}");
        check_status(f);
    }
    let diffs: Vec<&serde_json::Value> = figs
        .iter()
        .filter(|f| {
            f["metric"]
                .as_str()
                .unwrap()
                .contains("difference reduced vs full")
        })
        .collect();
    assert_eq!(diffs.len(), 3, "{v:#}");
    for f in diffs {
        // Reduced plans are exact condensations: equal to round-off (1e-9 is the target).
        assert_eq!(f["met"], true, "{f}");
    }
    // Average-acceleration Newmark balances its energies to round-off (an identity of the
    // method), in the fixed-size loop the bench times as in the general one.
    let balances: Vec<&serde_json::Value> = figs
        .iter()
        .filter(|f| f["metric"] == "|energy balance error| / input")
        .collect();
    assert_eq!(balances.len(), 2, "{v:#}");
    for f in balances {
        assert_eq!(f["met"], true, "{f}");
    }
    // The memory probe ran in child processes and reported both sizes.
    assert!(
        figs.iter().any(|f| f["metric"] == "peak RSS, 300 s"),
        "{v:#}"
    );
}

/// The equal-accuracy case reports what an engineer buys: newmark's time to reach a
/// peak-drift error of 1e-3 and 1e-4 against `exact` along its ladder of steps, exact's
/// time, their ratio, and OpenSees's times from the committed comparison beside them,
/// the speed-up over OpenSees judged against its guard (option A) with the retired 500×
/// beside it as withdrawn.
#[test]
fn equal_accuracy_figures_are_reported() {
    let v = bench_json(&["--only", "equal accuracy"]);
    let figs = v.as_array().unwrap();
    let value = |metric: &str| {
        figs.iter()
            .find(|f| f["metric"].as_str().unwrap().contains(metric))
            .unwrap_or_else(|| panic!("{metric}: {v:#}"))["value"]
            .as_f64()
            .unwrap()
    };
    let exact = value("exact, time per simulation");
    for target in ["1e-3", "1e-4"] {
        let newmark = value(&format!("time to reach {target}"));
        assert!(newmark > 0.0 && exact > 0.0, "{v:#}");
        let ratio = value(&format!("exact / newmark at {target}"));
        // the ratio is of the two times printed (ms), to their printed precision
        assert!((ratio - exact / newmark).abs() <= 1e-9 * ratio, "{v:#}");
        let os = value(&format!("OpenSees, time to reach {target}"));
        let os_ratio = value(&format!("OpenSees / newmark at {target}"));
        assert!((os_ratio - os / newmark).abs() <= 1e-9 * os_ratio, "{v:#}");
        // issue 30's 500× was retired by option A: the row is judged against its
        // regression guard under the measured floor, the 500× printed beside it as
        // withdrawn, never as NOT MET
        let rows: Vec<&serde_json::Value> = figs
            .iter()
            .filter(|f| f["metric"] == format!("OpenSees / newmark at {target}"))
            .collect();
        assert_eq!(rows.len(), 2, "{rows:?}");
        for f in &rows {
            check_status(f);
        }
        let guard: f64 = rows[0]["target"]
            .as_str()
            .unwrap()
            .trim_start_matches(">= ")
            .parse()
            .unwrap();
        assert!(guard > 0.0 && guard < 500.0, "{:?}", rows[0]);
        assert!(
            rows[0]["status"] == "met" || rows[0]["status"] == "NOT MET",
            "{:?}",
            rows[0]
        );
        assert_eq!(
            (rows[1]["target"].as_str(), rows[1]["status"].as_str()),
            (Some(">= 500"), Some("withdrawn"))
        );
    }
    // a finer target costs newmark at least as much time as a coarser one
    assert!(
        value("time to reach 1e-4") >= value("time to reach 1e-3"),
        "{v:#}"
    );
}

/// The banded step's speed-up over the dense step: at ten storeys issue 30's 3× was
/// retired by option A, so the row is judged against its regression guard under the
/// recorded floor and the 3× is printed beside it as withdrawn, never as NOT MET; at
/// fifty storeys the 6× target stands.
#[test]
fn the_banded_rows_retired_by_option_a_are_guards() {
    let v = bench_json(&["--only", "Rayleigh damping, newmark"]);
    let figs = v.as_array().unwrap();
    let rows = |n: usize| -> Vec<&serde_json::Value> {
        figs.iter()
            .filter(|f| {
                f["metric"] == format!("banded step's speed-up over the dense step, {n} storeys")
            })
            .collect()
    };
    let ten = rows(10);
    assert_eq!(ten.len(), 2, "{v:#}");
    for f in ten.iter().chain(rows(50).iter()) {
        check_status(f);
    }
    let guard: f64 = ten[0]["target"]
        .as_str()
        .unwrap()
        .trim_start_matches(">= ")
        .parse()
        .unwrap();
    // under the recorded floor (1.39×), far under the retired 3×
    assert!(guard > 1.0 && guard < 1.39, "{:?}", ten[0]);
    assert_ne!(ten[0]["status"], "withdrawn");
    assert_eq!(
        (ten[1]["target"].as_str(), ten[1]["status"].as_str()),
        (Some(">= 3"), Some("withdrawn"))
    );
    let fifty = rows(50);
    assert_eq!(fifty.len(), 1, "{v:#}");
    assert_eq!(fifty[0]["target"], ">= 6");
}

/// The tall frames' rows (issue 39): set-up and stepping at 10, 20, 50, 100 and 200
/// storeys with their log-log slopes, the set-up at 200 storeys judged against 0.3 s, and
/// one peak-memory row per size from a child process; the child's answer is four numbers
/// and a bad `METHOD:STOREYS` is refused naming the flag.
#[test]
fn tall_frame_rows_are_reported_beside_their_targets() {
    let v = bench_json(&[
        "--only",
        "tall frames: set-up",
        "--only",
        "tall frames: peak",
    ]);
    let figs = v.as_array().unwrap();
    for f in figs {
        check_status(f);
        assert!(
            f["case"].as_str().unwrap().starts_with("tall frames: "),
            "{f}"
        );
        assert!(f["value"].as_f64().unwrap().is_finite(), "{f}");
    }
    let find = |metric: &str| {
        figs.iter()
            .find(|f| f["metric"].as_str().unwrap().starts_with(metric))
            .unwrap_or_else(|| panic!("{metric}: {v:#}"))
    };
    for n in [10, 20, 50, 100, 200] {
        let setup = find(&format!("set-up, {n} storeys"));
        assert_eq!(setup["unit"], "ms", "{setup}");
        // only the 200-storey set-up carries the target
        assert_eq!(
            setup["target"].as_str(),
            (n == 200).then_some("<= 300"),
            "{setup}"
        );
        let stepping = find(&format!("stepping (6000 steps), {n} storeys"));
        assert!(stepping["value"].as_f64().unwrap() > 0.0, "{stepping}");
        let rss = find(&format!("peak RSS, {n} storeys"));
        assert_eq!(rss["unit"], "MiB", "{rss}");
        // a process that ran a simulation holds at least a MiB and far below a GiB
        let mib = rss["value"].as_f64().unwrap();
        assert!((1.0..1024.0).contains(&mib), "{rss}");
    }
    assert_eq!(
        find("exponent of set-up vs storeys, 10-200")["target"],
        "<= 3"
    );
    for slope in [
        "exponent of set-up vs storeys, 50-200",
        "exponent of stepping vs storeys, 10-200",
        "exponent of peak RSS vs storeys, 10-200",
    ] {
        assert!(
            find(slope)["value"].as_f64().unwrap().is_finite(),
            "{slope}"
        );
    }

    let out = slipload(&["bench", "--tall-probe", "newmark:10"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let answer: Vec<f64> = String::from_utf8_lossy(&out.stdout)
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    // peak RSS kB, run seconds, then exact's budget and cache peak: none for newmark
    assert_eq!(answer.len(), 4, "{answer:?}");
    assert!(answer[0] > 0.0 && answer[1] > 0.0, "{answer:?}");
    assert_eq!(&answer[2..], &[0.0, 0.0]);
    let bad = slipload(&["bench", "--tall-probe", "newmark"]);
    assert!(!bad.status.success());
    assert!(
        String::from_utf8_lossy(&bad.stderr).contains("--tall-probe takes METHOD:STOREYS"),
        "{}",
        String::from_utf8_lossy(&bad.stderr)
    );
}
