//! Buildings in plan (docs/MODEL.md § Buildings in plan): rigid floors with two
//! translations and a rotation, lateral lines placed in plan, friction dampers on the
//! lines, one or two horizontal ground components at an angle to the plan's axes.
//!
//! A [`FloorPlanConfig`] is what a JSON file says; [`FloorPlan::from_config`] validates
//! it into SI units with the bare frame's matrices on the floors' DOFs (ux, uy, θ of each
//! floor's origin, floor by floor: a 3×3 block per floor); [`compile`] turns a
//! [`FloorPlanScene`] into the same [`Plan`](crate::plan::Plan) the chain compiles to,
//! its contacts acting along the lines' kinematic vectors ([`crate::kinematics`]), so every
//! integrator that steps a general plan steps it.
//!
//! Files: `config` (the file as written), `build` (validation and assembly), `compile`
//! (scene to plan), `scene` (a scene in plan as written and resolved).

mod build;
mod compile;
mod config;
mod scene;

pub use compile::compile;
pub use config::{DirectionConfig, FloorConfig, FloorPlanConfig, LineConfig};
pub use scene::{FloorPlanScene, FloorPlanSceneConfig, GroundComponent};

use crate::building::{Dissipator, StoreyYield};
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
    /// Yield law per storey (`None`: elastic).
    pub storey_yield: Vec<Option<StoreyYield>>,
    /// Friction damper per storey (its top floor), if any.
    pub dissipators: Vec<Option<Dissipator>>,
}

impl Line {
    /// The direction's cosine and sine.
    pub fn direction(&self) -> (f64, f64) {
        (self.angle.cos(), self.angle.sin())
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
    /// inertia about the centre of mass kept: accidental torsion as a property case
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
        let mass = build::mass_matrix(&floors);
        let modes = Modes::compute(&mass, &self.stiffness).unwrap_or_else(|| self.modes.clone());
        FloorPlan {
            floors,
            mass,
            modes,
            ..self.clone()
        }
    }
}
