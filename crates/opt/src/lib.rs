//! slipload-opt: the per-floor slip loads μᵢNᵢ of friction dissipators that minimise a
//! drift or energy objective over whole ground-motion suites (docs/MODEL.md § Optimisation).
//!
//! A [`Study`] (JSON, validated before anything runs) names a building, record suites, a
//! [`DesignSpace`] and an [`Objective`]. A sweep runs a sample of designs × every record
//! as independent tasks ([`evaluate`]), journalled ([`journal`]) and shardable
//! ([`Shard`]); [`refine`] improves the best sweep points; [`table`] and [`rank`] turn the
//! results into the tables engineers hand on. [`pipeline`] runs those phases for a
//! command — [`pipeline::optimize_study`] is the whole study — and writes its files
//! ([`output::write_atomic`]), returning a report a caller renders.

pub mod collapse;
pub mod error;
pub mod evaluate;
pub mod family;
pub mod fidelity;
pub mod fingerprint;
pub mod folder_lock;
pub mod journal;
pub mod metrics;
pub mod objective;
pub mod optimize;
pub mod output;
pub mod pareto;
pub mod pipeline;
pub mod qp;
pub mod rank;
pub mod refine;
pub mod sampler;
pub mod shard;
pub mod space;
pub mod study;
pub mod sweep;
pub mod table;

pub use error::OptError;
pub use metrics::RecordMetrics;
pub use objective::{Metric, Objective, Statistic, Term};
pub use shard::Shard;
pub use space::{Bound, ConstraintsConfig, DesignSpace, OnBound, Shape, SpaceConfig};
pub use study::{Study, StudyConfig};
