//! Target spectra for suite scaling: the ASCE 7-16 design spectrum, a table of periods
//! and accelerations, or the EN 1998-1 elastic spectrum ([`TargetSpectrum`]).
//!
//! Contract:
//! * [`Target`]: what the scaling reads of a target — Sa at a period of its span, the
//!   periods where its slope jumps (added to the scaling grid) and its span; a range
//!   outside the span is refused ([`check_span`]), never extrapolated.
//! * [`SpectrumTable::sa_g`]: exact at every node; between two nodes of positive period,
//!   linear in ln T – ln Sa (a power law through the two); between a node at T = 0 and the
//!   next, linear in T. Span: the first to the last period.
//! * [`TargetSpectrum::scaled`]: every ordinate × h (the hazard factor).

use crate::{DesignSpectrum, En1998Spectrum, G, MotionError};
use serde::{Deserialize, Serialize};

/// What the suite scaling reads of a target spectrum.
pub trait Target {
    /// Sa at `period_s` (s, within [`Target::span_s`]), g.
    fn sa_g(&self, period_s: f64) -> f64;
    /// Sa at `period_s`, m/s².
    fn sa_m_s2(&self, period_s: f64) -> f64 {
        self.sa_g(period_s) * G
    }
    /// The periods where the target's slope jumps, s (the scaling grid takes those inside
    /// its range).
    fn corners_s(&self) -> Vec<f64>;
    /// The periods the target is defined over, s (the upper end may be +∞).
    fn span_s(&self) -> [f64; 2];
}

impl Target for DesignSpectrum {
    fn sa_g(&self, period_s: f64) -> f64 {
        DesignSpectrum::sa_g(self, period_s)
    }
    fn sa_m_s2(&self, period_s: f64) -> f64 {
        DesignSpectrum::sa_m_s2(self, period_s)
    }
    fn corners_s(&self) -> Vec<f64> {
        vec![self.t0_s(), self.ts_s(), self.tl_s()]
    }
    fn span_s(&self) -> [f64; 2] {
        [0.0, f64::INFINITY]
    }
}

impl Target for En1998Spectrum {
    fn sa_g(&self, period_s: f64) -> f64 {
        En1998Spectrum::sa_g(self, period_s)
    }
    fn corners_s(&self) -> Vec<f64> {
        vec![self.corners.tb_s, self.corners.tc_s, self.corners.td_s]
    }
    fn span_s(&self) -> [f64; 2] {
        [0.0, crate::EN1998_MAX_PERIOD_S]
    }
}

/// Refuses a range `range_s` (s) that leaves the span of `target`.
///
/// Errors: [`MotionError::OutsideSpectrum`] naming both.
pub fn check_span<T: Target + ?Sized>(target: &T, range_s: [f64; 2]) -> Result<(), MotionError> {
    let [lo, hi] = target.span_s();
    if range_s[0] < lo || range_s[1] > hi {
        return Err(MotionError::OutsideSpectrum {
            range_s,
            span_s: [lo, hi],
        });
    }
    Ok(())
}

/// A target spectrum given as a table of (period, Sa) points (a site-specific or
/// multi-period spectrum; see the module docs for the interpolation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpectrumTable {
    periods_s: Vec<f64>,
    sa_g: Vec<f64>,
}

impl SpectrumTable {
    /// The table of `periods_s` (s) and `sa_g` (g), point by point.
    ///
    /// Errors: [`MotionError::InvalidSpectrum`], naming the entry (`periods_s[3]`,
    /// `sa_g[0]`, `sa_g` for a length), unless there are at least two points, as many
    /// accelerations as periods, the periods finite, ≥ 0 and strictly increasing, and the
    /// accelerations finite and > 0.
    pub fn new(periods_s: Vec<f64>, sa_g: Vec<f64>) -> Result<SpectrumTable, MotionError> {
        let bad = |field: String, value: f64, expected: &str| MotionError::InvalidSpectrum {
            field,
            value,
            expected: expected.to_string(),
        };
        if periods_s.len() < 2 {
            return Err(bad(
                "periods_s".into(),
                periods_s.len() as f64,
                "at least 2 periods (the count is the value)",
            ));
        }
        if sa_g.len() != periods_s.len() {
            return Err(bad(
                "sa_g".into(),
                sa_g.len() as f64,
                "one acceleration per period (the count is the value)",
            ));
        }
        for (k, &t) in periods_s.iter().enumerate() {
            if !(t.is_finite() && t >= 0.0) {
                return Err(bad(format!("periods_s[{k}]"), t, "a period ≥ 0 s"));
            }
            if k > 0 && t <= periods_s[k - 1] {
                return Err(bad(
                    format!("periods_s[{k}]"),
                    t,
                    "greater than the period before it (periods strictly increasing)",
                ));
            }
        }
        for (k, &a) in sa_g.iter().enumerate() {
            if !(a.is_finite() && a > 0.0) {
                return Err(bad(format!("sa_g[{k}]"), a, "finite and > 0 g"));
            }
        }
        Ok(SpectrumTable { periods_s, sa_g })
    }

    /// The periods, s.
    pub fn periods_s(&self) -> &[f64] {
        &self.periods_s
    }

    /// The accelerations, g.
    pub fn sa_values_g(&self) -> &[f64] {
        &self.sa_g
    }

    /// The table with every acceleration × `factor` (> 0).
    pub fn scaled(&self, factor: f64) -> SpectrumTable {
        SpectrumTable {
            periods_s: self.periods_s.clone(),
            sa_g: self.sa_g.iter().map(|a| a * factor).collect(),
        }
    }

    /// Sa at `period_s` (s), g: the node's value at a node, interpolated between (module
    /// docs); held at the end value outside the span, which the scaling refuses before it
    /// asks ([`check_span`]).
    pub fn sa_g(&self, period_s: f64) -> f64 {
        let (p, a) = (&self.periods_s, &self.sa_g);
        let n = p.len();
        // the first node after period_s
        let k = p.partition_point(|&x| x <= period_s);
        if k == 0 {
            return a[0];
        }
        if p[k - 1] == period_s || k == n {
            return a[k - 1];
        }
        let (t0, t1, a0, a1) = (p[k - 1], p[k], a[k - 1], a[k]);
        if t0 == 0.0 {
            return a0 + (a1 - a0) * period_s / t1;
        }
        let x = (period_s / t0).ln() / (t1 / t0).ln();
        (a0.ln() + x * (a1 / a0).ln()).exp()
    }
}

impl Target for SpectrumTable {
    fn sa_g(&self, period_s: f64) -> f64 {
        SpectrumTable::sa_g(self, period_s)
    }
    fn corners_s(&self) -> Vec<f64> {
        self.periods_s.clone()
    }
    fn span_s(&self) -> [f64; 2] {
        [self.periods_s[0], self.periods_s[self.periods_s.len() - 1]]
    }
}

/// The target of a suite scaled to a code spectrum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TargetSpectrum {
    /// The ASCE 7-16 §11.4.6 design spectrum.
    Asce7(DesignSpectrum),
    /// A table of periods and accelerations.
    Table(SpectrumTable),
    /// The EN 1998-1 §3.2.2.2 horizontal elastic spectrum.
    En1998(En1998Spectrum),
}

impl TargetSpectrum {
    /// The target with every ordinate × `factor` (finite, > 0): S_DS and S_D1 × it for
    /// ASCE 7 (T_L kept), every Sa for a table, a_g for EN 1998-1.
    ///
    /// Errors: as the forms' constructors.
    pub fn scaled(&self, factor: f64) -> Result<TargetSpectrum, MotionError> {
        Ok(match self {
            TargetSpectrum::Asce7(d) => TargetSpectrum::Asce7(DesignSpectrum::new(
                d.sds_g() * factor,
                d.sd1_g() * factor,
                d.tl_s(),
            )?),
            TargetSpectrum::Table(t) => TargetSpectrum::Table(t.scaled(factor)),
            TargetSpectrum::En1998(e) => TargetSpectrum::En1998(En1998Spectrum::new(
                e.ag_g * factor,
                e.corners,
                e.damping_percent,
            )?),
        })
    }

    fn inner(&self) -> &dyn Target {
        match self {
            TargetSpectrum::Asce7(d) => d,
            TargetSpectrum::Table(t) => t,
            TargetSpectrum::En1998(e) => e,
        }
    }
}

impl Target for TargetSpectrum {
    fn sa_g(&self, period_s: f64) -> f64 {
        self.inner().sa_g(period_s)
    }
    fn sa_m_s2(&self, period_s: f64) -> f64 {
        self.inner().sa_m_s2(period_s)
    }
    fn corners_s(&self) -> Vec<f64> {
        self.inner().corners_s()
    }
    fn span_s(&self) -> [f64; 2] {
        self.inner().span_s()
    }
}
