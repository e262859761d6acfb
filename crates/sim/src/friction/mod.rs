//! Friction contacts: the box-constrained QP that gives each step's friction forces.

pub mod box_qp;
pub(crate) mod pattern;

pub use box_qp::{Bound, BoxQp, BoxQpError, BoxQpStats, kkt_residual};
