//! Contract: a suite entry `[first, second]` names the two horizontal components of one
//! event. A suite of pairs scaled to a code spectrum gets one factor, the smallest for which
//! the pairs' mean maximum-direction (RotD100) spectrum is at least 90 % of the target over
//! the whole range, and runs each component of a pair as its own record, in order. A code
//! suite is single components or pairs, not both; fewer than the standard's count (11
//! records, 7 pairs) is refused with the number needed unless the study gives
//! `min_records`; a pair is two files, not a pattern.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_motion::{DesignSpectrum, G, RecordPair, log_spaced_periods, rotd100_spectrum};
use slipload_opt::Study;
use std::path::Path;

/// The eight events of records/ with both horizontal components (records/README.md):
/// the second of most pairs is in records/pairs/.
const PAIRS: [[&str; 2]; 8] = [
    ["SYL090.AT2", "SYL360.AT2"],
    [
        "RSN1158_KOCAELI_DZC180.AT2",
        "pairs/RSN1158_KOCAELI_DZC270.AT2",
    ],
    [
        "pairs/RSN1197_CHICHI_CHY028-E.AT2",
        "pairs/RSN1197_CHICHI_CHY028-N.AT2",
    ],
    [
        "pairs/RSN1203_CHICHI_CHY036-E.AT2",
        "pairs/RSN1203_CHICHI_CHY036-N.AT2",
    ],
    [
        "pairs/RSN1605_DUZCE_DZC180.AT2",
        "pairs/RSN1605_DUZCE_DZC270.AT2",
    ],
    // 7830 and 7837 samples: the shorter is at rest after its end
    ["RSN777_LOMAP_HCH090.AT2", "pairs/RSN777_LOMAP_HCH180.AT2"],
    [
        "pairs/RSN8066_CCHURCH_CHHCN01W.AT2",
        "pairs/RSN8066_CCHURCH_CHHCS89W.AT2",
    ],
    [
        "RSN900_LANDERS_YER270.AT2",
        "pairs/RSN900_LANDERS_YER360.AT2",
    ],
];

fn study(records: &str, extra: &str) -> Result<Study, slipload_opt::OptError> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/ten-story.json",
  "suites": [ {{ "name": "pairs", "records": [{records}], "units": "g",
                 "scale": {{ "code_spectrum": {{ "sds_g": 1.0, "sd1_g": 0.6, "tl_s": 8{extra} }} }} }} ],
  "space": {{ "profile": {{ "shape": "uniform", "scale_kn": [0, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    Study::from_json(&text, &root.join("study.json"))
}

fn pairs(n: usize) -> String {
    PAIRS[..n]
        .iter()
        .map(|[a, b]| format!(r#"["records/{a}", "records/{b}"]"#))
        .collect::<Vec<_>>()
        .join(", ")
}

#[test]
fn seven_pairs_are_scaled_by_their_mean_rotd100_over_the_whole_range() {
    let st = study(&pairs(7), "").unwrap();
    let suite = &st.suites[0];
    let c = suite.code_scaling.as_ref().unwrap();
    assert_eq!(c.pairs, Some(7));
    // each component is a run, in order: first, second, first, second …
    assert_eq!(suite.range.len(), 14);
    for (k, [a, b]) in PAIRS[..7].iter().enumerate() {
        assert!(st.records[2 * k].name().ends_with(&format!("/{a}")));
        assert!(st.records[2 * k + 1].name().ends_with(&format!("/{b}")));
    }
    // recomputed independently from the scaled components on 300 other periods
    let target = DesignSpectrum::new(1.0, 0.6, 8.0).unwrap();
    let fine = log_spaced_periods(c.range_s[0], c.range_s[1], 300).unwrap();
    let mut mean = vec![0.0; fine.len()];
    for k in 0..7 {
        let p = RecordPair::new(
            "p",
            st.records[2 * k].as_ref().clone(),
            st.records[2 * k + 1].as_ref().clone(),
        )
        .unwrap();
        let s = rotd100_spectrum(&p, 0.05, &fine).unwrap();
        mean.iter_mut()
            .zip(&s.psa_m_s2)
            .for_each(|(m, x)| *m += x / 7.0);
    }
    let least = fine
        .iter()
        .zip(&mean)
        .map(|(&t, m)| m / target.sa_m_s2(t))
        .fold(f64::INFINITY, f64::min);
    // round-off of the sums only
    assert!(least >= 0.9 * (1.0 - 1e-12), "least ratio {least}");
    // the manifest's mean is the scaled mean RotD100 at the controlling period: 90 %
    let k = c
        .periods_s
        .iter()
        .position(|&t| t == c.controlling_period_s)
        .unwrap();
    assert!((c.mean_sa_g[k] * G / target.sa_m_s2(c.periods_s[k]) - 0.9).abs() < 1e-9);
}

#[test]
fn too_few_records_or_pairs_are_refused_with_the_number_needed() {
    let e = study(&pairs(6), "").unwrap_err().to_string();
    assert!(
        e.contains("suites[0].records") && e.contains("6 pairs") && e.contains("at least 7"),
        "{e}"
    );
    assert!(e.contains("add 1 more") && e.contains("min_records"), "{e}");
    // the study states its own rule
    let st = study(&pairs(6), r#", "min_records": 6"#).unwrap();
    assert_eq!(st.suites[0].code_scaling.as_ref().unwrap().pairs, Some(6));
    // single components: 11
    let singles = PAIRS[..5]
        .iter()
        .flatten()
        .map(|f| format!(r#""records/{f}""#))
        .collect::<Vec<_>>()
        .join(", ");
    let e = study(&singles, "").unwrap_err().to_string();
    assert!(
        e.contains("10 records") && e.contains("at least 11") && e.contains("add 1 more"),
        "{e}"
    );
}

#[test]
fn a_code_suite_is_singles_or_pairs_and_a_pair_is_two_files() {
    let mixed = format!(r#"{}, "records/WON185.AT2""#, pairs(7));
    let e = study(&mixed, "").unwrap_err().to_string();
    assert!(
        e.contains("suites[0].records") && e.contains("7 pairs") && e.contains("1 single"),
        "{e}"
    );
    let e = study(r#"["records/SYL*.AT2", "records/STM090.AT2"]"#, "")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("suites[0].records[0][0]") && e.contains("pattern"),
        "{e}"
    );
    // components of different sample intervals are not one event
    let e = study(
        r#"["records/SYL090.AT2", "records/WON185.AT2"]"#,
        r#", "min_records": 1"#,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("suites[0].records[0]") && e.contains("dt"),
        "{e}"
    );
}

#[test]
fn pairs_without_a_code_spectrum_are_two_records_each() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = r#"{ "building": "configs/ten-story.json",
  "suites": [ { "name": "pair", "records": [["records/SYL090.AT2", "records/SYL360.AT2"], "records/STM090.AT2"],
                "scale": { "pga_g": 0.4 } } ],
  "space": { "profile": { "shape": "uniform", "scale_kn": [0, 2000] } },
  "objective": { "terms": [ { "metric": "peak_drift_ratio", "statistic": "mean" } ] },
  "fidelity": { "method": "newmark" },
  "sweep": { "sampler": "halton", "points": 2, "seed": 5 } }"#;
    let st = Study::from_json(text, &root.join("study.json")).unwrap();
    let names: Vec<&str> = st.records.iter().map(|r| r.name()).collect();
    for (name, file) in names.iter().zip(["SYL090.AT2", "SYL360.AT2", "STM090.AT2"]) {
        assert!(name.ends_with(&format!("/{file}")), "{names:?}");
    }
    assert_eq!(names.len(), 3);
    assert!(st.records.iter().all(|r| (r.pga() / G - 0.4).abs() < 1e-12));
}
