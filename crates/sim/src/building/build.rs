//! The building model: floor masses, frame stiffness and damping, storey heights, and at
//! most one friction dissipator per floor (docs/MODEL.md § The model).
//!
//! A [`BuildingConfig`] is what a JSON file says (unknown fields rejected, units accepted
//! as strings); [`Building::from_config`] validates it into SI matrices with errors that
//! name the file and field. Beyond signs and finiteness, magnitudes must be physical:
//! the natural periods of the bare frame and of the frame with its braces locked lie in
//! [`PERIOD_BAND_S`], floor masses in [`FLOOR_MASS_BAND_KG`], damping ratios are at most
//! [`MAX_DAMPING_RATIO`], slip loads at most [`MAX_SLIP_LOAD_PER_WEIGHT`] × the weight
//! (so a stiffness of 1e300 N/m or a mass of 1e-300 kg is refused, naming the field).

use crate::error::SimError;
use crate::modes::Modes;
use crate::units::{Damping, Force, Length, Mass, Stiffness, is_non_negative, is_positive};
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};
use std::path::Path;

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

/// Default collapse limit: storey drift ratio past which a yielding or P-Δ frame is taken
/// to have collapsed.
pub const DEFAULT_COLLAPSE_DRIFT_RATIO: f64 = 0.10;

/// The physical band of a building's natural periods, s: [`PERIOD_BAND_S`].0 … .1. Real
/// structures (from a shake-table model to a kilometre-tall tower) have periods of a few
/// hundredths of a second to about ten seconds; a period outside 10⁻⁴ … 10⁴ s means a
/// units slip or a typo in a mass or a stiffness (a stiffness of 1e300 N/m), which would
/// give numbers but not answers. Applies to the bare frame and to the frame with every
/// brace locked.
pub const PERIOD_BAND_S: (f64, f64) = (1e-4, 1e4);

/// The band of a dissipator's own period 2π√(m′/k′) (mass on its brace), s, when
/// m′ > 0: wider below than [`PERIOD_BAND_S`] because light dissipators on stiff braces
/// are a real study (m′ → 0 tends to the massless model, and the convergence to it is
/// studied down to m′ = 1 mg on the benchmark's 448 MN/m brace, 3·10⁻⁷ s); below 1 ns
/// a mass is a units slip (give m′ = 0 for that limit).
pub const DISSIPATOR_PERIOD_BAND_S: (f64, f64) = (1e-9, 1e4);

/// The band of a floor mass, kg (1 g … 10⁹ t): from laboratory models to the heaviest floors.
pub const FLOOR_MASS_BAND_KG: (f64, f64) = (1e-3, 1e12);

/// Largest damping ratio of any mode of the frame (from `damping`) and of any brace
/// (c′ against its floor's mass on k′): heavily overdamped is ζ ≈ 1–2, beyond 10 is a
/// units slip.
pub const MAX_DAMPING_RATIO: f64 = 10.0;

/// Largest slip load (or friction bound) as a multiple of the building's weight (M·g,
/// all floors). Real slip loads are a few per cent of it per storey, and far larger ones
/// are legitimate ways to approach the locked limit; but a bound F carries a rounding
/// error of F × 2.2e-16, which beyond 10¹¹ × the weight exceeds 2·10⁻⁵ of the weight,
/// so the forces near it (and tolerances scaled by it) lose their digits. A contact that
/// must never slip is written `"locked"`.
pub const MAX_SLIP_LOAD_PER_WEIGHT: f64 = 1e11;

/// Largest harmonic floor force of a scene as a multiple of the building's weight: no
/// shaker or service load comes near a hundred times the weight.
pub const MAX_HARMONIC_FORCE_PER_WEIGHT: f64 = 100.0;

/// The band of a storey height, m.
pub const STOREY_HEIGHT_BAND_M: (f64, f64) = (1e-3, 1e3);

fn in_band(v: f64, band: (f64, f64)) -> bool {
    v >= band.0 && v <= band.1
}

/// The floor masses against [`FLOOR_MASS_BAND_KG`], before any eigen solve: a subnormal
/// or absurd mass must be named as such, not surface as an unstable stiffness.
fn check_floor_masses(
    cfg: &BuildingConfig,
    path: &Path,
    mass: &DMatrix<f64>,
) -> Result<(), SimError> {
    let n = mass.nrows();
    for i in 0..n {
        let m = mass[(i, i)];
        if !in_band(m, FLOOR_MASS_BAND_KG) {
            let field = if cfg.mass_matrix.is_some() {
                format!("mass_matrix[{i}][{i}]")
            } else {
                format!("floor_masses[{i}]")
            };
            return Err(SimError::invalid(
                path,
                field,
                format!(
                    "a floor mass of {m:e} kg is outside the physical band {:e} … {:e} kg (check the units)",
                    FLOOR_MASS_BAND_KG.0, FLOOR_MASS_BAND_KG.1
                ),
            ));
        }
    }
    Ok(())
}

/// The magnitudes of a validated building against the physical bands above; errors
/// name the field, the value and the band.
#[allow(clippy::too_many_arguments)] // the validated parts of one building
fn check_magnitudes(
    cfg: &BuildingConfig,
    path: &Path,
    mass: &DMatrix<f64>,
    stiffness: &DMatrix<f64>,
    damping: &DMatrix<f64>,
    modes: &Modes,
    dissipators: &[Option<Dissipator>],
    storey_heights: Option<&[f64]>,
) -> Result<(), SimError> {
    let (mass_field, stiffness_field) = (
        if cfg.mass_matrix.is_some() {
            "mass_matrix"
        } else {
            "floor_masses"
        },
        if cfg.stiffness_matrix.is_some() {
            "stiffness_matrix"
        } else {
            "storey_stiffness"
        },
    );
    let periods = modes.periods();
    let (t_long, t_short) = (periods[0], periods[periods.len() - 1]);
    if !(in_band(t_short, PERIOD_BAND_S) && in_band(t_long, PERIOD_BAND_S)) {
        return Err(SimError::invalid(
            path,
            stiffness_field,
            format!(
                "the bare frame's natural periods are {t_long:.3e} … {t_short:.3e} s; a building's must lie within {:e} … {:e} s: a mass or a stiffness is absurd (check `{mass_field}` and `{stiffness_field}` and their units)",
                PERIOD_BAND_S.0, PERIOD_BAND_S.1
            ),
        ));
    }
    // modal damping ratios ζ_k = φ_kᵀ C φ_k / (2 ω_k) (mass-normalised shapes)
    for (k, period) in periods.iter().enumerate() {
        let phi = modes.shapes.column(k);
        let zeta = (phi.transpose() * damping * phi)[(0, 0)] / (2.0 * modes.omega[k]);
        if !(zeta.is_finite() && zeta <= MAX_DAMPING_RATIO) {
            return Err(SimError::invalid(
                path,
                "damping",
                format!(
                    "gives mode {} (T = {:.3e} s) a damping ratio of {zeta:.3e}; at most {MAX_DAMPING_RATIO} is physical (check the damping values and their units)",
                    k + 1,
                    period
                ),
            ));
        }
    }
    if let Some(hs) = storey_heights
        && let Some(i) = hs.iter().position(|&h| !in_band(h, STOREY_HEIGHT_BAND_M))
    {
        return Err(SimError::invalid(
            path,
            format!("storey_heights[{i}]"),
            format!(
                "a storey height of {:e} m is outside {:e} … {:e} m (check the units)",
                hs[i], STOREY_HEIGHT_BAND_M.0, STOREY_HEIGHT_BAND_M.1
            ),
        ));
    }
    let weight = mass.sum() * slipload_motion::G;
    let max_slip = MAX_SLIP_LOAD_PER_WEIGHT * weight;
    // the cfg index of each floor's dissipator, to name fields
    let index_of = |floor: usize| {
        cfg.dissipators
            .iter()
            .position(|d| d.floor == floor + 1)
            .unwrap_or(floor)
    };
    let mut braced = stiffness.clone();
    let mut braced_mass = mass.clone();
    for (floor, d) in dissipators.iter().enumerate() {
        let Some(d) = d else { continue };
        let f = |name: &str| format!("dissipators[{}].{name}", index_of(floor));
        // the brace locked: k′ between floor i−1 (or the ground) and floor i, m′ on floor i
        let k = d.brace_stiffness;
        braced[(floor, floor)] += k;
        if floor > 0 {
            braced[(floor - 1, floor - 1)] += k;
            braced[(floor, floor - 1)] -= k;
            braced[(floor - 1, floor)] -= k;
        }
        braced_mass[(floor, floor)] += d.mass;
        let shortest = Modes::compute(&braced_mass, &braced)
            .map(|m| 2.0 * std::f64::consts::PI / m.omega[m.omega.len() - 1]);
        match shortest {
            Some(t) if in_band(t, PERIOD_BAND_S) => {}
            found => {
                return Err(SimError::invalid(
                    path,
                    f("brace_stiffness"),
                    format!(
                        "k′ = {k:e} N/m gives the frame with its braces locked a natural period of {}; a building's must lie within {:e} … {:e} s (check k′ and its units)",
                        found.map_or_else(|| "no real value".to_string(), |t| format!("{t:.3e} s")),
                        PERIOD_BAND_S.0,
                        PERIOD_BAND_S.1
                    ),
                ));
            }
        }
        if d.mass > 0.0 {
            let t = 2.0 * std::f64::consts::PI * (d.mass / d.brace_stiffness).sqrt();
            if !in_band(t, DISSIPATOR_PERIOD_BAND_S) {
                return Err(SimError::invalid(
                    path,
                    f("mass"),
                    format!(
                        "the dissipator's period on its brace, 2π√(m′/k′) = {t:.3e} s (m′ = {:e} kg, k′ = {:e} N/m), is outside {:e} … {:e} s: give m′ = 0 for a massless dissipator, else check m′ and k′ and their units",
                        d.mass,
                        d.brace_stiffness,
                        DISSIPATOR_PERIOD_BAND_S.0,
                        DISSIPATOR_PERIOD_BAND_S.1
                    ),
                ));
            }
        }
        let critical = 2.0 * (d.brace_stiffness * (mass[(floor, floor)] + d.mass)).sqrt();
        let zeta = d.brace_damping / critical;
        if !(zeta.is_finite() && zeta <= MAX_DAMPING_RATIO) {
            return Err(SimError::invalid(
                path,
                f("brace_damping"),
                format!(
                    "c′ = {:e} N·s/m is {zeta:.3e} × critical for the brace and its floor's mass (2√(k′·m) = {critical:.3e} N·s/m); at most {MAX_DAMPING_RATIO} is physical (check the units)",
                    d.brace_damping
                ),
            ));
        }
        if !d.is_locked() {
            let (field, value) = if d.upper >= -d.lower {
                (
                    if cfg
                        .dissipators
                        .get(index_of(floor))
                        .is_some_and(|c| c.bounds.is_some())
                    {
                        "bounds[1]"
                    } else {
                        "slip_load"
                    },
                    d.upper,
                )
            } else {
                ("bounds[0]", d.lower)
            };
            if value.abs() > max_slip {
                return Err(SimError::invalid(
                    path,
                    f(field),
                    format!(
                        "{value:e} N is more than {MAX_SLIP_LOAD_PER_WEIGHT:e} × the building's weight ({weight:.4e} N), where its rounding alone exceeds 2e-5 of the weight: write \"locked\" for a contact that never slips, else check the units"
                    ),
                ));
            }
        }
    }
    Ok(())
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

/// Standard gravity (m/s²), for the default P-Δ loads.
pub const STANDARD_GRAVITY: f64 = 9.806_65;

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

/// How the frame damping matrix Cˢˢ is given.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum DampingConfig {
    /// No frame damping.
    None,
    /// Rayleigh: C = α M + β K (bare frame matrices).
    Rayleigh {
        /// Mass coefficient α, 1/s.
        alpha: f64,
        /// Stiffness coefficient β, s.
        beta: f64,
    },
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

fn square<Q: Copy + Into<f64>>(
    path: &Path,
    field: &str,
    rows: &[Vec<Q>],
    n: Option<usize>,
) -> Result<DMatrix<f64>, SimError> {
    let rows: Vec<Vec<f64>> = rows
        .iter()
        .map(|r| r.iter().map(|&q| q.into()).collect())
        .collect();
    let size = rows.len();
    if size == 0 {
        return Err(SimError::invalid(path, field, "must not be empty"));
    }
    if let Some(n) = n
        && size != n
    {
        return Err(SimError::invalid(
            path,
            field,
            format!("has {size} rows, expected {n} (one per floor)"),
        ));
    }
    for (i, r) in rows.iter().enumerate() {
        if r.len() != size {
            return Err(SimError::invalid(
                path,
                format!("{field}[{i}]"),
                format!("has {} entries, expected {size}", r.len()),
            ));
        }
        if let Some(j) = r.iter().position(|v| !v.is_finite()) {
            return Err(SimError::invalid(
                path,
                format!("{field}[{i}][{j}]"),
                "must be finite",
            ));
        }
    }
    let m = DMatrix::from_fn(size, size, |i, j| rows[i][j]);
    for i in 0..size {
        for j in 0..i {
            let (a, b) = (m[(i, j)], m[(j, i)]);
            let scale = (m[(i, i)].abs() + m[(j, j)].abs()).max(f64::MIN_POSITIVE);
            if (a - b).abs() > 1e-9 * scale {
                return Err(SimError::invalid(
                    path,
                    format!("{field}[{i}][{j}]"),
                    format!("matrix is not symmetric: {a} vs {b} at [{j}][{i}]"),
                ));
            }
        }
    }
    Ok((&m + m.transpose()) * 0.5)
}

/// Validates a per-floor list: `n` entries (any non-zero count when `n` is `None`), each
/// accepted by `ok`; `what` says what an entry must be ("a positive finite mass").
fn per_floor(
    path: &Path,
    field: &str,
    values: &[f64],
    n: Option<usize>,
    ok: fn(f64) -> bool,
    what: &str,
) -> Result<Vec<f64>, SimError> {
    match n {
        None if values.is_empty() => {
            return Err(SimError::invalid(
                path,
                field,
                "must list at least one floor",
            ));
        }
        Some(n) if values.len() != n => {
            return Err(SimError::invalid(
                path,
                field,
                format!("has {} values, expected {n} (one per floor)", values.len()),
            ));
        }
        _ => {}
    }
    match values.iter().position(|v| !ok(*v)) {
        Some(i) => Err(SimError::invalid(
            path,
            format!("{field}[{i}]"),
            format!("must be {what}, got {}", values[i]),
        )),
        None => Ok(values.to_vec()),
    }
}

/// The own stiffness of storey `i` (from 0) in a frame of stiffness matrix `k` (N/m, SPD):
/// the storey shear over the storey drift when equal and opposite forces act on the
/// storey's two floors (one force on the first floor for the first storey),
/// 1 / (eᵀ K⁻¹ e) with e = e(floor i) − e(floor i−1). For a shear building (a chain of
/// storey springs) it is exactly the storey's spring: the floors above move with the top
/// floor and the storeys below carry no shear. For a full condensed matrix it is what the
/// whole frame offers between those two floors; a spring k between them can be taken out
/// of K (as a storey that yields takes out (1−α)k) and leave K − k e eᵀ positive
/// semi-definite exactly when k ≤ 1/(eᵀK⁻¹e).
/// `None` when `k` is not positive definite or `i` is not a storey.
pub fn storey_stiffness(k: &DMatrix<f64>, i: usize) -> Option<f64> {
    let n = k.nrows();
    if i >= n {
        return None;
    }
    let mut e = nalgebra::DVector::zeros(n);
    e[i] = 1.0;
    if i > 0 {
        e[i - 1] = -1.0;
    }
    let chol = k.clone().cholesky()?;
    let flex = e.dot(&chol.solve(&e));
    (flex > 0.0 && flex.is_finite()).then(|| 1.0 / flex)
}

/// The error of a frame whose stiffness is not positive definite, naming the field that
/// gave it.
fn unstable_frame(cfg: &BuildingConfig, path: &Path) -> SimError {
    SimError::invalid(
        path,
        if cfg.stiffness_matrix.is_some() {
            "stiffness_matrix"
        } else {
            "storey_stiffness"
        },
        "frame stiffness must be positive definite (the bare frame must be stable)",
    )
}

/// Validates `storey_yield` against the frame: one entry per listed storey, Fy or the
/// yield drift, α in [0, 1), and the spring's stiffness (from `storey_stiffness`, or given
/// for a matrix frame), which must not exceed the storey's own stiffness in the frame
/// ([`storey_stiffness`]).
fn storey_yield(
    cfg: &BuildingConfig,
    path: &Path,
    n: usize,
    stiffness: &DMatrix<f64>,
) -> Result<Vec<Option<StoreyYield>>, SimError> {
    let mut out = vec![None; n];
    for (idx, y) in cfg.storey_yield.iter().enumerate() {
        let f = |name: &str| format!("storey_yield[{idx}].{name}");
        if y.storey == 0 || y.storey > n {
            return Err(SimError::invalid(
                path,
                f("storey"),
                format!("must be a storey number from 1 to {n}, got {}", y.storey),
            ));
        }
        let i = y.storey - 1;
        if out[i].is_some() {
            return Err(SimError::invalid(
                path,
                f("storey"),
                format!(
                    "storey {} already has a yield law (one per storey)",
                    y.storey
                ),
            ));
        }
        let k = match (&y.stiffness, &cfg.storey_stiffness) {
            (Some(k), _) => k.0,
            (None, Some(ks)) => ks[i].0,
            (None, None) => {
                return Err(SimError::invalid(
                    path,
                    f("stiffness"),
                    "missing: a frame given as stiffness_matrix must say the stiffness of the storey spring that yields (N/m)",
                ));
            }
        };
        if !is_positive(k) {
            return Err(SimError::invalid(
                path,
                f("stiffness"),
                format!("must be positive and finite, got {k}"),
            ));
        }
        // The spring is part of the frame: it cannot be stiffer than the storey it sits in.
        let own = storey_stiffness(stiffness, i).ok_or_else(|| unstable_frame(cfg, path))?;
        if k > own * (1.0 + 1e-9) {
            let floors = if i == 0 {
                "a force on floor 1, the ground fixed".to_string()
            } else {
                format!("equal and opposite forces on floors {i} and {}", i + 1)
            };
            return Err(SimError::invalid(
                path,
                f("stiffness"),
                format!(
                    "storey {}: the yielding spring's stiffness {k:.6e} N/m is stiffer than the storey it sits in, whose own stiffness in the frame is {own:.6e} N/m (storey shear over storey drift under {floors}); give at most {own:.6e} N/m",
                    y.storey
                ),
            ));
        }
        let fy = match (&y.yield_shear, &y.yield_drift) {
            (Some(_), Some(_)) => {
                return Err(SimError::invalid(
                    path,
                    f("yield_drift"),
                    "give either yield_shear or yield_drift, not both",
                ));
            }
            (None, None) => {
                return Err(SimError::invalid(
                    path,
                    f("yield_shear"),
                    "missing: give yield_shear (N) or yield_drift (m)",
                ));
            }
            (Some(v), None) => v.0,
            (None, Some(d)) => d.0 * k,
        };
        if !is_positive(fy) {
            let name = if y.yield_shear.is_some() {
                "yield_shear"
            } else {
                "yield_drift"
            };
            return Err(SimError::invalid(
                path,
                f(name),
                format!("must be positive and finite, got {fy}"),
            ));
        }
        let alpha = y.post_yield_ratio.unwrap_or(0.0);
        if !(alpha.is_finite() && (0.0..1.0).contains(&alpha)) {
            return Err(SimError::invalid(
                path,
                f("post_yield_ratio"),
                format!("must be in [0, 1), got {alpha}"),
            ));
        }
        out[i] = Some(StoreyYield {
            stiffness: k,
            yield_shear: fy,
            post_yield_ratio: alpha,
        });
    }
    Ok(out)
}

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
            Some(DampingConfig::Rayleigh { alpha, beta }) => {
                for (name, v) in [("alpha", *alpha), ("beta", *beta)] {
                    if !is_non_negative(v) {
                        return Err(SimError::invalid(
                            path,
                            format!("damping.rayleigh.{name}"),
                            format!("must be finite and ≥ 0, got {v}"),
                        ));
                    }
                }
                &mass * *alpha + &stiffness * *beta
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
        let mut dissipators = vec![None; n];
        for (idx, d) in cfg.dissipators.iter().enumerate() {
            let f = |name: &str| format!("dissipators[{idx}].{name}");
            if d.floor == 0 || d.floor > n {
                return Err(SimError::invalid(
                    path,
                    f("floor"),
                    format!("must be a floor number from 1 to {n}, got {}", d.floor),
                ));
            }
            if dissipators[d.floor - 1].is_some() {
                return Err(SimError::invalid(
                    path,
                    f("floor"),
                    format!("floor {} already has a dissipator (one per floor)", d.floor),
                ));
            }
            let k = d.brace_stiffness.0;
            if !is_positive(k) {
                return Err(SimError::invalid(
                    path,
                    f("brace_stiffness"),
                    format!("must be positive and finite, got {k}"),
                ));
            }
            let m = d.mass.map_or(0.0, |m| m.0);
            if !is_non_negative(m) {
                return Err(SimError::invalid(
                    path,
                    f("mass"),
                    format!("must be finite and ≥ 0, got {m}"),
                ));
            }
            let c = d.brace_damping.map_or(0.0, |c| c.0);
            if !is_non_negative(c) {
                return Err(SimError::invalid(
                    path,
                    f("brace_damping"),
                    format!("must be finite and ≥ 0, got {c}"),
                ));
            }
            let (lower, upper) = match (&d.slip_load, &d.bounds) {
                (Some(_), Some(_)) => {
                    return Err(SimError::invalid(
                        path,
                        f("bounds"),
                        "give either slip_load or bounds, not both",
                    ));
                }
                (None, None) => {
                    return Err(SimError::invalid(
                        path,
                        f("slip_load"),
                        "missing: give slip_load (N, or \"locked\") or bounds [F-, F+]",
                    ));
                }
                (Some(SlipLoad::Locked), None) => (f64::NEG_INFINITY, f64::INFINITY),
                (Some(SlipLoad::Force(s)), None) => {
                    if !is_non_negative(*s) {
                        return Err(SimError::invalid(
                            path,
                            f("slip_load"),
                            format!("must be finite and ≥ 0, got {s}"),
                        ));
                    }
                    (-*s, *s)
                }
                (None, Some([lo, hi])) => {
                    if !lo.0.is_finite() || lo.0 > 0.0 {
                        return Err(SimError::invalid(
                            path,
                            f("bounds[0]"),
                            format!("F- must be finite and ≤ 0, got {}", lo.0),
                        ));
                    }
                    if !hi.0.is_finite() || hi.0 < 0.0 {
                        return Err(SimError::invalid(
                            path,
                            f("bounds[1]"),
                            format!("F+ must be finite and ≥ 0, got {}", hi.0),
                        ));
                    }
                    (lo.0, hi.0)
                }
            };
            dissipators[d.floor - 1] = Some(Dissipator {
                brace_stiffness: k,
                mass: m,
                brace_damping: c,
                lower,
                upper,
            });
        }
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
