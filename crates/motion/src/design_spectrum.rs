//! The ASCE 7 design response spectrum, a target for suite scaling.
//!
//! Contract: [`DesignSpectrum::sa_g`] is ASCE 7-16 §11.4.6 (Fig. 11.4-1), 5 % damping:
//! with T₀ = 0.2·S_D1/S_DS and T_S = S_D1/S_DS,
//! Sa = S_DS(0.4 + 0.6T/T₀) for T < T₀; S_DS for T₀ ≤ T ≤ T_S; S_D1/T for T_S < T ≤ T_L;
//! S_D1·T_L/T² for T > T_L. Continuous in T.

use crate::{G, MotionError};

/// An ASCE 7-16 design spectrum from S_DS, S_D1 (g) and T_L (s).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignSpectrum {
    sds_g: f64,
    sd1_g: f64,
    tl_s: f64,
}

impl DesignSpectrum {
    /// From the short-period design acceleration `sds_g` (g), the 1-s design acceleration
    /// `sd1_g` (g) and the long-period transition `tl_s` (s).
    ///
    /// Errors: [`MotionError::InvalidArgument`] unless all are finite and > 0 and
    /// T_L ≥ T_S = S_D1/S_DS.
    pub fn new(sds_g: f64, sd1_g: f64, tl_s: f64) -> Result<DesignSpectrum, MotionError> {
        for (what, value) in [("S_DS (g)", sds_g), ("S_D1 (g)", sd1_g), ("T_L (s)", tl_s)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(MotionError::InvalidArgument {
                    what,
                    value,
                    expected: "finite and > 0",
                });
            }
        }
        if tl_s < sd1_g / sds_g {
            return Err(MotionError::InvalidArgument {
                what: "T_L (s)",
                value: tl_s,
                expected: "at least T_S = S_D1/S_DS",
            });
        }
        Ok(DesignSpectrum { sds_g, sd1_g, tl_s })
    }

    /// S_DS, g.
    pub fn sds_g(&self) -> f64 {
        self.sds_g
    }

    /// S_D1, g.
    pub fn sd1_g(&self) -> f64 {
        self.sd1_g
    }

    /// T_L, s.
    pub fn tl_s(&self) -> f64 {
        self.tl_s
    }

    /// T₀ = 0.2·S_D1/S_DS, s.
    pub fn t0_s(&self) -> f64 {
        0.2 * self.sd1_g / self.sds_g
    }

    /// T_S = S_D1/S_DS, s.
    pub fn ts_s(&self) -> f64 {
        self.sd1_g / self.sds_g
    }

    /// Design spectral acceleration at period `period_s` (s, ≥ 0), g.
    pub fn sa_g(&self, period_s: f64) -> f64 {
        let t = period_s.max(0.0);
        if t < self.t0_s() {
            self.sds_g * (0.4 + 0.6 * t / self.t0_s())
        } else if t <= self.ts_s() {
            self.sds_g
        } else if t <= self.tl_s {
            self.sd1_g / t
        } else {
            self.sd1_g * self.tl_s / (t * t)
        }
    }

    /// Design spectral acceleration at `period_s` (s), m/s².
    pub fn sa_m_s2(&self, period_s: f64) -> f64 {
        self.sa_g(period_s) * G
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn branches_and_continuity() {
        let d = DesignSpectrum::new(1.0, 0.6, 8.0).unwrap();
        assert!((d.t0_s() - 0.12).abs() < 1e-15 && (d.ts_s() - 0.6).abs() < 1e-15);
        assert_eq!(d.sa_g(0.0), 0.4);
        assert_eq!(d.sa_g(0.3), 1.0);
        assert!((d.sa_g(1.0) - 0.6).abs() < 1e-15);
        assert!((d.sa_g(10.0) - 0.048).abs() < 1e-15);
        for t in [d.t0_s(), d.ts_s(), d.tl_s()] {
            let (a, b) = (d.sa_g(t * (1.0 - 1e-12)), d.sa_g(t * (1.0 + 1e-12)));
            assert!((a - b).abs() < 1e-11, "jump at {t}: {a} vs {b}");
        }
        assert!(DesignSpectrum::new(1.0, 0.6, 0.5).is_err());
        assert!(DesignSpectrum::new(0.0, 0.6, 8.0).is_err());
    }
}
