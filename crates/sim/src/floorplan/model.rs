//! The validated building in plan ([`FloorPlan`]) and its parts ([`Floor`], [`Line`]),
//! SI units, with what they answer by themselves.

use crate::building::{DampingConfig, Dissipator, StoreyYield, rayleigh_coefficients};
use crate::error::SimError;
use crate::modes::Modes;
use nalgebra::DMatrix;

/// A validated rigid floor, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Floor {
    /// Mass, kg.
    pub mass: f64,
    /// Mass moment of inertia about the vertical axis through the centre of mass, kg·m².
    pub inertia: f64,
    /// Centre of mass [x, y], m.
    pub centre: [f64; 2],
}

/// A validated lateral line, SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// Name.
    pub name: String,
    /// Direction: angle from the x axis, rad.
    pub angle: f64,
    /// A point the line passes through [x, y], m.
    pub point: [f64; 2],
    /// Storey stiffness along the line, per storey, N/m.
    pub stiffness: Vec<f64>,
    /// Storey dashpot along the line, per storey, N·s/m (zeros without any).
    pub dashpots: Vec<f64>,
    /// Yield law per storey (`None`: elastic).
    pub storey_yield: Vec<Option<StoreyYield>>,
    /// Friction damper per storey (its top floor), if any.
    pub dissipators: Vec<Option<Dissipator>>,
}

impl Line {
    /// The direction's cosine and sine ([`cos_sin`]: exact along x and y).
    pub fn direction(&self) -> (f64, f64) {
        cos_sin(self.angle)
    }

    /// The lever r of the line about the origin: a floor rotation θ moves the line along
    /// its direction by r·θ (r = x sin φ − y cos φ for a point (x, y) of the line).
    pub fn lever(&self) -> f64 {
        let (c, s) = self.direction();
        self.point[0] * s - self.point[1] * c
    }

    /// The line's kinematic weights on a floor's (ux, uy, θ): its motion along its
    /// direction is c·ux + s·uy + r·θ.
    pub fn weights(&self) -> [f64; 3] {
        let (c, s) = self.direction();
        [c, s, self.lever()]
    }
}

/// A validated building in plan, SI units; floor DOFs (ux, uy, θ) of floor f at 3f, 3f+1,
/// 3f+2, the translations those of the plan's origin.
#[derive(Debug, Clone)]
pub struct FloorPlan {
    /// Name.
    pub name: String,
    /// The floors, bottom to top.
    pub floors: Vec<Floor>,
    /// The lines.
    pub lines: Vec<Line>,
    /// Plan dimensions [Lx, Ly], m, when given.
    pub plan_size: Option<[f64; 2]>,
    /// Storey heights, m, when given.
    pub storey_heights: Option<Vec<f64>>,
    /// Mass matrix on the floors' DOFs (3N × 3N), kg and kg·m.
    pub mass: DMatrix<f64>,
    /// Stiffness of the bare frame (every line elastic, dampers disconnected), 3N × 3N.
    pub stiffness: DMatrix<f64>,
    /// Frame damping on the floors' DOFs.
    pub damping: DMatrix<f64>,
    /// Drift (m) past which a yielding line's storey stops the run, per storey.
    pub collapse_drift: Option<Vec<f64>>,
    /// Modes of the bare frame.
    pub modes: Modes,
    /// The damping as the file states it (what a moved centre of mass recomputes).
    pub damping_config: Option<DampingConfig>,
    /// P-Δ, when the file asks for it: each storey's gravity load (N) and the geometric
    /// stiffness block it gives on the storey's relative (Δux, Δuy, Δθ) (`p_delta_blocks`;
    /// subtracted from the stiffness when the plan is compiled).
    pub p_delta: Option<PDelta>,
    /// The gravity loads as the file states them (`None`: g times the mass above), for a
    /// moved centre of mass to spread again.
    pub p_delta_config: Option<crate::building::PDeltaConfig>,
    /// Named points [x, y] (m) whose motion every floor reports beside its centre of mass.
    pub points: Vec<(String, [f64; 2])>,
}

/// P-Δ of a building in plan, per storey.
#[derive(Debug, Clone, PartialEq)]
pub struct PDelta {
    /// Gravity load of each storey, N.
    pub loads: Vec<f64>,
    /// Each storey's geometric stiffness on its relative (Δux, Δuy, Δθ): P/h times the
    /// load's [[1, 0, −ȳ], [0, 1, x̄], [−ȳ, x̄, x̄² + ȳ² + ρ²]] (x̄, ȳ its centroid, ρ² its
    /// polar moment about it over P), N/m, N and N·m; positive semidefinite.
    pub blocks: Vec<[[f64; 3]; 3]>,
}

/// The P-Δ of `floors` with storey heights `heights`: each storey's gravity load (given,
/// or g times the mass at and above it) spread as the mass of the floors above it — its
/// centroid their centre of mass, its polar moment theirs (each floor's own J plus its
/// mass times its centre's distance squared) — so the second-order moment of a load
/// leaning on the storey's columns, −(1/h)∫w(δu_x² + δu_y²), is the block
/// (Wilson and Habibullah, 1987, for rigid diaphragms).
pub fn p_delta_blocks(floors: &[Floor], heights: &[f64], loads: Option<&[f64]>) -> PDelta {
    let n = floors.len();
    let mut out = PDelta {
        loads: Vec::with_capacity(n),
        blocks: Vec::with_capacity(n),
    };
    for f in 0..n {
        let above = &floors[f..];
        let m: f64 = above.iter().map(|fl| fl.mass).sum();
        let cx = above.iter().map(|fl| fl.mass * fl.centre[0]).sum::<f64>() / m;
        let cy = above.iter().map(|fl| fl.mass * fl.centre[1]).sum::<f64>() / m;
        let polar: f64 = above
            .iter()
            .map(|fl| {
                let (dx, dy) = (fl.centre[0] - cx, fl.centre[1] - cy);
                fl.inertia + fl.mass * (dx * dx + dy * dy)
            })
            .sum();
        let p = loads.map_or(crate::building::STANDARD_GRAVITY * m, |l| l[f]);
        // the load per unit mass above: its polar moment is the mass's scaled
        let s = p / m / heights[f];
        let ph = p / heights[f];
        out.loads.push(p);
        out.blocks.push([
            [ph, 0.0, -ph * cy],
            [0.0, ph, ph * cx],
            [-ph * cy, ph * cx, ph * (cx * cx + cy * cy) + s * polar],
        ]);
    }
    out
}

impl FloorPlan {
    /// Number of storeys (floors).
    pub fn storeys(&self) -> usize {
        self.floors.len()
    }

    /// Fundamental period of the bare frame, s.
    pub fn t1(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.modes.omega[0]
    }

    /// The floor plan with every floor's centre of mass moved by [dx, dy] (m), its
    /// inertia about the centre of mass kept, the modes and the damping (as the file
    /// states it) computed again: accidental torsion as a property case
    /// (ASCE 7-16 §12.8.4.2 moves it by 5 % of the plan dimension across the motion).
    pub fn with_centre_shift(&self, shift: [f64; 2]) -> FloorPlan {
        let floors: Vec<Floor> = self
            .floors
            .iter()
            .map(|f| Floor {
                centre: [f.centre[0] + shift[0], f.centre[1] + shift[1]],
                ..*f
            })
            .collect();
        let mass = mass_matrix(&floors);
        let modes = Modes::compute(&mass, &self.stiffness).unwrap_or_else(|| self.modes.clone());
        // the damping as stated, on this plan's own mass and modes (validated when the
        // file was read, so the same statement holds here)
        let damping = damping_matrix(
            self.damping_config.as_ref(),
            &mass,
            &self.stiffness,
            &modes,
            std::path::Path::new(&self.name),
        )
        .unwrap_or_else(|_| self.damping.clone());
        // the gravity loads spread again over the moved masses
        let p_delta = match (&self.p_delta, &self.storey_heights) {
            (Some(pd), Some(h)) => Some(p_delta_blocks(
                &floors,
                h,
                self.p_delta_config
                    .as_ref()
                    .and_then(|c| c.gravity_loads.as_ref())
                    .map(|_| pd.loads.as_slice()),
            )),
            _ => None,
        };
        FloorPlan {
            floors,
            mass,
            modes,
            damping,
            p_delta,
            ..self.clone()
        }
    }
}

/// The mass matrix of rigid floors on their DOFs (ux, uy, θ of the origin): the centre
/// of mass at (x, y) moves by (ux − y·θ, uy + x·θ), so each floor's block is
/// [[m, 0, −m·y], [0, m, m·x], [−m·y, m·x, J + m(x² + y²)]] with J about the centre.
pub(super) fn mass_matrix(floors: &[Floor]) -> DMatrix<f64> {
    let n = 3 * floors.len();
    let mut m = DMatrix::zeros(n, n);
    for (f, fl) in floors.iter().enumerate() {
        let [x, y] = fl.centre;
        let o = 3 * f;
        m[(o, o)] = fl.mass;
        m[(o + 1, o + 1)] = fl.mass;
        m[(o, o + 2)] = -fl.mass * y;
        m[(o + 2, o)] = -fl.mass * y;
        m[(o + 1, o + 2)] = fl.mass * x;
        m[(o + 2, o + 1)] = fl.mass * x;
        m[(o + 2, o + 2)] = fl.inertia + fl.mass * (x * x + y * y);
    }
    m
}

/// cos and sin of an angle (rad), exact at the quarter turns (0, ±90°, 180°, …): a line
/// along y or a ground component along y has no x part at all (cos 90° in floating point
/// is 6e-17), so a plan's x and y stay apart exactly where they are apart.
pub fn cos_sin(angle: f64) -> (f64, f64) {
    let quarters = angle / std::f64::consts::FRAC_PI_2;
    let k = quarters.round();
    if (quarters - k).abs() <= 4.0 * f64::EPSILON * quarters.abs().max(1.0) {
        match (k as i64).rem_euclid(4) {
            0 => (1.0, 0.0),
            1 => (0.0, 1.0),
            2 => (-1.0, 0.0),
            _ => (0.0, -1.0),
        }
    } else {
        (angle.cos(), angle.sin())
    }
}

/// The frame damping of a building in plan as `damping` states it, on the modes and mass
/// given: Rayleigh (its coefficients from ratios at modes or periods, or given), modal
/// (on the three-dimensional modes), or none. A plan whose centres of mass move (an
/// accidental-torsion case) recomputes it on its own mass and modes.
pub(super) fn damping_matrix(
    damping: Option<&DampingConfig>,
    mass: &DMatrix<f64>,
    stiffness: &DMatrix<f64>,
    modes: &Modes,
    path: &std::path::Path,
) -> Result<DMatrix<f64>, SimError> {
    let n = mass.nrows() / 3;
    Ok(match damping {
        None | Some(DampingConfig::None) => DMatrix::zeros(3 * n, 3 * n),
        Some(DampingConfig::Rayleigh(r)) => {
            let (alpha, beta) = rayleigh_coefficients(r, modes, path)?;
            mass * alpha + stiffness * beta
        }
        Some(DampingConfig::Modal { ratio, ratios }) => {
            let zeta: Vec<f64> = match (ratio, ratios) {
                (Some(z), None) => vec![*z; 3 * n],
                (None, Some(zs)) if !zs.is_empty() => {
                    (0..3 * n).map(|i| zs[i.min(zs.len() - 1)]).collect()
                }
                _ => {
                    return Err(SimError::invalid(
                        path,
                        "damping.modal",
                        "give `ratio` (every mode) or `ratios` (by mode, the last for the modes after)",
                    ));
                }
            };
            if let Some(z) = zeta.iter().find(|z| !(**z >= 0.0 && **z < 1.0)) {
                return Err(SimError::invalid(
                    path,
                    "damping.modal",
                    format!("a damping ratio is a fraction of critical in [0, 1), got {z}"),
                ));
            }
            modes.damping_matrix(mass, &zeta)
        }
        Some(DampingConfig::Storey(_) | DampingConfig::Matrix(_)) => {
            return Err(SimError::invalid(
                path,
                "damping",
                "a building in plan takes `rayleigh`, `modal` or `none` (on its three-dimensional modes); a damping matrix is a chain's; storey dashpots go on the lines (`lines[i].storey_damping`, N·s/m per storey)",
            ));
        }
    })
}
