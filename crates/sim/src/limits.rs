//! Work and memory limits: a run is estimated before anything is allocated or stepped,
//! and refused beyond limits no real study needs (a typo such as `--dt 1e-12` would
//! otherwise run for days or abort on an allocation). The limits can be lifted for one
//! process with [`set_allow_large`] (the CLI's `--allow-large`) or the environment
//! variable [`ALLOW_LARGE_ENV`]`=1`.

use crate::error::SimError;

/// Most integration steps of one simulation (10⁸: a 100 s record at Δt = 1 µs).
pub const MAX_STEPS: f64 = 1e8;

/// Most memory for one simulation's time histories (values and their CSV text), bytes.
pub const MAX_HISTORY_BYTES: f64 = 4.0 * 1024.0 * 1024.0 * 1024.0;

/// Bytes per history value: 8 stored, about 17 in the CSV text written from them.
pub const HISTORY_BYTES_PER_VALUE: f64 = 25.0;

/// The environment variable that lifts the limits (`1`, `true` or `yes`).
pub const ALLOW_LARGE_ENV: &str = slipload_motion::limits::ALLOW_LARGE_ENV;

/// How to go beyond a limit, for error messages.
pub const OVERRIDE_HINT: &str = slipload_motion::limits::OVERRIDE_HINT;

/// Lifts (or restores) the limits for this process: these and the input limits of
/// [`slipload_motion::limits`] (file sizes, suite sizes) share one switch.
pub fn set_allow_large(on: bool) {
    slipload_motion::limits::set_allow_large(on);
}

/// Whether the limits are lifted (by [`set_allow_large`] or [`ALLOW_LARGE_ENV`]).
pub fn allow_large() -> bool {
    slipload_motion::limits::allow_large()
}

/// A number of bytes for people (KiB … EiB), as [`slipload_motion::limits::bytes`].
pub fn bytes(b: f64) -> String {
    slipload_motion::limits::bytes(b)
}

/// [`SimError::TooLarge`] unless `estimate <= limit` or the limits are lifted.
pub fn check(
    what: &str,
    estimate: f64,
    limit: f64,
    shown: &dyn Fn(f64) -> String,
) -> Result<(), SimError> {
    if estimate <= limit || allow_large() {
        return Ok(());
    }
    Err(SimError::TooLarge {
        what: what.to_string(),
        estimate: shown(estimate),
        limit: shown(limit),
    })
}

/// The cores of this machine (1 when unknown).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Most worker threads while the limits are in force: 8 per core, at least 256 (more only
/// adds overhead; 100 000 threads take minutes to start).
pub fn max_threads() -> usize {
    (8 * cores()).max(256)
}

/// Checks a number of worker threads asked for, the one rule of every front (the command
/// line's `--threads`, the Python package's `threads=`): at least 1, and at most
/// [`max_threads`] unless the limits are lifted; else [`SimError::Threads`].
pub fn check_threads(threads: usize) -> Result<(), SimError> {
    let limit = max_threads();
    if threads == 0 || (threads > limit && !allow_large()) {
        return Err(SimError::Threads {
            threads,
            limit,
            cores: cores(),
        });
    }
    Ok(())
}

/// Steps as a count for people.
pub fn count(v: f64) -> String {
    if v < 1e6 {
        format!("{v:.0}")
    } else {
        format!("{v:.3e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thread_counts_from_one_to_the_limit_are_taken() {
        assert!(check_threads(1).is_ok());
        assert!(check_threads(max_threads()).is_ok());
        let none = check_threads(0).unwrap_err();
        assert!(none.to_string().contains("give at least 1"), "{none}");
        // the lifted limits are process-wide: the upper bound is tested only while they hold
        if !allow_large() {
            let many = check_threads(max_threads() + 1).unwrap_err();
            assert!(many.to_string().contains("at most"), "{many}");
            assert!(many.to_string().contains("--allow-large"), "{many}");
        }
    }
}
