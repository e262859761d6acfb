//! What a study holds at once ([`MemoryEstimate`], made by [`crate::eval::memory`] when
//! the study is loaded) and the limit it is held to.

use crate::base::error::OptError;
use std::path::Path;

/// Most memory a study may be estimated to hold at once, bytes (16 GiB: a real study of
/// a 120-storey frame on two threads is estimated at about 1 GiB, with `exact`'s check).
pub const MAX_STUDY_MEMORY_BYTES: f64 = 16.0 * 1024.0 * 1024.0 * 1024.0;

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
    /// lifted), naming the study's file `path` and what to change (`exact_check`: the
    /// study's check runs `exact`).
    pub fn check(&self, path: &Path, exact_check: bool, limit: f64) -> Result<(), OptError> {
        let total = self.total_bytes() as f64;
        if total <= limit || slipload_sim::limits::allow_large() {
            return Ok(());
        }
        let exact_check = exact_check && self.check_run_bytes >= self.sweep_run_bytes;
        let hint = if exact_check {
            "; the check's `exact` holds most of it: fewer threads (`--threads N`; `threads=N` in Python) or `fidelity.check_method: newmark` need less"
        } else {
            "; fewer threads (`--threads N`; `threads=N` in Python) need less"
        };
        Err(OptError::TooLarge {
            what: format!(
                "{}: the memory the study holds at once ({}){hint}",
                path.display(),
                self.text()
            ),
            estimate: slipload_sim::limits::bytes(total),
            limit: slipload_sim::limits::bytes(limit),
        })
    }
}
