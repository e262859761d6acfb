//! Elastic response spectra of a record.
//!
//! Contract: for each period T and damping ratio ζ, the relative displacement u of the
//! SDOF oscillator ü + 2ζωu̇ + ω²u = −a_g(t), ω = 2π/T, starting at rest, is integrated
//! **exactly** for the piecewise-linear record by the Nigam–Jennings (1969) recurrence
//! (see `propagator.rs`). When T < 10·dt each record step is split into
//! n = ⌈10·dt/T⌉ equal sub-steps (the input is interpolated linearly, so this is still
//! exact) so that the peak is sampled at least ten times per period. The spectral
//! displacement Sd = max |u| over the (sub-)step points within the record's duration (no
//! free-vibration tail after the last sample); pseudo-velocity PSV = ω·Sd and
//! pseudo-acceleration PSA = ω²·Sd. At T = 0 the oscillator is rigid: PSA = PGA,
//! Sd = PSV = 0. Peaks between (sub-)steps are not searched for; with ≥ 10 points per
//! period they are at most 1 − cos(π/10) ≈ 5 % high, typically far less.

use crate::propagator::Propagator;
use crate::{MotionError, Record};

/// The default damping ratio of a response spectrum (5 % of critical).
pub const DEFAULT_DAMPING: f64 = 0.05;

/// A response spectrum: peak responses of linear oscillators of one damping ratio.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Spectrum {
    /// Damping ratio ζ (fraction of critical).
    pub damping: f64,
    /// Periods, s.
    pub periods_s: Vec<f64>,
    /// Spectral (relative) displacement Sd, m.
    pub sd_m: Vec<f64>,
    /// Pseudo-spectral velocity ω·Sd, m/s.
    pub psv_m_s: Vec<f64>,
    /// Pseudo-spectral acceleration ω²·Sd, m/s².
    pub psa_m_s2: Vec<f64>,
}

impl Spectrum {
    /// The spectrum of `record` for damping ratio `damping` (finite, ≥ 0) at `periods_s`
    /// (s, each finite and ≥ 0).
    ///
    /// Errors: [`MotionError::InvalidArgument`] for a bad damping ratio or period, or a
    /// period in (0, dt/1000) (over 10⁴ sub-steps per sample).
    pub fn compute(
        record: &Record,
        damping: f64,
        periods_s: &[f64],
    ) -> Result<Spectrum, MotionError> {
        Spectrum::from_peaks(
            damping,
            periods_s,
            || record.pga(),
            |t| peak_displacement(record, t, damping),
        )
    }

    /// The spectrum of the peak relative displacements `peak(T)` (called at every period,
    /// T = 0 included, so its checks hold there too): Sd, PSV = ω·Sd, PSA = ω²·Sd, and at
    /// T = 0 the peak ground acceleration `pga()` (m/s², asked only there).
    pub(crate) fn from_peaks(
        damping: f64,
        periods_s: &[f64],
        pga: impl Fn() -> f64,
        mut peak: impl FnMut(f64) -> Result<f64, MotionError>,
    ) -> Result<Spectrum, MotionError> {
        let mut s = Spectrum {
            damping,
            periods_s: periods_s.to_vec(),
            sd_m: Vec::with_capacity(periods_s.len()),
            psv_m_s: Vec::with_capacity(periods_s.len()),
            psa_m_s2: Vec::with_capacity(periods_s.len()),
        };
        for &t in periods_s {
            let peak = peak(t)?;
            if t == 0.0 {
                s.sd_m.push(0.0);
                s.psv_m_s.push(0.0);
                s.psa_m_s2.push(pga());
            } else {
                let omega = 2.0 * std::f64::consts::PI / t;
                s.sd_m.push(peak);
                s.psv_m_s.push(omega * peak);
                s.psa_m_s2.push(omega * omega * peak);
            }
        }
        Ok(s)
    }
}

/// Pseudo-spectral acceleration ω²·Sd (m/s²) of `record` at one period (s) and damping
/// ratio; PGA at T = 0. Errors as [`Spectrum::compute`].
pub fn spectral_acceleration(
    record: &Record,
    period_s: f64,
    damping: f64,
) -> Result<f64, MotionError> {
    Ok(Spectrum::compute(record, damping, &[period_s])?.psa_m_s2[0])
}

/// Relative displacement u (m) of the oscillator at every sample of `record`
/// (sub-steps, if any, are integrated but not returned); u = 0 at T = 0.
/// Errors as [`Spectrum::compute`].
pub fn sdof_displacement(
    record: &Record,
    period_s: f64,
    damping: f64,
) -> Result<Vec<f64>, MotionError> {
    let mut u = Vec::with_capacity(record.len());
    integrate(record, period_s, damping, |at_sample, x| {
        if at_sample {
            u.push(x);
        }
    })?;
    Ok(u)
}

/// `count` periods (s) spaced evenly in log T from `min_s` to `max_s`, both included.
///
/// Errors: [`MotionError::InvalidArgument`] unless 0 < min ≤ max (finite) and count ≥ 2
/// (count = 1 requires min = max).
pub fn log_spaced_periods(min_s: f64, max_s: f64, count: usize) -> Result<Vec<f64>, MotionError> {
    if !(min_s.is_finite() && min_s > 0.0 && max_s.is_finite() && max_s >= min_s) {
        return Err(MotionError::InvalidArgument {
            what: "period range (s)",
            value: if min_s.is_finite() && min_s > 0.0 {
                max_s
            } else {
                min_s
            },
            expected: "0 < min <= max, finite",
        });
    }
    if count == 0 || (count == 1 && min_s != max_s) {
        return Err(MotionError::InvalidArgument {
            what: "number of periods",
            value: count as f64,
            expected: ">= 2 (or 1 when min = max)",
        });
    }
    if count == 1 {
        return Ok(vec![min_s]);
    }
    let (l0, l1) = (min_s.ln(), max_s.ln());
    let mut p: Vec<f64> = (0..count)
        .map(|k| (l0 + (l1 - l0) * k as f64 / (count - 1) as f64).exp())
        .collect();
    // the ends exactly as given
    p[0] = min_s;
    p[count - 1] = max_s;
    Ok(p)
}

/// The default period list: 0.02 s to 5 s, 60 periods log-spaced (about 25 per decade,
/// enough to resolve a 5 %-damped peak's half-power width of ≈ 10 % in period).
pub fn default_periods() -> Vec<f64> {
    log_spaced_periods(0.02, 5.0, 60).expect("constant, valid period range")
}

/// Most sub-steps per record step (T ≥ dt/1000).
const MAX_SUBSTEPS: usize = 10_000;

/// max |u| over all (sub-)step points, m (0 at T = 0).
fn peak_displacement(record: &Record, period_s: f64, damping: f64) -> Result<f64, MotionError> {
    let mut peak = 0.0f64;
    integrate(record, period_s, damping, |_, x| peak = peak.max(x.abs()))?;
    Ok(peak)
}

/// Largest damping ratio of a spectrum's oscillator (ratios beyond 1–2 are overdamped;
/// beyond 10 is a units slip, and the answer would be a meaningless zero).
pub const MAX_SPECTRUM_DAMPING: f64 = 10.0;

/// Longest period of a spectrum's oscillator, s (the physical band of building periods
/// ends at 10⁴ s; beyond it the oscillator only follows the ground).
pub const MAX_SPECTRUM_PERIOD_S: f64 = 1e4;

/// Runs the oscillator through the record, calling `visit(at_sample, u)` at t = 0 and after
/// every (sub-)step.
fn integrate(
    record: &Record,
    period_s: f64,
    damping: f64,
    mut visit: impl FnMut(bool, f64),
) -> Result<(), MotionError> {
    integrate_components(
        [record.samples()],
        record.dt(),
        period_s,
        damping,
        |at, [u]| visit(at, u),
    )
}

/// Runs one oscillator through each of N components sampled at `dt` (s) at once, calling
/// `visit(at_sample, [u₁ … u_N])` at t = 0 and after every (sub-)step. The run lasts as long
/// as the longest component; a shorter one is at rest (zero) after its last sample. Each
/// component's response is what [`integrate`] gives for it alone, operation for operation.
pub(crate) fn integrate_components<const N: usize>(
    components: [&[f64]; N],
    dt: f64,
    period_s: f64,
    damping: f64,
    mut visit: impl FnMut(bool, [f64; N]),
) -> Result<(), MotionError> {
    if !(damping.is_finite() && (0.0..=MAX_SPECTRUM_DAMPING).contains(&damping)) {
        return Err(MotionError::InvalidArgument {
            what: "damping ratio",
            value: damping,
            expected: "finite, >= 0 and at most 10 (beyond any structure's damping)",
        });
    }
    if !(period_s.is_finite() && (0.0..=MAX_SPECTRUM_PERIOD_S).contains(&period_s)) {
        return Err(MotionError::InvalidArgument {
            what: "period (s)",
            value: period_s,
            expected: "finite, >= 0 and at most 1e4 s (beyond any structure's period)",
        });
    }
    let len = components.iter().map(|c| c.len()).max().unwrap_or(0);
    let sample = |c: &[f64], j: usize| c.get(j).copied().unwrap_or(0.0);
    if period_s == 0.0 {
        (0..len).for_each(|_| visit(true, [0.0; N]));
        return Ok(());
    }
    let omega = 2.0 * std::f64::consts::PI / period_s;
    let ratio = (10.0 * dt / period_s).ceil();
    if ratio > MAX_SUBSTEPS as f64 {
        return Err(MotionError::InvalidArgument {
            what: "period (s)",
            value: period_s,
            expected: "at least dt/1000 (shorter periods need over 10^4 sub-steps per sample; use T = 0 for the rigid limit)",
        });
    }
    let substeps = (ratio as usize).max(1);
    let h = dt / substeps as f64;
    // Dimensionless form: x₁ = ω²u, x₂ = ω u̇, τ = ωt, input p = −a_g:
    // x₁' = x₂, x₂' = −x₁ − 2ζx₂ + p. Balanced entries keep the exponential accurate.
    let prop = Propagator::new([[0.0, 1.0], [-1.0, -2.0 * damping]], [0.0, 1.0], omega * h);
    let to_u = 1.0 / (omega * omega);
    let mut x = [[0.0, 0.0]; N];
    visit(true, [0.0; N]);
    for k in 1..len {
        let mut p_start: [f64; N] = std::array::from_fn(|c| -sample(components[c], k - 1));
        for j in 1..=substeps {
            let mut u = [0.0; N];
            for c in 0..N {
                let (a0, a1) = (sample(components[c], k - 1), sample(components[c], k));
                let p_end = if j == substeps {
                    -a1
                } else {
                    -(a0 + (a1 - a0) * j as f64 / substeps as f64)
                };
                x[c] = prop.step(&x[c], p_start[c], p_end);
                u[c] = x[c][0] * to_u;
                p_start[c] = p_end;
            }
            visit(j == substeps, u);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn period_list() {
        let p = default_periods();
        assert_eq!(p.len(), 60);
        assert_eq!((p[0], p[59]), (0.02, 5.0));
        assert!(p.windows(2).all(|w| w[1] > w[0]));
        assert!(log_spaced_periods(0.0, 1.0, 5).is_err());
        assert!(log_spaced_periods(0.1, 1.0, 1).is_err());
    }

    #[test]
    fn rigid_oscillator_follows_the_ground() {
        let r = Record::new("r", 0.01, vec![0.0, 1.0, -3.0, 2.0]).unwrap();
        let s = Spectrum::compute(&r, 0.05, &[0.0]).unwrap();
        assert_eq!(s.psa_m_s2[0], 3.0);
        assert!(Spectrum::compute(&r, -0.1, &[1.0]).is_err());
        assert!(Spectrum::compute(&r, 0.05, &[f64::NAN]).is_err());
    }
}
