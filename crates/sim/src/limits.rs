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

/// Steps as a count for people.
pub fn count(v: f64) -> String {
    if v < 1e6 {
        format!("{v:.0}")
    } else {
        format!("{v:.3e}")
    }
}
