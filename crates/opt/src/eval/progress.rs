//! Phases of a study run and how their progress reaches the caller.

use crate::base::error::OptError;
use crate::store::folder::Discarded;

/// A phase of a study run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Phase {
    /// The sweep: a sample of designs × every record.
    Sweep,
    /// The refinement from the best sweep points.
    Refine,
    /// The finalists at reference accuracy.
    Check,
    /// The design table's designs at reference accuracy.
    DesignTable,
    /// The objective map over two floors' slip loads.
    ObjectiveMap,
    /// Candidate designs over every record, for their ranking.
    Rank,
    /// Sweep and refinement of every member of a design family.
    Family,
    /// The search of a front over the study's `objectives` (sweep fidelity).
    Pareto,
    /// The front's designs at reference accuracy.
    ParetoCheck,
    /// The design table of a few front designs at reference accuracy.
    ParetoTable,
}

impl Phase {
    /// What the phase is called in progress output (`design table`).
    pub fn label(self) -> &'static str {
        match self {
            Phase::Sweep => "sweep",
            Phase::Refine => "refine",
            Phase::Check => "check",
            Phase::DesignTable => "design table",
            Phase::ObjectiveMap => "objective map",
            Phase::Rank => "rank",
            Phase::Family => "family",
            Phase::Pareto => "front search",
            Phase::ParetoCheck => "front check",
            Phase::ParetoTable => "front table",
        }
    }
}

/// How a study run reports its progress: per phase, a start with the simulations
/// expected, a tick per simulation (from worker threads), an end. Every method does
/// nothing by default.
pub trait Progress: Sync {
    /// `phase` starts; about `work` simulations are expected (0: not known ahead; the
    /// refinement's count is its budget, which a refiner may end before or pass by a
    /// few).
    fn start(&self, phase: Phase, work: usize) {
        let _ = (phase, work);
    }
    /// One simulation of the running phase finished, or was taken from a journal.
    fn tick(&self) {}
    /// `phase` is over.
    fn finish(&self, phase: Phase) {
        let _ = phase;
    }
    /// `fresh` emptied the output folder `dir` before the run: what it removed and kept.
    fn discarded(&self, dir: &std::path::Path, discarded: &Discarded) {
        let _ = (dir, discarded);
    }
}

/// No progress output.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {}

/// Runs `body` as `phase` of `progress`: started with `work`, ticked by the closure
/// `body` receives, finished when it returns successfully.
pub(crate) fn phase<T>(
    progress: &dyn Progress,
    phase: Phase,
    work: usize,
    body: impl FnOnce(&(dyn Fn() + Sync)) -> Result<T, OptError>,
) -> Result<T, OptError> {
    progress.start(phase, work);
    let out = body(&|| progress.tick())?;
    progress.finish(phase);
    Ok(out)
}
