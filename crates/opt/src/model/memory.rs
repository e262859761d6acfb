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

    /// [`OptError::AddressSpace`] when the process's address space is limited
    /// ([`AddressSpace::read`]) and the study's total exceeds what the limit leaves of
    /// it: an allocation past the limit aborts the process, so the study is refused
    /// before its first run (`--allow-large` does not lift this; only the limit does).
    pub fn check_address_space(
        &self,
        path: &Path,
        exact_check: bool,
        space: Option<AddressSpace>,
    ) -> Result<(), OptError> {
        let Some(space) = space else {
            return Ok(());
        };
        let mut hint = ", or run fewer threads (`--threads N`; `threads=N` in Python)".to_string();
        if exact_check && self.check_run_bytes >= self.sweep_run_bytes {
            hint.push_str(", or `fidelity.check_method: newmark`");
        }
        space.hold(self.total_bytes() as f64, &hint, || {
            format!(
                "{}: the memory the study holds at once ({})",
                path.display(),
                self.text()
            )
        })
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

/// [`OptError::AddressSpace`] when one run of `exact` to probe a study's sweep method
/// (`run_bytes`, on this thread) does not fit what the process's address-space limit
/// leaves: the probe would abort the process, so the study is refused before it, naming
/// the key that avoids the probe.
pub fn check_probe_fits(
    path: &Path,
    run_bytes: u64,
    space: Option<AddressSpace>,
) -> Result<(), OptError> {
    let Some(space) = space else {
        return Ok(());
    };
    space.hold(
        run_bytes as f64,
        ", or name the sweep's method (`fidelity.method: newmark` is not probed)",
        || {
            format!(
                "{}: one run of exact, to choose the sweep's method",
                path.display()
            )
        },
    )
}

/// The process's address-space limit (`ulimit -v`, the soft `RLIMIT_AS`) and what it has
/// mapped already, bytes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AddressSpace {
    /// The soft limit.
    pub limit: f64,
    /// The address space mapped now (`VmSize`).
    pub mapped: f64,
}

impl AddressSpace {
    /// The limit and what is mapped, from `/proc/self/limits` and `/proc/self/status`;
    /// `None` where the address space is unlimited or the files cannot be read (a system
    /// without them).
    pub fn read() -> Option<AddressSpace> {
        let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
        let status = std::fs::read_to_string("/proc/self/status").ok()?;
        Self::parse(&limits, &status)
    }

    /// Nothing when `need` bytes fit what the limit leaves (the limit less what is
    /// mapped), else the refusal of `what`; `hint`: what else needs less, from `, or`.
    fn hold(&self, need: f64, hint: &str, what: impl FnOnce() -> String) -> Result<(), OptError> {
        if need <= self.limit - self.mapped {
            return Ok(());
        }
        let b = slipload_sim::limits::bytes;
        Err(OptError::AddressSpace(format!(
            "{}: {} exceeds the {} the process's address-space limit of {} leaves (`ulimit -v`; {} is mapped already); raise the limit{hint}",
            what(),
            b(need),
            b((self.limit - self.mapped).max(0.0)),
            b(self.limit),
            b(self.mapped)
        )))
    }

    /// [`AddressSpace::read`] from the two files' text.
    pub fn parse(limits: &str, status: &str) -> Option<AddressSpace> {
        let soft = limits
            .lines()
            .find_map(|l| l.strip_prefix("Max address space"))?
            .split_whitespace()
            .next()?;
        let limit: f64 = soft.parse().ok()?;
        let mapped_kb: f64 = status
            .lines()
            .find_map(|l| l.strip_prefix("VmSize:"))?
            .split_whitespace()
            .next()?
            .parse()
            .ok()?;
        Some(AddressSpace {
            limit,
            mapped: mapped_kb * 1024.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIMITS: &str = "Limit                     Soft Limit           Hard Limit           Units     \n\
Max stack size            8388608              unlimited            bytes     \n\
Max address space         209715200            unlimited            bytes     \n";

    #[test]
    fn the_limit_and_the_mapped_size_are_read_from_procs_text() {
        let status = "Name:\tslipload\nVmPeak:\t   90000 kB\nVmSize:\t   40960 kB\n";
        let a = AddressSpace::parse(LIMITS, status).unwrap();
        assert_eq!(a.limit, 209715200.0);
        assert_eq!(a.mapped, 40960.0 * 1024.0);
        // unlimited: no limit to hold to
        let unlimited = LIMITS.replace("209715200   ", "unlimited   ");
        assert_eq!(AddressSpace::parse(&unlimited, status), None);
        assert_eq!(AddressSpace::parse(LIMITS, "Name: x\n"), None);
    }

    #[test]
    fn a_study_past_what_the_limit_leaves_is_refused_naming_it() {
        let m = MemoryEstimate {
            threads: 2,
            sweep_run_bytes: 200 << 10,
            check_run_bytes: 64 << 20,
            records_bytes: 2 << 10,
        };
        let path = Path::new("tall.json");
        // 128 MiB against 160 MiB less 40 MiB mapped, then against 170 MiB less 40
        let tight = AddressSpace {
            limit: 160.0 * 1048576.0,
            mapped: 40.0 * 1048576.0,
        };
        let msg = m
            .check_address_space(path, true, Some(tight))
            .unwrap_err()
            .to_string();
        assert!(
            msg.starts_with("tall.json: the memory the study holds at once"),
            "{msg}"
        );
        assert!(
            msg.contains("`ulimit -v`") && msg.contains("`--threads N`"),
            "{msg}"
        );
        assert!(msg.contains("`fidelity.check_method: newmark`"), "{msg}");
        let roomy = AddressSpace {
            limit: 170.0 * 1048576.0,
            mapped: 40.0 * 1048576.0,
        };
        m.check_address_space(path, true, Some(roomy)).unwrap();
        m.check_address_space(path, true, None).unwrap();
    }
}
