//! Scaling records and suites to a target.
//!
//! Contract:
//! * [`scale_to_spectral_acceleration`]: each record gets its own factor so that its
//!   pseudo-spectral acceleration at T₁ equals the target (to rounding);
//! * [`scale_suite_asce7`]: one common factor for the whole suite, the smallest for which
//!   the suite's mean spectrum is at least 90 % of the target spectrum at every period of
//!   a grid of [`ASCE7_PERIOD_POINTS`] log-spaced periods over [0.2·T₁, 2.0·T₁] — the
//!   period range and amplitude-scaling rule of ASCE 7-16 §16.2.3, applied to single-component records (ASCE 7-16 itself uses the maximum-direction
//!   spectra of horizontal pairs, and an MCE_R target). The factor is
//!   max over the grid of 0.9·target/mean, rounded up by a few ulps so that the inequality
//!   also holds in floating point. Means are summed in record order (deterministic).

use crate::{DesignSpectrum, MotionError, Record, Spectrum, log_spaced_periods};

/// Periods per scaling grid over [0.2·T₁, 2·T₁] (one decade): 50 per decade, finer than
/// the ≈ 10 % half-power width of a 5 %-damped spectral peak.
pub const ASCE7_PERIOD_POINTS: usize = 50;
/// The fraction of the target the mean spectrum must reach (ASCE 7-16 §16.2.3).
pub const ASCE7_FRACTION: f64 = 0.9;

/// Records scaled by the factors that were applied to them.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ScaledSuite {
    /// The scaled records, in input order.
    pub records: Vec<Record>,
    /// The factor applied to each record (dimensionless), in input order.
    pub factors: Vec<f64>,
}

/// Each record scaled to pseudo-spectral acceleration `target_m_s2` (m/s²) at
/// `period_s` (s) for damping ratio `damping`.
///
/// Errors: [`MotionError::InvalidArgument`] for a negative or non-finite target or a bad
/// period/damping, [`MotionError::ZeroMeasure`] for a record with zero response.
pub fn scale_to_spectral_acceleration(
    records: &[Record],
    period_s: f64,
    damping: f64,
    target_m_s2: f64,
) -> Result<ScaledSuite, MotionError> {
    if !(target_m_s2.is_finite() && target_m_s2 >= 0.0) {
        return Err(MotionError::InvalidArgument {
            what: "target spectral acceleration (m/s2)",
            value: target_m_s2,
            expected: "finite and >= 0",
        });
    }
    let mut suite = ScaledSuite {
        records: Vec::with_capacity(records.len()),
        factors: Vec::with_capacity(records.len()),
    };
    for r in records {
        let sa = crate::spectral_acceleration(r, period_s, damping)?;
        if sa == 0.0 {
            return Err(MotionError::ZeroMeasure {
                file: r.name().to_string(),
                measure: "spectral acceleration",
            });
        }
        let factor = target_m_s2 / sa;
        suite.records.push(r.try_scaled(factor)?);
        suite.factors.push(factor);
    }
    Ok(suite)
}

/// The outcome of [`scale_suite_asce7`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Asce7Scaling {
    /// The common factor applied to every record (dimensionless).
    pub factor: f64,
    /// The period where the scaled mean equals 90 % of the target, s.
    pub controlling_period_s: f64,
    /// The period grid, s.
    pub periods_s: Vec<f64>,
    /// Mean pseudo-spectral acceleration of the unscaled suite on the grid, m/s².
    pub mean_psa_m_s2: Vec<f64>,
    /// Target spectrum on the grid, m/s².
    pub target_psa_m_s2: Vec<f64>,
    /// The scaled records (every factor equal to `factor`).
    pub suite: ScaledSuite,
}

/// Scales `records` by one common factor so that their mean spectrum (damping ratio
/// `damping`) is at least 90 % of `target` over [0.2·t1_s, 2.0·t1_s] (see the module
/// docs).
///
/// Errors: [`MotionError::InvalidArgument`] for no records or a bad T₁ or damping,
/// [`MotionError::ZeroMeasure`] when the mean spectrum vanishes somewhere on the grid.
pub fn scale_suite_asce7(
    records: &[Record],
    target: &DesignSpectrum,
    t1_s: f64,
    damping: f64,
) -> Result<Asce7Scaling, MotionError> {
    if records.is_empty() {
        return Err(MotionError::InvalidArgument {
            what: "number of records",
            value: 0.0,
            expected: "at least 1",
        });
    }
    if !(t1_s.is_finite() && t1_s > 0.0) {
        return Err(MotionError::InvalidArgument {
            what: "T1 (s)",
            value: t1_s,
            expected: "finite and > 0",
        });
    }
    let periods = log_spaced_periods(0.2 * t1_s, 2.0 * t1_s, ASCE7_PERIOD_POINTS)?;
    let mut mean = vec![0.0; periods.len()];
    for r in records {
        let s = Spectrum::compute(r, damping, &periods)?;
        for (m, sa) in mean.iter_mut().zip(&s.psa_m_s2) {
            *m += sa;
        }
    }
    let n = records.len() as f64;
    mean.iter_mut().for_each(|m| *m /= n);
    let target_sa: Vec<f64> = periods.iter().map(|&t| target.sa_m_s2(t)).collect();
    let mut factor = 0.0;
    let mut controlling = periods[0];
    for ((&t, &m), &s) in periods.iter().zip(&mean).zip(&target_sa) {
        if m == 0.0 {
            return Err(MotionError::ZeroMeasure {
                file: "suite mean spectrum".to_string(),
                measure: "spectral acceleration",
            });
        }
        let f = ASCE7_FRACTION * s / m;
        if f > factor {
            factor = f;
            controlling = t;
        }
    }
    // a few ulps up so that mean·factor ≥ 0.9·target survives the rounding of the product
    factor *= 1.0 + 4.0 * f64::EPSILON;
    let scaled = records
        .iter()
        .map(|r| r.try_scaled(factor))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Asce7Scaling {
        factor,
        controlling_period_s: controlling,
        periods_s: periods,
        mean_psa_m_s2: mean,
        target_psa_m_s2: target_sa,
        suite: ScaledSuite {
            factors: vec![factor; scaled.len()],
            records: scaled,
        },
    })
}
