//! A building file as written ([`BuildingConfig`] and its parts): serde structs with
//! unknown fields rejected and quantities accepted as numbers (SI) or strings with units.
//! Nothing here is validated; `build` and `check` turn it into a
//! [`Building`](super::validated::Building).

use crate::units::{Damping, Force, Length, Mass, Stiffness, Time};
use serde::{Deserialize, Serialize};

/// A building file, as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BuildingConfig {
    /// Short name.
    #[serde(default)]
    pub name: Option<String>,
    /// Free text: where the numbers come from.
    #[serde(default)]
    pub description: Option<String>,
    /// Lumped floor masses, bottom to top (kg). Either this or `mass_matrix`.
    #[serde(default)]
    pub floor_masses: Option<Vec<Mass>>,
    /// Full symmetric mass matrix (kg; entries are numbers or strings with units).
    #[serde(default)]
    pub mass_matrix: Option<Vec<Vec<Mass>>>,
    /// Storey (shear) stiffnesses, bottom to top (N/m). Either this or `stiffness_matrix`.
    #[serde(default)]
    pub storey_stiffness: Option<Vec<Stiffness>>,
    /// Full symmetric frame stiffness matrix on floor displacements (N/m; entries are
    /// numbers or strings with units, `"436.575 MN/m"`), e.g. a condensed frame matrix.
    #[serde(default)]
    pub stiffness_matrix: Option<Vec<Vec<Stiffness>>>,
    /// Frame damping; default none.
    #[serde(default)]
    pub damping: Option<DampingConfig>,
    /// Storey heights, bottom to top (m); enables drift ratios.
    #[serde(default)]
    pub storey_heights: Option<Vec<Length>>,
    /// The dissipators, at most one per floor.
    #[serde(default)]
    pub dissipators: Vec<DissipatorConfig>,
    /// Storeys whose shear–drift law yields (bilinear, kinematic hardening); storeys not
    /// listed stay elastic.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub storey_yield: Vec<StoreyYieldConfig>,
    /// Linearised P-Δ: a geometric stiffness −Pᵢ/hᵢ per storey (needs `storey_heights`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub p_delta: Option<PDeltaConfig>,
    /// Storey drift ratio (drift / storey height) past which a run stops and reports the
    /// storey as collapsed. Default 0.10 when a storey yields or P-Δ acts and storey
    /// heights are given. Exclusive with `collapse_drift`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collapse_drift_ratio: Option<f64>,
    /// The same limit as a drift (m), for every storey. Exclusive with
    /// `collapse_drift_ratio`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collapse_drift: Option<Length>,
}

/// A yielding storey, as written: initial stiffness k, yield shear Fy (or yield drift
/// Fy/k) and post-yield ratio α (0 = elastic–perfectly plastic).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StoreyYieldConfig {
    /// Storey number, 1 = between the ground and the first floor.
    pub storey: usize,
    /// Yield shear Fy (N), > 0. Exclusive with `yield_drift`.
    #[serde(default)]
    pub yield_shear: Option<Force>,
    /// Yield drift Fy/k (m), > 0. Exclusive with `yield_shear`.
    #[serde(default)]
    pub yield_drift: Option<Length>,
    /// Post-yield stiffness ratio α in [0, 1); default 0 (elastic–perfectly plastic).
    #[serde(default)]
    pub post_yield_ratio: Option<f64>,
    /// Initial stiffness k of the storey spring that yields (N/m): by default the storey's
    /// `storey_stiffness`; required when the frame is given as `stiffness_matrix` (the
    /// spring between floors i−1 and i that is part of that matrix).
    #[serde(default)]
    pub stiffness: Option<Stiffness>,
}

/// P-Δ, as written.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PDeltaConfig {
    /// Gravity load carried by each storey, bottom to top (N); by default g times the
    /// floor masses at and above the storey.
    #[serde(default)]
    pub gravity_loads: Option<Vec<Force>>,
}

/// How the frame damping matrix Cˢˢ is given.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum DampingConfig {
    /// No frame damping.
    None,
    /// Rayleigh: C = α M + β K (bare frame matrices), given by its coefficients or by
    /// the damping ratios it has at two modes or two periods of the bare frame.
    Rayleigh(RayleighConfig),
    /// Modal damping ratios of the bare frame: one `ratio` for all modes, or `ratios`
    /// per mode (missing modes take the last ratio given).
    Modal {
        /// Ratio for every mode.
        #[serde(default)]
        ratio: Option<f64>,
        /// Ratios by mode, first mode first.
        #[serde(default)]
        ratios: Option<Vec<f64>>,
    },
    /// Storey dashpots (shear-building form), bottom to top, N·s/m.
    Storey(Vec<Damping>),
    /// Full symmetric damping matrix, N·s/m (entries are numbers or strings with units,
    /// `"509.253 kN·s/m"`).
    Matrix(Vec<Vec<Damping>>),
}

/// Rayleigh damping as written: `alpha` and `beta`, or the ratio (`ratio` for both, or
/// `ratios`) at two `modes` (1 = the first) or two `periods` of the bare frame.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RayleighConfig {
    /// Mass coefficient α, 1/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub alpha: Option<f64>,
    /// Stiffness coefficient β, s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beta: Option<f64>,
    /// One damping ratio at both modes or periods.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ratio: Option<f64>,
    /// The damping ratios at the two modes or periods, in their order.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ratios: Option<Vec<f64>>,
    /// The two modes of the bare frame (1 = the first) where the ratios hold.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<Vec<usize>>,
    /// The two periods where the ratios hold.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub periods: Option<Vec<Time>>,
}

/// One friction dissipator with its brace, as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DissipatorConfig {
    /// Floor it acts on, 1 = first floor above ground.
    pub floor: usize,
    /// Brace stiffness k′ (N/m), > 0.
    pub brace_stiffness: Stiffness,
    /// Dissipator mass m′ (kg), ≥ 0; 0 makes brace + contact an elastic–perfectly plastic spring.
    #[serde(default)]
    pub mass: Option<Mass>,
    /// Brace damping c′ (N·s/m), ≥ 0.
    #[serde(default)]
    pub brace_damping: Option<Damping>,
    /// Symmetric slip load μN (N), or `"locked"` for a contact that never slips.
    #[serde(default)]
    pub slip_load: Option<SlipLoad>,
    /// Asymmetric friction bounds [F⁻, F⁺] (N), F⁻ ≤ 0 ≤ F⁺. Exclusive with `slip_load`.
    #[serde(default)]
    pub bounds: Option<[Force; 2]>,
}

/// A slip load: a force, or locked (μN → ∞).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum SlipLoad {
    /// μN in N.
    Force(f64),
    /// Never slips: the dissipator moves with its floor.
    Locked,
}

impl<'de> Deserialize<'de> for SlipLoad {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Num(f64),
            Text(String),
        }
        match Raw::deserialize(d)? {
            Raw::Num(v) => Ok(SlipLoad::Force(v)),
            Raw::Text(s) if s.trim().eq_ignore_ascii_case("locked") => Ok(SlipLoad::Locked),
            Raw::Text(s) => crate::units::parse_quantity(&s, crate::units::Dimension::Force)
                .map(SlipLoad::Force)
                .map_err(|e| serde::de::Error::custom(format!("{e}, or \"locked\""))),
        }
    }
}
