//! Contract: the HTML report of real output folders (a simulation `--plot` folder, an
//! accuracy study, a small optimize study) loads in headless chromium with no console
//! errors, no page errors and no request outside the file; every inline SVG has a
//! rendered size and the tables are there (checked by `scripts/check-report`, which also
//! takes a full-page screenshot).
//!
//! Needs chromium (`apt-get install -y chromium`) and the script's npm packages (`npm ci`
//! in scripts/check-report); `bash scripts/test.sh`, the README's test command, installs
//! both and runs this test. When either is missing the test FAILS with these
//! instructions, unless `SLIPLOAD_SKIP_BROWSER=1` is set.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch, slipload, slipload_in};
use std::path::{Path, PathBuf};
use std::process::Command;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn chromium() -> PathBuf {
    std::env::var_os("CHROMIUM").map_or_else(|| PathBuf::from("/usr/bin/chromium"), PathBuf::from)
}

/// `None` when the browser check can run; otherwise what is missing and how to install it.
fn missing_tools() -> Option<String> {
    let script_dir = root().join("scripts/check-report");
    let mut missing = Vec::new();
    if Command::new("node").arg("--version").output().is_err() {
        missing.push("node (Node.js 20+, e.g. apt-get install -y nodejs npm)".to_string());
    }
    if !chromium().is_file() {
        missing.push(format!(
            "chromium at {} (apt-get install -y chromium, or set CHROMIUM to its path)",
            chromium().display()
        ));
    }
    if !script_dir.join("node_modules/playwright-core").is_dir() {
        missing.push(format!(
            "playwright-core (run `npm ci` in {})",
            script_dir.display()
        ));
    }
    (!missing.is_empty()).then(|| missing.join("; "))
}

/// Writes the report of `dir`, runs the browser check on it and returns its JSON summary.
fn check(
    dir: &Path,
    work: &Path,
    name: &str,
    min_tables: usize,
    min_svgs: usize,
) -> serde_json::Value {
    let page = work.join(format!("{name}.html"));
    let png = work.join(format!("{name}.png"));
    let out = slipload(&["report", s(dir), "--out", s(&page)]);
    assert!(
        out.status.success(),
        "report of {}: {}",
        dir.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    let out = Command::new("node")
        .arg(root().join("scripts/check-report/check-report.mjs"))
        .args([
            s(&page),
            s(&png),
            "--min-tables",
            &min_tables.to_string(),
            "--min-svgs",
            &min_svgs.to_string(),
        ])
        .env("CHROMIUM", chromium())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "browser check of the {name} report failed:\n{stderr}\n{stdout}"
    );
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["ok"], true, "{stdout}");
    assert!(
        std::fs::metadata(&png).unwrap().len() > 10_000,
        "the {name} screenshot is not empty"
    );
    eprintln!(
        "{name}: report {}, screenshot {}",
        page.display(),
        png.display()
    );
    v
}

/// A tiny optimize study: the benchmark building, 2 synthetic records of 3 s, 6 designs.
fn tiny_study(dir: &Path) -> PathBuf {
    let building = root().join("configs/benchmark-3story.json");
    let text = format!(
        r#"{{
  "name": "tiny",
  "building": {building:?},
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": 2, "seed": 3, "pga_g": 0.4, "duration_s": 3 }} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "sweep": {{ "sampler": "halton", "points": 6, "seed": 5 }},
  "refine": {{ "method": "trust-region", "starts": 1, "max_evaluations": 8, "finalists": 1 }}
}}"#
    );
    let p = dir.join("study.json");
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn reports_load_in_headless_chromium_without_errors() {
    if let Some(what) = missing_tools() {
        if std::env::var("SLIPLOAD_SKIP_BROWSER").is_ok_and(|v| v == "1") {
            eprintln!("SLIPLOAD_SKIP_BROWSER=1: browser check skipped (missing: {what})");
            return;
        }
        panic!(
            "the headless-browser check cannot run; missing: {what}. \
             Install them (`bash scripts/test.sh`, the README's test command, does), or set SLIPLOAD_SKIP_BROWSER=1 to skip this test explicitly."
        );
    }
    let work = scratch("report-browser", "all");

    // an accuracy study: two methods, two time steps, 2 s of the harmonic scene
    let acc = work.join("accuracy");
    let out = slipload(&[
        "accuracy",
        "configs/paper-1story-harmonic.json",
        "--duration",
        "2",
        "--methods",
        "newmark,exact",
        "--dts",
        "T1/50,T1/100",
        "--repeats",
        "1",
        "--out",
        s(&acc),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v = check(&acc, &work, "accuracy", 1, 0);
    assert!(v["tables"].as_u64().unwrap() >= 1);

    // a small optimize study
    let study = tiny_study(&work);
    let opt = work.join("optimize");
    let out = slipload_in(&work, &["optimize", s(&study), "--out", s(&opt), "--quiet"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // design table (2 Markdown tables), ranking-free summary tables: at least 3
    // drift profiles, per-record scatter and convergence are inlined
    let v = check(&opt, &work, "optimize", 3, 3);
    assert!(v["title"].as_str().unwrap().starts_with("tiny"), "{v}");

    // the check itself can fail: a page with a script error, an external image and a
    // zero-size SVG is rejected with each problem named
    let bad = work.join("bad.html");
    std::fs::write(
        &bad,
        "<!DOCTYPE html><html><head><title>bad</title></head><body><h1>bad</h1>\
         <table><tr><td>1</td></tr></table><svg width=\"0\" height=\"0\"></svg>\
         <img src=\"https://example.invalid/x.png\"><script>undefinedFunction()</script></body></html>",
    )
    .unwrap();
    let out = Command::new("node")
        .arg(root().join("scripts/check-report/check-report.mjs"))
        .args([s(&bad), s(&work.join("bad.png"))])
        .env("CHROMIUM", chromium())
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let problems = v["problems"].to_string();
    for what in ["page error", "external request blocked", "has size 0 x 0"] {
        assert!(problems.contains(what), "{what}: {problems}");
    }

    let _ = std::fs::remove_dir_all(&work);
}
