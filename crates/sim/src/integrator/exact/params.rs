//! The fixed parameters of `exact`: the series' length, the substep's phase, the scans,
//! the work caps, the memory budget's terms and the grazing threshold (their roles are
//! in the module docs).

/// Terms of the exponential's Taylor series kept on a substep.
pub const TAYLOR_TERMS: usize = 22;
/// Largest ρ·τ of a substep (ρ bounds the spectral radius of the mode matrices).
pub const SUBSTEP_PHASE: f64 = 0.5;
/// Scan intervals per substep for event and extremum detection.
pub const SCAN_POINTS: usize = 8;
/// Cap on the substeps of one run.
pub const MAX_SUBSTEPS: u64 = 4_000_000;
/// Cap on the events of one run.
pub const MAX_EVENTS: u64 = 5_000_000;
/// Mode sets whose use a run counts (how many grid substeps it took with each, which
/// decides when it steps with their propagators): no matrices, a few bytes each; the
/// count restarts for all of them when a run has met this many.
pub const MODE_CACHE: usize = 4096;
/// Mode sets of the plan's largest size that the default memory budget holds
/// ([`MemoryBudget::for_plan`](super::MemoryBudget::for_plan)).
pub const MODE_SETS_KEPT: u64 = 16;
/// Least default memory budget, bytes (64 MiB): small frames keep every mode set they
/// meet.
pub const MEMORY_FLOOR: u64 = 64 << 20;
/// Largest default memory budget, bytes (1.5 GiB): a scene whose run needs more at once
/// is refused ([`SimError::ExactMemory`](crate::error::SimError::ExactMemory)).
pub const MEMORY_CAP: u64 = 3 << 29;
/// Leading Taylor coefficients of a scanned function formed exactly on a grid substep
/// before its full series is (the second exclusion test).
pub const LEAD_TERMS: usize = 4;
/// Grazing threshold, relative to the force bound or the velocity scale.
pub const GRAZE_REL: f64 = 1e-10;
