//! Evaluation, above [`crate::store`]: a design simulated over a study's records at a
//! fidelity, in parallel and in task order, journalled by task; the automatic choice of
//! the sweep's method (a probe run); the progress a study run reports.

pub mod evaluate;
pub mod memory;
pub mod probe;
pub mod progress;
