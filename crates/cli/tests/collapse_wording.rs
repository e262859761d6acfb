//! Contract: where a frame collapses, the commands say so in words. On a yielding frame
//! whose bare frame (and the building file's light design) collapse while heavier
//! dampers hold: `sweep`'s designs.csv, `optimize`'s summary, optimum.json and design
//! table, and `rank` say "collapsed" / "bare frame collapsed" — never inf, NaN, null or
//! "100 % lower" — and a `table` cell that cannot be built names its scales.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use std::path::{Path, PathBuf};

mod common;
use common::slipload_within;

const T: u64 = 300;

/// The frame: storeys yield at 0.5 % drift, collapse at 0.8 %; three 4-s records at
/// 0.5 g; a uniform profile 0–2000 kN on a 5-level grid (0 and 500 kN collapse, 1000 kN
/// and up hold).
fn study(dir: &Path) -> PathBuf {
    let text = r#"{ "name": "collapsing", "building": {
  "floor_masses": ["300 t", "300 t", "250 t"],
  "storey_stiffness": ["300 MN/m", "250 MN/m", "180 MN/m"],
  "storey_heights": [3.5, 3.5, 3.5],
  "damping": { "modal": { "ratio": 0.02 } },
  "dissipators": [
    { "floor": 1, "brace_stiffness": "300 MN/m", "mass": 0, "slip_load": "600 kN" },
    { "floor": 2, "brace_stiffness": "250 MN/m", "mass": 0, "slip_load": "500 kN" } ],
  "storey_yield": [
    { "storey": 1, "yield_drift": "17.5 mm", "post_yield_ratio": 0.02 },
    { "storey": 2, "yield_drift": "17.5 mm", "post_yield_ratio": 0.02 },
    { "storey": 3, "yield_drift": "17.5 mm", "post_yield_ratio": 0.02 } ] },
  "collapse_drift_ratio": 0.008,
  "suites": [ { "name": "design", "synthetic": { "count": 3, "seed": 5, "pga_g": 0.5, "duration_s": 4 } } ],
  "space": { "profile": { "shape": "uniform", "scale_kn": [0, 2000] } },
  "objective": { "terms": [ { "metric": "peak_drift_ratio", "statistic": "mean" } ] },
  "fidelity": { "method": "newmark", "check_method": "newmark" },
  "sweep": { "sampler": "grid", "levels": 5 },
  "refine": { "method": "nelder-mead", "starts": 1, "max_evaluations": 6, "finalists": 2 } }"#;
    let p = dir.join("study.json");
    std::fs::write(&p, text).unwrap();
    p
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn no_number_for_collapse(what: &str, text: &str) {
    for bad in ["inf", "NaN", "null", "100.0 %"] {
        assert!(!text.contains(bad), "{what} shows {bad:?}:\n{text}");
    }
}

#[test]
fn collapses_are_said_in_words_by_every_command() {
    let dir = common::scratch("collapse", "words");
    let st = study(&dir);
    let out = dir.join("o");
    let o = slipload_within(T, &["optimize", s(&st), "--out", s(&out)]);
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    no_number_for_collapse("the summary", &stdout);
    let line = stdout
        .lines()
        .find(|l| l.starts_with("objective "))
        .unwrap();
    assert!(
        line.contains(
            "— bare frame collapsed, building file's slip loads 600.0 / 500.0 kN: collapsed"
        ),
        "{line}"
    );
    let designs = std::fs::read_to_string(out.join("designs.csv")).unwrap();
    no_number_for_collapse("designs.csv", &designs);
    assert!(
        designs
            .lines()
            .nth(1)
            .unwrap()
            .starts_with("0,bare,0,0,collapsed,collapsed,collapsed,")
    );
    assert!(designs.contains(",bare frame collapsed,1\n"), "{designs}");
    let optimum = std::fs::read_to_string(out.join("optimum.json")).unwrap();
    no_number_for_collapse("optimum.json", &optimum);
    assert!(
        optimum.contains(r#""bare_objective": "collapsed""#),
        "{optimum}"
    );
    assert!(
        optimum.contains(r#""file_objective": "collapsed""#),
        "{optimum}"
    );
    for f in ["design-table.md", "design-table.csv", "refine.csv"] {
        let text = std::fs::read_to_string(out.join(f)).unwrap();
        no_number_for_collapse(f, &text);
    }
    let md = std::fs::read_to_string(out.join("design-table.md")).unwrap();
    assert!(md.contains("| bare | collapsed | collapsed |"), "{md}");
    assert!(md.contains("| bare frame collapsed |"), "{md}");
    // rank over optimize's candidates
    let ranked = dir.join("r");
    let o = slipload_within(
        T,
        &[
            "rank",
            s(&st),
            "--designs",
            s(&out.join("candidates.json")),
            "--out",
            s(&ranked),
            "--bootstrap",
            "5",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in ["rank.md", "rank.csv", "rank.json"] {
        let text = std::fs::read_to_string(ranked.join(f)).unwrap();
        no_number_for_collapse(f, &text);
        assert!(text.contains("collapsed"), "{f}:\n{text}");
    }
    // a family cell where every design collapses names its scales
    let family = dir.join("t");
    let o = slipload_within(
        T,
        &[
            "table",
            s(&st),
            "--period-scales",
            "1",
            "--intensity-scales",
            "4",
            "--out",
            s(&family),
        ],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("period scale 1, intensity scale 4") && err.contains("collapses"),
        "{err}"
    );
    assert!(!family.join("family.csv").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Where every design the sweep ran collapses (a slip-load range of 0–200 kN on the frame
/// above), `optimize` stops with the collapse message and writes no recommendation —
/// without limits and with them (where no design meeting the limits would otherwise
/// make it recommend the "closest", a collapsing design with an objective of inf).
#[test]
fn a_study_whose_every_design_collapses_stops_with_the_collapse_message() {
    let dir = common::scratch("collapse", "every");
    let text = std::fs::read_to_string(study(&dir)).unwrap();
    let text = text.replace("\"scale_kn\": [0, 2000]", "\"scale_kn\": [0, 200]");
    let with_limits = text.replace(
        "\"pga_g\": 0.5, \"duration_s\": 4 }",
        "\"pga_g\": 0.5, \"duration_s\": 4 }, \"limits\": { \"criteria\": [ { \"metric\": \"peak_drift_ratio\", \"statistic\": \"mean\", \"max\": 0.006 } ] }",
    );
    assert_ne!(text, with_limits);
    for (name, text) in [("plain", text), ("limits", with_limits)] {
        let st = dir.join(format!("{name}.json"));
        std::fs::write(&st, text).unwrap();
        let out = dir.join(name);
        let o = slipload_within(T, &["optimize", s(&st), "--out", s(&out)]);
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{name}: {e}");
        assert!(
            e.contains("every sampled design collapses on some record of the study"),
            "{name}: {e}"
        );
        assert!(
            !out.join("optimum.json").exists(),
            "{name}: an optimum was written"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
