//! The top layer: one library call per study command — [`optimize_study`]
//! (`slipload optimize`), [`sweep_study`] (`sweep`), [`merge_shards`] (`merge`),
//! [`rank_study`] (`rank`) and [`family_study`] (`table`). Each takes the study, the
//! command's options, the output folder as a [`crate::store::folder::FolderRequest`], a progress observer
//! ([`crate::eval::progress::Progress`]) and, where it draws, a [`FigureWriter`]; it
//! checks what it was given, opens the folder ([`crate::store::folder::StudyFolder`]: the
//! path, the one-writer lock, `fresh`), runs the command's phases in order, journalled
//! where they simulate, writes the files through the folder, draws the figures, and
//! returns a typed report holding everything those files, the figures and the printed
//! summary are made from. A front (the CLI, the Python package, a test) parses its
//! arguments, makes this one call and shows the report: nothing of the folder, its lock,
//! its journals or its file list is done there.
//!
//! The flow of [`optimize_study`], each phase resumable under the study's fingerprint
//! ([`crate::model::fingerprint`]):
//!
//! | phase | runs | journal |
//! |---|---|---|
//! | [`Phase::Sweep`] | sample × every record, sweep fidelity | `journal.jsonl` |
//! | [`Phase::Pareto`] | (a study with `objectives`) the front's search, sweep fidelity | `pareto.jsonl` |
//! | [`Phase::Refine`] | the refiner from the best sweep (and search) points | `refine-METHOD.jsonl` (with a front, its runs in `pareto.jsonl` too) |
//! | [`Phase::Check`] | the finalists at the check fidelity | `check.jsonl` |
//! | [`Phase::DesignTable`] | the standard designs and their ±25 % variants, check fidelity | `check.jsonl` |
//! | [`Phase::ObjectiveMap`] | (when asked) a grid over two floors' slip loads, sweep fidelity | — |
//! | [`Phase::ParetoCheck`] | the front's designs (search, file, refinement) at the check fidelity | `check.jsonl` |
//! | [`Phase::ParetoTable`] | the design table of the front's optima and knee | `check.jsonl` |
//!
//! before them the building the study runs (`building.json`, `building.md`:
//! [`crate::phases::building`]), after them the candidates (the design table's designs),
//! the figure data
//! ([`crate::phases::figures`]) and the files ([`StudyReport::write_files`]): `refine.csv`, `optimum.json`,
//! `design-table.{csv,md,json}`, `candidates.json`, beside the sweep's `manifest.json`,
//! `designs.csv`, `responses.csv` (and, with `objectives`, `pareto.{csv,json}` and
//! `pareto-table.{csv,md,json}`: [`crate::phases::pareto`]), and the figures.
//!
//! A new phase goes into [`crate::phases`] (taking its journal's path from the folder) and
//! is called from the command that runs it here; a new output file is written through
//! [`crate::store::folder::StudyFolder::write`] (and its name added to
//! [`crate::store::folder::is_output_name`] when older folders may hold it).
//!
//! [`Phase::Sweep`]: crate::eval::progress::Phase::Sweep
//! [`Phase::Refine`]: crate::eval::progress::Phase::Refine
//! [`Phase::Check`]: crate::eval::progress::Phase::Check
//! [`Phase::DesignTable`]: crate::eval::progress::Phase::DesignTable
//! [`Phase::ObjectiveMap`]: crate::eval::progress::Phase::ObjectiveMap
//! [`Phase::Pareto`]: crate::eval::progress::Phase::Pareto
//! [`Phase::ParetoCheck`]: crate::eval::progress::Phase::ParetoCheck
//! [`Phase::ParetoTable`]: crate::eval::progress::Phase::ParetoTable

mod design_run;
mod figures;
mod optimize;
mod plan;
mod rank;
mod report;
mod sweep;

pub use design_run::{DesignRun, design_run_scene};
pub use figures::{FigureWriter, NoFigures};
pub use optimize::{OptimizeOptions, OptimizeRun, optimize_study};
pub use plan::{PLAN_JOURNAL, PlanRun, optimize_in_plan};
pub use rank::{family_study, rank_study};
pub use report::{PhaseWork, StudyReport, Work};
pub use sweep::{SweepRun, merge_shards, sweep_study};
