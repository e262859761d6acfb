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
//!
//! Files: `config` (the file as written), `validated` (the validated building and its
//! parts), `check` (the checks and the physical bands), `build` (the assembly, running
//! the checks), `dynamics` (the modes' damping ratios, the periods with the dampers stuck).

mod build;
mod check;
mod config;
mod dynamics;
mod validated;

pub(crate) use build::rayleigh_coefficients;
pub use build::{DEFAULT_COLLAPSE_DRIFT_RATIO, STANDARD_GRAVITY};
pub(crate) use check::line_parts;
pub use check::{
    DISSIPATOR_PERIOD_BAND_S, FLOOR_MASS_BAND_KG, MAX_DAMPING_RATIO, MAX_HARMONIC_FORCE_PER_WEIGHT,
    MAX_SLIP_LOAD_PER_WEIGHT, MIN_PLAUSIBLE_SLIP_LOAD_PER_FLOOR_WEIGHT, PERIOD_BAND_S,
    Plausibility, STOREY_HEIGHT_BAND_M, plausibility, slip_load_plausibility, storey_stiffness,
};
pub use config::{
    BuildingConfig, DampingConfig, DissipatorConfig, PDeltaConfig, RayleighConfig, SlipLoad,
    StoreyYieldConfig,
};
pub(crate) use dynamics::MassParticipation;
pub use dynamics::{Dynamics, ScalingPeriods};
pub use validated::{Building, Dissipator, StoreyYield};
