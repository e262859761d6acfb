//! A design from a study folder goes to `simulate` and `opensees` directly
//! (`--study S --designs OUT --design NAME --run RECORD`): every run of the optimum,
//! re-simulated this way, gives the peak drift ratios the study's design table reports
//! for it (the largest over the records, to the bit); a wrong design, run or folder is
//! refused naming what there is; `--scale` multiplies a record.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use std::path::{Path, PathBuf};
mod common;
use common::{root, slipload, stderr};

fn study(dir: &Path, name: &str, pga: f64) -> PathBuf {
    let text = format!(
        r#"{{ "name": "{name}", "building": "{building}",
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": 2, "seed": 2007, "pga_g": {pga}, "duration_s": 4.0 }} }},
              {{ "name": "strong", "synthetic": {{ "count": 2, "seed": 2007, "pga_g": 0.6, "duration_s": 4.0 }} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark", "check_method": "newmark", "check_dt_factor": 0.5 }},
  "sweep": {{ "sampler": "halton", "points": 6, "seed": 2007 }},
  "refine": {{ "method": "trust-region", "starts": 1, "max_evaluations": 4, "finalists": 2 }} }}"#,
        building = root().join("configs/benchmark-3story.json").display()
    );
    std::fs::create_dir_all(dir).unwrap();
    let p = dir.join(format!("{name}.json"));
    std::fs::write(&p, text).unwrap();
    p
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn ok(args: &[&str]) -> String {
    let o = slipload(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn refused(args: &[&str], words: &[&str]) {
    let o = slipload(args);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{args:?} should fail: {}",
        stderr(&o)
    );
    let e = stderr(&o);
    for w in words {
        assert!(e.contains(w), "{w:?} not in: {e}");
    }
}

#[test]
fn every_run_of_the_optimum_re_simulated_gives_the_design_tables_drifts() {
    let dir = common::scratch("design-run", "table");
    let st = study(&dir, "design-run", 0.4);
    let out = dir.join("out");
    ok(&["--quiet", "optimize", s(&st), "--out", s(&out)]);
    let table: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("design-table.json")).unwrap())
            .unwrap();
    let optimum = table["rows"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["design"] == "optimum")
        .unwrap();
    let want: Vec<f64> = optimum["drift_ratio_max"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("manifest.json")).unwrap()).unwrap();
    let records: Vec<String> = manifest["records"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap().to_string())
        .collect();
    // the same two records in two suites, each scaled its own way
    assert_eq!(records.len(), 4);
    assert_eq!(records[0], records[2]);
    let design_run = |extra: &[&str]| -> Vec<String> {
        let mut a: Vec<String> = ["--study", s(&st), "--designs", s(&out)]
            .iter()
            .map(|x| x.to_string())
            .collect();
        a.extend(extra.iter().map(|x| x.to_string()));
        a
    };
    let strs = |v: &[String]| -> Vec<String> { v.to_vec() };
    let run = |cmd: &str, extra: &[&str]| -> std::process::Output {
        let mut a = vec!["--quiet".to_string(), cmd.to_string()];
        a.extend(strs(&design_run(extra)));
        let refs: Vec<&str> = a.iter().map(String::as_str).collect();
        slipload(&refs)
    };
    let mut max = vec![0.0f64; want.len()];
    for suite in manifest["suites"].as_array().unwrap() {
        let name = suite["name"].as_str().unwrap();
        let (a, b) = (
            suite["range"]["start"].as_u64().unwrap() as usize,
            suite["range"]["end"].as_u64().unwrap() as usize,
        );
        for r in &records[a..b] {
            let o = run(
                "simulate",
                &["--run", r, "--suite", name, "--format", "json"],
            );
            assert!(o.status.success(), "{}", stderr(&o));
            let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
            assert_eq!(v["method"], "newmark", "the check's method");
            for (m, d) in max
                .iter_mut()
                .zip(v["peak_drift_ratio"].as_array().unwrap())
            {
                *m = m.max(d.as_f64().unwrap());
            }
        }
    }
    // the same runs (the check's method and step, the suite's scaled record): the same
    // bits
    assert_eq!(max, want, "re-simulated vs the design table");

    // the same run goes to OpenSees (as `bilinear`: its dampers have mass)
    let script = dir.join("optimum.py");
    let r0 = records[0].as_str();
    let o = run(
        "opensees",
        &[
            "--run",
            r0,
            "--suite",
            "syn",
            "--method",
            "bilinear",
            "--out",
            s(&script),
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(script.exists());

    // what cannot be found is named beside what there is
    let refused_run = |extra: &[&str], words: &[&str]| {
        let o = run("simulate", extra);
        assert_eq!(o.status.code(), Some(1), "{extra:?} should fail");
        let e = stderr(&o);
        for w in words {
            assert!(e.contains(w), "{w:?} not in: {e}");
        }
    };
    refused_run(
        &["--design", "best", "--run", r0, "--suite", "syn"],
        &["--design \"best\"", "optimum", "uniform", "bare"],
    );
    refused_run(&["--run", "nope"], &["--run \"nope\"", r0, "4 in all"]);
    // a record of two suites needs its suite
    refused_run(
        &["--run", r0],
        &["names 2 runs", "give --suite (syn, strong)"],
    );
    refused_run(
        &["--run", r0, "--suite", "weak"],
        &["--suite \"weak\"", "syn, strong"],
    );
    // a folder another study (here: the same one at another intensity) wrote
    let other = study(&dir, "design-run", 0.3);
    let other_path = dir.join("other.json");
    std::fs::rename(&other, &other_path).unwrap();
    refused(
        &[
            "simulate",
            "--study",
            s(&other_path),
            "--designs",
            s(&out),
            "--run",
            r0,
            "--suite",
            "syn",
        ],
        &[
            "holds the results of another version of the study",
            "changed:",
        ],
    );
    // --study needs --designs and --run, and takes no scene
    let o = slipload(&["simulate", "--study", s(&st), "--run", r0]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn scale_multiplies_the_record() {
    let rec = root().join("records/elCentro.AT2");
    let one = ok(&["--quiet", "simulate", "--record", s(&rec)]);
    let two = ok(&["--quiet", "simulate", "--record", s(&rec), "--scale", "2"]);
    let pga = |t: &str| -> f64 {
        let line = t.lines().find(|l| l.starts_with("ground motion")).unwrap();
        let at = line.find("PGA ").unwrap() + 4;
        line[at..].split(' ').next().unwrap().parse().unwrap()
    };
    // the table prints four decimals of g
    assert!((pga(&two) - 2.0 * pga(&one)).abs() <= 1e-4, "{one}\n{two}");
    assert!(two.contains("scaled by 2"), "{two}");
    // the plotted run's scene.json keeps the factor: run again, it gives the same peaks
    let dir = common::scratch("design-run", "scale-plot");
    let plot = dir.join("plot");
    let json = |args: &[&str]| -> serde_json::Value { serde_json::from_str(&ok(args)).unwrap() };
    let first = json(&[
        "--quiet",
        "simulate",
        "--record",
        s(&rec),
        "--scale",
        "2",
        "--format",
        "json",
        "--plot",
        s(&plot),
    ]);
    // (with --plot too: a run with histories steps on the general path, whose peaks
    // differ from the peaks-only path's in the last bits)
    let again = json(&[
        "--quiet",
        "simulate",
        s(&plot.join("scene.json")),
        "--format",
        "json",
        "--plot",
        s(&dir.join("again")),
    ]);
    assert_eq!(first["peak_drift"], again["peak_drift"]);
    std::fs::remove_dir_all(&dir).unwrap();
    refused(&["simulate", "--scale", "-1"], &["--scale -1", "> 0"]);
    refused(
        &["simulate", "--scale", "2", "--scale-pga-g", "0.3"],
        &["not both"],
    );
}
