//! Ground-motion intensity measures.
//!
//! Contract: all measures treat the acceleration as linear between samples (the
//! [`Record`] convention) and integrate that interpolant exactly:
//!
//! * velocity v(tₖ) = ∫a dt by the trapezoid rule (exact for piecewise-linear a), and
//!   displacement d(tₖ₊₁) = dₖ + vₖ·dt + dt²(2aₖ + aₖ₊₁)/6 (exact), both from rest at t = 0;
//! * **no baseline correction** is applied. Processed records (all PEER records) are already
//!   baseline-corrected, and a correction here would make PGV/PGD describe a different
//!   motion from the one the simulator integrates (it uses the record as given). An
//!   uncorrected record's drift therefore shows up in PGV and, mostly, PGD;
//! * PGA, PGV and PGD are peaks of |·| at the samples (for PGA that is the true peak; for
//!   PGV and PGD the peak between samples can be larger by O(dt²) relative);
//! * Arias intensity I_A = π/(2g) ∫a² dt (m/s), exact for piecewise-linear a:
//!   ∫ over a step = dt(aₖ² + aₖaₖ₊₁ + aₖ₊₁²)/3;
//! * significant duration D5–95 (s): the time between the cumulative Arias intensity
//!   reaching 5 % and 95 % of its total (Trifunac & Brady 1975), each crossing located
//!   exactly on the cubic cumulative of its step (bisection to round-off).

use crate::{G, MotionError, Record};

/// The intensity measures of one record (SI units).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Intensity {
    /// Peak ground acceleration, m/s².
    pub pga_m_s2: f64,
    /// Peak ground velocity at the samples, m/s (no baseline correction).
    pub pgv_m_s: f64,
    /// Peak ground displacement at the samples, m (no baseline correction).
    pub pgd_m: f64,
    /// Arias intensity, m/s.
    pub arias_m_s: f64,
    /// Significant duration D5–95, s (0 for a record without motion).
    pub d5_95_s: f64,
}

impl Intensity {
    /// All measures of `record`.
    pub fn of(record: &Record) -> Intensity {
        let v = ground_velocity(record);
        let d = ground_displacement(record);
        let peak = |x: &[f64]| x.iter().fold(0.0, |m: f64, y| m.max(y.abs()));
        Intensity {
            pga_m_s2: record.pga(),
            pgv_m_s: peak(&v),
            pgd_m: peak(&d),
            arias_m_s: arias_intensity(record),
            d5_95_s: significant_duration(record, 0.05, 0.95).unwrap_or(0.0),
        }
    }
}

/// Ground velocity at each sample, m/s, from rest (trapezoid rule, exact for the
/// piecewise-linear record; no baseline correction).
pub fn ground_velocity(record: &Record) -> Vec<f64> {
    let (a, dt) = (record.samples(), record.dt());
    let mut v = Vec::with_capacity(a.len());
    let mut vk = 0.0;
    v.push(vk);
    for w in a.windows(2) {
        vk += 0.5 * dt * (w[0] + w[1]);
        v.push(vk);
    }
    v
}

/// Ground displacement at each sample, m, from rest (exact for the piecewise-linear
/// record; no baseline correction).
pub fn ground_displacement(record: &Record) -> Vec<f64> {
    let (a, dt) = (record.samples(), record.dt());
    let mut d = Vec::with_capacity(a.len());
    let (mut vk, mut dk) = (0.0, 0.0);
    d.push(dk);
    for w in a.windows(2) {
        dk += vk * dt + dt * dt * (2.0 * w[0] + w[1]) / 6.0;
        vk += 0.5 * dt * (w[0] + w[1]);
        d.push(dk);
    }
    d
}

/// Arias intensity π/(2g) ∫a² dt, m/s (exact for the piecewise-linear record).
pub fn arias_intensity(record: &Record) -> f64 {
    std::f64::consts::PI / (2.0 * G) * cumulative_square(record).last().copied().unwrap_or(0.0)
}

/// ∫₀^{tₖ} a² dt at each sample, m²/s³.
fn cumulative_square(record: &Record) -> Vec<f64> {
    let (a, dt) = (record.samples(), record.dt());
    let mut c = Vec::with_capacity(a.len());
    let mut s = 0.0;
    c.push(s);
    for w in a.windows(2) {
        s += dt * (w[0] * w[0] + w[0] * w[1] + w[1] * w[1]) / 3.0;
        c.push(s);
    }
    c
}

/// Time (s) between the cumulative Arias intensity first reaching the fractions `from`
/// and `to` of its total (0 ≤ from < to ≤ 1); `(0.05, 0.95)` gives D5–95. A record with
/// no motion (all samples zero) gives 0.
///
/// Errors: [`MotionError::InvalidArgument`] unless 0 ≤ from < to ≤ 1.
pub fn significant_duration(record: &Record, from: f64, to: f64) -> Result<f64, MotionError> {
    if !(0.0..1.0).contains(&from) {
        return Err(MotionError::InvalidArgument {
            what: "lower Arias fraction",
            value: from,
            expected: "in [0, 1) and below the upper fraction",
        });
    }
    if !(to > from && to <= 1.0) {
        return Err(MotionError::InvalidArgument {
            what: "upper Arias fraction",
            value: to,
            expected: "in (lower fraction, 1]",
        });
    }
    let c = cumulative_square(record);
    let total = c.last().copied().unwrap_or(0.0);
    if total == 0.0 {
        return Ok(0.0);
    }
    Ok(crossing_time(record, &c, to * total) - crossing_time(record, &c, from * total))
}

/// First time (s) at which the cumulative ∫a² reaches `level` (0 ≤ level ≤ total).
fn crossing_time(record: &Record, c: &[f64], level: f64) -> f64 {
    let (a, dt) = (record.samples(), record.dt());
    // first sample index with c ≥ level; c is non-decreasing
    let k1 = c.partition_point(|&ck| ck < level);
    if k1 == 0 {
        return 0.0;
    }
    if k1 >= c.len() {
        return record.duration();
    }
    let k = k1 - 1;
    let (a0, slope) = (a[k], (a[k + 1] - a[k]) / dt);
    // ∫₀^s (a0 + slope σ)² dσ, non-decreasing in s
    let partial =
        |s: f64| c[k] + a0 * a0 * s + a0 * slope * s * s + slope * slope * s * s * s / 3.0;
    let (mut lo, mut hi) = (0.0, dt);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if partial(mid) < level {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    k as f64 * dt + hi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_acceleration_closed_forms() {
        // a = 2 m/s² for 1 s: v = 2t, d = t², ∫a² = 4t
        let r = Record::new("c", 0.1, vec![2.0; 11]).unwrap();
        let i = Intensity::of(&r);
        assert!((i.pgv_m_s - 2.0).abs() < 1e-14);
        assert!((i.pgd_m - 1.0).abs() < 1e-14);
        assert!((i.arias_m_s - std::f64::consts::PI / (2.0 * G) * 4.0).abs() < 1e-14);
        // uniform intensity: 5 % at 0.05 s, 95 % at 0.95 s
        assert!((i.d5_95_s - 0.9).abs() < 1e-12);
    }

    #[test]
    fn ramp_is_integrated_exactly() {
        // a = t on [0, 1]: v = t²/2, d = t³/6, ∫a² = t³/3, 5 % at t = 0.05^(1/3)
        let n = 10;
        let dt = 1.0 / n as f64;
        let r = Record::new("ramp", dt, (0..=n).map(|k| k as f64 * dt).collect()).unwrap();
        let v = ground_velocity(&r);
        let d = ground_displacement(&r);
        for k in 0..=n {
            let t = k as f64 * dt;
            assert!((v[k] - t * t / 2.0).abs() < 1e-15, "v at {t}");
            assert!((d[k] - t * t * t / 6.0).abs() < 1e-15, "d at {t}");
        }
        let expect = 0.95f64.cbrt() - 0.05f64.cbrt();
        assert!((significant_duration(&r, 0.05, 0.95).unwrap() - expect).abs() < 1e-13);
        assert!(significant_duration(&r, 0.5, 0.4).is_err());
    }

    #[test]
    fn silent_record_has_zero_duration() {
        let r = Record::new("z", 0.01, vec![0.0; 5]).unwrap();
        assert_eq!(Intensity::of(&r).d5_95_s, 0.0);
        assert_eq!(Intensity::of(&r).arias_m_s, 0.0);
    }
}
