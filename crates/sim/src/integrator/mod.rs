//! Integrators: one trait, several methods (docs/MODEL.md § Integrators).

pub mod delacruz;
pub mod exact;
mod method;
pub mod newmark;
pub(crate) mod state;

pub use delacruz::DelaCruz;
pub use exact::Exact;
pub use method::Integrator;
pub use newmark::Newmark;
