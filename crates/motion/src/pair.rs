//! Pairs of horizontal components of one event, their maximum-direction spectrum, and
//! suites of pairs scaled to a target by it.
//!
//! Contract:
//! * a [`RecordPair`] is two components sampled at the same dt (the shorter is at rest
//!   after its last sample); [`RecordPair::rotated`] is the component along azimuth θ from
//!   the first, a_θ = a₁ cos θ + a₂ sin θ;
//! * [`rotd100_spectrum`] is the maximum-direction spectrum RotD100 (Boore, 2010, *BSSA*
//!   100(4), 1830–1835): per period, the peak over rotation angles θ of the peak response
//!   of the oscillator to a_θ. The oscillator is linear, so its response to a_θ is
//!   u_θ(t) = u₁(t) cos θ + u₂(t) sin θ, whose largest |u_θ(t)| over θ is the length of
//!   (u₁(t), u₂(t)): RotD100 Sd = max over t of √(u₁² + u₂²), exactly — over every angle,
//!   not a grid of them (peaks sampled at the same (sub-)step points as [`crate::Spectrum`]);
//!   PSA = ω²·Sd. At T = 0, the peak length of the ground-acceleration vector.
//! * [`scale_pairs_over_range`]: one factor for every pair, the smallest for which the
//!   suite's mean RotD100 spectrum is at least 90 % of the target at every period of the
//!   range (ASCE 7-22 §16.2.3.2, as [`crate::smallest_factor`] finds it).

use crate::spectrum::integrate_components;
use crate::{DesignSpectrum, MotionError, Record, ScalingOptions, Spectrum, Target, TargetMatch};

/// The two horizontal components of one event.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RecordPair {
    name: String,
    first: Record,
    second: Record,
}

impl RecordPair {
    /// The pair `name` of components `first` and `second`.
    ///
    /// Errors: [`MotionError::PairMismatch`] when their sample intervals differ.
    pub fn new(
        name: impl Into<String>,
        first: Record,
        second: Record,
    ) -> Result<RecordPair, MotionError> {
        let name = name.into();
        // the same dt to 1e-9 of itself: the headers' rounding, not another interval
        if (first.dt() - second.dt()).abs() > 1e-9 * first.dt() {
            return Err(MotionError::PairMismatch {
                pair: name,
                reason: format!(
                    "{} is sampled at dt = {} s and {} at dt = {} s: the two components of one event share a time axis",
                    first.name(),
                    first.dt(),
                    second.name(),
                    second.dt()
                ),
            });
        }
        Ok(RecordPair {
            name,
            first,
            second,
        })
    }

    /// The pair's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The first component.
    pub fn first(&self) -> &Record {
        &self.first
    }

    /// The second component.
    pub fn second(&self) -> &Record {
        &self.second
    }

    /// Both components × `factor` ([`Record::try_scaled`]).
    pub fn try_scaled(&self, factor: f64) -> Result<RecordPair, MotionError> {
        Ok(RecordPair {
            name: self.name.clone(),
            first: self.first.try_scaled(factor)?,
            second: self.second.try_scaled(factor)?,
        })
    }

    /// The component along azimuth `theta_rad` from the first component towards the second:
    /// a₁ cos θ + a₂ sin θ, as long as the longer component (the shorter is zero after its
    /// end), named `NAME@θ°`.
    pub fn rotated(&self, theta_rad: f64) -> Result<Record, MotionError> {
        self.along(
            theta_rad.cos(),
            theta_rad.sin(),
            format!("{}@{}deg", self.name, theta_rad.to_degrees()),
        )
    }

    /// The component along azimuth `theta_deg` degrees, as [`RecordPair::rotated`], with
    /// cos θ and sin θ exact (0 or ±1) at multiples of 90°, so that 0° is the first
    /// component and 90° the second to the bit; named `NAME@θdeg`.
    pub fn rotated_deg(&self, theta_deg: f64) -> Result<Record, MotionError> {
        let quarter = theta_deg / 90.0;
        let (c, s) = if quarter == quarter.round() && quarter.abs() < 1e6 {
            // the quarter turn's index mod 4: (cos, sin) of 0°, 90°, 180°, 270°
            match (quarter as i64).rem_euclid(4) {
                0 => (1.0, 0.0),
                1 => (0.0, 1.0),
                2 => (-1.0, 0.0),
                _ => (0.0, -1.0),
            }
        } else {
            let t = theta_deg.to_radians();
            (t.cos(), t.sin())
        };
        self.along(c, s, format!("{}@{}deg", self.name, theta_deg))
    }

    /// a₁ c + a₂ s over the longer component's length, named `name`; its scale factor is
    /// the components' when they share one (a scaled pair's), else 1.
    fn along(&self, c: f64, s: f64, name: String) -> Result<Record, MotionError> {
        let (a, b) = (self.first.samples(), self.second.samples());
        let len = a.len().max(b.len());
        let at = |x: &[f64], j: usize| x.get(j).copied().unwrap_or(0.0);
        let samples = (0..len).map(|j| at(a, j) * c + at(b, j) * s).collect();
        let (f1, f2) = (self.first.scale_factor(), self.second.scale_factor());
        let factor = if (f1 - f2).abs() <= 1e-12 * f1.abs() {
            f1
        } else {
            1.0
        };
        let provenance = format!(
            "{} × {c} + {} × {s} (the pair {} rotated)",
            self.first.name(),
            self.second.name(),
            self.name
        );
        Ok(Record::new(name, self.first.dt(), samples)?
            .with_scale_factor(factor)
            .with_provenance(provenance))
    }
}

/// The maximum-direction (RotD100) spectrum of `pair` for damping ratio
/// `damping` at `periods_s` (see the module docs): Sd, PSV = ω·Sd, PSA = ω²·Sd.
///
/// Errors: as [`Spectrum::compute`].
pub fn rotd100_spectrum(
    pair: &RecordPair,
    damping: f64,
    periods_s: &[f64],
) -> Result<Spectrum, MotionError> {
    let (a, b) = (pair.first.samples(), pair.second.samples());
    // the largest ground acceleration over every direction, the T = 0 ordinate (a shorter
    // component at rest after its end)
    let at = |x: &[f64], j: usize| x.get(j).copied().unwrap_or(0.0);
    let pga = || (0..a.len().max(b.len())).fold(0.0f64, |m, j| m.max(at(a, j).hypot(at(b, j))));
    Spectrum::from_peaks(damping, periods_s, pga, |t| {
        let mut peak = 0.0f64;
        integrate_components([a, b], pair.first.dt(), t, damping, |_, [u, v]| {
            peak = peak.max(u.hypot(v));
        })?;
        Ok(peak)
    })
}

/// Pairs scaled by one common factor ([`scale_pairs_over_range`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PairScaling {
    /// The factor, the controlling period and the mean RotD100 spectrum (unscaled) beside
    /// the target.
    pub matched: TargetMatch,
    /// The scaled pairs, in input order.
    pub pairs: Vec<RecordPair>,
}

/// Scales `pairs` by one common factor, the smallest for which their mean RotD100
/// spectrum (damping ratio `damping`) is at least 90 % of `target` at every period of
/// `range_s` (s).
///
/// Errors: [`MotionError::InvalidArgument`] for no pairs or a bad range or damping,
/// [`MotionError::ZeroMeasure`] when the mean vanishes somewhere in the range.
pub fn scale_pairs_over_range(
    pairs: &[RecordPair],
    target: &DesignSpectrum,
    range_s: [f64; 2],
    damping: f64,
) -> Result<PairScaling, MotionError> {
    scale_pairs_weighted(
        pairs,
        &vec![1.0; pairs.len()],
        target,
        range_s,
        damping,
        None,
    )
}

/// Scales `pairs` to `target` over `range_s` as `options` say: one factor for all
/// ([`scale_pairs_over_range`]) or each pair's own first ([`scale_pairs_over_range_each`]),
/// with or without a zero-period floor on the mean of the pairs' peak ground acceleration
/// over every direction (their RotD100 at T = 0; [`crate::scale_suite`]).
///
/// Errors: as [`crate::scale_suite`].
pub fn scale_pairs<T: Target + ?Sized>(
    pairs: &[RecordPair],
    target: &T,
    range_s: [f64; 2],
    damping: f64,
    options: &ScalingOptions,
) -> Result<PairScaling, MotionError> {
    let own = if options.per_record {
        own_pair_factors(pairs, target, range_s, damping)?
    } else {
        vec![1.0; pairs.len()]
    };
    scale_pairs_weighted(
        pairs,
        &own,
        target,
        range_s,
        damping,
        options.zero_period_floor_m_s2,
    )
}

/// `pairs`, pair i first × `own[i]`, then all by the smallest common factor for which their
/// mean RotD100 spectrum meets 90 % of `target` over `range_s` (× 1 is exact: with every
/// `own` 1 this is one factor for all, to the bit).
fn scale_pairs_weighted<T: Target + ?Sized>(
    pairs: &[RecordPair],
    own: &[f64],
    target: &T,
    range_s: [f64; 2],
    damping: f64,
    floor_m_s2: Option<f64>,
) -> Result<PairScaling, MotionError> {
    if pairs.is_empty() {
        return Err(MotionError::InvalidArgument {
            what: "number of record pairs",
            value: 0.0,
            expected: "at least 1",
        });
    }
    let matched = crate::scaling::weighted_match(
        own,
        |i, periods| Ok(rotd100_spectrum(&pairs[i], damping, periods)?.psa_m_s2),
        target,
        range_s,
        floor_m_s2,
    )?;
    let pairs = pairs
        .iter()
        .zip(own)
        .map(|(p, a)| p.try_scaled(a * matched.factor))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(PairScaling { matched, pairs })
}

/// Scales `pairs` as the per-record option of a code-scaled suite does: each pair first by
/// its own factor, the fit of its RotD100 spectrum to `target` over `range_s`
/// ([`crate::fit_to_target`]), then all by one common factor, the smallest for which the
/// mean of the fitted RotD100 spectra is at least 90 % of the target at every period of
/// the range. `matched.factor` is the common factor; each scaled component's
/// [`Record::scale_factor`] the product of the two.
///
/// Errors: as [`scale_pairs_over_range`].
pub fn scale_pairs_over_range_each(
    pairs: &[RecordPair],
    target: &DesignSpectrum,
    range_s: [f64; 2],
    damping: f64,
) -> Result<PairScaling, MotionError> {
    let own = own_pair_factors(pairs, target, range_s, damping)?;
    scale_pairs_weighted(pairs, &own, target, range_s, damping, None)
}

/// Each pair's own factor, the fit of its RotD100 spectrum to `target` over `range_s`.
fn own_pair_factors<T: Target + ?Sized>(
    pairs: &[RecordPair],
    target: &T,
    range_s: [f64; 2],
    damping: f64,
) -> Result<Vec<f64>, MotionError> {
    pairs
        .iter()
        .map(|p| {
            crate::fit_to_target(
                |t: &[f64]| Ok(rotd100_spectrum(p, damping, t)?.psa_m_s2),
                target,
                range_s,
            )
        })
        .collect()
}
