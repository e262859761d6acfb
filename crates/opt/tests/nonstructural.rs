//! Contract (issue 45 §4): with `nonstructural` the code check flags, per suite and storey,
//! a mean peak storey drift ratio (over the suite's ground motions, at the property case
//! where it is largest) above `factor` (default 1.5) × the drift ratio the
//! deformation-sensitive nonstructural components are designed for; the compliance matrix
//! states it per suite in place of its `not checked` row, the flag does not change the
//! verdict, and bad keys are refused naming their field.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::eval::evaluate::run_designs;
use slipload_opt::model::fidelity::Fidelity;
use slipload_opt::phases::compliance::{Status, matrix};
use slipload_opt::phases::nonstructural::{CLAUSE, drift_flags, into_matrix, to_markdown};
use std::path::Path;

/// The benchmark three-storey frame under two short records, property bounds ±15 %.
fn study(nonstructural: &str) -> Result<Study, slipload_opt::OptError> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/benchmark-3story.json",
  "suites": [ {{ "name": "two", "records": ["records/SYL090.AT2", "records/RSN900_LANDERS_YER270.AT2"],
                 "limits": {{ "criteria": [ {{ "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.05 }} ] }} }} ],
  "property_bounds": {{ "slip_load": {{ "lower": 0.85, "upper": 1.15 }} }}{nonstructural},
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    Study::from_json(&text, &root.join("study.json"))
}

#[test]
fn storeys_past_the_flag_are_flagged_and_the_matrix_says_so() {
    let design = vec![300e3, 250e3, 150e3];
    // the storeys' means by hand from the runs, each at its largest case
    let plain = study("").unwrap();
    let runs = run_designs(
        &plain,
        std::slice::from_ref(&design),
        &Fidelity::check(&plain),
        &|| {},
    )
    .unwrap()
    .remove(0);
    let n = plain.records.len();
    let mut mean = [f64::NEG_INFINITY; 3];
    for c in 0..3 {
        for (s, m) in mean.iter_mut().enumerate() {
            let v = (0..n).map(|r| runs[c * n + r].drift_ratio[s]).sum::<f64>() / n as f64;
            *m = m.max(v);
        }
    }
    // designed-for drifts 1 % either side of mean / 1.5: storeys 1 and 3 flagged, 2 not
    let designed: Vec<f64> = mean
        .iter()
        .enumerate()
        .map(|(s, m)| m / 1.5 * if s == 1 { 1.01 } else { 0.99 })
        .collect();
    let st = study(&format!(
        r#", "nonstructural": {{ "drift_ratios": [{}, {}, {}] }}"#,
        designed[0], designed[1], designed[2]
    ))
    .unwrap();
    let flags = drift_flags(&st, &runs);
    assert_eq!(flags.len(), 1);
    let f = &flags[0];
    assert_eq!(f.factor, 1.5);
    assert_eq!(f.flagged, vec![1, 3]);
    for (got, want) in f.mean_drift_ratio.iter().zip(mean) {
        assert!((got - want).abs() <= 1e-15 * want);
    }
    let (ratio, storey) = f.worst();
    assert!((ratio - 1.0 / 0.99).abs() < 1e-12, "{ratio}");
    assert!(storey == 1 || storey == 3);
    // the matrix: the clause's row becomes the suite's, flagged
    let mut rows = matrix(&st, &Default::default(), &design);
    let before = rows.len();
    assert!(
        rows.iter()
            .any(|r| r.clause == CLAUSE && r.status == Status::NotChecked)
    );
    into_matrix(&mut rows, &flags);
    assert_eq!(rows.len(), before);
    let row = rows.iter().find(|r| r.clause.starts_with(CLAUSE)).unwrap();
    assert_eq!(row.status, Status::Flagged);
    assert!(row.value.contains("storeys 1, 3 flagged"), "{}", row.value);
    let md = to_markdown(&flags);
    assert_eq!(md.matches("**flagged**").count(), 2);
    // a larger factor clears them all
    let wide = study(&format!(
        r#", "nonstructural": {{ "drift_ratio": {}, "factor": 3 }}"#,
        designed[0].max(designed[1]).max(designed[2])
    ))
    .unwrap();
    let f = &drift_flags(&wide, &runs)[0];
    assert!(f.flagged.is_empty());
    let mut rows = matrix(&wide, &Default::default(), &design);
    into_matrix(&mut rows, std::slice::from_ref(f));
    assert_eq!(
        rows.iter()
            .find(|r| r.clause.starts_with(CLAUSE))
            .unwrap()
            .status,
        Status::Pass
    );
}

#[test]
fn without_the_key_nothing_is_flagged_or_changed() {
    let st = study("").unwrap();
    assert!(drift_flags(&st, &[]).is_empty());
    assert!(to_markdown(&[]).is_empty());
}

#[test]
fn bad_nonstructural_keys_name_their_field() {
    let e = study(r#", "nonstructural": { "drift_ratio": 1.5 }"#)
        .unwrap_err()
        .to_string();
    assert!(e.contains("nonstructural.drift_ratio"), "{e}");
    let e = study(r#", "nonstructural": { "drift_ratios": [0.01, 0.01] }"#)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("nonstructural.drift_ratios") && e.contains("3 storeys"),
        "{e}"
    );
    let e = study(r#", "nonstructural": { "drift_ratios": [0.01, -1, 0.01] }"#)
        .unwrap_err()
        .to_string();
    assert!(e.contains("nonstructural.drift_ratios[1]"), "{e}");
    let e = study(r#", "nonstructural": { "factor": 2 }"#)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`drift_ratio`") && e.contains("`drift_ratios`"),
        "{e}"
    );
    let e = study(r#", "nonstructural": { "drift_ratio": 0.01, "factor": 0.5 }"#)
        .unwrap_err()
        .to_string();
    assert!(e.contains("nonstructural.factor"), "{e}");
}
