//! A validated building ([`Building`]) and its validated parts ([`Dissipator`],
//! [`StoreyYield`]), SI units, with what they answer by themselves.

use crate::modes::Modes;
use nalgebra::DMatrix;

/// A validated yielding storey, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StoreyYield {
    /// Initial stiffness k of the storey spring, N/m.
    pub stiffness: f64,
    /// Yield shear Fy, N.
    pub yield_shear: f64,
    /// Post-yield stiffness ratio α in [0, 1).
    pub post_yield_ratio: f64,
}

impl StoreyYield {
    /// Yield drift Fy/k, m.
    pub fn yield_drift(&self) -> f64 {
        self.yield_shear / self.stiffness
    }
}

/// A validated dissipator, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dissipator {
    /// Brace stiffness k′, N/m.
    pub brace_stiffness: f64,
    /// Dissipator mass m′, kg.
    pub mass: f64,
    /// Brace damping c′, N·s/m.
    pub brace_damping: f64,
    /// Lower friction bound F⁻ ≤ 0, N (−∞ when locked).
    pub lower: f64,
    /// Upper friction bound F⁺ ≥ 0, N (+∞ when locked).
    pub upper: f64,
}

impl Dissipator {
    /// True when the contact can never slip.
    pub fn is_locked(&self) -> bool {
        self.upper == f64::INFINITY && self.lower == f64::NEG_INFINITY
    }
    /// True when the contact transmits no force.
    pub fn is_free(&self) -> bool {
        self.upper == 0.0 && self.lower == 0.0
    }
}

/// A validated building, SI units, floors numbered 0..n from the bottom.
#[derive(Debug, Clone)]
pub struct Building {
    /// Name.
    pub name: String,
    /// Frame mass matrix Mˢˢ (kg).
    pub mass: DMatrix<f64>,
    /// Frame stiffness matrix Kˢˢ (N/m).
    pub stiffness: DMatrix<f64>,
    /// Frame damping matrix Cˢˢ (N·s/m).
    pub damping: DMatrix<f64>,
    /// Storey heights (m), when given.
    pub storey_heights: Option<Vec<f64>>,
    /// Dissipator of each floor, if any.
    pub dissipators: Vec<Option<Dissipator>>,
    /// Yield law of each storey, if it yields (`None`: elastic).
    pub storey_yield: Vec<Option<StoreyYield>>,
    /// P-Δ gravity load Pᵢ of each storey (N), when P-Δ is on.
    pub gravity_loads: Option<Vec<f64>>,
    /// Drift of each storey (m) past which a run stops with a collapse, when set.
    pub collapse_drift: Option<Vec<f64>>,
    /// Modes of the bare frame.
    pub modes: Modes,
}

impl Building {
    /// Whether any storey yields or P-Δ acts (effects beyond the linear frame).
    pub fn is_nonlinear_frame(&self) -> bool {
        self.storey_yield.iter().any(Option::is_some) || self.gravity_loads.is_some()
    }

    /// Number of floors.
    pub fn floors(&self) -> usize {
        self.mass.nrows()
    }

    /// Fundamental period of the bare frame, s.
    pub fn t1(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.modes.omega[0]
    }

    /// Replaces the slip load of every dissipator by `slip_loads[i]` (N; `None` keeps the
    /// floor as it is). Used by sweeps.
    pub fn with_slip_loads(&self, slip_loads: &[Option<f64>]) -> Building {
        let mut b = self.clone();
        for (d, s) in b.dissipators.iter_mut().zip(slip_loads) {
            if let (Some(d), Some(s)) = (d.as_mut(), s) {
                d.lower = -s;
                d.upper = *s;
            }
        }
        b
    }
}
