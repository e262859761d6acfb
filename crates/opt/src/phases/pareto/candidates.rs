//! Every design a study evaluated at the sweep fidelity is a candidate for its front:
//! after the search, the building file's design (where the space holds it) and the
//! refinement's evaluations join the search's designs, so no design the study ran
//! dominates the front it writes.

use super::search::{Evaluated, Search, Source};
use super::vector::objective_vector;
use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::eval::evaluate::{TaskJournal, run_designs_journalled, suite_ranges};
use crate::model::fidelity::Fidelity;
use crate::model::study::Study;
use crate::phases::sweep::Manifest;

/// One refinement evaluation offered to the front: its scaled variables and, when this
/// run computed it, its runs at the sweep fidelity.
pub type RefinedDesign<'a> = (&'a [f64], Option<&'a [RecordMetrics]>);

/// The refinement's designs of `refined` not yet among `search`'s, in their order, with
/// the position of those whose runs are missing (replayed from the refinement's journal).
fn new_designs<'a>(
    search: &Search,
    refined: &'a [RefinedDesign<'a>],
) -> Vec<&'a RefinedDesign<'a>> {
    let mut out: Vec<&RefinedDesign<'a>> = Vec::new();
    for d in refined {
        let seen = search.evaluated.iter().any(|e| e.z == d.0) || out.iter().any(|o| o.0 == d.0);
        if !seen {
            out.push(d);
        }
    }
    out
}

/// How many of the refinement's new designs have no runs in memory (simulations at the
/// sweep fidelity [`add_candidates`] will take from `pareto.jsonl` or run), times the
/// runs of a design.
pub fn missing_runs(study: &Study, search: &Search, refined: &[RefinedDesign<'_>]) -> usize {
    new_designs(search, refined)
        .iter()
        .filter(|d| d.1.is_none())
        .count()
        * study.runs()
}

/// Appends to `search.evaluated` the building file's design (`file`, where the space
/// holds it and it is not there already) and the refinement's designs (`r0001`… by their
/// place among `refined`), with their objective vectors at the sweep fidelity. A design
/// whose runs are not in memory runs now, journalled in `journal` (`pareto.jsonl`).
/// Returns the simulations run and those taken from the journal.
pub fn add_candidates(
    study: &Study,
    manifest: &Manifest,
    rows: &[RecordMetrics],
    search: &mut Search,
    refined: &[RefinedDesign<'_>],
    journal: Option<&TaskJournal>,
    tick: &(dyn Fn() + Sync),
) -> Result<(usize, usize), OptError> {
    let nr = manifest.records.len();
    let bare = &rows[..nr];
    let ranges = suite_ranges(study);
    if let Some(file) = manifest.designs.get(1).filter(|d| d.friction_n.is_none())
        && let Some(z) = study.space.point_of(&file.slip_loads_n)
        && !search.evaluated.iter().any(|e| e.z == z)
    {
        search.evaluated.push(Evaluated {
            label: "file".into(),
            source: Source::File,
            z,
            slip_loads_n: file.slip_loads_n.clone(),
            objectives: search.file.clone(),
            scalar: None,
        });
    }
    let fresh = new_designs(search, refined);
    let missing: Vec<Vec<f64>> = fresh
        .iter()
        .filter(|d| d.1.is_none())
        .map(|d| study.space.slip_loads(d.0))
        .collect();
    let before = journal.map_or(0, TaskJournal::reused);
    let mut ran_runs =
        run_designs_journalled(study, &missing, &Fidelity::sweep(study), journal, tick)?
            .into_iter();
    let reused = journal.map_or(0, TaskJournal::reused) - before;
    let mut out = Vec::with_capacity(fresh.len());
    for d in &fresh {
        let k = refined
            .iter()
            .position(|r| r.0 == d.0)
            .expect("a design of the list");
        let loads = study.space.slip_loads(d.0);
        let held;
        let runs: &[RecordMetrics] = match d.1 {
            Some(r) => r,
            None => {
                held = ran_runs.next().expect("one run list per missing design");
                &held
            }
        };
        out.push(Evaluated {
            label: format!("r{:04}", k + 1),
            source: Source::Refine,
            z: d.0.to_vec(),
            objectives: objective_vector(study, &loads, runs, Some(bare), &ranges)?,
            slip_loads_n: loads,
            scalar: None,
        });
    }
    search.evaluated.extend(out);
    Ok((missing.len() * study.runs() - reused, reused))
}
