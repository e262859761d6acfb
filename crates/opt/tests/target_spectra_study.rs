//! Contract: `scale.code_spectrum` takes, besides S_DS, S_D1 and T_L (ASCE 7-16 §11.4.6),
//! a `table` of periods and accelerations and an `en1998` spectrum (EN 1998-1 §3.2.2.2),
//! and a `rule`: `asce7` (11 records or 7 pairs, the 90 % rule) or `en1998` (EN 1998-1
//! §3.2.3.1.2(4): 3 accelerograms, the mean PGA at least a_g·S, the 90 % rule; fewer than
//! 7 take the most unfavourable response). A table that is the ASCE spectrum gives its
//! factor; the compliance matrix names EN 1998-1's clauses for a suite scaled by its rule;
//! every refusal names its field.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_motion::DesignSpectrum;
use slipload_opt::Study;
use slipload_opt::model::check::{CaseName, CheckLine, DesignCheck};
use slipload_opt::model::config::ScalingRule;
use slipload_opt::phases::compliance::{Status, matrix, to_markdown};
use std::path::Path;

/// The ten-storey frame over `records`, scaled to `code_spectrum` (the object's members),
/// with the suite's `extra` members.
fn study_with(records: &str, code: &str, extra: &str) -> Result<Study, slipload_opt::OptError> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/ten-story.json",
  "suites": [ {{ "name": "code", "records": [{records}],
                 "scale": {{ "code_spectrum": {{ {code} }} }}{extra} }} ],
  "space": {{ "profile": {{ "shape": "uniform", "scale_kn": [0, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    Study::from_json(&text, &root.join("study.json"))
}

const ALL: &str = r#""records/RSN*.AT2""#;
const THREE: &str = r#""records/RSN1084_NORTHR_SCS142.AT2", "records/RSN1148_KOCAELI_ARE090.AT2", "records/RSN6_IMPVALL.I_I-ELC180.AT2""#;
const EN: &str = r#""en1998": { "agr_g": 0.25, "ground_type": "C", "spectrum_type": 1 }"#;

fn err(records: &str, code: &str, extra: &str) -> String {
    study_with(records, code, extra).unwrap_err().to_string()
}

fn json_list(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:?}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The ASCE spectrum S_DS = 1.0 g, S_D1 = 0.6 g, T_L = 8 s given as a table.
///
/// Nodes at every corner (T₀, T_S, T_L) and beyond: each segment lies in one branch, a
/// power law (the plateau, 1/T, 1/T²) that the table reproduces to round-off, so over the
/// range (above T₀) the target is the same function. The factors differ only in the
/// search: the table's nodes join the scaling grid, and each refined minimum is located to
/// 1e-8 in ln T, where the ratio's slope in ln T is at most a few tens (it is bounded by
/// the spectra's own slopes, 1/(2ζ) = 10 at 5 % damping, plus the target's 2): 1e-6 bounds
/// it with room.
///
/// Dense but blind: 400 log-spaced nodes over 0.01–10 s miss the corners. Between two
/// nodes h = ln(1000)/399 apart in ln T that straddle T_S, the chord of ln Sa cuts the
/// corner (slope 0 to −1) by at most h/4 in ln Sa, below it (ln Sa is concave there), and
/// is exact elsewhere above T₀; the factor is 0.9 × target/mean at its worst period, so the
/// table's factor is at most the ASCE one and at least exp(−h/4) of it.
#[test]
fn a_table_of_the_asce_spectrum_gives_its_factor() {
    let asce = study_with(ALL, r#""sds_g": 1.0, "sd1_g": 0.6, "tl_s": 8"#, "").unwrap();
    let f = asce.suites[0].code_scaling.as_ref().unwrap().factor;
    let d = DesignSpectrum::new(1.0, 0.6, 8.0).unwrap();
    let table = |periods: &[f64]| {
        let sa: Vec<f64> = periods.iter().map(|&t| d.sa_g(t)).collect();
        format!(
            r#""table": {{ "periods_s": [{}], "sa_g": [{}] }}"#,
            json_list(periods),
            json_list(&sa)
        )
    };
    let corners = [d.t0_s(), d.ts_s(), 1.0, 3.0, d.tl_s(), 10.0];
    let st = study_with(ALL, &table(&corners), "").unwrap();
    let c = st.suites[0].code_scaling.as_ref().unwrap();
    assert!((c.factor / f - 1.0).abs() < 1e-6, "{} vs {f}", c.factor);
    assert!(c.sds_g.is_none() && c.table.is_some() && c.rule.is_none());
    let dense = slipload_motion::log_spaced_periods(0.01, 10.0, 400).unwrap();
    let h = (1000f64).ln() / 399.0;
    let st = study_with(ALL, &table(&dense), "").unwrap();
    let g = st.suites[0].code_scaling.as_ref().unwrap().factor;
    assert!(
        g <= f * (1.0 + 1e-6) && g >= f * (-h / 4.0).exp(),
        "{g} vs {f} (h/4 = {})",
        h / 4.0
    );
    eprintln!(
        "ASCE factor {f}; table at the corners {}; dense table {g} ({:+.3e})",
        c.factor,
        g / f - 1.0
    );
}

/// The `mce_r` level of a table is 1.5 × the table, as for the ASCE form.
#[test]
fn the_hazard_scales_a_table() {
    let t = r#""table": { "periods_s": [0.05, 0.5, 1.0, 3.0], "sa_g": [0.8, 1.0, 0.6, 0.2] }"#;
    let design = study_with(ALL, t, "").unwrap();
    let mce = study_with(ALL, &format!(r#"{t}, "hazard": "mce_r""#), "").unwrap();
    let (a, b) = (
        design.suites[0].code_scaling.as_ref().unwrap(),
        mce.suites[0].code_scaling.as_ref().unwrap(),
    );
    assert!((b.factor / a.factor / 1.5 - 1.0).abs() < 1e-12);
    for (x, y) in a.target_sa_g.iter().zip(&b.target_sa_g) {
        assert!((y / x / 1.5 - 1.0).abs() < 1e-12);
    }
}

/// Three records scaled to an EN 1998-1 spectrum, by its rule (the form's default): the
/// mean PGA reaches a_g·S, the mean spectrum 90 % of the target; code-check.md and the
/// compliance matrix name EN 1998-1's clauses.
#[test]
fn an_en1998_suite_is_scaled_and_checked_by_its_rule() {
    let limits = r#", "limits": { "criteria": [ { "metric": "peak_drift_ratio", "statistic": "max", "max": 0.02 } ] }"#;
    let st = study_with(THREE, EN, limits).unwrap();
    let c = st.suites[0].code_scaling.as_ref().unwrap();
    assert_eq!(c.rule, Some(ScalingRule::En1998));
    let e = c.en1998.as_ref().unwrap();
    // Table 3.2, ground C: S = 1.15; a_g = γ_I a_gR = 0.25 g
    assert_eq!((e.spectrum.ag_g, e.spectrum.corners.s), (0.25, 1.15));
    let z = c.zero_period.unwrap();
    assert!((z.ag_s_g / (0.25 * 1.15) - 1.0).abs() < 1e-12);
    assert!(z.mean_pga_g >= z.ag_s_g * (1.0 - 1e-12));
    for (m, t) in c.mean_sa_g.iter().zip(&c.target_sa_g) {
        assert!(m / t >= 0.9 * (1.0 - 1e-12));
    }
    assert!(c.target_text().contains("ground type C, Type 1"));
    let line = |case| CheckLine {
        suite: "code".into(),
        case,
        criterion: "max peak_drift_ratio".into(),
        limit: 0.02,
        demand: 0.01,
        ratio: 0.5,
        pass: true,
        source: "suites[0].limits.criteria[0]".into(),
    };
    let check = DesignCheck {
        lines: vec![line(CaseName::Nominal)],
    };
    let rows = matrix(&st, &check, &[]);
    let find = |clause: &str| {
        rows.iter()
            .find(|r| r.clause == clause)
            .unwrap_or_else(|| panic!("{clause} not in {rows:?}"))
    };
    let count = find("EN 1998-1 §3.2.3.1.2(4)a");
    assert_eq!(
        (count.value.as_str(), count.limit.as_str()),
        ("3 records", "≥ 3")
    );
    assert_eq!(find("EN 1998-1 §3.2.3.1.2(4)b").status, Status::Pass);
    assert_eq!(find("EN 1998-1 §3.2.3.1.2(4)c").status, Status::Pass);
    assert!(
        rows.iter()
            .all(|r| r.clause != "§16.2.2" && r.clause != "§16.2.3")
    );
    assert!(to_markdown(&rows).contains("and EN 1998-1 where a row names it"));
}

#[test]
fn the_en1998_rule_counts_three_and_takes_the_maximum_below_seven() {
    let two = r#""records/RSN1084_NORTHR_SCS142.AT2", "records/RSN1148_KOCAELI_ARE090.AT2""#;
    let e = err(two, EN, "");
    assert!(
        e.contains("suites[0].records")
            && e.contains("at least 3")
            && e.contains("EN 1998-1 §3.2.3.1.2(4)a")
            && e.contains("add 1 more"),
        "{e}"
    );
    let mean = r#", "limits": { "criteria": [ { "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.02 } ] }"#;
    let e = err(THREE, EN, mean);
    assert!(
        e.contains("suites[0].limits.criteria[0].statistic") && e.contains("§4.3.3.4.3"),
        "{e}"
    );
    // eleven records: the mean is the design value
    study_with(ALL, EN, mean).unwrap();
    // the ASCE rule named on the EN spectrum counts 11
    let e = err(THREE, &format!(r#"{EN}, "rule": "asce7""#), "");
    assert!(e.contains("at least 11"), "{e}");
}

#[test]
fn refusals_name_their_fields() {
    let cases: &[(&str, &str)] = &[
        (
            r#""table": { "periods_s": [0.05, 0.1, 0.5, 0.5, 3.0], "sa_g": [1, 1, 1, 1, 1] }"#,
            "suites[0].scale.code_spectrum.table.periods_s[3]",
        ),
        (
            r#""table": { "periods_s": [0.05, 0.5, 3.0], "sa_g": [1, -1, 1] }"#,
            "suites[0].scale.code_spectrum.table.sa_g[1]",
        ),
        (
            r#""table": { "periods_s": [0.05, 0.5, 3.0], "sa_g": [1, 1] }"#,
            "suites[0].scale.code_spectrum.table.sa_g",
        ),
        (
            // the range (to 2.4 s) beyond the table's 2 s
            r#""table": { "periods_s": [0.05, 0.5, 2.0], "sa_g": [1, 1, 0.3] }"#,
            "suites[0].scale.code_spectrum.table.periods_s",
        ),
        (
            r#""table": { "periods_s": [0.05, 0.5, 3.0], "sa_g": [1, 1, 0.2] }, "rule": "en1998""#,
            "suites[0].scale.code_spectrum.table.periods_s[0]",
        ),
        (
            r#""en1998": { "agr_g": 0.25, "ground_type": "S1", "spectrum_type": 1 }"#,
            "suites[0].scale.code_spectrum.en1998.ground_type",
        ),
        (
            r#""en1998": { "agr_g": 0.25, "ground_type": "C", "spectrum_type": 3 }"#,
            "suites[0].scale.code_spectrum.en1998.spectrum_type",
        ),
        (
            r#""en1998": { "agr_g": 0.25, "ground_type": "C", "spectrum_type": 1, "td_s": 0.5 }"#,
            "suites[0].scale.code_spectrum.en1998.td_s",
        ),
        (
            r#""en1998": { "agr_g": 0.25, "ground_type": "C", "spectrum_type": 1, "damping_percent": -2 }"#,
            "suites[0].scale.code_spectrum.en1998.damping_percent",
        ),
        (
            r#""en1998": { "agr_g": 0.25, "ground_type": "C", "spectrum_type": 1 }, "hazard": "mce_r""#,
            "suites[0].scale.code_spectrum.hazard",
        ),
        (
            r#""sds_g": 1.0, "sd1_g": 0.6, "tl_s": 8, "rule": "en1998""#,
            "suites[0].scale.code_spectrum.rule",
        ),
        (
            r#""sds_g": 1.0, "sd1_g": 0.6, "tl_s": 8, "rule": "nz1170""#,
            "suites[0].scale.code_spectrum.rule",
        ),
        (
            r#""sds_g": 1.0, "sd1_g": 0.6"#,
            "suites[0].scale.code_spectrum.tl_s",
        ),
        (
            r#""sds_g": 1.0, "sd1_g": 0.6, "tl_s": 8, "table": { "periods_s": [0.05, 3.0], "sa_g": [1, 1] }"#,
            "suites[0].scale.code_spectrum",
        ),
        (r#""hazard": "design""#, "suites[0].scale.code_spectrum"),
    ];
    for (code, field) in cases {
        let e = err(ALL, code, "");
        assert!(e.contains(field), "{code}: {e}");
    }
    // a ground type S1 is sent to the table form; two forms are named
    assert!(err(ALL, cases[5].0, "").contains("table"));
    assert!(err(ALL, cases[13].0, "").contains("exactly one target"));
}

/// The frame's strength check reads S_DS, S_D1 and T_L: a study whose code-scaled suites
/// are all tables or EN 1998-1 spectra is refused, naming the ASCE form.
#[test]
fn the_strength_check_needs_the_asce_form() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/ten-story-yielding.json",
  "suites": [ {{ "name": "code", "records": ["records/RSN*.AT2"], "scale": {{ "code_spectrum": {{ {EN} }} }} }} ],
  "frame_strength": {{ "response_modification": 8 }},
  "space": {{ "profile": {{ "shape": "uniform", "scale_kn": [0, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    let e = Study::from_json(&text, &root.join("study.json"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("frame_strength.response_modification") && e.contains("sds_g, sd1_g, tl_s"),
        "{e}"
    );
}
