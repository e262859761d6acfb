//! Contract: per-record scaling meets a spectral-acceleration target at T₁; the ASCE 7-16
//! style rule finds the smallest common factor with the suite mean spectrum ≥ 90 % of the
//! target over the whole of 0.2·T₁–2.0·T₁ (checked at 1,000 other periods), touching it at
//! the controlling period.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_motion::{
    ASCE7_FRACTION, DesignSpectrum, REFINE_MARGIN, Record, Spectrum, default_suite,
    log_spaced_periods, read_record, scale_suite_asce7, scale_suite_over_range,
    scale_to_spectral_acceleration, spectral_acceleration,
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

/// The eleven records of the shipped check example (configs/study-ten-story-check.json).
fn example_records() -> Vec<Record> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../records");
    [
        "RSN1084_NORTHR_SCS142.AT2",
        "RSN1148_KOCAELI_ARE090.AT2",
        "RSN1158_KOCAELI_DZC180.AT2",
        "RSN125_FRIULI.A_A-TMZ000.AT2",
        "RSN1602_DUZCE_BOL000.AT2",
        "RSN6_IMPVALL.I_I-ELC180.AT2",
        "RSN721_SUPER.B_B-ICC090.AT2",
        "RSN777_LOMAP_HCH090.AT2",
        "RSN77_SFERN_PUL164.AT2",
        "RSN879_LANDERS_LCN260.AT2",
        "RSN900_LANDERS_YER270.AT2",
    ]
    .iter()
    .map(|f| read_record(&dir.join(f), None, None).expect("example record reads"))
    .collect()
}

/// The least ratio (scaled mean)/(target) of `records` × `factor` on `periods`, with its
/// period; the mean is summed record by record from the scaled records' own spectra.
fn least_ratio(
    records: &[Record],
    factor: f64,
    target: &DesignSpectrum,
    periods: &[f64],
) -> (f64, f64) {
    let mut mean = vec![0.0; periods.len()];
    for r in records {
        let s = Spectrum::compute(&r.try_scaled(factor).unwrap(), 0.05, periods).unwrap();
        mean.iter_mut().zip(&s.psa_m_s2).for_each(|(m, x)| *m += x);
    }
    let n = records.len() as f64;
    periods
        .iter()
        .zip(&mean)
        .map(|(&t, m)| (m / n / target.sa_m_s2(t), t))
        .fold((f64::INFINITY, 0.0), |a, b| if b.0 < a.0 { b } else { a })
}

#[test]
fn the_90_percent_rule_holds_between_the_grid_periods() {
    // The shipped example: S_DS = 0.5 g, S_D1 = 0.3 g at MCE_R (× 1.5), the ten-storey
    // frame's range [0.2 T, 2 T] around its bare T₁ ≈ 1.20 s.
    let target = DesignSpectrum::new(0.75, 0.45, 8.0).unwrap();
    let records = example_records();
    let range = [0.2 * 1.2, 2.0 * 1.2];
    let out = scale_suite_over_range(&records, &target, range, 0.05).unwrap();
    // an independent grid of 1,000 log-spaced periods, none of them the scaling's own
    // but the ends
    let fine = log_spaced_periods(range[0], range[1], 1000).unwrap();
    let (least, at) = least_ratio(&records, out.factor, &target, &fine);
    // the tolerance is round-off: the spectrum is linear in the record, and the scaled
    // records' spectra are summed in another order than the unscaled mean (≪ 1e-12)
    assert!(
        least >= ASCE7_FRACTION * (1.0 - 1e-12),
        "scaled mean at {least} of the target at T = {at} s"
    );
    // and the factor is the smallest: the refined minimum touches 90 %
    let (own, _) = least_ratio(&records, out.factor, &target, &[out.controlling_period_s]);
    assert!((own / ASCE7_FRACTION - 1.0).abs() < 1e-12, "{own}");
    // the 50-period grid of before missed the minimum: its factor is smaller, and the
    // fine grid finds its scaled mean below 90 % (the 88 % near 0.66 s)
    let coarse = log_spaced_periods(range[0], range[1], 50).unwrap();
    let (c, _) = least_ratio(&records, 1.0, &target, &coarse);
    let old_factor = ASCE7_FRACTION / c;
    let (old_least, old_at) = least_ratio(&records, old_factor, &target, &fine);
    eprintln!(
        "factor {} (50-point grid: {old_factor}, +{:.2} %), controlling {} s; the old factor's least ratio on 1,000 periods {old_least:.4} at {old_at:.3} s",
        out.factor,
        100.0 * (out.factor / old_factor - 1.0),
        out.controlling_period_s
    );
    assert!(out.factor > old_factor && old_least < ASCE7_FRACTION);
}

#[test]
fn refinement_finds_a_minimum_the_grid_straddles() {
    // the refined minimum is no higher than the grid's least, and how far below it is
    // the margin the refinement needs (REFINE_MARGIN must exceed it by far)
    let target = DesignSpectrum::new(1.0, 0.6, 8.0).unwrap();
    for records in [example_records(), paper_records(), default_suite()] {
        for t in [0.5, 1.2, 3.0] {
            let out = scale_suite_over_range(&records, &target, [0.2 * t, 2.0 * t], 0.05).unwrap();
            let count = out.periods_s.len();
            let grid = log_spaced_periods(0.2 * t, 2.0 * t, 201).unwrap();
            let (g, _) = least_ratio(&records, out.factor, &target, &grid);
            assert!(g >= ASCE7_FRACTION * (1.0 - 1e-12), "T = {t}: {g}");
            assert!(
                g / ASCE7_FRACTION - 1.0 < 0.2 * REFINE_MARGIN,
                "T = {t}: grid least {g}, {count} periods"
            );
        }
    }
}

/// Per-record factors (`scale_suite_over_range_each`): each record's own factor is the
/// geometric mean of target/spectrum over the range (recomputed here on an independent
/// 1,000-period grid: the fit's grid average and this one agree to the quadrature of a
/// smooth ln ratio, 1 %), the suite's common factor is the smallest that lifts the fitted
/// records' mean to 90 % of the target (checked on the same fine grid, touching it at the
/// controlling period), and the fitted records are closer to the target than one factor
/// for all (the spread of ln(Sa/target) across the records shrinks at every period).
#[test]
fn per_record_factors_fit_each_record_then_the_suite() {
    let target = DesignSpectrum::new(0.75, 0.45, 8.0).unwrap();
    let records = example_records();
    let range = [0.2 * 1.2, 2.0 * 1.2];
    let out = slipload_motion::scale_suite_over_range_each(&records, &target, range, 0.05).unwrap();
    let fine = log_spaced_periods(range[0], range[1], 1000).unwrap();
    let mut spread_one = 0.0;
    let mut spread_each = 0.0;
    let common = scale_suite_over_range(&records, &target, range, 0.05).unwrap();
    for (r, f) in records.iter().zip(&out.suite.factors) {
        let s = Spectrum::compute(r, 0.05, &fine).unwrap();
        let ln_ratio: Vec<f64> = fine
            .iter()
            .zip(&s.psa_m_s2)
            .map(|(t, a)| (target.sa_m_s2(*t) / a).ln())
            .collect();
        let own = (ln_ratio.iter().sum::<f64>() / fine.len() as f64).exp();
        let fitted = f / out.factor;
        assert!(
            (fitted / own - 1.0).abs() < 0.01,
            "{}: {fitted} vs {own}",
            r.name()
        );
        // mean squared misfit in ln Sa, one factor for all against each its own
        for l in &ln_ratio {
            spread_one += (l - common.factor.ln()).powi(2);
            spread_each += (l - f.ln()).powi(2);
        }
    }
    assert!(spread_each < spread_one, "{spread_each} vs {spread_one}");
    // the factors differ from record to record
    let (lo, hi) = out
        .suite
        .factors
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), f| (a.min(*f), b.max(*f)));
    assert!(hi > 1.5 * lo, "{lo} {hi}");
    // the 90 % rule on the fine grid, for the records as scaled
    let mut mean = vec![0.0; fine.len()];
    for r in &out.suite.records {
        let s = Spectrum::compute(r, 0.05, &fine).unwrap();
        mean.iter_mut().zip(&s.psa_m_s2).for_each(|(m, x)| *m += x);
    }
    let n = records.len() as f64;
    let least = fine
        .iter()
        .zip(&mean)
        .map(|(t, m)| m / n / target.sa_m_s2(*t))
        .fold(f64::INFINITY, f64::min);
    assert!(least >= ASCE7_FRACTION * (1.0 - 1e-12), "{least}");
    let mut at = 0.0;
    for r in &out.suite.records {
        at += Spectrum::compute(r, 0.05, &[out.controlling_period_s])
            .unwrap()
            .psa_m_s2[0];
    }
    let touch = at / n / target.sa_m_s2(out.controlling_period_s);
    assert!((touch / ASCE7_FRACTION - 1.0).abs() < 1e-12, "{touch}");
}
