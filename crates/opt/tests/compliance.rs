//! Contract (issue 45 §4): the code check's compliance matrix states each requirement with
//! its clause, value, limit and status from what the check computed — the record count and
//! the 90 % rule of a code-scaled suite from its scaling, each criterion at its worst
//! property case, the count of unacceptable responses — and names what the study gives no
//! data for (`not checked`) and what a planar model cannot show (`not covered`).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::model::check::{CaseName, CheckLine, DesignCheck};
use slipload_opt::phases::compliance::{Status, matrix, to_markdown};
use std::path::Path;

/// The ten-storey frame over the RSN records of records/ scaled to a design spectrum, with
/// a drift limit, a count of unacceptable responses and property bounds; `devices`: the
/// study's `devices` members.
fn study(devices: &str) -> Study {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/ten-story.json",
  "suites": [ {{ "name": "code", "records": ["records/RSN*.AT2"],
                 "scale": {{ "code_spectrum": {{ "sds_g": 1.0, "sd1_g": 0.6, "tl_s": 8 }} }},
                 "limits": {{ "criteria": [ {{ "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.02 }} ],
                              "unacceptable": {{ "max_count": 1 }} }} }} ],
  "property_bounds": {{ "slip_load": {{ "lower": 0.85, "upper": 1.15 }} }},
  "devices": {{ {devices} }},
  "space": {{ "profile": {{ "shape": "uniform", "scale_kn": [0, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    Study::from_json(&text, &root.join("study.json")).unwrap()
}

fn line(case: CaseName, criterion: &str, limit: f64, demand: f64, source: &str) -> CheckLine {
    CheckLine {
        suite: "code".into(),
        case,
        criterion: criterion.into(),
        limit,
        demand,
        ratio: demand / limit,
        pass: demand <= limit,
        source: source.into(),
    }
}

/// The check's lines: drift 0.012 / 0.015 / 0.011 at the nominal, lower and upper cases,
/// and 0 / 2 / 0 unacceptable responses against 1 allowed.
fn check() -> DesignCheck {
    let drift = "suites[0].limits.criteria[0]";
    let count = "suites[0].limits.unacceptable";
    let mut lines = Vec::new();
    for (case, d, n) in [
        (CaseName::Nominal, 0.012, 0.0),
        (CaseName::Lower, 0.015, 2.0),
        (CaseName::Upper, 0.011, 0.0),
    ] {
        lines.push(line(case, "mean peak_drift_ratio", 0.02, d, drift));
        lines.push(line(case, "unacceptable responses", 1.0, n, count));
    }
    DesignCheck { lines }
}

#[test]
fn the_matrix_states_each_requirement_from_the_check() {
    let st = study(r#""brace_angle_deg": 35"#);
    let rows = matrix(&st, &check(), &[]);
    let find = |clause: &str| {
        rows.iter()
            .find(|r| r.clause == clause)
            .unwrap_or_else(|| panic!("{clause} not in {rows:?}"))
    };
    // the record count and the 90 % rule of the scaled suite, from its scaling
    let n = st.suites[0].range.len();
    let count = find("§16.2.2");
    assert_eq!(count.value, format!("{n} records"));
    assert_eq!((count.limit.as_str(), count.status), ("≥ 11", Status::Pass));
    let sc = st.suites[0].code_scaling.as_ref().unwrap();
    let lowest = sc
        .mean_sa_g
        .iter()
        .zip(&sc.target_sa_g)
        .map(|(m, t)| m / t)
        .fold(f64::INFINITY, f64::min);
    assert!(lowest >= 0.9 - 1e-9, "{lowest}");
    let rule = find("§16.2.3");
    assert_eq!(
        rule.value,
        format!("{lowest:.3} of the target at its lowest")
    );
    assert_eq!(rule.status, Status::Pass);
    // the drift at its worst case (the lower bound's 0.015) passes; the count of
    // unacceptable responses at its worst (2 at the lower bound, 1 allowed) fails
    let drift = find("§16.4.1.2");
    assert!(drift.requirement.contains("lower"), "{drift:?}");
    // a drift in percent of the storey height, as every drift a person reads
    assert_eq!(
        (drift.value.as_str(), drift.limit.as_str(), drift.status),
        ("1.500 %", "≤ 2.000 %", Status::Pass)
    );
    let bad = find("§16.4.1.1");
    assert_eq!((bad.value.as_str(), bad.limit.as_str()), ("2", "≤ 1"));
    assert_eq!(bad.status, Status::Fail);
    // the bounds are stated; no protocol, strength, wind or nonstructural data: not
    // checked; torsion, two components and vertical motion: not covered
    assert_eq!(find("Ch. 18 (Eq. 17.2-1, 17.2-2)").status, Status::Stated);
    for clause in ["§18.6.2", "§18.2.1.1", "§16.1.2", "design practice"] {
        assert_eq!(find(clause).status, Status::NotChecked, "{clause}");
    }
    for clause in ["§12.3.2.1, §12.8.4.2", "§16.2.4", "§12.4.2.2"] {
        assert_eq!(find(clause).status, Status::NotCovered, "{clause}");
    }
    let md = to_markdown(&rows);
    assert!(md.starts_with("## Compliance matrix"), "{md}");
    assert!(md.contains("| §16.4.1.1 | code: unacceptable responses (at the worst property case, lower) | 2 | ≤ 1 | **FAIL** |"), "{md}");
    // equal counts everywhere: the nominal case is named (the first of equals)
    let mut tied = check();
    for l in &mut tied.lines {
        if l.source.ends_with("unacceptable") {
            l.demand = 0.0;
            l.ratio = 0.0;
            l.pass = true;
        }
    }
    let rows = matrix(&st, &tied, &[]);
    let count = rows.iter().find(|r| r.clause == "§16.4.1.1").unwrap();
    assert!(
        count
            .requirement
            .ends_with("(at the worst property case, nominal)"),
        "{count:?}"
    );
    let bounds = rows
        .iter()
        .find(|r| r.clause.starts_with("Ch. 18"))
        .unwrap();
    assert_eq!(
        bounds.value,
        "slip load × 0.85 and × 1.15, given as numbers"
    );
    // with a test protocol the prototype tests are stated
    let st = study(r#""test_protocol": { "cycles": 5, "band_percent": 15 }"#);
    let rows = matrix(&st, &check(), &[]);
    let p = rows.iter().find(|r| r.clause == "§18.6.2").unwrap();
    assert_eq!(p.status, Status::Stated);
    assert_eq!(p.value, "5 cycles, ±15 % band (device-table.md)");
}

/// The verdict (the summary's last line, `optimum.json` and `code-check.md`) states a
/// drift's demand and limit in percent of the storey height, as every drift a person
/// reads; a base shear stays in N and a count whole.
#[test]
fn the_verdict_states_a_drift_in_percent() {
    let drift = |demand| {
        line(
            CaseName::Lower,
            "mean residual_drift_ratio",
            0.005,
            demand,
            "suites[1].limits.criteria[1]",
        )
    };
    let passing = DesignCheck {
        lines: vec![drift(0.004975)],
    };
    let v = passing.verdict();
    assert!(v.starts_with("PASS"), "{v}");
    assert!(
        v.contains("demand 0.4975 % against limit 0.5000 %, ratio 0.995"),
        "{v}"
    );
    // 100 × the ratio, not the ratio: no drift is stated as a bare ratio
    assert!(!v.contains("0.004975"), "{v}");
    let shear = line(
        CaseName::Nominal,
        "max base_shear",
        4.0e6,
        4.4e6,
        "suites[0].limits.criteria[0]",
    );
    let failing = DesignCheck {
        lines: vec![drift(0.004), shear.clone()],
    };
    let v = failing.verdict();
    assert!(v.starts_with("FAIL"), "{v}");
    assert!(v.contains("demand 4.400e6 against limit 4.000e6"), "{v}");
    let count = line(
        CaseName::Upper,
        "unacceptable responses",
        1.0,
        2.0,
        "suites[0].limits.unacceptable",
    );
    assert_eq!(
        (
            count.value_text(count.demand),
            count.value_text(count.limit)
        ),
        ("2".to_string(), "1".to_string())
    );
    assert!(!shear.is_drift() && !count.is_drift() && drift(0.0).is_drift());
}
