//! Contract: a study of several suites draws its drift profiles and its per-record
//! scatter once per suite (`drift-profiles-SUITE`, `records-scatter-SUITE`; no figure
//! over both suites), each profile with the drift limits its suite states as vertical
//! lines at their values in percent, named in the legend; every row of a scatter's CSV
//! names its suite; the report inlines each suite's figures. With property bounds every
//! objective value of the summary names the case it is read at.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch, slipload_in};
use slipload_figures::plot::meta;
use std::path::{Path, PathBuf};

/// The benchmark building at two levels of 2 synthetic records of 3 s each, the
/// `design` suite limited to a mean peak drift ratio of 2 % (and 3 % on any record), the
/// `mce_r` suite to 4 %; slip loads × 0.85 and × 1.15, the objective read at the worst;
/// a short sweep and refinement.
fn two_suites(dir: &Path) -> PathBuf {
    let building = root().join("configs/benchmark-3story.json");
    let text = format!(
        r#"{{
  "name": "two-levels",
  "building": {building:?},
  "suites": [
    {{ "name": "design", "synthetic": {{ "count": 2, "seed": 3, "pga_g": 0.3, "duration_s": 3 }},
       "limits": {{ "criteria": [ {{ "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.02 }} ],
                    "unacceptable": {{ "max_count": 1, "record_limits": [ {{ "metric": "peak_drift_ratio", "max": 0.03 }} ] }} }} }},
    {{ "name": "mce_r", "synthetic": {{ "count": 3, "seed": 4, "pga_g": 0.45, "duration_s": 3 }},
       "limits": {{ "criteria": [ {{ "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.04 }} ] }} }}
  ],
  "property_bounds": {{ "slip_load": {{ "lower": 0.85, "upper": 1.15 }}, "objective_reads": "worst" }},
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 1500, 1000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "sweep": {{ "sampler": "halton", "points": 4, "seed": 5 }},
  "refine": {{ "method": "trust-region", "starts": 1, "max_evaluations": 4, "finalists": 1 }}
}}"#
    );
    let p = dir.join("study.json");
    std::fs::write(&p, text).unwrap();
    p
}

fn run(dir: &Path, args: &[&str]) -> String {
    let out = slipload_in(dir, args);
    assert!(
        out.status.success(),
        "slipload {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn panel(dir: &Path, stem: &str) -> (String, meta::PanelMeta, String) {
    let svg = std::fs::read_to_string(dir.join(format!("{stem}.svg")))
        .unwrap_or_else(|e| panic!("{stem}.svg: {e}"));
    assert!(dir.join(format!("{stem}.png")).is_file(), "{stem}.png");
    let m = meta::FigureMeta::from_svg(&svg).unwrap();
    (m.title, m.panels.into_iter().next().unwrap(), svg)
}

/// The suite column of every row of a scatter's CSV (the header names it last).
fn suites_of_rows(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(head.last(), Some(&"suite"), "{}", path.display());
    lines
        .map(|l| l.rsplit(',').next().unwrap().to_string())
        .collect()
}

/// Checks the per-suite figures of `out`; each record is `cases` runs in the scatter (a
/// sweep's figures show the bound runs too, named `RECORD [lower]`, `RECORD [upper]`).
fn check_folder(out: &Path, what: &str, cases: usize) {
    for plain in ["drift-profiles", "records-scatter"] {
        for ext in ["svg", "png", "csv"] {
            assert!(
                !out.join(format!("{plain}.{ext}")).exists(),
                "{what}: no {plain}.{ext} over both suites"
            );
        }
    }
    for (suite, records, limits) in [
        (
            "design",
            2,
            vec![("limit, mean: 2 %", 2.0), ("limit, per record: 3 %", 3.0)],
        ),
        ("mce_r", 3, vec![("limit, mean: 4 %", 4.0)]),
    ] {
        let (title, p, svg) = panel(out, &format!("drift-profiles-{suite}"));
        assert!(
            title.ends_with(&format!("suite {suite}")),
            "{what}: {title}"
        );
        assert_eq!(p.x.label, "peak drift ratio (%)");
        for (name, x) in limits {
            let line = p
                .series
                .iter()
                .find(|s| s.name == name)
                .unwrap_or_else(|| panic!("{what} {suite}: no {name:?} in {:?}", p.series));
            assert_eq!(line.x, [Some(x), Some(x)], "{what} {suite}: {name}");
            assert_eq!(line.y, [Some(0.5), Some(3.5)], "{what} {suite}: {name}");
            assert!(p.x.min <= x && x <= p.x.max, "{what} {suite}: {name} shown");
            assert!(
                svg.contains(&format!(">\n{name}\n</text>")),
                "{what} {suite}: {name} in the legend"
            );
        }
        let rows = suites_of_rows(&out.join(format!("records-scatter-{suite}.csv")));
        assert_eq!(
            rows.len(),
            records * cases,
            "{what} {suite}: one row per run"
        );
        assert!(rows.iter().all(|s| s == suite), "{what} {suite}: {rows:?}");
        let (title, p, _) = panel(out, &format!("records-scatter-{suite}"));
        assert!(
            title.ends_with(&format!("suite {suite}")),
            "{what}: {title}"
        );
        assert_eq!(p.series[0].points, records * cases);
    }
}

#[test]
fn optimize_and_sweep_draw_each_suite_apart_with_its_limits() {
    let dir = scratch("figures-suites", "optimize");
    let study = two_suites(&dir);
    let stdout = run(
        &dir,
        &["--quiet", "optimize", study.to_str().unwrap(), "--out", "o"],
    );
    assert!(
        stdout.contains("drift-profiles-design,records-scatter-design,drift-profiles-mce_r,records-scatter-mce_r"),
        "{stdout}"
    );
    check_folder(&dir.join("o"), "optimize", 1);
    assert!(
        stdout.contains("\nobjective at the worst properties 0."),
        "{stdout}"
    );
    assert!(
        stdout.contains(" kN: objective at the worst properties 0."),
        "the finalists: {stdout}"
    );
    run(
        &dir,
        &["--quiet", "sweep", study.to_str().unwrap(), "--out", "s"],
    );
    check_folder(&dir.join("s"), "sweep", 3);

    // the report inlines every suite's figures; --fresh removes them as slipload's own
    run(&dir, &["report", "o"]);
    let html = std::fs::read_to_string(dir.join("o/report.html")).unwrap();
    for stem in ["drift-profiles-design", "records-scatter-mce_r"] {
        assert!(html.contains(&format!("id=\"fig-{stem}\"")), "{stem}");
    }
    run(
        &dir,
        &[
            "--quiet",
            "sweep",
            study.to_str().unwrap(),
            "--out",
            "s",
            "--fresh",
        ],
    );
    check_folder(&dir.join("s"), "sweep --fresh", 3);
    let _ = std::fs::remove_dir_all(&dir);
}
