//! The study's description, above [`crate::base`]: the design space, the objectives (one
//! weighted objective, or the front's two to four), the study file's configuration, the
//! samplers and designs, the fidelities, the study itself and its fingerprint. Nothing here
//! simulates or touches an output folder.

pub mod bounds;
pub mod check;
pub mod checks_config;
pub mod code_scaling;
pub mod code_spectrum;
pub mod config;
pub mod devices_config;
pub mod fidelity;
pub mod fingerprint;
pub mod memory;
pub mod objective;
pub mod objectives;
pub mod orientation;
pub mod refine_config;
pub mod sampler;
pub mod space;
pub mod study;
pub mod suites;
