//! A study's memory, estimated before anything runs: what one run holds at the sweep's
//! and at the check's fidelity (for `exact`, its memory budget,
//! [`MemoryBudget::for_plan`], which bounds every mode set it keeps; for the step-by-step
//! methods, the plan's dense matrices and the step's operators), times the threads that
//! run at once, plus the records every run shares. A study whose estimate exceeds
//! [`MAX_STUDY_MEMORY_BYTES`] is refused before its first run (`--allow-large` lifts it,
//! as it lifts the other size limits); the sweep's and optimize's summaries print it.

use crate::base::error::OptError;
use crate::eval::evaluate::{DesignLoads, design_plan};
use crate::model::fidelity::Fidelity;
pub use crate::model::memory::{
    AddressSpace, MAX_STUDY_MEMORY_BYTES, MemoryEstimate, check_probe_fits,
};
use crate::model::study::Study;
use slipload_sim::Plan;
use slipload_sim::integrator::exact::MemoryBudget;
use slipload_sim::scene::MethodName;

/// The dense N×N matrices a step-by-step run holds, at most: the plan's mass, damping and
/// stiffness, and the dense step's operators (its effective matrix and factor, the
/// Delassus matrix, the condensed blocks). Measured: one `newmark` run of the bench's
/// 200-storey frame raises the process's peak resident memory by about 3.4 MiB over a
/// 10-storey one, about 11 such matrices.
pub const STEP_DENSE_MATRICES: u64 = 16;

/// The bytes one run of `plan` holds: its dense matrices and, for `exact`, its memory
/// budget.
pub fn run_bytes(plan: &Plan) -> u64 {
    let n = plan.dofs() as u64;
    let dense = STEP_DENSE_MATRICES * n * n * size_of::<f64>() as u64;
    if plan.method.name == MethodName::Exact {
        dense.saturating_add(MemoryBudget::for_plan(plan).bytes)
    } else {
        dense
    }
}

/// The study's memory estimate on `threads` threads: its plans at the sweep's and the
/// check's fidelity, on the building file's design under the first record (every design
/// and record of a study has the same sizes; the record's length only adds its samples,
/// counted once with the records).
pub fn estimate(study: &Study, threads: usize) -> Result<MemoryEstimate, OptError> {
    let design = DesignLoads::file(study);
    let bytes = |fid: &Fidelity| -> Result<u64, OptError> {
        let plan = design_plan(study, &design, 0, fid, "file (the memory estimate)")?;
        Ok(run_bytes(&plan))
    };
    // the records and the orientations a `worst` pair keeps beside its record
    let records_bytes = study
        .records
        .iter()
        .chain(study.orientations.iter().flatten())
        .map(|r| (r.len() * size_of::<f64>()) as u64)
        .sum();
    Ok(MemoryEstimate {
        threads: threads.max(1),
        sweep_run_bytes: bytes(&Fidelity::sweep(study))?,
        check_run_bytes: bytes(&Fidelity::check(study))?,
        records_bytes,
    })
}
