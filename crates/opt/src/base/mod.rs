//! The bottom layer: what every other layer uses and that uses nothing of this crate
//! above it — the error type, atomic output files, per-record metrics, the wording of a
//! collapsed objective, shards of a task list, and the small convex QP of the refiners.

pub mod collapse;
pub mod error;
pub mod metrics;
pub mod output;
pub mod qp;
pub mod shard;
