//! Study runs: the library entry points behind `slipload optimize`, `sweep`, `merge`,
//! `rank` and `table`. Each runs the phases of its command in order, journalled where
//! the phase simulates, writes the command's files through
//! [`crate::output::write_atomic`] and returns a typed report holding everything those
//! files, the figures and the printed summary are made from. A caller (the CLI, a
//! notebook binding, a job-array wrapper, a test) only chooses the options, shows the
//! progress and renders the report.
//!
//! The flow of [`optimize_study`], each phase resumable under the study's fingerprint
//! ([`crate::fingerprint`]):
//!
//! | phase | runs | journal |
//! |---|---|---|
//! | [`Phase::Sweep`] | sample × every record, sweep fidelity | `journal.jsonl` |
//! | [`Phase::Refine`] | the refiner from the best sweep points | `refine-METHOD.jsonl` |
//! | [`Phase::Check`] | the finalists at the check fidelity | `check.jsonl` |
//! | [`Phase::DesignTable`] | the standard designs and their ±25 % variants, check fidelity | `check.jsonl` |
//! | [`Phase::ObjectiveMap`] | (when asked) a grid over two floors' slip loads, sweep fidelity | — |
//! | [`Phase::Pareto`] | (a study with `objectives`) the front's search, sweep fidelity | `pareto.jsonl` |
//! | [`Phase::ParetoCheck`] | the front's designs at the check fidelity | `check.jsonl` |
//! | [`Phase::ParetoTable`] | the design table of the front's optima and knee | `check.jsonl` |
//!
//! then the candidates (the design table's designs), the figure data ([`figures`]) and
//! the files ([`report`]): `refine.csv`, `optimum.json`, `design-table.{csv,md,json}`,
//! `candidates.json`, beside the sweep's `manifest.json`, `designs.csv`, `responses.csv`
//! (and, with `objectives`, `pareto.{csv,json}` and `pareto-table.{csv,md,json}`:
//! [`crate::pareto`]).
//!
//! Submodules, each importing only those above it: [`progress`] (phases and the progress
//! callback), [`figures`] (figure data), [`report`] (the report and its files),
//! [`optimize`](mod@optimize), [`sweep`](mod@sweep) and [`rank`](mod@rank) (the entry
//! points).

pub mod figures;
pub mod optimize;
pub mod progress;
pub mod rank;
pub mod report;
pub mod sweep;

pub use figures::{Convergence, DriftProfile, FigureData, MapRequest, ObjectiveMap, RecordScatter};
pub use optimize::{OptimizeOptions, optimize_study};
pub use progress::{NoProgress, Phase, Progress};
pub use rank::{family_study, rank_study};
pub use report::{PhaseWork, StudyReport, Work};
pub use sweep::{SweepRun, merge_shards, sweep_study};
