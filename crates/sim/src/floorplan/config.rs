//! A building in plan as written ([`FloorPlanConfig`] and its parts): serde structs with
//! unknown fields rejected and quantities accepted as numbers (SI) or strings with units.
//! Nothing here is validated; `build` turns it into a [`FloorPlan`](super::FloorPlan).

use crate::building::{DampingConfig, DissipatorConfig, StoreyYieldConfig};
use crate::units::{Damping, Length, Mass, Stiffness};
use serde::{Deserialize, Serialize};

/// A building in plan, as written: rigid floors (diaphragms) with two translations and a
/// rotation, joined storey by storey by lateral lines (frames, walls, braced bays) placed
/// in plan, each with its storey stiffnesses, yield laws and friction dampers.
///
/// Coordinates: x and y in plan (m), the origin where the file puts it (a corner of the
/// plan when `plan_size` is given: the plan is then the rectangle 0 ≤ x ≤ Lx, 0 ≤ y ≤ Ly);
/// rotations counter-clockwise seen from above.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FloorPlanConfig {
    /// Short name.
    #[serde(default)]
    pub name: Option<String>,
    /// Free text: where the numbers come from.
    #[serde(default)]
    pub description: Option<String>,
    /// The plan's dimensions [Lx, Ly] (m): the default centre of mass (the centre of the
    /// rectangle), the default mass moment of inertia (a uniform rectangle,
    /// m(Lx² + Ly²)/12), the corners whose drifts are measured, and the accidental
    /// eccentricity (a fraction of the dimension across the ground motion).
    #[serde(default)]
    pub plan_size: Option<[Length; 2]>,
    /// The floors, bottom to top.
    pub floors: Vec<FloorConfig>,
    /// Storey heights, bottom to top (m); enables drift ratios.
    #[serde(default)]
    pub storey_heights: Option<Vec<Length>>,
    /// The lateral lines.
    pub lines: Vec<LineConfig>,
    /// Frame damping on the three-dimensional modes of the bare frame: `rayleigh` (by its
    /// coefficients or by ratios at two modes or periods), `modal`, or `none` (default).
    /// `matrix` is the chain's and is refused here; storey dashpots go on the lines
    /// (`storey_damping`).
    #[serde(default)]
    pub damping: Option<DampingConfig>,
    /// Drift ratio past which a run stops and reports the collapse (a yielding line's
    /// storey drift; default 0.10 when a line yields and storey heights are given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collapse_drift_ratio: Option<f64>,
    /// P-Δ of the whole storey: each storey's gravity load (default g times the floors'
    /// masses at and above it) spread over the plan as the mass above it, its geometric
    /// stiffness acting on the storey's two translations and its twist. Needs
    /// `storey_heights`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub p_delta: Option<crate::building::PDeltaConfig>,
    /// Named points in plan whose displacement and absolute acceleration every floor
    /// reports along x and y (equipment, a corner, a façade), beside its centre of mass.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub points: Vec<PlanPointConfig>,
}

/// A named point in plan, as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanPointConfig {
    /// Its name in the outputs ("3 NE x": floor 3, point NE, along x).
    pub name: String,
    /// Where it is [x, y], m.
    pub at: [Length; 2],
}

/// One rigid floor, as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FloorConfig {
    /// Mass (kg, or a string with units).
    pub mass: Mass,
    /// Mass moment of inertia about the vertical axis through the centre of mass, kg·m²
    /// (default m(Lx² + Ly²)/12 from `plan_size`).
    #[serde(default)]
    pub inertia_kg_m2: Option<f64>,
    /// Centre of mass [x, y] (m; default the centre of `plan_size`).
    #[serde(default)]
    pub centre_of_mass: Option<[Length; 2]>,
}

/// A line's direction as written: `"x"`, `"y"`, or an angle from the x axis,
/// counter-clockwise: a number (degrees) or a string with a unit (`"30 deg"`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum DirectionConfig {
    /// Along x (0°).
    X,
    /// Along y (90°).
    Y,
    /// An angle from the x axis, degrees.
    Degrees(f64),
}

impl<'de> Deserialize<'de> for DirectionConfig {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Num(f64),
            Text(String),
        }
        match Raw::deserialize(d)? {
            Raw::Num(v) => Ok(DirectionConfig::Degrees(v)),
            Raw::Text(s) if s.trim().eq_ignore_ascii_case("x") => Ok(DirectionConfig::X),
            Raw::Text(s) if s.trim().eq_ignore_ascii_case("y") => Ok(DirectionConfig::Y),
            // a bare number written as a string is degrees, as a number is; with a unit it
            // is an angle ("30 deg", "0.5 rad")
            Raw::Text(s) => match s.trim().parse::<f64>() {
                Ok(v) => Ok(DirectionConfig::Degrees(v)),
                Err(_) => crate::units::parse_quantity(&s, crate::units::Dimension::Angle)
                    .map(|rad| DirectionConfig::Degrees(rad.to_degrees()))
                    .map_err(|e| {
                        serde::de::Error::custom(format!(
                            "{e}; or \"x\", \"y\", or an angle in degrees from the x axis"
                        ))
                    }),
            },
        }
    }
}

/// One lateral line (a frame, a wall, a braced bay), as written: where it is in plan and,
/// storey by storey, what it resists with.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LineConfig {
    /// Name (a grid line: "A", "1"); default "L1", "L2", … in file order.
    #[serde(default)]
    pub name: Option<String>,
    /// Direction in plan.
    pub direction: DirectionConfig,
    /// A point [x, y] the line passes through (m). Exclusive with `at`.
    #[serde(default)]
    pub through: Option<[Length; 2]>,
    /// For a line along x, its y; along y, its x (m). Exclusive with `through`.
    #[serde(default)]
    pub at: Option<Length>,
    /// Storey stiffness of the line along its direction, bottom to top (N/m).
    pub storey_stiffness: Vec<Stiffness>,
    /// Storey dashpots of the line along its direction, bottom to top (N·s/m; a chain's
    /// `damping.storey`, per line): viscous elements between the line's points on two
    /// floors, added to the building's frame damping.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub storey_damping: Vec<Damping>,
    /// Storeys of the line that yield (bilinear, as a chain's `storey_yield`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub storey_yield: Vec<StoreyYieldConfig>,
    /// The line's friction dampers, at most one per floor (`floor` 1 = the first storey),
    /// acting along the line (as a chain's `dissipators`).
    #[serde(default)]
    pub dissipators: Vec<DissipatorConfig>,
}
