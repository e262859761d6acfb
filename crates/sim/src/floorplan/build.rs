//! Validation and assembly of a [`FloorPlan`] from its file: floors (mass, inertia, centre
//! of mass), lines (direction, position, storey springs, yield laws, dampers), the bare
//! frame's mass and stiffness on the floors' DOFs, its modes, and its damping. Errors name
//! the file and the field (`lines[2].storey_stiffness[4]`).

use super::config::{DirectionConfig, FloorPlanConfig};
use super::model::{Floor, FloorPlan, Line, damping_matrix, mass_matrix, p_delta_blocks};
use crate::building::{
    DEFAULT_COLLAPSE_DRIFT_RATIO, FLOOR_MASS_BAND_KG, PERIOD_BAND_S, line_parts,
};
use crate::error::SimError;
use crate::kinematics::{Kin, add_between};
use crate::modes::Modes;
use crate::units::{is_non_negative, is_positive};
use nalgebra::DMatrix;
use std::path::Path;

/// A line's point on floor `f` (0-based): its motion along the line's direction.
pub(super) fn line_point(line: &Line, f: usize) -> Kin {
    let [c, s, r] = line.weights();
    Kin::weighted(&[(3 * f, c), (3 * f + 1, s), (3 * f + 2, r)])
}

/// A line's two ends at storey `f` (0-based, its top floor): the floor's point and the
/// floor below's (the ground's for the first storey).
pub(super) fn line_ends(line: &Line, f: usize) -> (Kin, Kin) {
    let bottom = if f == 0 {
        Kin::GROUND
    } else {
        line_point(line, f - 1)
    };
    (line_point(line, f), bottom)
}

/// Most named points a building in plan takes.
const MAX_POINTS: usize = 64;

impl FloorPlan {
    /// Reads and validates a building-in-plan JSON file.
    pub fn load(path: &Path) -> Result<FloorPlan, SimError> {
        let text = slipload_motion::limits::read_input_text(
            path,
            "building in plan",
            slipload_motion::limits::MAX_CONFIG_BYTES,
        )?;
        let cfg: FloorPlanConfig =
            serde_json::from_str(&text).map_err(|source| SimError::Json {
                path: path.to_path_buf(),
                source,
            })?;
        FloorPlan::from_config(&cfg, path)
    }

    /// Validates a config; `path` names the source in errors.
    pub fn from_config(cfg: &FloorPlanConfig, path: &Path) -> Result<FloorPlan, SimError> {
        let invalid = |field: String, message: String| SimError::invalid(path, field, message);
        let n = cfg.floors.len();
        if n == 0 {
            return Err(invalid(
                "floors".into(),
                "must list at least one floor".into(),
            ));
        }
        let size = match cfg.plan_size {
            Some([lx, ly]) => {
                for (i, v) in [lx.0, ly.0].into_iter().enumerate() {
                    if !is_positive(v) {
                        return Err(invalid(
                            format!("plan_size[{i}]"),
                            format!("must be a positive finite length (m), got {v}"),
                        ));
                    }
                }
                Some([lx.0, ly.0])
            }
            None => None,
        };
        let mut floors = Vec::with_capacity(n);
        for (i, f) in cfg.floors.iter().enumerate() {
            let m = f.mass.0;
            if !(is_positive(m) && m >= FLOOR_MASS_BAND_KG.0 && m <= FLOOR_MASS_BAND_KG.1) {
                return Err(invalid(
                    format!("floors[{i}].mass"),
                    format!(
                        "must be a positive mass within [{:e}, {:e}] kg, got {m}",
                        FLOOR_MASS_BAND_KG.0, FLOOR_MASS_BAND_KG.1
                    ),
                ));
            }
            let centre = match (f.centre_of_mass, size) {
                (Some([x, y]), _) => {
                    for (k, v) in [x.0, y.0].into_iter().enumerate() {
                        if !v.is_finite() {
                            return Err(invalid(
                                format!("floors[{i}].centre_of_mass[{k}]"),
                                format!("must be a finite coordinate (m), got {v}"),
                            ));
                        }
                    }
                    [x.0, y.0]
                }
                (None, Some([lx, ly])) => [lx / 2.0, ly / 2.0],
                (None, None) => {
                    return Err(invalid(
                        format!("floors[{i}].centre_of_mass"),
                        "missing: give the centre of mass [x, y] (m), or plan_size for the centre of the plan".into(),
                    ));
                }
            };
            let inertia = match (f.inertia_kg_m2, size) {
                (Some(j), _) => {
                    if !is_positive(j) {
                        return Err(invalid(
                            format!("floors[{i}].inertia_kg_m2"),
                            format!(
                                "must be a positive finite mass moment of inertia (kg*m^2), got {j}"
                            ),
                        ));
                    }
                    j
                }
                (None, Some([lx, ly])) => m * (lx * lx + ly * ly) / 12.0,
                (None, None) => {
                    return Err(invalid(
                        format!("floors[{i}].inertia_kg_m2"),
                        "missing: give the mass moment of inertia about the centre of mass (kg*m^2), or plan_size for a uniform rectangular floor's".into(),
                    ));
                }
            };
            floors.push(Floor {
                mass: m,
                inertia,
                centre,
            });
        }
        let heights = match &cfg.storey_heights {
            Some(hs) => {
                if hs.len() != n {
                    return Err(invalid(
                        "storey_heights".into(),
                        format!("has {} values, expected {n} (one per storey)", hs.len()),
                    ));
                }
                if let Some(i) = hs.iter().position(|h| !is_positive(h.0)) {
                    return Err(invalid(
                        format!("storey_heights[{i}]"),
                        format!("must be a positive finite height (m), got {}", hs[i].0),
                    ));
                }
                Some(hs.iter().map(|h| h.0).collect::<Vec<f64>>())
            }
            None => None,
        };
        if cfg.lines.is_empty() {
            return Err(invalid(
                "lines".into(),
                "must list the lateral lines (at least two directions, not all through one point, so the floors resist both translations and the rotation)".into(),
            ));
        }
        let mut lines = Vec::with_capacity(cfg.lines.len());
        for (l, lc) in cfg.lines.iter().enumerate() {
            let at = |name: &str| format!("lines[{l}].{name}");
            let angle = match lc.direction {
                DirectionConfig::X => 0.0,
                DirectionConfig::Y => std::f64::consts::FRAC_PI_2,
                DirectionConfig::Degrees(d) if d.is_finite() => d.to_radians(),
                DirectionConfig::Degrees(d) => {
                    return Err(invalid(
                        at("direction"),
                        format!("must be a finite angle, got {d}"),
                    ));
                }
            };
            let point = match (&lc.through, &lc.at, lc.direction) {
                (Some(_), Some(_), _) => {
                    return Err(invalid(
                        at("at"),
                        "give either `at` or `through`, not both".into(),
                    ));
                }
                (Some([x, y]), None, _) => [x.0, y.0],
                (None, Some(a), DirectionConfig::X) => [0.0, a.0],
                (None, Some(a), DirectionConfig::Y) => [a.0, 0.0],
                (None, Some(_), DirectionConfig::Degrees(_)) => {
                    return Err(invalid(
                        at("at"),
                        "a line at an angle is placed by `through` [x, y] (m); `at` places a line along x (its y) or y (its x)".into(),
                    ));
                }
                (None, None, _) => {
                    return Err(invalid(
                        at("at"),
                        "missing: give the line's position, `at` (a line along x: its y; along y: its x, m) or `through` [x, y]".into(),
                    ));
                }
            };
            if let Some(k) = point.iter().position(|v| !v.is_finite()) {
                return Err(invalid(
                    at("through"),
                    format!("coordinate {k} must be finite, got {}", point[k]),
                ));
            }
            let ks: Vec<f64> = lc.storey_stiffness.iter().map(|k| k.0).collect();
            if ks.len() != n {
                return Err(invalid(
                    at("storey_stiffness"),
                    format!("has {} values, expected {n} (one per storey)", ks.len()),
                ));
            }
            if let Some(i) = ks.iter().position(|k| !is_non_negative(*k)) {
                return Err(invalid(
                    at(&format!("storey_stiffness[{i}]")),
                    format!(
                        "must be a finite stiffness ≥ 0 (N/m; 0 where the line has no storey), got {}",
                        ks[i]
                    ),
                ));
            }
            let dashpots: Vec<f64> = if lc.storey_damping.is_empty() {
                vec![0.0; n]
            } else {
                lc.storey_damping.iter().map(|c| c.0).collect()
            };
            if dashpots.len() != n {
                return Err(invalid(
                    at("storey_damping"),
                    format!(
                        "has {} values, expected {n} (one per storey, N·s/m)",
                        dashpots.len()
                    ),
                ));
            }
            if let Some(i) = dashpots.iter().position(|c| !is_non_negative(*c)) {
                return Err(invalid(
                    at(&format!("storey_damping[{i}]")),
                    format!(
                        "must be a finite damping coefficient ≥ 0 (N·s/m), got {}",
                        dashpots[i]
                    ),
                ));
            }
            let (storey_yield, dissipators) = line_parts(
                &format!("lines[{l}]."),
                &lc.storey_stiffness,
                &lc.storey_yield,
                &lc.dissipators,
                path,
            )?;
            lines.push(Line {
                name: lc.name.clone().unwrap_or_else(|| format!("L{}", l + 1)),
                angle,
                point,
                stiffness: ks,
                dashpots,
                storey_yield,
                dissipators,
            });
        }
        for (l, line) in lines.iter().enumerate() {
            if let Some(k) = lines[..l].iter().position(|o| o.name == line.name) {
                return Err(invalid(
                    format!("lines[{l}].name"),
                    format!("\"{}\" is already the name of lines[{k}]", line.name),
                ));
            }
        }
        let mass = mass_matrix(&floors);
        let mut stiffness = DMatrix::zeros(3 * n, 3 * n);
        for line in &lines {
            for (f, k) in line.stiffness.iter().enumerate() {
                let (top, bottom) = line_ends(line, f);
                add_between(&mut stiffness, &top, &bottom, *k);
            }
        }
        let modes = Modes::compute(&mass, &stiffness).ok_or_else(|| {
            invalid(
                "lines".into(),
                "the lines leave a floor free to move: the bare frame's stiffness is singular (the lines must resist x, y and the rotation at every storey: two directions, and lines not all through one point)".into(),
            )
        })?;
        let periods = modes.periods();
        if let Some(t) = periods
            .iter()
            .find(|t| !(**t >= PERIOD_BAND_S.0 && **t <= PERIOD_BAND_S.1))
        {
            return Err(invalid(
                "lines".into(),
                format!(
                    "the bare frame has a period of {t:e} s, outside [{:e}, {:e}] s: check the units of the masses, inertias and stiffnesses",
                    PERIOD_BAND_S.0, PERIOD_BAND_S.1
                ),
            ));
        }
        let damping = damping_matrix(cfg.damping.as_ref(), &mass, &stiffness, &modes, path)?;
        let yields = lines
            .iter()
            .any(|l| l.storey_yield.iter().any(Option::is_some));
        let collapse_drift = match (cfg.collapse_drift_ratio, &heights) {
            (Some(r), _) if !(is_positive(r) && r < 1.0) => {
                return Err(invalid(
                    "collapse_drift_ratio".into(),
                    format!("must be a drift ratio in (0, 1), got {r}"),
                ));
            }
            (Some(_), None) => {
                return Err(invalid(
                    "collapse_drift_ratio".into(),
                    "needs storey_heights".into(),
                ));
            }
            (Some(r), Some(h)) => Some(h.iter().map(|h| r * h).collect()),
            (None, Some(h)) if yields => {
                Some(h.iter().map(|h| DEFAULT_COLLAPSE_DRIFT_RATIO * h).collect())
            }
            (None, _) => None,
        };
        let p_delta = match &cfg.p_delta {
            None => None,
            Some(pd) => {
                let Some(h) = &heights else {
                    return Err(invalid(
                        "p_delta".into(),
                        "needs storey_heights (the geometric stiffness of storey i is P_i/h_i)"
                            .into(),
                    ));
                };
                let loads = match &pd.gravity_loads {
                    None => None,
                    Some(ps) => {
                        if ps.len() != n {
                            return Err(invalid(
                                "p_delta.gravity_loads".into(),
                                format!("has {} values, expected {n} (one per storey)", ps.len()),
                            ));
                        }
                        for (i, p) in ps.iter().enumerate() {
                            if !is_non_negative(p.0) {
                                return Err(invalid(
                                    format!("p_delta.gravity_loads[{i}]"),
                                    format!("a finite load >= 0 (N), got {}", p.0),
                                ));
                            }
                        }
                        Some(ps.iter().map(|p| p.0).collect::<Vec<f64>>())
                    }
                };
                Some(p_delta_blocks(&floors, h, loads.as_deref()))
            }
        };
        let mut points: Vec<(String, [f64; 2])> = Vec::with_capacity(cfg.points.len());
        if cfg.points.len() > MAX_POINTS {
            return Err(invalid(
                "points".into(),
                format!(
                    "{} points: at most {MAX_POINTS} (each floor reports every one)",
                    cfg.points.len()
                ),
            ));
        }
        for (k, pc) in cfg.points.iter().enumerate() {
            let name = pc.name.trim();
            if name.is_empty() {
                return Err(invalid(
                    format!("points[{k}].name"),
                    "must not be empty".into(),
                ));
            }
            if let Some(j) = points.iter().position(|(n, _)| n == name) {
                return Err(invalid(
                    format!("points[{k}].name"),
                    format!("\"{name}\" is already the name of points[{j}]"),
                ));
            }
            let at = [pc.at[0].0, pc.at[1].0];
            if let Some(i) = at.iter().position(|v| !v.is_finite()) {
                return Err(invalid(
                    format!("points[{k}].at[{i}]"),
                    format!("must be a finite coordinate (m), got {}", at[i]),
                ));
            }
            points.push((name.to_string(), at));
        }
        Ok(FloorPlan {
            name: cfg
                .name
                .clone()
                .unwrap_or_else(|| "building in plan".into()),
            floors,
            lines,
            plan_size: size,
            storey_heights: heights,
            mass,
            stiffness,
            damping,
            collapse_drift,
            modes,
            damping_config: cfg.damping.clone(),
            p_delta,
            p_delta_config: cfg.p_delta.clone(),
            points,
        })
    }
}
