//! Design spaces: variables z ∈ [0, 1]^d mapped affinely to per-dissipator slip loads
//! s = offset + D z (N), with linear constraints A z ≤ b carried over from constraints on
//! s (total budget, non-increasing with height). The space and its constraints as a study
//! file writes them ([`SpaceConfig`], [`ConstraintsConfig`]) live here with the resolved
//! [`DesignSpace`]; a study holds both and this module knows nothing of studies.
//!
//! Feasibility is decided before any simulation by an exact LP argument: the
//! componentwise smallest slip-load vector that is non-increasing and above the lower
//! bounds is sᵢ = max_{j ≥ i} lowerⱼ; the constraints are feasible iff it lies below the
//! upper bounds and (with a budget) its sum is within the budget — every other feasible
//! vector is componentwise larger, so has a larger sum.

use crate::base::error::OptError;
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};
use slipload_sim::Building;
use std::path::Path;

/// Shapes of a profile design space.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Shape {
    /// The same slip load on every floor.
    Uniform,
    /// Proportional to the storey shear of a triangular load pattern,
    /// Vᵢ = Σ_{j ≥ i} m_j h_j (h_j the floor's height above ground), normalised to V₁ = 1.
    StoreyShear,
    /// Proportional to the storey stiffness of the bare frame, kᵢ = Vᵢ/δᵢ under the same
    /// triangular pattern (δᵢ the storey drift of K x = f; exact storey stiffness for a
    /// shear building), normalised to k₁ = 1.
    Stiffness,
}

impl Shape {
    /// Name as written.
    pub fn as_str(self) -> &'static str {
        match self {
            Shape::Uniform => "uniform",
            Shape::StoreyShear => "storey_shear",
            Shape::Stiffness => "stiffness",
        }
    }

    /// The shape on every floor of `building`, first floor = 1.
    pub fn on_floors(self, building: &Building) -> Vec<f64> {
        let n = building.floors();
        let heights = building
            .storey_heights
            .clone()
            .unwrap_or_else(|| vec![1.0; n]);
        let mut elev = Vec::with_capacity(n);
        let mut h = 0.0;
        for hi in &heights {
            h += hi;
            elev.push(h);
        }
        let f: Vec<f64> = (0..n).map(|i| building.mass[(i, i)] * elev[i]).collect();
        let shear: Vec<f64> = (0..n).map(|i| f[i..].iter().sum()).collect();
        match self {
            Shape::Uniform => vec![1.0; n],
            Shape::StoreyShear => shear.iter().map(|v| v / shear[0]).collect(),
            Shape::Stiffness => {
                let x = building
                    .stiffness
                    .clone()
                    .lu()
                    .solve(&DVector::from_vec(f.clone()))
                    .unwrap_or_else(|| DVector::from_element(n, 1.0));
                let k: Vec<f64> = (0..n)
                    .map(|i| {
                        let d = x[i] - if i > 0 { x[i - 1] } else { 0.0 };
                        shear[i] / d
                    })
                    .collect();
                k.iter().map(|v| v / k[0]).collect()
            }
        }
    }
}

/// The design space, as written (slip loads in kN).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum SpaceConfig {
    /// One free slip load per dissipator, bottom to top.
    Free {
        /// Lower bounds, kN.
        lower_kn: Vec<f64>,
        /// Upper bounds, kN.
        upper_kn: Vec<f64>,
    },
    /// A fixed shape over the floors times one scale (the base storey's slip load).
    Profile {
        /// The shape.
        shape: Shape,
        /// [lower, upper] of the first dissipator's slip load, kN.
        scale_kn: [f64; 2],
    },
}

/// Linear constraints on the slip loads.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstraintsConfig {
    /// Σ slip loads ≤ this, kN.
    #[serde(default)]
    pub budget_kn: Option<f64>,
    /// Slip loads do not increase with height.
    #[serde(default)]
    pub non_increasing: bool,
}

/// A design space, resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignSpace {
    /// Floors (from 0) of the dissipators the slip loads apply to, bottom to top.
    pub dampers: Vec<usize>,
    /// Slip loads at z = 0, N.
    pub offset: Vec<f64>,
    /// ∂s/∂z, N per unit of z (dampers × d).
    pub basis: DMatrix<f64>,
    /// Constraint rows on z (A z ≤ b).
    pub a: DMatrix<f64>,
    /// Right-hand sides.
    pub b: Vec<f64>,
    /// Variable names for tables.
    pub names: Vec<String>,
    /// Profile shape on the dampers, when the space is a profile.
    pub shape: Option<(Shape, Vec<f64>)>,
    /// The storey-shear profile of the building on the dampers ([`Shape::StoreyShear`]:
    /// the shear of a triangular load pattern, first damper's storey = 1): what an
    /// engineer knows of the slip loads' shape before a study, the refiners' first
    /// search direction.
    pub profile: Vec<f64>,
}

/// Relative slack on constraint checks (round-off of the affine map).
const FEAS_TOL: f64 = 1e-9;

/// A scaled variable within this of 0 or 1 (a millionth of its range) is on its bound.
pub const BOUND_TOL: f64 = 1e-6;

/// Which bound of a design variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Bound {
    /// The lower bound (z = 0).
    Lower,
    /// The upper bound (z = 1).
    Upper,
}

impl Bound {
    /// `lower` or `upper`.
    pub fn as_str(self) -> &'static str {
        match self {
            Bound::Lower => "lower",
            Bound::Upper => "upper",
        }
    }
}

/// A design variable sitting on a bound of the design space.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OnBound {
    /// The variable (`floor1`, …; `scale` for a profile).
    pub variable: String,
    /// The floors (from 1) whose slip loads it sets.
    pub floors: Vec<usize>,
    /// Which bound.
    pub bound: Bound,
}

impl DesignSpace {
    /// Builds and checks a space; errors name the study field.
    pub fn new(
        cfg: &SpaceConfig,
        cons: &ConstraintsConfig,
        building: &Building,
        path: &Path,
    ) -> Result<DesignSpace, OptError> {
        let dampers: Vec<usize> = (0..building.floors())
            .filter(|&f| building.dissipators[f].is_some())
            .collect();
        let m = dampers.len();
        if m == 0 {
            return Err(OptError::invalid(
                path,
                "building",
                "the building has no dissipators: there are no slip loads to choose",
            ));
        }
        let check_pair = |field: &str, lo: f64, hi: f64| -> Result<(), OptError> {
            if !(lo.is_finite() && hi.is_finite()) || lo < 0.0 {
                return Err(OptError::invalid(
                    path,
                    field,
                    format!("bounds must be finite and >= 0, got [{lo}, {hi}]"),
                ));
            }
            if hi <= lo {
                return Err(OptError::invalid(
                    path,
                    field,
                    format!("bounds reversed or empty: lower {lo} kN must be below upper {hi} kN"),
                ));
            }
            Ok(())
        };
        let (offset, basis, names, shape, lower, upper) = match cfg {
            SpaceConfig::Free { lower_kn, upper_kn } => {
                for (field, v) in [
                    ("space.free.lower_kn", lower_kn),
                    ("space.free.upper_kn", upper_kn),
                ] {
                    if v.len() != m {
                        return Err(OptError::invalid(
                            path,
                            field,
                            format!(
                                "has {} values, expected {m} (one per dissipator, bottom to top)",
                                v.len()
                            ),
                        ));
                    }
                }
                for i in 0..m {
                    check_pair(
                        &format!("space.free.upper_kn[{i}]"),
                        lower_kn[i],
                        upper_kn[i],
                    )?;
                }
                let lo: Vec<f64> = lower_kn.iter().map(|v| v * 1e3).collect();
                let hi: Vec<f64> = upper_kn.iter().map(|v| v * 1e3).collect();
                let basis = DMatrix::from_fn(m, m, |i, j| if i == j { hi[i] - lo[i] } else { 0.0 });
                let names = dampers.iter().map(|f| format!("floor{}", f + 1)).collect();
                (lo.clone(), basis, names, None, lo, hi)
            }
            SpaceConfig::Profile { shape, scale_kn } => {
                check_pair("space.profile.scale_kn", scale_kn[0], scale_kn[1])?;
                let all = shape.on_floors(building);
                let sh: Vec<f64> = dampers.iter().map(|&f| all[f]).collect();
                if sh.iter().any(|v| !(v.is_finite() && *v >= 0.0)) {
                    return Err(OptError::invalid(
                        path,
                        "space.profile.shape",
                        format!(
                            "shape {} gives invalid factors {sh:?} on this building",
                            shape.as_str()
                        ),
                    ));
                }
                let (lo, hi) = (scale_kn[0] * 1e3, scale_kn[1] * 1e3);
                let offset: Vec<f64> = sh.iter().map(|v| v * lo).collect();
                let basis = DMatrix::from_fn(m, 1, |i, _| sh[i] * (hi - lo));
                let lower = offset.clone();
                let upper: Vec<f64> = sh.iter().map(|v| v * hi).collect();
                (
                    offset,
                    basis,
                    vec!["scale".into()],
                    Some((*shape, sh)),
                    lower,
                    upper,
                )
            }
        };
        // the building's own bound on a slip load (its rounding must stay far below the
        // weight), so a sweep never builds a contact the building file would refuse
        let weight = building.mass.sum() * slipload_motion::G;
        let max_slip = slipload_sim::building::MAX_SLIP_LOAD_PER_WEIGHT * weight;
        if let Some(i) = upper.iter().position(|&u| u > max_slip) {
            let field = match cfg {
                SpaceConfig::Free { .. } => format!("space.free.upper_kn[{i}]"),
                SpaceConfig::Profile { .. } => "space.profile.scale_kn".to_string(),
            };
            return Err(OptError::invalid(
                path,
                field,
                format!(
                    "gives a slip load of {:e} kN, more than {:e} × the building's weight ({:.4e} kN): write the dissipator \"locked\" in the building instead, else check the units",
                    upper[i] / 1e3,
                    slipload_sim::building::MAX_SLIP_LOAD_PER_WEIGHT,
                    weight / 1e3
                ),
            ));
        }
        // Constraints on s = offset + basis z, turned into rows on z.
        let d = basis.ncols();
        let mut rows: Vec<(Vec<f64>, f64)> = Vec::new();
        if let Some(budget) = cons.budget_kn {
            if !(budget.is_finite() && budget > 0.0) {
                return Err(OptError::invalid(
                    path,
                    "constraints.budget_kn",
                    format!("must be finite and > 0, got {budget}"),
                ));
            }
            let b = budget * 1e3;
            let row: Vec<f64> = (0..d).map(|j| basis.column(j).sum()).collect();
            rows.push((row, b - offset.iter().sum::<f64>()));
        }
        if cons.non_increasing {
            for k in 0..m.saturating_sub(1) {
                let row: Vec<f64> = (0..d).map(|j| basis[(k + 1, j)] - basis[(k, j)]).collect();
                rows.push((row, offset[k] - offset[k + 1]));
            }
        }
        // Feasibility (the LP argument of the module doc).
        let mut least = lower.clone();
        if cons.non_increasing {
            for i in (0..m.saturating_sub(1)).rev() {
                least[i] = least[i].max(least[i + 1]);
            }
            if shape.is_some() {
                // a profile is non-increasing for all scales iff its shape is
                if let Some(k) =
                    (0..m - 1).find(|&k| basis[(k + 1, 0)] > basis[(k, 0)] * (1.0 + FEAS_TOL))
                {
                    return Err(OptError::invalid(
                        path,
                        "constraints.non_increasing",
                        format!(
                            "infeasible: the profile increases from dissipator {} to {}",
                            k + 1,
                            k + 2
                        ),
                    ));
                }
            }
            if let Some(i) = (0..m).find(|&i| least[i] > upper[i] * (1.0 + FEAS_TOL)) {
                return Err(OptError::invalid(
                    path,
                    "constraints.non_increasing",
                    format!(
                        "infeasible: dissipator {} must carry at least {:.3} kN (a lower bound above it) but its upper bound is {:.3} kN",
                        i + 1,
                        least[i] / 1e3,
                        upper[i] / 1e3
                    ),
                ));
            }
        }
        if let Some(budget) = cons.budget_kn {
            let need: f64 = least.iter().sum();
            if need > budget * 1e3 * (1.0 + FEAS_TOL) {
                return Err(OptError::invalid(
                    path,
                    "constraints.budget_kn",
                    format!(
                        "infeasible: the bounds{} need at least {:.3} kN in total, above the budget {budget} kN",
                        if cons.non_increasing {
                            " and non-increasing loads"
                        } else {
                            ""
                        },
                        need / 1e3
                    ),
                ));
            }
        }
        let a = DMatrix::from_fn(rows.len(), d, |i, j| rows[i].0[j]);
        let b = rows.iter().map(|r| r.1).collect();
        let shear = Shape::StoreyShear.on_floors(building);
        let profile = dampers.iter().map(|&f| shear[f]).collect();
        Ok(DesignSpace {
            dampers,
            offset,
            basis,
            a,
            b,
            names,
            shape,
            profile,
        })
    }

    /// Number of design variables.
    pub fn dim(&self) -> usize {
        self.basis.ncols()
    }

    /// Slip loads per dissipator, N, at scaled point `z`.
    pub fn slip_loads(&self, z: &[f64]) -> Vec<f64> {
        let zz = DVector::from_column_slice(z);
        let s = &self.basis * zz;
        self.offset
            .iter()
            .zip(s.iter())
            .map(|(o, v)| (o + v).max(0.0))
            .collect()
    }

    /// The scaled point of slip loads `loads` (N per dissipator), when the space holds
    /// them: `offset + basis z = loads` to round-off (relative 1e-9, the affine map's) at a
    /// feasible `z`; `None` for loads off the space (another profile, beyond a bound,
    /// breaking a constraint).
    pub fn point_of(&self, loads: &[f64]) -> Option<Vec<f64>> {
        let z = self.least_squares_point(loads)?;
        let back = self.slip_loads(&z);
        let scale = loads.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let close = back
            .iter()
            .zip(loads)
            .all(|(a, b)| (a - b).abs() <= 1e-9 * scale);
        (close && self.is_feasible(&z)).then(|| z.iter().map(|v| v.clamp(0.0, 1.0)).collect())
    }

    /// The scaled point whose slip loads are closest to `loads` (N per dissipator) in least
    /// squares on the (full column rank) basis, by the normal equations: exact for loads
    /// the space holds, unclamped and unchecked otherwise. `None` for loads of another
    /// length or a singular solve.
    pub fn least_squares_point(&self, loads: &[f64]) -> Option<Vec<f64>> {
        if loads.len() != self.offset.len() {
            return None;
        }
        let rhs = DVector::from_iterator(
            loads.len(),
            loads.iter().zip(&self.offset).map(|(s, o)| s - o),
        );
        let btb = self.basis.transpose() * &self.basis;
        let z = btb.lu().solve(&(self.basis.transpose() * &rhs))?;
        Some(z.iter().copied().collect())
    }

    /// Whether `z` is inside [0, 1]^d and satisfies the constraints (relative slack 1e-9).
    pub fn is_feasible(&self, z: &[f64]) -> bool {
        if z.iter().any(|v| !(-FEAS_TOL..=1.0 + FEAS_TOL).contains(v)) {
            return false;
        }
        (0..self.a.nrows()).all(|i| {
            let lhs: f64 = (0..z.len()).map(|j| self.a[(i, j)] * z[j]).sum();
            let scale = self.b[i].abs().max(self.a.row(i).abs().sum()).max(1.0);
            lhs <= self.b[i] + FEAS_TOL * scale
        })
    }

    /// The variables of `z` that sit on a bound of the space (within [`BOUND_TOL`]): a
    /// design there may want to go further than the space allows.
    pub fn on_bounds(&self, z: &[f64]) -> Vec<OnBound> {
        let mut out = Vec::new();
        for (j, &v) in z.iter().enumerate() {
            let bound = if v <= BOUND_TOL {
                Bound::Lower
            } else if v >= 1.0 - BOUND_TOL {
                Bound::Upper
            } else {
                continue;
            };
            let floors = (0..self.basis.nrows())
                .filter(|&i| self.basis[(i, j)] != 0.0)
                .map(|i| self.dampers[i] + 1)
                .collect();
            out.push(OnBound {
                variable: self.names[j].clone(),
                floors,
                bound,
            });
        }
        out
    }

    /// Per-floor slip loads for [`Building::with_slip_loads`] (`None` where no dissipator).
    pub fn per_floor(&self, floors: usize, loads: &[f64]) -> Vec<Option<f64>> {
        let mut v = vec![None; floors];
        for (k, &f) in self.dampers.iter().enumerate() {
            v[f] = Some(loads[k]);
        }
        v
    }
}
