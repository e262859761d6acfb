//! Scaling records and suites to a target.
//!
//! Contract:
//! * [`scale_to_spectral_acceleration`]: each record gets its own factor so that its
//!   pseudo-spectral acceleration at T₁ equals the target (to rounding);
//! * [`scale_suite_over_range`] (and [`scale_suite_asce7`], its range [0.2·T₁, 2.0·T₁]):
//!   one common factor for the whole suite, the smallest for which the suite's mean
//!   spectrum is at least 90 % of the target spectrum at **every** period of the range —
//!   the amplitude-scaling rule of ASCE 7-16 §16.2.3, applied to single-component records
//!   (pairs of components are scaled by their maximum-direction spectrum,
//!   [`crate::scale_pairs_over_range`]). The range is continuous, so the factor is found
//!   as the minimum of the ratio mean/target over it ([`smallest_factor`]): the ratio on a
//!   grid of [`SCALING_POINTS_PER_DECADE`] log-spaced periods per decade (plus the
//!   target's corner periods T₀, T_S, T_L inside the range), then a golden-section search
//!   of ln T between the neighbours of every local minimum of the grid within
//!   [`REFINE_MARGIN`] of the least. The factor is 0.9·target/mean at that minimum,
//!   rounded up by a few ulps so that the inequality also holds in floating point. Means
//!   are summed in record order (deterministic).
//! * The target is any [`Target`] (the ASCE 7-16 spectrum, a table, EN 1998-1); its
//!   corner periods join the grid, and a range outside its span is refused.
//! * [`scale_suite`] / [`crate::scale_pairs`] with a zero-period floor
//!   ([`ScalingOptions::zero_period_floor_m_s2`], EN 1998-1 §3.2.3.1.2(4)b: the mean of
//!   the records' zero-period spectral values, their PGAs, at least a_g·S): the factor is
//!   the larger of the spectral one and floor / mean PGA (rounded up as above), the
//!   smallest meeting both.

use crate::{DesignSpectrum, MotionError, Record, Spectrum, Target, log_spaced_periods};

/// Periods per decade of the scaling grid. A 5 %-damped oscillator's response to a record
/// changes on the scale of its half-power band, 2ζ ≈ 0.1 in ln T (Chopra, *Dynamics of
/// Structures*, §3.2.5), and so does a suite's mean spectrum; 200 per decade is a step of
/// 0.0115 in ln T, a ninth of that band, so that no dip of the mean spectrum falls between
/// two grid periods without lowering one of them. The refinement then finds the minimum
/// between them.
pub const SCALING_POINTS_PER_DECADE: usize = 200;

/// Local minima of the grid's ratio within this fraction of the least are refined: a
/// minimum between two grid periods lies below the better of them by far less than this
/// at the grid's step (crates/motion/tests/scaling.rs measures it), so no minimum that
/// could be the least is left out.
pub const REFINE_MARGIN: f64 = 0.05;

/// The width in ln T to which a minimum is refined (a relative precision of 10⁻⁸ in
/// period, where the ratio moves by less than 10⁻⁶ of itself).
const REFINE_TOLERANCE_LN_T: f64 = 1e-8;

/// The fraction of the target the mean spectrum must reach (ASCE 7-16 §16.2.3).
pub const ASCE7_FRACTION: f64 = 0.9;

/// The smallest factor that lifts a mean spectrum to 90 % of a target over a period range
/// ([`smallest_factor`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TargetMatch {
    /// The factor (dimensionless).
    pub factor: f64,
    /// The period where the scaled mean equals 90 % of the target, s.
    pub controlling_period_s: f64,
    /// The periods the mean was computed at, s, ascending: the grid, the target's corners
    /// and every period the refinement evaluated.
    pub periods_s: Vec<f64>,
    /// The unscaled mean there, m/s².
    pub mean_psa_m_s2: Vec<f64>,
    /// The target there, m/s².
    pub target_psa_m_s2: Vec<f64>,
    /// With a zero-period floor: the mean zero-period value and the floor.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub zero_period: Option<ZeroPeriod>,
}

/// The zero-period condition of a suite's scaling (EN 1998-1 §3.2.3.1.2(4)b).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ZeroPeriod {
    /// The unscaled mean of the records' zero-period spectral values (PGA; a pair's peak
    /// ground acceleration over every direction), each × its own factor, m/s².
    pub mean_m_s2: f64,
    /// The floor the scaled mean must reach, m/s².
    pub floor_m_s2: f64,
    /// Whether the floor sets the factor (else the spectral condition does).
    pub binds: bool,
}

/// How a suite is scaled beyond the 90 % rule ([`scale_suite`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ScalingOptions {
    /// Each record first fitted to the target by its own factor ([`fit_to_target`]).
    pub per_record: bool,
    /// The least mean zero-period spectral value (PGA) of the scaled suite, m/s²
    /// (EN 1998-1 §3.2.3.1.2(4)b: a_g·S); none by default.
    pub zero_period_floor_m_s2: Option<f64>,
}

/// The scaling grid of `range_s` (s): [`SCALING_POINTS_PER_DECADE`] log-spaced periods a
/// decade, both ends included (one period for a range of one).
fn scaling_grid(range_s: [f64; 2]) -> Result<Vec<f64>, MotionError> {
    let [lo, hi] = range_s;
    let count = if lo == hi {
        1
    } else {
        let decades = (hi / lo).log10();
        ((SCALING_POINTS_PER_DECADE as f64 * decades).ceil() as usize + 1).max(2)
    };
    log_spaced_periods(lo, hi, count)
}

/// The smallest factor, over `count` spectra each × `own[i]` (`spectrum(i, periods)` gives
/// spectrum i, m/s²), that lifts their mean to 90 % of `target` over `range_s`: the mean
/// summed in index order ([`smallest_factor`]).
pub(crate) fn weighted_match<T: Target + ?Sized>(
    own: &[f64],
    spectrum: impl Fn(usize, &[f64]) -> Result<Vec<f64>, MotionError>,
    target: &T,
    range_s: [f64; 2],
    floor_m_s2: Option<f64>,
) -> Result<TargetMatch, MotionError> {
    let n = own.len() as f64;
    let mean = |periods: &[f64]| -> Result<Vec<f64>, MotionError> {
        let mut sum = vec![0.0; periods.len()];
        for (i, a) in own.iter().enumerate() {
            for (m, sa) in sum.iter_mut().zip(&spectrum(i, periods)?) {
                *m += a * sa;
            }
        }
        Ok(sum.into_iter().map(|m| m / n).collect())
    };
    let mut m = smallest_factor(mean, target, range_s)?;
    if let Some(floor) = floor_m_s2 {
        if !(floor.is_finite() && floor > 0.0) {
            return Err(MotionError::InvalidArgument {
                what: "zero-period floor (m/s2)",
                value: floor,
                expected: "finite and > 0",
            });
        }
        let zero = mean(&[0.0])?[0];
        if zero.is_nan() || zero <= 0.0 {
            return Err(MotionError::ZeroMeasure {
                file: "suite mean PGA".into(),
                measure: "PGA",
            });
        }
        let f = floor / zero * (1.0 + 4.0 * f64::EPSILON);
        let binds = f > m.factor;
        if binds {
            m.factor = f;
            m.controlling_period_s = 0.0;
        }
        m.zero_period = Some(ZeroPeriod {
            mean_m_s2: zero,
            floor_m_s2: floor,
            binds,
        });
    }
    Ok(m)
}

/// The smallest factor f with f·mean(T) ≥ 0.9·target(T) for every T of `range_s`
/// (s, 0 < lower ≤ upper), where `mean` gives the (unscaled) mean spectrum, m/s², at a
/// list of periods (see the module docs for the search).
///
/// Errors: [`MotionError::InvalidArgument`] for a bad range, [`MotionError::ZeroMeasure`]
/// when the mean vanishes at a period of the range, and whatever `mean` returns.
pub fn smallest_factor<T: Target + ?Sized>(
    mean: impl Fn(&[f64]) -> Result<Vec<f64>, MotionError>,
    target: &T,
    range_s: [f64; 2],
) -> Result<TargetMatch, MotionError> {
    let [lo, hi] = range_s;
    let mut grid = scaling_grid(range_s)?;
    crate::check_span(target, range_s)?;
    for corner in target.corners_s() {
        if corner > lo && corner < hi {
            grid.push(corner);
        }
    }
    grid.sort_by(f64::total_cmp);
    grid.dedup();
    let ratio_of = |t: f64, m: f64| -> Result<f64, MotionError> {
        if m.is_nan() || m <= 0.0 {
            return Err(MotionError::ZeroMeasure {
                file: format!("suite mean spectrum at T = {t} s"),
                measure: "spectral acceleration",
            });
        }
        Ok(m / target.sa_m_s2(t))
    };
    let grid_mean = mean(&grid)?;
    let mut points: Vec<(f64, f64)> = grid.iter().copied().zip(grid_mean).collect();
    let ratios = points
        .iter()
        .map(|&(t, m)| ratio_of(t, m))
        .collect::<Result<Vec<f64>, _>>()?;
    let least = ratios.iter().copied().fold(f64::INFINITY, f64::min);
    let n = grid.len();
    for k in 0..n {
        let r = ratios[k];
        let local = (k == 0 || r <= ratios[k - 1]) && (k + 1 == n || r <= ratios[k + 1]);
        if !local || r > least * (1.0 + REFINE_MARGIN) || n == 1 {
            continue;
        }
        let (mut a, mut b) = (
            grid[k.saturating_sub(1)].ln(),
            grid[(k + 1).min(n - 1)].ln(),
        );
        // golden-section search of the ratio in ln T; every evaluation is kept
        let shrink = (5f64.sqrt() - 1.0) / 2.0;
        let eval = |x: f64, points: &mut Vec<(f64, f64)>| -> Result<f64, MotionError> {
            let t = x.exp().clamp(lo, hi);
            let m = mean(&[t])?[0];
            points.push((t, m));
            ratio_of(t, m)
        };
        let mut c = b - shrink * (b - a);
        let mut d = a + shrink * (b - a);
        let mut fc = eval(c, &mut points)?;
        let mut fd = eval(d, &mut points)?;
        while b - a > REFINE_TOLERANCE_LN_T {
            if fc <= fd {
                b = d;
                d = c;
                fd = fc;
                c = b - shrink * (b - a);
                fc = eval(c, &mut points)?;
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + shrink * (b - a);
                fd = eval(d, &mut points)?;
            }
        }
    }
    points.sort_by(|x, y| x.0.total_cmp(&y.0));
    points.dedup_by(|x, y| x.0 == y.0);
    let mut factor = 0.0;
    let mut controlling = points[0].0;
    for &(t, m) in &points {
        let f = ASCE7_FRACTION * target.sa_m_s2(t) / m;
        if f > factor {
            factor = f;
            controlling = t;
        }
    }
    // a few ulps up so that mean·factor ≥ 0.9·target survives the rounding of the product
    factor *= 1.0 + 4.0 * f64::EPSILON;
    Ok(TargetMatch {
        factor,
        controlling_period_s: controlling,
        target_psa_m_s2: points.iter().map(|&(t, _)| target.sa_m_s2(t)).collect(),
        mean_psa_m_s2: points.iter().map(|&(_, m)| m).collect(),
        periods_s: points.into_iter().map(|(t, _)| t).collect(),
        zero_period: None,
    })
}

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

/// The outcome of [`scale_suite_over_range`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Asce7Scaling {
    /// The common factor applied to every record (dimensionless).
    pub factor: f64,
    /// The period where the scaled mean equals 90 % of the target, s.
    pub controlling_period_s: f64,
    /// The periods the mean was computed at, s ([`TargetMatch::periods_s`]).
    pub periods_s: Vec<f64>,
    /// Mean pseudo-spectral acceleration of the unscaled suite there (each record at its
    /// own factor, with per-record factors), m/s².
    pub mean_psa_m_s2: Vec<f64>,
    /// Target spectrum there, m/s².
    pub target_psa_m_s2: Vec<f64>,
    /// With a zero-period floor: the mean PGA and the floor ([`TargetMatch::zero_period`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub zero_period: Option<ZeroPeriod>,
    /// The scaled records (every factor equal to `factor`, or with per-record factors
    /// each record's own times it).
    pub suite: ScaledSuite,
}

/// Scales `records` by one common factor so that their mean spectrum (damping ratio
/// `damping`) is at least 90 % of `target` over [0.2·t1_s, 2.0·t1_s]
/// ([`scale_suite_over_range`]).
///
/// Errors: as [`scale_suite_over_range`], and [`MotionError::InvalidArgument`] for a bad T₁.
pub fn scale_suite_asce7(
    records: &[Record],
    target: &DesignSpectrum,
    t1_s: f64,
    damping: f64,
) -> Result<Asce7Scaling, MotionError> {
    if !(t1_s.is_finite() && t1_s > 0.0) {
        return Err(MotionError::InvalidArgument {
            what: "T1 (s)",
            value: t1_s,
            expected: "finite and > 0",
        });
    }
    scale_suite_over_range(records, target, [0.2 * t1_s, 2.0 * t1_s], damping)
}

/// Scales `records` by one common factor, the smallest for which their mean spectrum
/// (damping ratio `damping`) is at least 90 % of `target` at every period of `range_s`
/// (see the module docs).
///
/// Errors: [`MotionError::InvalidArgument`] for no records or a bad range or damping,
/// [`MotionError::ZeroMeasure`] when the mean spectrum vanishes somewhere in the range.
pub fn scale_suite_over_range(
    records: &[Record],
    target: &DesignSpectrum,
    range_s: [f64; 2],
    damping: f64,
) -> Result<Asce7Scaling, MotionError> {
    scale_weighted(
        records,
        &vec![1.0; records.len()],
        target,
        range_s,
        damping,
        None,
    )
}

/// Scales `records` to `target` over `range_s` as `options` say: one factor for all
/// ([`scale_suite_over_range`]) or each record's own first ([`scale_suite_over_range_each`]),
/// with or without a zero-period floor (module docs).
///
/// Errors: as [`scale_suite_over_range`], [`MotionError::OutsideSpectrum`] for a range
/// outside the target's span, [`MotionError::InvalidArgument`] for a bad floor.
pub fn scale_suite<T: Target + ?Sized>(
    records: &[Record],
    target: &T,
    range_s: [f64; 2],
    damping: f64,
    options: &ScalingOptions,
) -> Result<Asce7Scaling, MotionError> {
    let own = if options.per_record {
        own_factors(records, target, range_s, damping)?
    } else {
        vec![1.0; records.len()]
    };
    scale_weighted(
        records,
        &own,
        target,
        range_s,
        damping,
        options.zero_period_floor_m_s2,
    )
}

/// `records`, record i first × `own[i]`, then all by the smallest common factor for which
/// their mean spectrum meets 90 % of `target` over `range_s` (× 1 is exact: with every
/// `own` 1 this is one factor for all, to the bit).
fn scale_weighted<T: Target + ?Sized>(
    records: &[Record],
    own: &[f64],
    target: &T,
    range_s: [f64; 2],
    damping: f64,
    floor_m_s2: Option<f64>,
) -> Result<Asce7Scaling, MotionError> {
    if records.is_empty() {
        return Err(MotionError::InvalidArgument {
            what: "number of records",
            value: 0.0,
            expected: "at least 1",
        });
    }
    let m = weighted_match(
        own,
        |i, periods| Ok(Spectrum::compute(&records[i], damping, periods)?.psa_m_s2),
        target,
        range_s,
        floor_m_s2,
    )?;
    let factors: Vec<f64> = own.iter().map(|a| a * m.factor).collect();
    let scaled = records
        .iter()
        .zip(&factors)
        .map(|(r, f)| r.try_scaled(*f))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Asce7Scaling {
        factor: m.factor,
        controlling_period_s: m.controlling_period_s,
        periods_s: m.periods_s,
        mean_psa_m_s2: m.mean_psa_m_s2,
        target_psa_m_s2: m.target_psa_m_s2,
        zero_period: m.zero_period,
        suite: ScaledSuite {
            factors,
            records: scaled,
        },
    })
}

/// The factor that fits a spectrum to `target` over `range_s` (s): exp of the mean of
/// ln(target/Sa) on the scaling grid's periods (log-spaced, [`SCALING_POINTS_PER_DECADE`]
/// a decade), the least-squares fit of ln Sa — each record's own factor before a suite's
/// common one ([`scale_suite_over_range_each`]). `spectrum` gives Sa, m/s², at a list of
/// periods.
///
/// Errors: [`MotionError::InvalidArgument`] for a bad range, [`MotionError::ZeroMeasure`]
/// when the spectrum vanishes at a period of the range, and whatever `spectrum` returns.
pub fn fit_to_target<T: Target + ?Sized>(
    spectrum: impl Fn(&[f64]) -> Result<Vec<f64>, MotionError>,
    target: &T,
    range_s: [f64; 2],
) -> Result<f64, MotionError> {
    let grid = scaling_grid(range_s)?;
    crate::check_span(target, range_s)?;
    let sa = spectrum(&grid)?;
    let mut sum = 0.0;
    for (&t, &a) in grid.iter().zip(&sa) {
        if a.is_nan() || a <= 0.0 {
            return Err(MotionError::ZeroMeasure {
                file: format!("record spectrum at T = {t} s"),
                measure: "spectral acceleration",
            });
        }
        sum += (target.sa_m_s2(t) / a).ln();
    }
    Ok((sum / grid.len() as f64).exp())
}

/// Scales `records` as the per-record option of a code-scaled suite does: each first by
/// its own factor aᵢ, the fit of its spectrum (damping ratio `damping`) to `target` over
/// `range_s` ([`fit_to_target`]), then all by one common factor, the smallest for which the
/// mean of the fitted spectra is at least 90 % of the target at every period of the range
/// ([`smallest_factor`]). `factor` is that common factor; `suite.factors` each record's
/// product of the two.
///
/// Errors: as [`scale_suite_over_range`].
pub fn scale_suite_over_range_each(
    records: &[Record],
    target: &DesignSpectrum,
    range_s: [f64; 2],
    damping: f64,
) -> Result<Asce7Scaling, MotionError> {
    let own = own_factors(records, target, range_s, damping)?;
    scale_weighted(records, &own, target, range_s, damping, None)
}

/// Each record's own factor, its fit to `target` over `range_s` ([`fit_to_target`]).
fn own_factors<T: Target + ?Sized>(
    records: &[Record],
    target: &T,
    range_s: [f64; 2],
    damping: f64,
) -> Result<Vec<f64>, MotionError> {
    records
        .iter()
        .map(|r| {
            fit_to_target(
                |t: &[f64]| Ok(Spectrum::compute(r, damping, t)?.psa_m_s2),
                target,
                range_s,
            )
        })
        .collect()
}
