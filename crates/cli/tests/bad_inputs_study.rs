//! Issue 16, the study commands (`sweep`, `optimize`, `merge`, `rank`): a study's results
//! are its own. A journal of another study (method, step, building, records changed) is
//! refused naming what changed, `--fresh` starts afresh with the bytes of a fresh run,
//! `optimize` journals its check and table phase, shards of different studies are not
//! merged; sweeps beyond any real study are refused before they start; non-finite
//! records and a bootstrap of 0 are errors.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch, slipload_within, stderr};
use std::path::{Path, PathBuf};
use std::process::Output;

/// Seconds any run of these small studies may take.
const T: u64 = 300;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A small study of a building over 2 synthetic records of 2 s, written to `dir/name`;
/// `extra` is spliced into the JSON object (fidelity, sweep, …).
fn study(dir: &Path, name: &str, building: &Path, pga: f64, extra: &str) -> PathBuf {
    let text = format!(
        r#"{{
  "building": {building:?},
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": 2, "seed": 11, "pga_g": {pga}, "duration_s": 2 }} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "refine": {{ "starts": 1, "max_evaluations": 3, "finalists": 2 }},
  "sweep": {{ "sampler": "halton", "points": 3, "seed": 5 }}{extra}
}}"#
    );
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn bench() -> PathBuf {
    root().join("configs/benchmark-3story.json")
}

fn ok(args: &[&str]) -> Output {
    let o = slipload_within(T, args);
    assert!(o.status.success(), "slipload {args:?}: {}", stderr(&o));
    o
}

fn fails(args: &[&str], needles: &[&str]) -> String {
    let o = slipload_within(T, args);
    let err = stderr(&o);
    assert!(!o.status.success(), "slipload {args:?} succeeded: {err}");
    for n in needles {
        assert!(err.contains(n), "slipload {args:?}: {n:?} not in: {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
    err
}

fn same(a: &Path, b: &Path, files: &[&str]) {
    for f in files {
        assert!(
            std::fs::read(a.join(f)).unwrap() == std::fs::read(b.join(f)).unwrap(),
            "{f} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}

const SWEEP_FILES: [&str; 3] = ["manifest.json", "responses.csv", "designs.csv"];

#[test]
fn resume_after_the_study_changed_is_refused_naming_what_changed() {
    let dir = scratch("bad-study", "resume");
    let a = study(&dir, "a.json", &bench(), 0.4, "");
    let out = dir.join("out");
    ok(&["sweep", s(&a), "--out", s(&out), "--quiet"]);
    // the same study resumes (every task from the journal)
    let o = ok(&["sweep", s(&a), "--out", s(&out), "--resume", "--quiet"]);
    assert!(
        stderr(&o).contains("(10 from the journal, 0 run"),
        "{}",
        stderr(&o)
    );
    // the building's stiffness
    let text = std::fs::read_to_string(bench()).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut v2 = v.clone();
    let mut stiffer = false;
    for key in ["storey_stiffness", "stiffness_matrix"] {
        if let Some(x) = v2.get_mut(key) {
            *x = scale_numbers(x, 1.1);
            stiffer = true;
        }
    }
    assert!(stiffer, "the benchmark building gives a stiffness");
    let b2 = dir.join("stiffer.json");
    std::fs::write(&b2, v2.to_string()).unwrap();
    for (name, changed, needle) in [
        (
            "hht.json",
            study(
                &dir,
                "hht.json",
                &bench(),
                0.4,
                r#", "fidelity": { "method": "hht" }"#,
            ),
            "method/step",
        ),
        (
            "dt.json",
            study(
                &dir,
                "dt.json",
                &bench(),
                0.4,
                r#", "fidelity": { "dt_s": 0.002 }"#,
            ),
            "method/step",
        ),
        (
            "pga.json",
            study(&dir, "pga.json", &bench(), 0.8, ""),
            "record 1 samples",
        ),
        ("k.json", study(&dir, "k.json", &b2, 0.4, ""), "building"),
    ] {
        let err = fails(
            &[
                "sweep",
                s(&changed),
                "--out",
                s(&out),
                "--resume",
                "--quiet",
            ],
            &["another study", needle, "--fresh"],
        );
        assert!(!err.contains("from the journal"), "{name}: {err}");
        // the folder still holds study a's results, untouched
        assert!(
            std::fs::read_to_string(out.join("manifest.json"))
                .unwrap()
                .contains("\"hash\"")
        );
    }
    // --fresh starts afresh: the bytes of a fresh run
    let pga = dir.join("pga.json");
    ok(&["sweep", s(&pga), "--out", s(&out), "--fresh", "--quiet"]);
    let clean = dir.join("clean");
    ok(&["sweep", s(&pga), "--out", s(&clean), "--quiet"]);
    same(&out, &clean, &SWEEP_FILES);
    // the same header line (the fingerprint) and entries (in the threads' order)
    let sorted = |p: &Path| {
        let t = std::fs::read_to_string(p.join("journal.jsonl")).unwrap();
        let mut l: Vec<String> = t.lines().map(String::from).collect();
        l[1..].sort();
        l
    };
    assert_eq!(sorted(&out), sorted(&clean));
    std::fs::remove_dir_all(&dir).unwrap();
}

fn scale_numbers(v: &serde_json::Value, f: f64) -> serde_json::Value {
    match v {
        serde_json::Value::Number(n) => serde_json::json!(n.as_f64().unwrap() * f),
        // "68913.163 kN/m": the number scaled, the unit kept
        serde_json::Value::String(t) => match t.split_once(' ') {
            Some((num, unit)) if num.parse::<f64>().is_ok() => {
                serde_json::json!(format!("{} {unit}", num.parse::<f64>().unwrap() * f))
            }
            _ => v.clone(),
        },
        serde_json::Value::Array(a) => a.iter().map(|x| scale_numbers(x, f)).collect(),
        serde_json::Value::Object(o) => serde_json::Value::Object(
            o.iter()
                .map(|(k, x)| (k.clone(), scale_numbers(x, f)))
                .collect(),
        ),
        other => other.clone(),
    }
}

const OPT_FILES: [&str; 5] = [
    "optimum.json",
    "refine.csv",
    "design-table.csv",
    "designs.csv",
    "responses.csv",
];

#[test]
fn optimize_into_another_studys_folder_is_refused_and_its_check_is_journalled() {
    let dir = scratch("bad-study", "optimize");
    let a = study(&dir, "a.json", &bench(), 0.4, "");
    let b = study(&dir, "b.json", &bench(), 0.8, "");
    let out = dir.join("out");
    ok(&["optimize", s(&a), "--out", s(&out), "--quiet"]);
    let check = out.join("check.jsonl");
    let lines = std::fs::read_to_string(&check).unwrap();
    let n = lines.lines().count();
    assert!(n > 2, "the check and table runs are journalled: {n} lines");
    // without --resume or --fresh, another study's folder is refused (no old optimum)
    let err = fails(
        &["optimize", s(&b), "--out", s(&out), "--quiet"],
        &["another study", "record 1 samples", "--fresh"],
    );
    assert!(!err.contains("ranking held"), "{err}");
    // a kill late in the check: half the check journal survives; the rerun takes it
    // from there and writes the same bytes
    let first: Vec<Vec<u8>> = OPT_FILES
        .iter()
        .map(|f| std::fs::read(out.join(f)).unwrap())
        .collect();
    let keep: String = lines
        .lines()
        .take(n / 2)
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(&check, keep + "{\"fidelity\":\"exa").unwrap();
    let o = ok(&["optimize", s(&a), "--out", s(&out), "--quiet"]);
    let msg = String::from_utf8_lossy(&o.stdout);
    assert!(msg.contains("reused from check.jsonl)"), "{msg}");
    for (f, bytes) in OPT_FILES.iter().zip(&first) {
        assert!(
            std::fs::read(out.join(f)).unwrap() == *bytes,
            "{f} changed on resume"
        );
    }
    // --fresh discards a's journals; b's results equal a fresh run of b
    ok(&["optimize", s(&b), "--out", s(&out), "--fresh", "--quiet"]);
    let clean = dir.join("clean");
    ok(&["optimize", s(&b), "--out", s(&clean), "--quiet"]);
    same(&out, &clean, &OPT_FILES);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn merge_refuses_shards_of_different_studies() {
    let dir = scratch("bad-study", "merge");
    let a = study(&dir, "a.json", &bench(), 0.4, "");
    let b = study(
        &dir,
        "b.json",
        &bench(),
        0.4,
        r#", "fidelity": { "method": "hht" }"#,
    );
    let (s0, s1) = (dir.join("s0"), dir.join("s1"));
    ok(&["sweep", s(&a), "--out", s(&s0), "--shard", "0/2", "--quiet"]);
    ok(&["sweep", s(&b), "--out", s(&s1), "--shard", "1/2", "--quiet"]);
    let m = dir.join("m");
    fails(
        &["merge", s(&s0), s(&s1), "--out", s(&m)],
        &["different studies", "method/step"],
    );
    assert!(!m.join("responses.csv").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn sweeps_beyond_any_real_study_are_refused_up_front() {
    let dir = scratch("bad-study", "limits");
    let tiny = study(
        &dir,
        "tiny.json",
        &bench(),
        0.4,
        r#", "fidelity": { "dt_s": 1e-12 }"#,
    );
    fails(
        &["sweep", s(&tiny), "--out", s(&dir.join("o1"))],
        &["fidelity.dt_s", "steps", "--allow-large"],
    );
    let grid = dir.join("grid.json");
    let text = std::fs::read_to_string(study(&dir, "g0.json", &bench(), 0.4, ""))
        .unwrap()
        .replace(
            r#""sampler": "halton", "points": 3"#,
            r#""sampler": "grid", "levels": 100000"#,
        );
    std::fs::write(&grid, text).unwrap();
    fails(
        &["sweep", s(&grid), "--out", s(&dir.join("o2"))],
        &["sweep.levels", "designs", "--allow-large"],
    );
    // a step coarser than the records' sampling (0.02 s) skips samples
    let syl = root().join("records/SYL090.AT2");
    let coarse = dir.join("coarse.json");
    std::fs::write(
        &coarse,
        format!(
            r#"{{ "building": {:?}, "suites": [ {{ "name": "s", "records": [{syl:?}] }} ],
                 "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
                 "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
                 "fidelity": {{ "dt_s": 0.05 }} }}"#,
            bench()
        ),
    )
    .unwrap();
    fails(
        &["sweep", s(&coarse), "--out", s(&dir.join("o3"))],
        &["fidelity.dt_s", "0.02", "SYL090.AT2"],
    );
    assert!(!dir.join("o1").exists() && !dir.join("o2").exists() && !dir.join("o3").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_study_record_beyond_any_physical_record_is_refused() {
    let dir = scratch("bad-study", "huge");
    let rec = dir.join("huge.AT2");
    std::fs::write(&rec, "TITLE\nNPTS= 4, DT= .0100 SEC\n0.0 0.1\n1e300 0.0\n").unwrap();
    let st = dir.join("st.json");
    std::fs::write(
        &st,
        format!(
            r#"{{ "building": {:?}, "suites": [ {{ "name": "s", "records": ["huge.AT2"] }} ],
                 "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
                 "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }} }}"#,
            bench()
        ),
    )
    .unwrap();
    fails(
        &["sweep", s(&st), "--out", s(&dir.join("o"))],
        &["huge.AT2:4", "beyond any physical record"],
    );
    assert!(!dir.join("o").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn rank_refuses_a_bootstrap_of_zero() {
    let dir = scratch("bad-study", "rank");
    let a = study(&dir, "a.json", &bench(), 0.4, "");
    let d = dir.join("d.json");
    std::fs::write(&d, r#"[{"name": "u", "slip_loads_kn": [500, 500, 500]}]"#).unwrap();
    fails(
        &[
            "rank",
            s(&a),
            "--designs",
            s(&d),
            "--bootstrap",
            "0",
            "--out",
            s(&dir.join("r")),
        ],
        &["--bootstrap"],
    );
    assert!(!dir.join("r").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
