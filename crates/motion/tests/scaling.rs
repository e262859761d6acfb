//! Contract: per-record scaling meets a spectral-acceleration target at T₁; the ASCE 7-16
//! style rule finds the smallest common factor with the suite mean spectrum ≥ 90 % of the
//! target over 0.2·T₁–2.0·T₁, touching it at the controlling period.

use slipload_motion::{
    ASCE7_FRACTION, DesignSpectrum, Record, Spectrum, default_suite, read_record,
    scale_suite_asce7, scale_to_spectral_acceleration, spectral_acceleration,
};

fn paper_records() -> Vec<Record> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../records");
    ["I-ELC180.AT2", "STM090.AT2", "SYL090.AT2"]
        .iter()
        .map(|f| read_record(&dir.join(f), None, None).expect("paper record reads"))
        .collect()
}

#[test]
fn each_record_meets_its_spectral_target() {
    let records = paper_records();
    let s = scale_to_spectral_acceleration(&records, 1.0, 0.05, 4.0).unwrap();
    assert_eq!(s.records.len(), 3);
    for (r, (orig, f)) in s.records.iter().zip(records.iter().zip(&s.factors)) {
        let sa = spectral_acceleration(r, 1.0, 0.05).unwrap();
        // the spectrum is linear in the record: only roundings of the factor and samples
        assert!((sa - 4.0).abs() <= 1e-12 * 4.0, "{}: {sa}", r.name());
        assert_eq!(r.pga(), orig.pga() * f);
    }
    assert!(scale_to_spectral_acceleration(&records, 1.0, 0.05, f64::NAN).is_err());
}

#[test]
fn asce7_common_factor_is_the_smallest_that_reaches_90_percent() {
    let target = DesignSpectrum::new(1.0, 0.6, 8.0).unwrap();
    for records in [paper_records(), default_suite()] {
        let t1 = 1.01; // the paper building's first period
        let out = scale_suite_asce7(&records, &target, t1, 0.05).unwrap();
        assert!(out.suite.factors.iter().all(|&f| f == out.factor));
        assert_eq!(out.periods_s.first(), Some(&(0.2 * t1)));
        assert_eq!(out.periods_s.last(), Some(&(2.0 * t1)));
        // recompute the scaled suite's mean independently
        let mut mean = vec![0.0; out.periods_s.len()];
        for r in &out.suite.records {
            let s = Spectrum::compute(r, 0.05, &out.periods_s).unwrap();
            mean.iter_mut().zip(&s.psa_m_s2).for_each(|(m, x)| *m += x);
        }
        let n = out.suite.records.len() as f64;
        let mut tightest = f64::INFINITY;
        for ((m, tgt), t) in mean.iter().zip(&out.target_psa_m_s2).zip(&out.periods_s) {
            let ratio = m / n / (ASCE7_FRACTION * tgt);
            assert!(ratio >= 1.0, "T = {t}: mean/(0.9 target) = {ratio}");
            tightest = tightest.min(ratio);
        }
        // smallest factor: it touches 90 % at the controlling period (to rounding of the
        // sums and the few-ulp round-up, ≪ 1e-12)
        assert!(tightest - 1.0 < 1e-12, "not minimal: {tightest}");
    }
}
