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
use crate::model::study::Study;
use slipload_sim::Plan;
use slipload_sim::integrator::exact::MemoryBudget;
use slipload_sim::scene::MethodName;

/// Most memory a study may be estimated to hold at once, bytes (16 GiB: a real study of
/// a 120-storey frame on two threads is estimated at about 1 GiB, with `exact`'s check).
pub const MAX_STUDY_MEMORY_BYTES: f64 = 16.0 * 1024.0 * 1024.0 * 1024.0;

/// The dense N×N matrices a step-by-step run holds, at most: the plan's mass, damping and
/// stiffness, and the dense step's operators (its effective matrix and factor, the
/// Delassus matrix, the condensed blocks). Measured: one `newmark` run of the bench's
/// 200-storey frame raises the process's peak resident memory by about 3.4 MiB over a
/// 10-storey one, about 11 such matrices.
pub const STEP_DENSE_MATRICES: u64 = 16;

/// What a study holds at once, estimated before it runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryEstimate {
    /// Threads that run at once (rayon's pool).
    pub threads: usize,
    /// One run at the sweep's fidelity, bytes.
    pub sweep_run_bytes: u64,
    /// One run at the check's fidelity, bytes.
    pub check_run_bytes: u64,
    /// The records, shared by every run, bytes.
    pub records_bytes: u64,
}

impl MemoryEstimate {
    /// The most the study holds at once: the records and, on every thread, the larger of
    /// a sweep run and a check run.
    pub fn total_bytes(&self) -> u64 {
        let per_run = self.sweep_run_bytes.max(self.check_run_bytes);
        self.records_bytes
            .saturating_add(per_run.saturating_mul(self.threads as u64))
    }

    /// The estimate for people: `about X (T thread(s) × Y per run (sweep S, check C),
    /// records R)`.
    pub fn text(&self) -> String {
        let b = |v: u64| slipload_sim::limits::bytes(v as f64);
        format!(
            "about {} ({} thread(s) x {} per run (sweep {}, check {}), records {})",
            b(self.total_bytes()),
            self.threads,
            b(self.sweep_run_bytes.max(self.check_run_bytes)),
            b(self.sweep_run_bytes),
            b(self.check_run_bytes),
            b(self.records_bytes)
        )
    }

    /// [`OptError::TooLarge`] when the total exceeds `limit` bytes (unless the limits are
    /// lifted), naming what to change.
    pub fn check(&self, study: &Study, limit: f64) -> Result<(), OptError> {
        let total = self.total_bytes() as f64;
        if total <= limit || slipload_sim::limits::allow_large() {
            return Ok(());
        }
        let exact_check = study.check_method.method == MethodName::Exact
            && self.check_run_bytes >= self.sweep_run_bytes;
        let hint = if exact_check {
            "; the check's `exact` holds most of it: fewer threads (RAYON_NUM_THREADS) or `fidelity.check_method: newmark` need less"
        } else {
            "; fewer threads (RAYON_NUM_THREADS) need less"
        };
        Err(OptError::TooLarge {
            what: format!(
                "{}: the memory the study holds at once ({}){hint}",
                study.path.display(),
                self.text()
            ),
            estimate: slipload_sim::limits::bytes(total),
            limit: slipload_sim::limits::bytes(limit),
        })
    }
}

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
    let records_bytes = study
        .records
        .iter()
        .map(|r| (r.len() * size_of::<f64>()) as u64)
        .sum();
    Ok(MemoryEstimate {
        threads: threads.max(1),
        sweep_run_bytes: bytes(&Fidelity::sweep(study))?,
        check_run_bytes: bytes(&Fidelity::check(study))?,
        records_bytes,
    })
}
