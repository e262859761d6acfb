//! slipload-opt: the per-floor slip loads μᵢNᵢ of friction dissipators that minimise a
//! drift or energy objective over whole ground-motion suites (docs/MODEL.md § Optimisation).
//!
//! The crate is built in layers, each importing only from the layers below it (a test,
//! `crates/cli/tests/module_graph.rs`, fails on any import that runs back up or round):
//!
//! | layer | owns |
//! |---|---|
//! | [`pipeline`] | one library call per study command (`optimize`, `sweep`, `merge`, `rank`, `table`): opens the study folder, runs the phases, draws the figures through a [`pipeline::FigureWriter`], returns the report |
//! | [`phases`] | the phases of a study: the sweep, the refinement and its finalists, the design table, the front search, the ranking, the design family, the figure data |
//! | [`eval`] | evaluation: simulating a design over the records at a fidelity, task journals, the automatic sweep-method probe, progress |
//! | [`store`] | the study folder: its one-writer lock, the files slipload wrote there, `fresh`, the journals and their fingerprint check |
//! | [`model`] | the study's description: its configuration, design space, objectives, samplers, fidelities and fingerprint |
//! | [`base`] | errors, atomic output, metrics, collapse wording, shards, the small QP |
//!
//! A [`Study`] (JSON, validated before anything runs) names a building, record suites, a
//! [`DesignSpace`] and an [`Objective`]. A front (the CLI, the Python package) loads it,
//! and calls one function of [`pipeline`] with the options, the output folder, a progress
//! observer and a figure writer; it shows the report that call returns.

pub mod base;
pub mod eval;
pub mod model;
pub mod phases;
pub mod pipeline;
pub mod plan;
pub mod store;

pub use base::error::OptError;
pub use base::metrics::RecordMetrics;
pub use base::shard::Shard;
pub use model::config::StudyConfig;
pub use model::objective::{Metric, Objective, Statistic, Term};
pub use model::space::{Bound, ConstraintsConfig, DesignSpace, OnBound, Shape, SpaceConfig};
pub use model::study::Study;
