//! Time envelopes that make stationary noise look like an earthquake.
//!
//! Contract: [`Envelope::at`] is a dimensionless modulating function of time, 0 at t = 0,
//! with maximum 1, evaluated with `libm` so its bits do not depend on the platform.

use crate::MotionError;

/// A modulating function e(t) ∈ [0, 1].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Envelope {
    /// Saragoni & Hart (1974) shape e(t) = (τ/ε)^b · exp(−c(τ − ε)), τ = t/t_n with t_n the
    /// record's duration, parametrised as in Boore (2003, PAGEOPH 160: 635–676): the peak
    /// (1) is at τ = ε and e(t_n) = η, which gives b = −ε ln η / (1 + ε(ln ε − 1)),
    /// c = b/ε. Boore's values are ε = 0.2, η = 0.05.
    SaragoniHart {
        /// ε: time of the peak as a fraction of the duration, in (0, 1).
        peak_fraction: f64,
        /// η: envelope at the end of the record, in (0, 1).
        end_level: f64,
    },
    /// Trapezoid: linear rise over `rise_s`, 1 for `hold_s`, linear decay to 0 over
    /// `decay_s`, 0 after (seconds).
    Trapezoidal {
        /// Rise time, s (> 0).
        rise_s: f64,
        /// Strong-motion (flat) duration, s (≥ 0).
        hold_s: f64,
        /// Decay time, s (> 0).
        decay_s: f64,
    },
}

impl Default for Envelope {
    /// Saragoni–Hart with Boore's (2003) ε = 0.2, η = 0.05.
    fn default() -> Envelope {
        Envelope::SaragoniHart {
            peak_fraction: 0.2,
            end_level: 0.05,
        }
    }
}

impl Envelope {
    /// Checks the parameters; [`MotionError::InvalidArgument`] names the bad one.
    pub fn validate(&self) -> Result<(), MotionError> {
        let bad = |what, value, expected| {
            Err(MotionError::InvalidArgument {
                what,
                value,
                expected,
            })
        };
        match *self {
            Envelope::SaragoniHart {
                peak_fraction,
                end_level,
            } => {
                if !(peak_fraction > 0.0 && peak_fraction < 1.0) {
                    return bad("envelope peak fraction", peak_fraction, "in (0, 1)");
                }
                if !(end_level > 0.0 && end_level < 1.0) {
                    return bad("envelope end level", end_level, "in (0, 1)");
                }
            }
            Envelope::Trapezoidal {
                rise_s,
                hold_s,
                decay_s,
            } => {
                if !(rise_s.is_finite() && rise_s > 0.0) {
                    return bad("envelope rise time (s)", rise_s, "finite and > 0");
                }
                if !(hold_s.is_finite() && hold_s >= 0.0) {
                    return bad("envelope hold time (s)", hold_s, "finite and >= 0");
                }
                if !(decay_s.is_finite() && decay_s > 0.0) {
                    return bad("envelope decay time (s)", decay_s, "finite and > 0");
                }
            }
        }
        Ok(())
    }

    /// e(t) for a record of duration `duration_s` (s) at time `t_s` (s); parameters must
    /// be valid ([`Envelope::validate`]).
    pub fn at(&self, t_s: f64, duration_s: f64) -> f64 {
        match *self {
            Envelope::SaragoniHart {
                peak_fraction: eps,
                end_level: eta,
            } => {
                if t_s <= 0.0 {
                    return 0.0;
                }
                let b = -eps * libm::log(eta) / (1.0 + eps * (libm::log(eps) - 1.0));
                let c = b / eps;
                let tau = t_s / duration_s;
                libm::exp(b * libm::log(tau / eps) - c * (tau - eps))
            }
            Envelope::Trapezoidal {
                rise_s,
                hold_s,
                decay_s,
            } => {
                if t_s <= 0.0 {
                    0.0
                } else if t_s < rise_s {
                    t_s / rise_s
                } else if t_s <= rise_s + hold_s {
                    1.0
                } else {
                    (1.0 - (t_s - rise_s - hold_s) / decay_s).max(0.0)
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn saragoni_hart_peak_and_end() {
        let e = Envelope::default();
        assert!((e.at(4.0, 20.0) - 1.0).abs() < 1e-15);
        assert!((e.at(20.0, 20.0) - 0.05).abs() < 1e-14);
        assert!(e.at(3.9, 20.0) < 1.0 && e.at(4.1, 20.0) < 1.0);
        assert_eq!(e.at(0.0, 20.0), 0.0);
    }

    #[test]
    fn trapezoid() {
        let e = Envelope::Trapezoidal {
            rise_s: 2.0,
            hold_s: 5.0,
            decay_s: 4.0,
        };
        assert_eq!(e.at(1.0, 20.0), 0.5);
        assert_eq!(e.at(5.0, 20.0), 1.0);
        assert_eq!(e.at(9.0, 20.0), 0.5);
        assert_eq!(e.at(12.0, 20.0), 0.0);
        assert!(
            Envelope::SaragoniHart {
                peak_fraction: 1.0,
                end_level: 0.05
            }
            .validate()
            .is_err()
        );
    }
}
