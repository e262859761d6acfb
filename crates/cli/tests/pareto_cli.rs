//! Contract: `slipload optimize` on a study with `objectives` names the trade-off in
//! words and numbers (the front, the first objective's optimum and its cost against the
//! building file's design, the knee and its place, each other optimum, the bounds,
//! whether the front held), writes the front's files and figure, and `slipload report`
//! shows the trade-off; a one-objective study prints the free trade-off of its sweep.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, slipload_in};

/// `configs/NAME` made a study of seconds in `dir` (created): its building by absolute
/// path, two 4-s records, six sweep points; the caller shrinks the rest.
fn shrunk(name: &str, dir: &std::path::Path) -> serde_json::Value {
    std::fs::create_dir_all(dir).unwrap();
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root().join("configs").join(name)).unwrap())
            .unwrap();
    v["building"] = root()
        .join("configs/benchmark-3story.json")
        .to_string_lossy()
        .into_owned()
        .into();
    v["suites"][0]["synthetic"]["count"] = 2.into();
    v["suites"][0]["synthetic"]["duration_s"] = 4.0.into();
    v["sweep"]["points"] = 6.into();
    v
}

#[test]
fn optimize_names_the_trade_off_and_writes_the_front() {
    let dir = common::scratch("pareto", "front");
    let mut v = shrunk("study-pareto.json", &dir);
    v["refine"]["starts"] = 1.into();
    v["refine"]["max_evaluations"] = 4.into();
    v["refine"]["finalists"] = 1.into();
    v["pareto"]["designs"] = 6.into();
    v["pareto"]["batch"] = 3.into();
    let study = dir.join("study.json");
    std::fs::write(&study, v.to_string()).unwrap();
    let out = slipload_in(
        &dir,
        &[
            "optimize",
            study.to_str().unwrap(),
            "--out",
            "res",
            "--quiet",
        ],
    );
    assert!(out.status.success(), "{}", common::stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    for needle in [
        "front of mean peak_drift_ratio vs mean peak_floor_acceleration: ",
        "(28 simulations at the sweep fidelity: sweep 16, search 12; 12 run now); ",
        " more candidates from the building file and the refinement",
        "  mean peak_drift_ratio optimum ",
        "    what it costs against the building file's design (834.1 / 740.8 / 437.5 kN)",
        "base shear ",
        "floor acceleration ",
        "  knee ",
        " along the front by mean peak_drift_ratio",
        "  mean peak_floor_acceleration optimum ",
        "  on a bound of the design space — the peak_drift_ratio optimum: ",
        "  the study's optimum (",
        "  front at reference accuracy (exact at 1 x the sweep time step): ",
        "pareto.csv,pareto.json,pareto-table.csv,pareto-table.md,pareto-table.json}",
        "pareto-front}",
    ] {
        assert!(text.contains(needle), "{needle:?} in:\n{text}");
    }
    // the one-objective trade-off line is for one-objective studies only
    assert!(!text.contains("trade-off in the sweep's"), "{text}");
    let res = dir.join("res");
    // the drift optimum's drift in percent of the storey height: 100 × the ratio
    // pareto.json holds for it (the sweep fidelity), to the printed thousandth
    let p: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(res.join("pareto.json")).unwrap()).unwrap();
    let best = p["extremes"][0][1].as_str().unwrap();
    let ratio = p["front"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["label"] == best)
        .unwrap()["sweep"][0]
        .as_f64()
        .unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with(&format!("  mean peak_drift_ratio optimum {best} (")))
        .unwrap_or_else(|| panic!("the optimum's line in:\n{text}"));
    let shown: f64 = line
        .split("): mean peak_drift_ratio ")
        .nth(1)
        .and_then(|r| r.split(" %,").next())
        .unwrap_or_else(|| panic!("a drift in percent in {line}"))
        .parse()
        .unwrap();
    assert!(
        (shown - 100.0 * ratio).abs() <= 5e-4 + 1e-12,
        "{line}: {ratio}"
    );
    let costs = text
        .lines()
        .find(|l| l.starts_with("    what it costs"))
        .unwrap_or_else(|| panic!("the costs line in:\n{text}"));
    // `mean peak drift ratio D % (-x % against the file's F %), base shear …`
    let file_drift: Vec<&str> = costs
        .split("against the file's ")
        .nth(1)
        .unwrap()
        .split(' ')
        .take(2)
        .collect();
    assert!(
        file_drift[0].parse::<f64>().is_ok() && file_drift[1] == "%),",
        "{costs}"
    );
    for f in [
        "pareto.csv",
        "pareto.json",
        "pareto-table.md",
        "pareto-front.svg",
        "pareto-front.png",
        "pareto-front.csv",
        "pareto.jsonl",
    ] {
        assert!(res.join(f).is_file(), "{f} written");
    }
    let csv = std::fs::read_to_string(res.join("pareto-front.csv")).unwrap();
    assert!(csv.lines().any(|l| l.ends_with(",knee")), "{csv}");
    assert!(csv.lines().any(|l| l.starts_with("bare,")), "{csv}");

    // the report's trade-off section
    let out = slipload_in(&dir, &["report", "res", "--quiet"]);
    assert!(out.status.success(), "{}", common::stderr(&out));
    let html = std::fs::read_to_string(res.join("report.html")).unwrap();
    assert!(html.contains("id=\"trade-off\""), "trade-off section");
    assert!(html.contains("optimum of mean peak_floor_acceleration"));
    // the drift optimum's drift in percent there too
    let shown = format!("{best} — slip loads ");
    let at = html
        .find(&shown)
        .unwrap_or_else(|| panic!("{shown} in the page"));
    let entry = &html[at..at + html[at..].find("</td>").unwrap()];
    assert!(
        entry.contains(&format!("objectives (sweep) {:.3} % / ", 100.0 * ratio)),
        "{entry}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_one_objective_study_prints_its_sweeps_trade_off() {
    let dir = common::scratch("pareto", "one");
    let mut v = shrunk("study-benchmark.json", &dir);
    v["refine"]["max_evaluations"] = 4.into();
    let study = dir.join("study.json");
    std::fs::write(&study, v.to_string()).unwrap();
    let out = slipload_in(
        &dir,
        &[
            "optimize",
            study.to_str().unwrap(),
            "--out",
            "res",
            "--quiet",
        ],
    );
    assert!(out.status.success(), "{}", common::stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text
        .lines()
        .find(|l| l.starts_with("trade-off in the sweep's 6 designs (no extra simulation"))
        .unwrap_or_else(|| panic!("the trade-off line in:\n{text}"));
    assert!(line.contains("; knee s0"), "{line}");
    // each design's drift in percent of the storey height: 100 × its mean peak drift
    // ratio in designs.csv (the study's objective), to the printed thousandth
    let csv = std::fs::read_to_string(dir.join("res/designs.csv")).unwrap();
    let head: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
    let (label, drift) = (col("label"), col("mean_peak_drift_ratio"));
    let mut said = 0;
    let parts: Vec<&str> = line.split(" (").collect();
    for w in parts.windows(2) {
        // `NAME (LOADS kN: drift D %, floor acceleration …)`
        let Some(d) = w[1].split(": drift ").nth(1) else {
            continue;
        };
        let name = w[0].rsplit(' ').next().unwrap();
        let shown: f64 = d.split(" %").next().unwrap().parse().unwrap();
        let ratio: f64 = csv
            .lines()
            .map(|l| l.split(',').collect::<Vec<_>>())
            .find(|r| r[label] == name)
            .unwrap_or_else(|| panic!("{name} in designs.csv"))[drift]
            .parse()
            .unwrap();
        assert!(
            (shown - 100.0 * ratio).abs() <= 5e-4 + 1e-12,
            "{name}: {shown} % against the ratio {ratio}"
        );
        said += 1;
    }
    assert_eq!(said, 3, "the front's two ends and its knee: {line}");
    assert!(!text.contains("front of "), "{text}");
    assert!(!dir.join("res/pareto.csv").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
