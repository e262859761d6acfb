//! Contract: a suite scaled to a code spectrum (`scale.code_spectrum`, ASCE 7-16 §16.2.3)
//! gets one factor for every record — the smallest for which the suite's mean 5 %-damped
//! spectrum is at least 90 % of the target at every period of its range, by default from
//! 0.2 × the braced frame's first period (or the 90 %-mass mode's) to 2 × the bare
//! frame's, [0.2 T, 2 T] for a given T — and the study
//! keeps that factor, the range, the controlling period and both spectra for its manifest.
//! The MCE_R level is 1.5 × the design level (ASCE 7-16 §11.4.5), so its factor is 1.5 ×
//! the design level's. Bad targets are refused naming the field.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_motion::{DesignSpectrum, G, Spectrum};
use slipload_opt::Study;
use std::path::Path;

/// The ten-storey frame over the eleven-or-more RSN records of records/, scaled to the
/// design spectrum S_DS = 1.0 g, S_D1 = 0.6 g, T_L = 8 s at `hazard`.
fn study(hazard: &str, extra: &str) -> Result<Study, slipload_opt::OptError> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/ten-story.json",
  "suites": [ {{ "name": "code", "records": ["records/RSN*.AT2"],
                 "scale": {{ "code_spectrum": {{ "sds_g": 1.0, "sd1_g": 0.6, "tl_s": 8, "hazard": "{hazard}"{extra} }} }} }} ],
  "space": {{ "profile": {{ "shape": "uniform", "scale_kn": [0, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    Study::from_json(&text, &root.join("study.json"))
}

#[test]
fn one_factor_puts_the_mean_spectrum_at_90_percent_of_the_target() {
    let st = study("design", "").unwrap();
    let suite = &st.suites[0];
    assert!(
        suite.range.len() >= 11,
        "ASCE 7-16 §16.2.2: 11 records at least"
    );
    let c = suite.code_scaling.as_ref().unwrap();
    let t1 = st.building.t1();
    assert_eq!(c.period_s, t1);
    // the range covers the frame with its dampers stuck (braced, stiffer) and slipping
    // (bare), and the modes of 90 % of the mass
    let p = st.building.scaling_periods().unwrap();
    assert!(p.stuck_t1_s < 0.75 * t1, "{p:?}");
    let lower = (0.2 * p.stuck_t1_s).min(p.mass_90_period_s);
    assert_eq!(c.range_s, [lower, 2.0 * t1]);
    assert!(c.range_s[0] <= p.mass_90_period_s && c.range_s[0] <= 0.2 * p.stuck_t1_s);
    assert_eq!(c.stuck_period_s, Some(p.stuck_t1_s));
    assert_eq!(c.mass_90_period_s, Some(p.mass_90_period_s));
    // recomputed independently: the scaled records' mean spectrum on the same periods
    let target = DesignSpectrum::new(1.0, 0.6, 8.0).unwrap();
    let mut mean = vec![0.0; c.periods_s.len()];
    for r in &st.records[suite.range.clone()] {
        let s = Spectrum::compute(r, 0.05, &c.periods_s).unwrap();
        for (m, v) in mean.iter_mut().zip(&s.psa_m_s2) {
            *m += v / suite.range.len() as f64;
        }
    }
    let ratios: Vec<f64> = c
        .periods_s
        .iter()
        .zip(&mean)
        .map(|(&t, m)| m / target.sa_m_s2(t))
        .collect();
    let least = ratios.iter().copied().fold(f64::INFINITY, f64::min);
    // at least 90 % everywhere, and exactly 90 % at the controlling period (the factor is
    // the smallest that does it); the tolerance is summation round-off over 11+ records
    assert!(least >= 0.9 * (1.0 - 1e-12), "least ratio {least}");
    assert!(
        (least - 0.9).abs() < 1e-9,
        "least ratio {least}: not the smallest factor"
    );
    let k = c
        .periods_s
        .iter()
        .position(|&t| t == c.controlling_period_s)
        .unwrap();
    assert!((ratios[k] - 0.9).abs() < 1e-9);
    // what the manifest carries is what was computed
    for (a, b) in c.mean_sa_g.iter().zip(&mean) {
        assert!((a - b / G).abs() <= 1e-12 * a.abs());
    }
    for (&t, &s) in c.periods_s.iter().zip(&c.target_sa_g) {
        assert_eq!(s, target.sa_m_s2(t) / G);
    }
}

#[test]
fn the_mce_level_is_one_and_a_half_times_the_design_level() {
    let de = study("design", "").unwrap();
    let mce = study("mce_r", "").unwrap();
    let (a, b) = (
        de.suites[0].code_scaling.as_ref().unwrap().factor,
        mce.suites[0].code_scaling.as_ref().unwrap().factor,
    );
    // the rule is linear in the target; the factors differ by their rounding only
    assert!((b / a - 1.5).abs() < 1e-12, "{b} / {a}");
    // and a chosen period moves the range to [0.2 T, 2 T]
    let at = study("design", r#", "period_s": 2.0"#).unwrap();
    let c = at.suites[0].code_scaling.as_ref().unwrap();
    assert_eq!(c.range_s, [0.4, 4.0]);
    assert_eq!((c.stuck_period_s, c.mass_90_period_s), (None, None));
}

#[test]
fn a_bad_target_is_refused_naming_the_field() {
    let e = study("design", r#", "period_s": -1"#)
        .unwrap_err()
        .to_string();
    assert!(e.contains("suites[0].scale.code_spectrum.period_s"), "{e}");
    // a period whose range starts below twice the records' coarsest sample interval
    // (0.2 × 0.05 s = 0.01 s; the RSN records are sampled at 0.005 to 0.02 s): the spectra
    // are not resolved there
    let e = study("design", r#", "period_s": 0.05"#)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("suites[0].scale.code_spectrum.period_s")
            && e.contains("below twice the sample interval of"),
        "{e}"
    );
    let e = study("maximum", "").unwrap_err().to_string();
    assert!(e.contains("maximum") || e.contains("hazard"), "{e}");
}

/// An object given as an array is read by position, so two swapped values would pass in
/// the wrong fields: the code spectrum (and any other key whose value is an object of
/// named fields) is refused as an array, naming the key and its fields.
#[test]
fn a_code_spectrum_given_as_an_array_is_refused() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let study_with = |scale: &str, sweep: &str| {
        let text = format!(
            r#"{{ "building": "configs/ten-story.json",
  "suites": [ {{ "name": "code", "records": ["records/RSN*.AT2"], "scale": {scale} }} ],
  "space": {{ "profile": {{ "shape": "uniform", "scale_kn": [0, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {sweep} }}"#
        );
        Study::from_json(&text, &root.join("study.json"))
    };
    let sweep = r#"{ "sampler": "halton", "points": 2, "seed": 5 }"#;
    // S_D1 and S_DS swapped: read by position they would pass as another spectrum
    let e = study_with(
        r#"{ "code_spectrum": [0.6, 1.0, 8, "design", null] }"#,
        sweep,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("suites[0].scale.code_spectrum"), "{e}");
    assert!(e.contains("got an array"), "{e}");
    assert!(e.contains("\"sds_g\"") && e.contains("\"sd1_g\""), "{e}");
    // another object key given as an array: the sweep's settings
    let e = study_with(
        r#"{ "code_spectrum": { "sds_g": 1.0, "sd1_g": 0.6, "tl_s": 8 } }"#,
        r#"["halton", 2, 5]"#,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("sweep") && e.contains("got an array"), "{e}");
    // written with its keys, the same spectrum loads
    study_with(
        r#"{ "code_spectrum": { "sds_g": 1.0, "sd1_g": 0.6, "tl_s": 8 } }"#,
        sweep,
    )
    .unwrap();
}

/// `per_record`: each record runs at its own factor (its fit to the target times the
/// suite's), which the suite's scaling lists in record order; the scaled mean still meets
/// 90 % of the target at every period kept; without the key every record has the suite's
/// one factor and none is listed.
#[test]
fn per_record_factors_are_the_records_own_and_listed() {
    let st = study("design", r#", "per_record": true"#).unwrap();
    let c = st.suites[0].code_scaling.as_ref().unwrap();
    let n = st.suites[0].range.len();
    assert_eq!(c.record_factors.len(), n);
    for (r, f) in st.records[st.suites[0].range.clone()]
        .iter()
        .zip(&c.record_factors)
    {
        assert_eq!(r.scale_factor(), *f, "{}", r.name());
    }
    assert!(c.record_factors.iter().any(|f| *f != c.record_factors[0]));
    for (m, t) in c.mean_sa_g.iter().zip(&c.target_sa_g) {
        assert!(m / t >= 0.9 * (1.0 - 1e-12), "{m} vs {t}");
    }
    let plain = study("design", "").unwrap();
    let p = plain.suites[0].code_scaling.as_ref().unwrap();
    assert!(p.record_factors.is_empty());
    for r in &plain.records[plain.suites[0].range.clone()] {
        assert_eq!(r.scale_factor(), p.factor);
    }
}
