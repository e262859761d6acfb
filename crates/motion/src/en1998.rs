//! The EN 1998-1 horizontal elastic response spectrum, a target for suite scaling.
//!
//! Contract: [`En1998Spectrum::sa_g`] is EN 1998-1:2004 §3.2.2.2 (Eq. 3.2–3.5), the
//! horizontal elastic response spectrum S_e(T), with a_g = γ_I·a_gR (§3.2.1(3)) and the
//! damping correction η = √(10/(5 + ξ)) ≥ 0.55, ξ the viscous damping in percent (Eq. 3.6):
//!
//! * 0 ≤ T ≤ T_B: S_e = a_g·S·(1 + T/T_B·(2.5η − 1)) (Eq. 3.2);
//! * T_B ≤ T ≤ T_C: S_e = a_g·S·η·2.5 (Eq. 3.3);
//! * T_C ≤ T ≤ T_D: S_e = a_g·S·η·2.5·T_C/T (Eq. 3.4);
//! * T_D ≤ T ≤ 4 s: S_e = a_g·S·η·2.5·T_C·T_D/T² (Eq. 3.5).
//!
//! Continuous in T. The spectrum is defined up to [`EN1998_MAX_PERIOD_S`]; a scaling range
//! beyond it is refused ([`crate::Target::span_s`]), not extrapolated. S, T_B, T_C and T_D
//! are by default the values EN 1998-1 recommends for the ground type and spectrum type
//! ([`En1998Corners::recommended`], Tables 3.2 and 3.3); each is a Nationally Determined
//! Parameter and may be given instead.

use crate::MotionError;
use serde::{Deserialize, Serialize};

/// The longest period of the EN 1998-1 elastic spectrum (§3.2.2.2, Eq. 3.5), s.
pub const EN1998_MAX_PERIOD_S: f64 = 4.0;

/// The least damping correction η (EN 1998-1 §3.2.2.2(3), Eq. 3.6).
pub const EN1998_MIN_ETA: f64 = 0.55;

/// A ground type of EN 1998-1 Table 3.1 that has recommended spectrum parameters (S1 and
/// S2 need special studies, §3.1.2(4)–(5), and have none).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum GroundType {
    /// Rock or rock-like formation.
    A,
    /// Very dense sand, gravel or very stiff clay.
    B,
    /// Deep deposits of dense or medium-dense sand, gravel or stiff clay.
    C,
    /// Loose-to-medium cohesionless soil or soft-to-firm cohesive soil.
    D,
    /// A surface alluvium layer of type C or D over stiffer material.
    E,
}

impl GroundType {
    /// The ground type named `name` (`A` … `E`, one capital letter), if any.
    pub fn from_name(name: &str) -> Option<GroundType> {
        match name {
            "A" => Some(GroundType::A),
            "B" => Some(GroundType::B),
            "C" => Some(GroundType::C),
            "D" => Some(GroundType::D),
            "E" => Some(GroundType::E),
            _ => None,
        }
    }

    /// Its letter.
    pub fn as_str(self) -> &'static str {
        match self {
            GroundType::A => "A",
            GroundType::B => "B",
            GroundType::C => "C",
            GroundType::D => "D",
            GroundType::E => "E",
        }
    }

    /// Every ground type, A to E.
    pub const ALL: [GroundType; 5] = [
        GroundType::A,
        GroundType::B,
        GroundType::C,
        GroundType::D,
        GroundType::E,
    ];
}

/// S, T_B, T_C and T_D of an EN 1998-1 spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct En1998Corners {
    /// The soil factor S.
    pub s: f64,
    /// T_B, s: the lower limit of the constant-acceleration branch.
    pub tb_s: f64,
    /// T_C, s: its upper limit.
    pub tc_s: f64,
    /// T_D, s: the start of the constant-displacement branch.
    pub td_s: f64,
}

impl En1998Corners {
    /// The values EN 1998-1:2004 recommends for ground type `ground` and spectrum type
    /// `spectrum_type` (1: Table 3.2, high seismicity; 2: Table 3.3, surface-wave magnitude
    /// M_s ≤ 5.5, §3.2.2.2(2)P), as the project reads them (docs/MODEL.md § Target
    /// spectra); `None` for a type other than 1 or 2.
    pub fn recommended(ground: GroundType, spectrum_type: u8) -> Option<En1998Corners> {
        let (s, tb_s, tc_s, td_s) = match (spectrum_type, ground) {
            (1, GroundType::A) => (1.0, 0.15, 0.4, 2.0),
            (1, GroundType::B) => (1.2, 0.15, 0.5, 2.0),
            (1, GroundType::C) => (1.15, 0.20, 0.6, 2.0),
            (1, GroundType::D) => (1.35, 0.20, 0.8, 2.0),
            (1, GroundType::E) => (1.4, 0.15, 0.5, 2.0),
            (2, GroundType::A) => (1.0, 0.05, 0.25, 1.2),
            (2, GroundType::B) => (1.35, 0.05, 0.25, 1.2),
            (2, GroundType::C) => (1.5, 0.10, 0.25, 1.2),
            (2, GroundType::D) => (1.8, 0.10, 0.30, 1.2),
            (2, GroundType::E) => (1.6, 0.05, 0.25, 1.2),
            _ => return None,
        };
        Some(En1998Corners {
            s,
            tb_s,
            tc_s,
            td_s,
        })
    }
}

/// The damping correction η = √(10/(5 + ξ)), at least [`EN1998_MIN_ETA`] (EN 1998-1
/// Eq. 3.6), of the viscous damping `damping_percent` ξ (%).
pub fn en1998_eta(damping_percent: f64) -> f64 {
    (10.0 / (5.0 + damping_percent)).sqrt().max(EN1998_MIN_ETA)
}

/// An EN 1998-1 horizontal elastic response spectrum (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct En1998Spectrum {
    /// a_g = γ_I·a_gR, g.
    pub ag_g: f64,
    /// S, T_B, T_C, T_D.
    pub corners: En1998Corners,
    /// The viscous damping ξ, %.
    pub damping_percent: f64,
    /// η of ξ (Eq. 3.6).
    pub eta: f64,
}

/// An invalid parameter of an EN 1998-1 spectrum.
fn bad(field: &str, value: f64, expected: &str) -> MotionError {
    MotionError::InvalidSpectrum {
        field: field.to_string(),
        value,
        expected: expected.to_string(),
    }
}

impl En1998Spectrum {
    /// The spectrum of design ground acceleration `ag_g` (g, a_g = γ_I·a_gR), `corners`
    /// (S, T_B, T_C, T_D) and viscous damping `damping_percent` (%).
    ///
    /// Errors: [`MotionError::InvalidSpectrum`], naming the parameter (`ag_g`, `s`, `tb_s`,
    /// `tc_s`, `td_s`, `damping_percent`), unless a_g and S are finite and > 0,
    /// 0 < T_B < T_C < T_D ≤ 4 s, and 0 ≤ ξ < 100.
    pub fn new(
        ag_g: f64,
        corners: En1998Corners,
        damping_percent: f64,
    ) -> Result<En1998Spectrum, MotionError> {
        let En1998Corners {
            s,
            tb_s,
            tc_s,
            td_s,
        } = corners;
        for (field, v) in [("ag_g", ag_g), ("s", s), ("tb_s", tb_s)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(field, v, "finite and > 0"));
            }
        }
        if !(tc_s.is_finite() && tc_s > tb_s) {
            return Err(bad("tc_s", tc_s, "finite and greater than T_B"));
        }
        if !(td_s.is_finite() && td_s > tc_s && td_s <= EN1998_MAX_PERIOD_S) {
            return Err(bad(
                "td_s",
                td_s,
                "greater than T_C and at most 4 s (the spectrum's last period)",
            ));
        }
        if !(damping_percent.is_finite() && (0.0..100.0).contains(&damping_percent)) {
            return Err(bad(
                "damping_percent",
                damping_percent,
                "a viscous damping ξ in percent, 0 ≤ ξ < 100",
            ));
        }
        Ok(En1998Spectrum {
            ag_g,
            corners,
            damping_percent,
            eta: en1998_eta(damping_percent),
        })
    }

    /// a_g·S, g: the spectrum at T = 0, the value the mean PGA of a suite must reach
    /// (§3.2.3.1.2(4)b).
    pub fn ag_s_g(&self) -> f64 {
        self.ag_g * self.corners.s
    }

    /// S_e at period `period_s` (s, 0 … 4; a negative period is taken as 0, a period
    /// beyond 4 s continues Eq. 3.5, which the scaling never asks for), g.
    pub fn sa_g(&self, period_s: f64) -> f64 {
        let t = period_s.max(0.0);
        let En1998Corners {
            s,
            tb_s,
            tc_s,
            td_s,
        } = self.corners;
        let plateau = self.ag_g * s * self.eta * 2.5;
        if t <= tb_s {
            self.ag_g * s * (1.0 + t / tb_s * (2.5 * self.eta - 1.0))
        } else if t <= tc_s {
            plateau
        } else if t <= td_s {
            plateau * tc_s / t
        } else {
            plateau * tc_s * td_s / (t * t)
        }
    }
}
