//! `slipload simulate --method delacruz` as a user runs it: the paper's one-storey free
//! vibration agrees with `newmark` at the paper's Δt (T₁/200) on the peak displacement and
//! slip (1 %); a case beyond the method's stability limit fails with a non-zero exit and a
//! message naming the loop and a time step to use, with no output file written; the
//! table shows the loops' iteration counts.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::slipload;

fn json(args: &[&str]) -> serde_json::Value {
    let out = slipload(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn free_vibration_agrees_with_newmark_at_the_papers_dt() {
    // delacruz's default is the paper's Δt = T₁/200; newmark runs at the same step.
    let d = json(&[
        "simulate",
        "configs/paper-1story-free.json",
        "--method",
        "delacruz",
        "--format",
        "json",
    ]);
    let dt = d["dt"].as_f64().unwrap().to_string();
    let n = json(&[
        "simulate",
        "configs/paper-1story-free.json",
        "--method",
        "newmark",
        "--dt",
        &dt,
        "--format",
        "json",
    ]);
    assert_eq!(d["method"], "delacruz");
    assert_eq!(d["dt"], n["dt"]);
    for key in ["peak_displacement", "peak_slip"] {
        let (a, b) = (d[key][0].as_f64().unwrap(), n[key][0].as_f64().unwrap());
        // 1 %: both are accurate to O(Δt) across stick/slip events at Δt = T₁/200.
        assert!((a - b).abs() < 0.01 * b.abs(), "{key}: {a} vs {b}");
    }
}

#[test]
fn beyond_its_stability_limit_it_fails_clearly() {
    let dir = std::env::temp_dir().join(format!("slipload-delacruz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let hist = dir.join("h.csv");
    let out = slipload(&[
        "simulate",
        "configs/paper-benchmark-sylmar.json",
        "--method",
        "delacruz",
        "--history",
        hist.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("outer loop") && err.contains("try dt <="),
        "{err}"
    );
    assert!(!hist.exists(), "no partial output");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn table_shows_the_loop_iterations() {
    let out = slipload(&[
        "simulate",
        "configs/paper-1story-harmonic.json",
        "--method",
        "delacruz",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("fixed-point iterations"), "{text}");
}
