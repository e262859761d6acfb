//! slipload-sim: N-storey frames with one friction dissipator per floor under earthquake
//! records — building model, scenes, plans, integrators, responses and energies.
//!
//! Flow: a [`Scene`] (building + excitation + outputs + method) is compiled into a
//! [`Plan`] that carries only the effects the scene calls for, then run by an
//! [`Integrator`] into an [`Outcome`] whose [`Response`] is the output contract.

pub mod accuracy;
#[doc(hidden)]
pub mod bench_scenes;
pub mod building;
pub mod error;
pub mod floorplan;
pub mod friction;
pub mod integrator;
pub mod kind;
pub mod kinematics;
pub mod limits;
pub mod modes;
pub mod opensees;
pub mod plan;
mod py_literal;
pub mod response;
pub mod scene;
pub mod simulate;
pub mod units;

pub use building::{Building, BuildingConfig, Dissipator, ScalingPeriods, StoreyYield};
pub use error::SimError;
pub use integrator::{DelaCruz, Exact, Integrator, Newmark};
pub use kind::FileKind;
pub use opensees::opensees_script;
pub use plan::Plan;
pub use response::{Collapse, Energy, History, LoopIterations, Outcome, Response};
pub use scene::{MethodName, Scene, SceneOverrides};
pub use simulate::{run_plan, simulate};

/// Version of the integrators' numerics: part of every study journal's fingerprint, so a
/// journal written by other numerics is not mixed with new results. Bump it whenever a
/// change moves any output bit of any method (a change that keeps every bit does not).
/// 2: `exact` rules out scans on off-grid substeps and sums its dot products in four
/// interleaved parts (the same answers to round-off, other last bits).
/// 3: `newmark` steps massless elements without a brace dashpot by the return mapping (other
/// answers, at the step's accuracy), and banded frames of ten or more DOFs in O(N) (the same
/// answers to round-off, other last bits).
pub const NUMERICS_VERSION: u32 = 3;
