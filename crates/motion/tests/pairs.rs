//! Contract: the maximum-direction (RotD100) spectrum of a pair meets its closed forms —
//! identical components give √2 × the component's spectrum (the component rotated 45°), a
//! zero second component gives the first's spectrum, it is at least either component's,
//! it does not change when the pair is rotated, and it is the peak over angles of the
//! rotated component's spectrum (checked on a 1° grid) — and a suite of pairs scaled by it
//! has a mean RotD100 of at least 90 % of the target over the whole range.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_motion::{
    ASCE7_FRACTION, DesignSpectrum, MotionError, Record, RecordPair, Spectrum, log_spaced_periods,
    read_record, rotd100_spectrum, scale_pairs_over_range,
};

fn sylmar() -> RecordPair {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../records");
    let a = read_record(&dir.join("SYL090.AT2"), None, None).unwrap();
    let b = read_record(&dir.join("SYL360.AT2"), None, None).unwrap();
    RecordPair::new("SYL", a, b).unwrap()
}

/// Periods from the rigid limit to long ones, including sub-stepped short ones.
fn periods() -> Vec<f64> {
    vec![0.0, 0.05, 0.1, 0.3, 0.66, 1.0, 2.0, 4.0]
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

#[test]
fn identical_components_give_root_two_times_the_spectrum() {
    let a = sylmar().first().clone();
    let pair = RecordPair::new("twin", a.clone(), a.clone()).unwrap();
    let r = rotd100_spectrum(&pair, 0.05, &periods()).unwrap();
    let s = Spectrum::compute(&a, 0.05, &periods()).unwrap();
    // the same response twice: |(u, u)| = √2 |u| up to the rounding of hypot
    for (x, y) in r.psa_m_s2.iter().zip(&s.psa_m_s2) {
        assert!(rel(*x, 2f64.sqrt() * y) < 1e-14, "{x} vs √2 × {y}");
    }
    // and that is the component rotated 45° (a(cos 45° + sin 45°) = √2 a)
    let at45 = Spectrum::compute(
        &pair.rotated(std::f64::consts::FRAC_PI_4).unwrap(),
        0.05,
        &periods(),
    )
    .unwrap();
    for (x, y) in r.psa_m_s2.iter().zip(&at45.psa_m_s2) {
        assert!(rel(*x, *y) < 1e-12, "{x} vs {y}");
    }
}

#[test]
fn a_zero_second_component_gives_the_first_spectrum() {
    let a = sylmar().first().clone();
    let zero = Record::new("zero", a.dt(), vec![0.0; a.len()]).unwrap();
    let r = rotd100_spectrum(
        &RecordPair::new("one", a.clone(), zero).unwrap(),
        0.05,
        &periods(),
    )
    .unwrap();
    let s = Spectrum::compute(&a, 0.05, &periods()).unwrap();
    // hypot(u, 0) = |u| exactly, and u is integrated operation for operation as alone
    assert_eq!(r.psa_m_s2, s.psa_m_s2);
    assert_eq!(r.sd_m, s.sd_m);
}

#[test]
fn rotd100_is_at_least_either_component_and_the_peak_over_angles() {
    let pair = sylmar();
    let p = periods();
    let r = rotd100_spectrum(&pair, 0.05, &p).unwrap();
    let s1 = Spectrum::compute(pair.first(), 0.05, &p).unwrap();
    let s2 = Spectrum::compute(pair.second(), 0.05, &p).unwrap();
    let mut by_angle = vec![0.0f64; p.len()];
    for deg in 0..180 {
        let rot = pair.rotated((deg as f64).to_radians()).unwrap();
        let s = Spectrum::compute(&rot, 0.05, &p).unwrap();
        for (m, x) in by_angle.iter_mut().zip(&s.psa_m_s2) {
            *m = m.max(*x);
        }
    }
    for k in 0..p.len() {
        let x = r.psa_m_s2[k];
        // round-off of the rotation and of hypot: 1e-12
        assert!(
            x >= s1.psa_m_s2[k].max(s2.psa_m_s2[k]) * (1.0 - 1e-12),
            "T = {}",
            p[k]
        );
        // the 1° grid is within cos(0.5°) of the exact peak over every angle, never above
        assert!(
            by_angle[k] <= x * (1.0 + 1e-12),
            "T = {}: {} > {x}",
            p[k],
            by_angle[k]
        );
        let half = (0.5f64).to_radians().cos();
        assert!(
            by_angle[k] >= x * half * (1.0 - 1e-12),
            "T = {}: {} < {x}",
            p[k],
            by_angle[k]
        );
        eprintln!(
            "T = {:5.2} s: RotD100 {x:.4} m/s², components {:.4} and {:.4}, 1° grid {:.4}",
            p[k], s1.psa_m_s2[k], s2.psa_m_s2[k], by_angle[k]
        );
    }
}

#[test]
fn rotating_the_pair_leaves_rotd100_unchanged() {
    let pair = sylmar();
    let p = periods();
    let r = rotd100_spectrum(&pair, 0.05, &p).unwrap();
    for deg in [17.0f64, 90.0, 123.0] {
        let (t, q) = (deg.to_radians(), (deg + 90.0).to_radians());
        let turned =
            RecordPair::new("turned", pair.rotated(t).unwrap(), pair.rotated(q).unwrap()).unwrap();
        let rt = rotd100_spectrum(&turned, 0.05, &p).unwrap();
        for (x, y) in rt.psa_m_s2.iter().zip(&r.psa_m_s2) {
            assert!(rel(*x, *y) < 1e-12, "rotated {deg}°: {x} vs {y}");
        }
    }
    // (a, 0) turned by any angle is a's spectrum
    let a = pair.first().clone();
    let zero = Record::new("zero", a.dt(), vec![0.0; a.len()]).unwrap();
    let single = RecordPair::new("one", a.clone(), zero).unwrap();
    let s = Spectrum::compute(&a, 0.05, &p).unwrap();
    let (t, q) = (0.6f64, 0.6 + std::f64::consts::FRAC_PI_2);
    let turned =
        RecordPair::new("t", single.rotated(t).unwrap(), single.rotated(q).unwrap()).unwrap();
    let rt = rotd100_spectrum(&turned, 0.05, &p).unwrap();
    for (x, y) in rt.psa_m_s2.iter().zip(&s.psa_m_s2) {
        assert!(rel(*x, *y) < 1e-12, "{x} vs {y}");
    }
}

#[test]
fn components_of_different_intervals_are_not_a_pair() {
    let a = Record::new("a", 0.01, vec![0.0, 1.0]).unwrap();
    let b = Record::new("b", 0.02, vec![0.0, 1.0]).unwrap();
    let e = RecordPair::new("ab", a, b).unwrap_err();
    assert!(matches!(e, MotionError::PairMismatch { .. }));
    let m = e.to_string();
    assert!(
        m.contains("ab") && m.contains("0.01") && m.contains("0.02"),
        "{m}"
    );
}

#[test]
fn a_suite_of_pairs_meets_90_percent_by_its_mean_rotd100() {
    // the Sylmar pair and a second pair made from its components, swapped and scaled
    // (a stand-in event for the arithmetic)
    let syl = sylmar();
    let other = RecordPair::new(
        "SYL-b",
        syl.second().try_scaled(0.7).unwrap(),
        syl.first().try_scaled(0.5).unwrap(),
    )
    .unwrap();
    let pairs = vec![syl, other];
    let target = DesignSpectrum::new(1.0, 0.6, 8.0).unwrap();
    let range = [0.17, 2.4];
    let out = scale_pairs_over_range(&pairs, &target, range, 0.05).unwrap();
    let fine = log_spaced_periods(range[0], range[1], 400).unwrap();
    let mut mean = vec![0.0; fine.len()];
    for p in &out.pairs {
        let s = rotd100_spectrum(p, 0.05, &fine).unwrap();
        mean.iter_mut()
            .zip(&s.psa_m_s2)
            .for_each(|(m, x)| *m += x / 2.0);
    }
    let least = fine
        .iter()
        .zip(&mean)
        .map(|(&t, m)| m / target.sa_m_s2(t))
        .fold(f64::INFINITY, f64::min);
    // round-off only (the spectrum is linear in the pair)
    assert!(least >= ASCE7_FRACTION * (1.0 - 1e-12), "{least}");
    // RotD100 is at least either component's spectrum, so the pairs' mean is at least the
    // first components' mean, and their factor at most what the first components need
    let firsts: Vec<Record> = pairs.iter().map(|p| p.first().clone()).collect();
    let single = slipload_motion::scale_suite_over_range(&firsts, &target, range, 0.05).unwrap();
    assert!(
        out.matched.factor <= single.factor,
        "{} vs {}",
        out.matched.factor,
        single.factor
    );
    // both components of every pair × the one factor
    for (p, q) in pairs.iter().zip(&out.pairs) {
        assert_eq!(q.first().pga(), p.first().pga() * out.matched.factor);
        assert_eq!(q.second().pga(), p.second().pga() * out.matched.factor);
    }
}
