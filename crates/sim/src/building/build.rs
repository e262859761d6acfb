//! Assembly of a [`Building`] from its file: the SI mass, stiffness and damping matrices,
//! the bare frame's modes, the storey heights, the P-Δ loads and the collapse limit, in
//! the order the checks of `check` run (the first refusal is the one reported).

use super::check::{
    check_floor_masses, check_magnitudes, dissipators, per_floor, square, storey_yield,
    unstable_frame,
};
use super::config::{BuildingConfig, DampingConfig, PDeltaConfig, RayleighConfig};
use super::validated::Building;
use crate::error::SimError;
use crate::modes::Modes;
use crate::units::{is_non_negative, is_positive};
use nalgebra::{DMatrix, DVector};
use std::path::Path;

/// Default collapse limit: storey drift ratio past which a yielding or P-Δ frame is taken
/// to have collapsed.
pub const DEFAULT_COLLAPSE_DRIFT_RATIO: f64 = 0.10;

/// Standard gravity (m/s²), for the default P-Δ loads.
pub const STANDARD_GRAVITY: f64 = 9.806_65;

/// The P-Δ gravity load of each storey: given, or g times the floor masses (row sums of
/// the mass matrix) at and above it.
fn gravity_loads(
    pd: &PDeltaConfig,
    path: &Path,
    mass: &DMatrix<f64>,
    heights: Option<&[f64]>,
) -> Result<Vec<f64>, SimError> {
    let n = mass.nrows();
    if heights.is_none() {
        return Err(SimError::invalid(
            path,
            "p_delta",
            "needs storey_heights (the geometric stiffness of storey i is -P_i/h_i)",
        ));
    }
    match &pd.gravity_loads {
        Some(ps) => {
            let ps: Vec<f64> = ps.iter().map(|p| p.0).collect();
            per_floor(
                path,
                "p_delta.gravity_loads",
                &ps,
                Some(n),
                is_non_negative,
                "a finite load ≥ 0",
            )
        }
        None => {
            let floor_mass: Vec<f64> = (0..n).map(|i| mass.row(i).sum()).collect();
            let mut p = vec![0.0; n];
            let mut above = 0.0;
            for i in (0..n).rev() {
                above += floor_mass[i];
                p[i] = STANDARD_GRAVITY * above;
            }
            Ok(p)
        }
    }
}

/// α and β of Rayleigh damping as written: given, or from the ratios ζᵢ, ζⱼ at two
/// circular frequencies ωᵢ ≠ ωⱼ (two modes of the bare frame, or two periods), solving
/// ζ = α/(2ω) + βω/2 at both (Chopra, Dynamics of Structures, §11.4):
/// α = 2ωᵢωⱼ(ζᵢωⱼ − ζⱼωᵢ)/(ωⱼ² − ωᵢ²), β = 2(ζⱼωⱼ − ζᵢωᵢ)/(ωⱼ² − ωᵢ²).
pub(crate) fn rayleigh_coefficients(
    r: &RayleighConfig,
    modes: &Modes,
    path: &Path,
) -> Result<(f64, f64), SimError> {
    let field = |name: &str| format!("damping.rayleigh.{name}");
    let invalid = |name: &str, message: String| SimError::invalid(path, field(name), message);
    let by_ratios =
        r.ratio.is_some() || r.ratios.is_some() || r.modes.is_some() || r.periods.is_some();
    let (alpha, beta) = match (r.alpha, r.beta) {
        (Some(a), Some(b)) if !by_ratios => (a, b),
        (None, None) if by_ratios => {
            let zeta = match (r.ratio, &r.ratios) {
                (Some(z), None) => [z, z],
                (None, Some(zs)) if zs.len() == 2 => [zs[0], zs[1]],
                (None, Some(zs)) => {
                    return Err(invalid(
                        "ratios",
                        format!(
                            "expected the ratios at the two modes or periods, got {} values",
                            zs.len()
                        ),
                    ));
                }
                _ => {
                    return Err(invalid(
                        "ratio",
                        "give exactly one of `ratio` (the same at both) and `ratios` (one per mode or period)".into(),
                    ));
                }
            };
            if let Some(z) = zeta.iter().find(|z| !(**z >= 0.0 && **z < 1.0)) {
                return Err(invalid(
                    if r.ratio.is_some() { "ratio" } else { "ratios" },
                    format!("a damping ratio is a fraction of critical in [0, 1), got {z}"),
                ));
            }
            let n = modes.omega.len();
            let omega: [f64; 2] = match (&r.modes, &r.periods) {
                (Some(ms), None) if ms.len() == 2 => {
                    if let Some(m) = ms.iter().find(|m| **m == 0 || **m > n) {
                        return Err(invalid(
                            "modes",
                            format!("mode {m}: the bare frame has modes 1 to {n}"),
                        ));
                    }
                    [modes.omega[ms[0] - 1], modes.omega[ms[1] - 1]]
                }
                (None, Some(ts)) if ts.len() == 2 => {
                    if let Some(t) = ts.iter().find(|t| !is_positive(t.0)) {
                        return Err(invalid(
                            "periods",
                            format!("a period must be finite and > 0, got {} s", t.0),
                        ));
                    }
                    let w = |t: f64| 2.0 * std::f64::consts::PI / t;
                    [w(ts[0].0), w(ts[1].0)]
                }
                (Some(v), None) => {
                    return Err(invalid(
                        "modes",
                        format!("expected two modes, got {}", v.len()),
                    ));
                }
                (None, Some(v)) => {
                    return Err(invalid(
                        "periods",
                        format!("expected two periods, got {}", v.len()),
                    ));
                }
                _ => {
                    return Err(invalid(
                        "modes",
                        "give exactly one of `modes` (two modes of the bare frame, 1 = the first) and `periods` (two periods) where the ratios hold".into(),
                    ));
                }
            };
            let (wi, wj) = (omega[0], omega[1]);
            // (both finite and > 0 here; closer than 1e-6 the 2 × 2 system is singular
            // to the digits a ratio is given with)
            if (wi - wj).abs() <= 1e-6 * wi.max(wj) {
                return Err(invalid(
                    if r.modes.is_some() {
                        "modes"
                    } else {
                        "periods"
                    },
                    "the two modes or periods must differ: one frequency cannot fix both α and β"
                        .into(),
                ));
            }
            let d = wj * wj - wi * wi;
            let alpha = 2.0 * wi * wj * (zeta[0] * wj - zeta[1] * wi) / d;
            let beta = 2.0 * (zeta[1] * wj - zeta[0] * wi) / d;
            // round-off of equal ratios may leave a coefficient a hair below 0
            let clean = |x: f64, scale: f64| {
                if x < 0.0 && x > -1e-12 * scale {
                    0.0
                } else {
                    x
                }
            };
            let alpha = clean(alpha, zeta[0].max(zeta[1]) * wi.max(wj));
            let beta = clean(beta, zeta[0].max(zeta[1]) / wi.min(wj));
            if alpha < 0.0 || beta < 0.0 {
                return Err(invalid(
                    if r.ratio.is_some() { "ratio" } else { "ratios" },
                    format!(
                        "ratios {} and {} at {:.4} s and {:.4} s give α = {alpha:.6e} 1/s, β = {beta:.6e} s: Rayleigh damping cannot fall or rise that fast between the two (a negative coefficient makes modes with negative damping); bring the ratios closer or use `modal` damping",
                        zeta[0],
                        zeta[1],
                        2.0 * std::f64::consts::PI / wi,
                        2.0 * std::f64::consts::PI / wj
                    ),
                ));
            }
            (alpha, beta)
        }
        _ => {
            return Err(SimError::invalid(
                path,
                "damping.rayleigh",
                "give `alpha` and `beta`, or the damping ratio (`ratio` or `ratios`) at two `modes` or two `periods` of the bare frame",
            ));
        }
    };
    for (name, v) in [("alpha", alpha), ("beta", beta)] {
        if !is_non_negative(v) {
            return Err(invalid(name, format!("must be finite and ≥ 0, got {v}")));
        }
    }
    Ok((alpha, beta))
}

fn chain(values: &[f64]) -> DMatrix<f64> {
    let n = values.len();
    let mut k = DMatrix::zeros(n, n);
    for (i, &ki) in values.iter().enumerate() {
        k[(i, i)] += ki;
        if i > 0 {
            k[(i - 1, i - 1)] += ki;
            k[(i, i - 1)] -= ki;
            k[(i - 1, i)] -= ki;
        }
    }
    k
}

impl Building {
    /// Reads and validates a building JSON file.
    pub fn load(path: &Path) -> Result<Building, SimError> {
        let text = slipload_motion::limits::read_input_text(
            path,
            "building",
            slipload_motion::limits::MAX_CONFIG_BYTES,
        )?;
        let cfg: BuildingConfig = crate::kind::parse(&text, path, crate::kind::Expected::Building)?;
        Building::from_config(&cfg, path)
    }
    /// Validates a config; `path` names the source in errors.
    pub fn from_config(cfg: &BuildingConfig, path: &Path) -> Result<Building, SimError> {
        let mass = match (&cfg.floor_masses, &cfg.mass_matrix) {
            (Some(_), Some(_)) => {
                return Err(SimError::invalid(
                    path,
                    "mass_matrix",
                    "give either floor_masses or mass_matrix, not both",
                ));
            }
            (None, None) => {
                return Err(SimError::invalid(
                    path,
                    "floor_masses",
                    "missing: give floor_masses (kg per floor) or mass_matrix",
                ));
            }
            (Some(ms), None) => {
                let ms: Vec<f64> = ms.iter().map(|m| m.0).collect();
                let ms = per_floor(
                    path,
                    "floor_masses",
                    &ms,
                    None,
                    is_positive,
                    "a positive finite mass",
                )?;
                DMatrix::from_diagonal(&DVector::from_vec(ms))
            }
            (None, Some(rows)) => square(path, "mass_matrix", rows, None)?,
        };
        let n = mass.nrows();
        if mass.clone().cholesky().is_none() {
            return Err(SimError::invalid(
                path,
                "mass_matrix",
                "must be positive definite",
            ));
        }
        check_floor_masses(cfg, path, &mass)?;
        let stiffness = match (&cfg.storey_stiffness, &cfg.stiffness_matrix) {
            (Some(_), Some(_)) => {
                return Err(SimError::invalid(
                    path,
                    "stiffness_matrix",
                    "give either storey_stiffness or stiffness_matrix, not both",
                ));
            }
            (None, None) => {
                return Err(SimError::invalid(
                    path,
                    "storey_stiffness",
                    "missing: give storey_stiffness (N/m per storey) or stiffness_matrix",
                ));
            }
            (Some(ks), None) => {
                let ks: Vec<f64> = ks.iter().map(|k| k.0).collect();
                chain(&per_floor(
                    path,
                    "storey_stiffness",
                    &ks,
                    Some(n),
                    is_positive,
                    "a positive finite stiffness",
                )?)
            }
            (None, Some(rows)) => square(path, "stiffness_matrix", rows, Some(n))?,
        };
        let modes = Modes::compute(&mass, &stiffness).ok_or_else(|| unstable_frame(cfg, path))?;
        let damping = match &cfg.damping {
            None | Some(DampingConfig::None) => DMatrix::zeros(n, n),
            Some(DampingConfig::Rayleigh(r)) => {
                let (alpha, beta) = rayleigh_coefficients(r, &modes, path)?;
                &mass * alpha + &stiffness * beta
            }
            Some(DampingConfig::Modal { ratio, ratios }) => {
                let zeta: Vec<f64> = match (ratio, ratios) {
                    (Some(z), None) => vec![*z; n],
                    (None, Some(zs)) if !zs.is_empty() => {
                        (0..n).map(|i| zs[i.min(zs.len() - 1)]).collect()
                    }
                    _ => {
                        return Err(SimError::invalid(
                            path,
                            "damping.modal",
                            "give exactly one of `ratio` (all modes) or a non-empty `ratios` list",
                        ));
                    }
                };
                if let Some(i) = zeta.iter().position(|z| !(*z >= 0.0 && *z < 1.0)) {
                    return Err(SimError::invalid(
                        path,
                        "damping.modal",
                        format!("ratio of mode {} must be in [0, 1), got {}", i + 1, zeta[i]),
                    ));
                }
                modes.damping_matrix(&mass, &zeta)
            }
            Some(DampingConfig::Storey(cs)) => {
                let cs: Vec<f64> = cs.iter().map(|c| c.0).collect();
                chain(&per_floor(
                    path,
                    "damping.storey",
                    &cs,
                    Some(n),
                    is_non_negative,
                    "finite and ≥ 0",
                )?)
            }
            Some(DampingConfig::Matrix(rows)) => {
                let c = square(path, "damping.matrix", rows, Some(n))?;
                if c.symmetric_eigenvalues()
                    .iter()
                    .any(|&l| l < -1e-9 * c.norm())
                {
                    return Err(SimError::invalid(
                        path,
                        "damping.matrix",
                        "must be positive semi-definite",
                    ));
                }
                c
            }
        };
        let storey_heights = match &cfg.storey_heights {
            None => None,
            Some(hs) => {
                let hs: Vec<f64> = hs.iter().map(|h| h.0).collect();
                Some(per_floor(
                    path,
                    "storey_heights",
                    &hs,
                    Some(n),
                    is_positive,
                    "a positive length",
                )?)
            }
        };
        let dissipators = dissipators(cfg, path, n)?;
        check_magnitudes(
            cfg,
            path,
            &mass,
            &stiffness,
            &damping,
            &modes,
            &dissipators,
            storey_heights.as_deref(),
        )?;
        let storey_yield = storey_yield(cfg, path, n, &stiffness)?;
        let gravity_loads = match &cfg.p_delta {
            None => None,
            Some(pd) => Some(gravity_loads(pd, path, &mass, storey_heights.as_deref())?),
        };
        let nonlinear = storey_yield.iter().any(Option::is_some) || gravity_loads.is_some();
        let collapse_drift = match (cfg.collapse_drift_ratio, &cfg.collapse_drift) {
            (Some(_), Some(_)) => {
                return Err(SimError::invalid(
                    path,
                    "collapse_drift",
                    "give either collapse_drift_ratio or collapse_drift, not both",
                ));
            }
            (Some(r), None) => {
                if !is_positive(r) {
                    return Err(SimError::invalid(
                        path,
                        "collapse_drift_ratio",
                        format!("must be positive and finite, got {r}"),
                    ));
                }
                let Some(h) = &storey_heights else {
                    return Err(SimError::invalid(
                        path,
                        "collapse_drift_ratio",
                        "needs storey_heights (or give collapse_drift in m)",
                    ));
                };
                Some(h.iter().map(|h| r * h).collect())
            }
            (None, Some(d)) => {
                if !is_positive(d.0) {
                    return Err(SimError::invalid(
                        path,
                        "collapse_drift",
                        format!("must be positive and finite, got {}", d.0),
                    ));
                }
                Some(vec![d.0; n])
            }
            (None, None) if nonlinear => storey_heights
                .as_ref()
                .map(|h| h.iter().map(|h| DEFAULT_COLLAPSE_DRIFT_RATIO * h).collect()),
            (None, None) => None,
        };
        Ok(Building {
            name: cfg.name.clone().unwrap_or_else(|| {
                path.file_stem()
                    .map_or_else(|| "building".into(), |s| s.to_string_lossy().into_owned())
            }),
            mass,
            stiffness,
            damping,
            storey_heights,
            dissipators,
            storey_yield,
            gravity_loads,
            collapse_drift,
            modes,
        })
    }
}
