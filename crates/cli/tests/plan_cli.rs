//! `slipload simulate` on a scene in plan: the shipped example runs and its flexible edge
//! drifts more than its stiff one; the flags a plan does not take are refused by name; a
//! building in plan alone says what a run needs; a bad line names its field; `--history`
//! writes the histories.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{refused, scratch, slipload};

#[test]
fn the_example_in_plan_runs_and_its_flexible_edge_drifts_most() {
    let o = slipload(&[
        "simulate",
        "configs/plan-ten-story-pair.json",
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", common::stderr(&o));
    let r: slipload_sim::Response = serde_json::from_slice(&o.stdout).unwrap();
    let ip = r.in_plan.as_ref().unwrap();
    // four lines and four plan edges over ten storeys; three points and four dampers a floor
    assert_eq!(r.peak_drift.len(), 80);
    assert_eq!(ip.points.len(), 30);
    assert_eq!(ip.dampers.len(), 40);
    let drift = |name: &str| r.peak_drift[ip.drifts.iter().position(|d| d == name).unwrap()];
    for s in 1..=10 {
        // the centre of rigidity sits toward line A: line D, at the flexible edge, drifts more
        assert!(
            drift(&format!("D/{s}")) > 1.5 * drift(&format!("A/{s}")),
            "storey {s}"
        );
        // the edges are where the lines A and D stand
        assert_eq!(
            drift(&format!("D/{s}")),
            drift(&format!("edge x=Lx (y)/{s}"))
        );
        let t = ip.torsional_irregularity.as_ref().unwrap()[s - 1];
        assert!(
            t[1] > 1.2,
            "storey {s}: the plan is torsionally irregular along y: {t:?}"
        );
    }
    // the table names the lines, the edges and the ratios
    let o = slipload(&["simulate", "configs/plan-ten-story-pair.json"]);
    let table = String::from_utf8(o.stdout).unwrap();
    for needle in [
        "building in plan: 10 floors, 4 lines",
        "D/10",
        "edge x=Lx (y)/1",
        "torsional irregularity",
        "10 rot",
    ] {
        assert!(table.contains(needle), "{needle}: {table}");
    }
}

#[test]
fn what_a_plan_does_not_take_is_refused_by_name() {
    refused(
        &[
            "simulate",
            "configs/plan-ten-story-pair.json",
            "--record",
            "records/I-ELC180.AT2",
        ],
        &["--record", "scene in plan", "`ground`"],
    );
    refused(
        &[
            "simulate",
            "configs/plan-ten-story-pair.json",
            "--method",
            "delacruz",
        ],
        &["delacruz steps a chain of floors"],
    );
    let out = scratch("plan-cli", "script").join("plan.py");
    refused(
        &[
            "opensees",
            "configs/plan-ten-story-pair.json",
            "--out",
            out.to_str().unwrap(),
        ],
        &["modal damping has no OpenSees element", "`rayleigh`"],
    );
    assert!(!out.exists(), "no script is written");
    refused(
        &[
            "opensees",
            "configs/plan-ten-story-pair.json",
            "--out",
            "configs/plan-ten-story.json",
        ],
        &["which this command reads"],
    );
    refused(
        &["simulate", "configs/plan-ten-story.json"],
        &["is a building in plan", "\"ground\""],
    );
    let dir = scratch("plan-cli", "bad");
    let text = std::fs::read_to_string("configs/plan-ten-story.json")
        .or_else(|_| std::fs::read_to_string(common::root().join("configs/plan-ten-story.json")))
        .unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["lines"][1]["storey_stiffness"]
        .as_array_mut()
        .unwrap()
        .pop();
    let building = dir.join("bad-plan.json");
    std::fs::write(&building, v.to_string()).unwrap();
    let scene = dir.join("bad-scene.json");
    std::fs::write(
        &scene,
        r#"{"building": "bad-plan.json", "duration": 1, "ground": []}"#,
    )
    .unwrap();
    refused(
        &["simulate", scene.to_str().unwrap()],
        &["bad-plan.json", "lines[1].storey_stiffness", "expected 10"],
    );
}

#[test]
fn history_writes_the_plans_columns() {
    let dir = scratch("plan-cli", "history");
    let h = dir.join("h.csv");
    let o = slipload(&[
        "simulate",
        "configs/plan-ten-story-pair.json",
        "--duration",
        "2",
        "--method",
        "exact",
        "--history",
        h.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", common::stderr(&o));
    let csv = std::fs::read_to_string(&h).unwrap();
    let header = csv.lines().next().unwrap();
    // named by what they measure: 30 points, 80 drifts, 40 dampers' xd, F and w
    assert!(
        header.starts_with("t_s,ag_m_s2,x_1_x_m,x_1_y_m,x_1_rot_rad"),
        "{header}"
    );
    for name in [
        "drift_D/10_m",
        "drift_edge_x=Lx_(y)/10_m",
        "F_A/1_N",
        "w_2/10_m_s",
        "xd_D/3_m",
    ] {
        assert!(header.split(',').any(|c| c == name), "{name}: {header}");
    }
    let columns: Vec<&str> = header.split(',').collect();
    let unique: std::collections::BTreeSet<&&str> = columns.iter().collect();
    assert_eq!(unique.len(), columns.len(), "every column has its own name");
    assert!(csv.lines().count() > 100);
}

#[test]
fn explain_prints_the_plans_modes_and_what_it_compiles_into() {
    let o = slipload(&["explain", "configs/plan-ten-story-pair.json"]);
    assert!(o.status.success(), "{}", common::stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(
        text.contains("bare frame in plan: 10 floors x 3 DOFs, 4 lines"),
        "{text}"
    );
    // 30 modes, each with its shares; along x they sum to the whole mass
    let shares: Vec<[f64; 3]> = text
        .lines()
        .filter(|l| l.trim_start().starts_with("mode"))
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            let at = |k: &str| {
                w[w.iter().position(|x| *x == k).unwrap() + 1]
                    .parse::<f64>()
                    .unwrap()
            };
            [at("x"), at("y"), at("rotation")]
        })
        .collect();
    assert_eq!(shares.len(), 30);
    for k in 0..3 {
        let sum: f64 = shares.iter().map(|s| s[k]).sum();
        // the printed shares are rounded to 1e-3 each
        assert!((sum - 1.0).abs() < 30.0 * 5e-4, "share {k} sums to {sum}");
    }
    assert!(text.contains("plan for"), "{text}");
    assert!(text.contains("second ground component"), "{text}");
}
