//! The checks a building is held to: the shapes, signs and finiteness of its lists and
//! matrices, the physical bands of its magnitudes (periods, masses, damping ratios, slip
//! loads, storey heights), its dissipators and its storeys' yield laws. Each refusal names
//! the file, the field, the value and what was expected. Beside the refusals,
//! [`plausibility`]: what a run's inputs make doubtful without making them wrong, as
//! warnings (data, for a front to print).

use super::config::{BuildingConfig, SlipLoad};
use super::validated::{Building, Dissipator, StoreyYield};
use crate::error::SimError;
use crate::modes::Modes;
use crate::units::{is_non_negative, is_positive, short_number};
use nalgebra::DMatrix;
use std::path::Path;

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

pub(super) fn in_band(v: f64, band: (f64, f64)) -> bool {
    v >= band.0 && v <= band.1
}

/// The floor masses against [`FLOOR_MASS_BAND_KG`], before any eigen solve: a subnormal
/// or absurd mass must be named as such, not surface as an unstable stiffness.
pub(super) fn check_floor_masses(
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
pub(super) fn check_magnitudes(
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
    // Each brace locked in turn must keep the shortest period in band; where the bounds
    // on all of those periods show it, none is formed (one eigen solve per brace would make
    // this check O(N⁴)).
    let all_in_band = braced_periods_in_band(mass, stiffness, dissipators);
    let mut braced = stiffness.clone();
    let mut braced_mass = mass.clone();
    for (floor, d) in dissipators.iter().enumerate() {
        let Some(d) = d else { continue };
        let f = |name: &str| format!("dissipators[{}].{name}", index_of(floor));
        // the brace locked: k′ between floor i−1 (or the ground) and floor i, m′ on floor i
        let k = d.brace_stiffness;
        if !all_in_band {
            lock_brace(&mut braced, &mut braced_mass, floor, d);
        }
        let shortest = if all_in_band {
            None
        } else {
            Some(
                Modes::compute(&braced_mass, &braced)
                    .map(|m| 2.0 * std::f64::consts::PI / m.omega[m.omega.len() - 1]),
            )
        };
        match shortest {
            None => {}
            Some(Some(t)) if in_band(t, PERIOD_BAND_S) => {}
            Some(found) => {
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

/// Adds `d`'s brace, locked, to a frame: k′ between floor `floor` − 1 (or the ground) and
/// floor `floor`, m′ on floor `floor`.
pub(crate) fn lock_brace(k: &mut DMatrix<f64>, m: &mut DMatrix<f64>, floor: usize, d: &Dissipator) {
    let kb = d.brace_stiffness;
    k[(floor, floor)] += kb;
    if floor > 0 {
        k[(floor - 1, floor - 1)] += kb;
        k[(floor, floor - 1)] -= kb;
        k[(floor - 1, floor)] -= kb;
    }
    m[(floor, floor)] += d.mass;
}

/// Relative margin inside [`PERIOD_BAND_S`] that [`braced_periods_in_band`] asks of its
/// bounds: far above the round-off of any one braced frame's computed period, so a frame
/// its bounds admit is one [`Modes::compute`] admits.
const BOUND_MARGIN: f64 = 1e-6;

/// Smallest ratio of the least to the largest eigenvalue ω² that [`braced_periods_in_band`]
/// accepts from its bounds: above it, round-off (about N·ε of the largest) cannot turn a
/// braced frame's least eigenvalue non-positive, which [`Modes::compute`] would refuse.
const BOUND_CONDITION: f64 = 1e-10;

/// Whether every frame [`check_magnitudes`] forms as it locks the braces floor by floor
/// (frame j: the bare frame with the braces of the first j dissipators locked) has all its
/// eigenvalues positive and its shortest period inside [`PERIOD_BAND_S`], shown with two
/// eigenvalue solves instead of one eigen decomposition per brace. Locking a brace adds
/// k′ ≥ 0 to K and m′ ≥ 0 to M, so K ≤ K_j ≤ K_all and M ≤ M_j ≤ M_all (Loewner order)
/// and by the Rayleigh quotient every eigenvalue ω² of frame j lies in
/// [λ_min(M_all, K), λ_max(M, K_all)], and its largest in [λ_max(M_all, K), λ_max(M, K_all)].
/// `true` when those bounds are in band by [`BOUND_MARGIN`] and [`BOUND_CONDITION`]; `false`
/// means "not shown" (the frames are then formed one by one, as the refusals name the brace
/// that first leaves the band).
fn braced_periods_in_band(
    mass: &DMatrix<f64>,
    stiffness: &DMatrix<f64>,
    dissipators: &[Option<Dissipator>],
) -> bool {
    let (mut k_all, mut m_all) = (stiffness.clone(), mass.clone());
    for (floor, d) in dissipators.iter().enumerate() {
        if let Some(d) = d {
            lock_brace(&mut k_all, &mut m_all, floor, d);
        }
    }
    let (Some(stiffest), Some(heaviest)) = (
        pencil_eigenvalues(mass, &k_all),
        pencil_eigenvalues(&m_all, stiffness),
    ) else {
        return false;
    };
    let largest = |l: &[f64]| l.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let least = heaviest.iter().copied().fold(f64::INFINITY, f64::min);
    let (high, low) = (largest(&stiffest), largest(&heaviest));
    let period = |l: f64| 2.0 * std::f64::consts::PI / l.sqrt();
    let (shortest, longest) = (period(high), period(low));
    shortest >= PERIOD_BAND_S.0 * (1.0 + BOUND_MARGIN)
        && longest <= PERIOD_BAND_S.1 * (1.0 - BOUND_MARGIN)
        && least > BOUND_CONDITION * high
}

/// The eigenvalues of K φ = λ M φ (through M's Cholesky factor, as [`Modes::compute`]),
/// unordered; `None` when M is not positive definite or one is not finite.
fn pencil_eigenvalues(m: &DMatrix<f64>, k: &DMatrix<f64>) -> Option<Vec<f64>> {
    let linv = m.clone().cholesky()?.l().try_inverse()?;
    let a = &linv * k * linv.transpose();
    let a = (&a + a.transpose()) * 0.5;
    if !a.iter().all(|x| x.is_finite()) {
        return None;
    }
    let l: Vec<f64> = a.symmetric_eigenvalues().iter().copied().collect();
    l.iter().all(|x| x.is_finite()).then_some(l)
}

pub(super) fn square<Q: Copy + Into<f64>>(
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
pub(super) fn per_floor(
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
pub(super) fn unstable_frame(cfg: &BuildingConfig, path: &Path) -> SimError {
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

/// Validates `dissipators`: one per floor, k′ > 0, m′ and c′ ≥ 0, and a slip load (or
/// `"locked"`) or asymmetric bounds [F⁻, F⁺] with F⁻ ≤ 0 ≤ F⁺; `n` floors.
pub(super) fn dissipators(
    cfg: &BuildingConfig,
    path: &Path,
    n: usize,
) -> Result<Vec<Option<Dissipator>>, SimError> {
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
    Ok(dissipators)
}

/// Validates `storey_yield` against the frame: one entry per listed storey, Fy or the
/// yield drift, α in [0, 1), and the spring's stiffness (from `storey_stiffness`, or given
/// for a matrix frame), which must not exceed the storey's own stiffness in the frame
/// ([`storey_stiffness`]).
pub(super) fn storey_yield(
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

/// A slip load below this fraction of its floor's weight (m·g) is warned about: real ones
/// are a few per cent of it, and 10⁻³ × is what a slip load in kN written as a bare
/// number (newtons in a building file) looks like.
pub const MIN_PLAUSIBLE_SLIP_LOAD_PER_FLOOR_WEIGHT: f64 = 1e-3;

/// What a run's inputs make doubtful without making them wrong: the run goes ahead, and
/// a front says it (the command line on stderr). `Display` gives the sentence.
#[derive(Debug, Clone, PartialEq)]
pub enum Plausibility {
    /// A slip load below [`MIN_PLAUSIBLE_SLIP_LOAD_PER_FLOOR_WEIGHT`] × its floor's weight:
    /// likely kN written as a bare number, which a building file reads in N.
    TinySlipLoad {
        /// The floor, 1 from the bottom.
        floor: usize,
        /// The smaller of the friction bounds' magnitudes, N.
        slip_load_n: f64,
        /// The floor's weight m·g, N.
        floor_weight_n: f64,
    },
    /// The time step does not divide the duration: the run takes whole steps and its last
    /// one ends past the duration.
    PastDuration {
        /// The time step, s.
        dt_s: f64,
        /// The duration asked for, s.
        duration_s: f64,
        /// The steps taken.
        steps: usize,
    },
}

impl std::fmt::Display for Plausibility {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Plausibility::TinySlipLoad {
                floor,
                slip_load_n,
                floor_weight_n,
            } => write!(
                f,
                "floor {floor}: the slip load {} N is below {} % of the floor's weight (m·g = {} N): a bare number in a building file is newtons, where a study's slip loads are kN; did you mean kN (\"{} kN\")?",
                short_number(slip_load_n),
                short_number(100.0 * MIN_PLAUSIBLE_SLIP_LOAD_PER_FLOOR_WEIGHT),
                short_number(floor_weight_n),
                short_number(slip_load_n),
            ),
            Plausibility::PastDuration {
                dt_s,
                duration_s,
                steps,
            } => {
                let end = steps as f64 * dt_s;
                write!(
                    f,
                    "dt = {} s does not divide the duration {} s: the run takes {steps} steps and ends at t = {} s, {} s past it (give a duration or a dt that divides it to end on it)",
                    short_number(dt_s),
                    short_number(duration_s),
                    short_number(end),
                    short_number(end - duration_s)
                )
            }
        }
    }
}

/// The warnings of a run of `building` for `duration_s` in `steps` steps of `dt_s`
/// ([`crate::Scene::steps`]): each slip load below
/// [`MIN_PLAUSIBLE_SLIP_LOAD_PER_FLOOR_WEIGHT`] × its floor's weight (a free contact,
/// slip load 0, is the bare frame, and a locked one never slips: neither is warned
/// about), and a last step that ends past the duration (beyond the relative slack of
/// 10⁻⁹ the step count allows). Empty for a plausible run.
pub fn plausibility(
    building: &Building,
    dt_s: f64,
    duration_s: f64,
    steps: usize,
) -> Vec<Plausibility> {
    let mut out = slip_load_plausibility(building);
    if steps as f64 * dt_s > duration_s * (1.0 + 1e-9) {
        out.push(Plausibility::PastDuration {
            dt_s,
            duration_s,
            steps,
        });
    }
    out
}

/// The part of [`plausibility`] that reads the building alone: each slip load below
/// [`MIN_PLAUSIBLE_SLIP_LOAD_PER_FLOOR_WEIGHT`] of its floor's weight (a bare number in a
/// building file is newtons; a study's slip loads are kN). A study reads it of the
/// building file's design.
pub fn slip_load_plausibility(building: &Building) -> Vec<Plausibility> {
    let mut out = Vec::new();
    for (i, d) in building.dissipators.iter().enumerate() {
        let Some(d) = d else { continue };
        let slip = d.upper.min(-d.lower);
        let weight = building.mass[(i, i)] * slipload_motion::G;
        if slip > 0.0
            && slip.is_finite()
            && slip < MIN_PLAUSIBLE_SLIP_LOAD_PER_FLOOR_WEIGHT * weight
        {
            out.push(Plausibility::TinySlipLoad {
                floor: i + 1,
                slip_load_n: slip,
                floor_weight_n: weight,
            });
        }
    }
    out
}

/// A line's yield law and damper per storey ([`line_parts`]).
pub(crate) type LineParts = (Vec<Option<StoreyYield>>, Vec<Option<Dissipator>>);

/// The yield laws and dissipators of one line of a building in plan, validated as a
/// chain's (`storey_yield` against the line's own storey springs, `dissipators` one per
/// floor), with the fields named under `prefix` (`lines[2].`).
pub(crate) fn line_parts(
    prefix: &str,
    storey_stiffness: &[crate::units::Stiffness],
    yields: &[super::config::StoreyYieldConfig],
    dampers: &[super::config::DissipatorConfig],
    path: &Path,
) -> Result<LineParts, SimError> {
    let n = storey_stiffness.len();
    let cfg = BuildingConfig {
        name: None,
        description: None,
        floor_masses: None,
        mass_matrix: None,
        storey_stiffness: Some(storey_stiffness.to_vec()),
        stiffness_matrix: None,
        damping: None,
        storey_heights: None,
        dissipators: dampers.to_vec(),
        storey_yield: yields.to_vec(),
        p_delta: None,
        collapse_drift_ratio: None,
        collapse_drift: None,
    };
    let under = |e: SimError| match e {
        SimError::Invalid {
            path,
            field,
            message,
        } => SimError::Invalid {
            path,
            field: format!("{prefix}{field}"),
            message,
        },
        other => other,
    };
    let mut k = DMatrix::zeros(n, n);
    for (i, s) in storey_stiffness.iter().enumerate() {
        k[(i, i)] += s.0;
        if i > 0 {
            k[(i - 1, i - 1)] += s.0;
            k[(i, i - 1)] -= s.0;
            k[(i - 1, i)] -= s.0;
        }
    }
    let y = storey_yield(&cfg, path, n, &k).map_err(under)?;
    let d = dissipators(&cfg, path, n).map_err(under)?;
    Ok((y, d))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::collection::vec;
    use proptest::prelude::*;

    /// A shear frame (floor masses, storey stiffnesses) with a dissipator on every floor.
    fn frame(
        masses: &[f64],
        storeys: &[f64],
        braces: &[(f64, f64)],
    ) -> (DMatrix<f64>, DMatrix<f64>, Vec<Option<Dissipator>>) {
        let n = masses.len();
        let m = DMatrix::from_diagonal(&nalgebra::DVector::from_column_slice(masses));
        let mut k = DMatrix::zeros(n, n);
        for (i, &ks) in storeys.iter().enumerate() {
            k[(i, i)] += ks;
            if i > 0 {
                k[(i - 1, i - 1)] += ks;
                k[(i, i - 1)] -= ks;
                k[(i - 1, i)] -= ks;
            }
        }
        let ds = braces
            .iter()
            .map(|&(brace_stiffness, mass)| {
                Some(Dissipator {
                    brace_stiffness,
                    mass,
                    brace_damping: 0.0,
                    lower: -1.0,
                    upper: 1.0,
                })
            })
            .collect();
        (m, k, ds)
    }

    /// Every frame the per-brace check forms, in band as it judges it.
    fn each_frame_in_band(m: &DMatrix<f64>, k: &DMatrix<f64>, ds: &[Option<Dissipator>]) -> bool {
        let (mut kb, mut mb) = (k.clone(), m.clone());
        ds.iter().enumerate().all(|(floor, d)| {
            let d = d.as_ref().expect("every floor has one");
            lock_brace(&mut kb, &mut mb, floor, d);
            Modes::compute(&mb, &kb).is_some_and(|md| {
                in_band(
                    2.0 * std::f64::consts::PI / md.omega[md.omega.len() - 1],
                    PERIOD_BAND_S,
                )
            })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]
        /// The bounds never admit what the per-brace check refuses: braces from 10⁻³ to 10¹⁴
        /// × the storey stiffness (the stiffest leave the band) and dissipator masses up to
        /// ten times the floor's.
        #[test]
        fn the_bounds_admit_only_frames_the_per_brace_check_admits(
            masses in vec(1e2..1e6f64, 1..7),
            storey in 1e3..1e9f64,
            braces in vec((-3.0..14.0f64, prop_oneof![Just(0.0), 0.0..10.0f64]), 7),
        ) {
            let n = masses.len();
            let storeys = vec![storey; n];
            let braces: Vec<(f64, f64)> = braces[..n]
                .iter()
                .zip(&masses)
                .map(|(&(e, r), &m)| (storey * 10f64.powf(e), r * m))
                .collect();
            let (m, k, ds) = frame(&masses, &storeys, &braces);
            if braced_periods_in_band(&m, &k, &ds) {
                prop_assert!(each_frame_in_band(&m, &k, &ds));
            }
        }
    }

    #[test]
    fn a_tall_frame_with_moderate_braces_is_admitted_by_the_bounds() {
        // the bench's shear building: the bounds decide, no brace is formed on its own
        let n = 60;
        let (m, k, ds) = frame(&vec![5e5; n], &vec![1e9; n], &vec![(2e9, 0.0); n]);
        assert!(braced_periods_in_band(&m, &k, &ds));
        assert!(each_frame_in_band(&m, &k, &ds));
    }

    #[test]
    fn a_brace_that_leaves_the_band_is_not_admitted_by_the_bounds() {
        // k′ = 1e14 × k on floor 2: period ~1e-5 s, below the band
        let (m, k, ds) = frame(&[1e3; 3], &[1e5; 3], &[(1e5, 0.0), (1e19, 0.0), (1e5, 0.0)]);
        assert!(!braced_periods_in_band(&m, &k, &ds));
        assert!(!each_frame_in_band(&m, &k, &ds));
    }
}
