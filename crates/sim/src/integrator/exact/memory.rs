//! `exact`'s memory: the bytes of a formed mode set's matrices and propagators, their
//! bounds for a plan before any is formed ([`Sizes`]), what a run holds at once
//! ([`working_set_bytes`]), and the budget the mode sets a thread keeps must fit
//! ([`MemoryBudget`]), with the refusal of a scene whose run cannot fit it.
//!
//! Everything `exact` keeps that grows with the building or the stick/slip patterns it
//! meets is a mode set's matrices (the mode matrix, the contacts' rows, the event
//! functions, about (dim + 2·contacts)·dim values) and its propagators (exp(Ah), the
//! scanned functions' Taylor rows, [`TAYLOR_TERMS`]·dim·(events + floors) values, which
//! dominate): O(N²) bytes each, at 60 storeys about 9 MiB. Those are kept by the thread in
//! a cache bounded by the budget (`cache`); a run holds at most two of them at once (the
//! mode set in force and the next one, or the one the contacts are decided with) and the
//! scratch of forming one, so a budget that holds that working set bounds the run. Per
//! pattern a run keeps only a use count ([`MODE_CACHE`](super::MODE_CACHE) of them at most).

use super::model::{EventFn, ModeOps, Stepping, frame_steps};
use super::params::{MEMORY_CAP, MEMORY_FLOOR, MODE_SETS_KEPT, TAYLOR_TERMS};
use crate::error::SimError;
use crate::plan::{ContactKind, Plan};
use nalgebra::{DMatrix, DVector};

const F64: usize = size_of::<f64>();

fn mat(m: &DMatrix<f64>) -> usize {
    m.len() * F64
}

fn vec_bytes(v: &DVector<f64>) -> usize {
    v.len() * F64
}

impl Stepping {
    /// Bytes of the propagators.
    pub(super) fn bytes(&self) -> usize {
        mat(&self.phi)
            + self.work.as_ref().map_or(0, |w| w.iter().map(mat).sum())
            + mat(&self.rows)
            + mat(&self.tails)
            + mat(&self.tails_far)
            + mat(&self.rate_tails_far)
            + mat(&self.obs_tails)
            + self.phi_out.as_ref().map_or(0, mat)
    }
}

impl ModeOps {
    /// Bytes of the mode set's matrices, with its propagators when formed.
    pub(super) fn bytes(&self) -> usize {
        let events: usize = self
            .events
            .iter()
            .map(|e| size_of::<EventFn>() + vec_bytes(&e.row))
            .sum::<usize>()
            + self.event_abs.iter().map(vec_bytes).sum::<usize>();
        size_of::<ModeOps>()
            + mat(&self.a)
            + self.a_rows.bytes()
            + mat(&self.acc_rows)
            + mat(&self.force)
            + mat(&self.slip_rate)
            + mat(&self.xdot)
            + events
            + self.proj.as_ref().map_or(0, mat)
            + mat(&self.obs_rows)
            + self.stepping.get().map_or(0, Stepping::bytes)
    }
}

/// Bounds, in bytes, on what any mode set of one plan takes, from the plan's sizes alone.
#[derive(Debug, Clone, Copy)]
pub(super) struct Sizes {
    /// A mode set's matrices, without propagators ([`ModeOps::bytes`]).
    pub(super) ops: usize,
    /// Its propagators ([`Stepping::bytes`]).
    pub(super) stepping: usize,
    /// The scratch of forming a mode set's matrices (`Model::build`).
    pub(super) build_scratch: usize,
    /// The scratch of forming its propagators (`Model::stepping`: the powers Aᵏ/k!, the
    /// energies' forms).
    pub(super) stepping_scratch: usize,
}

impl Sizes {
    /// The bounds for `plan`'s mode sets: every contact with two finite bounds gives a
    /// stuck mode set two event functions; the observed rows and exp(AΔt) exist only on
    /// frames of several output steps, the work forms only with energies.
    pub(super) fn of(plan: &Plan) -> Sizes {
        let n = plan.dofs();
        let nc = plan.contacts.len();
        let nf = plan.drifts.len();
        let epp = plan
            .contacts
            .iter()
            .filter(|c| matches!(c.kind, ContactKind::Epp))
            .count();
        let dim = 2 * n + epp + if plan.second.is_some() { 7 } else { 5 };
        let events = 2 * nc;
        let observed = if frame_steps(plan) >= 2 {
            plan.observed_contacts_offset() + nc
        } else {
            0
        };
        let energies = plan.outputs.energies;
        let work_forms = if !energies {
            0
        } else if plan.has_yielding_storeys() {
            4
        } else {
            3
        };
        // A's nonzeros: its n acceleration rows are full, its velocity rows one entry, an
        // element's row at most six, the generators' one each.
        let nnz = n * dim + n + 6 * epp + 3;
        let a_rows = nnz * (F64 + size_of::<usize>()) + (dim + 1) * size_of::<usize>();
        let ops = size_of::<ModeOps>()
            + F64 * (dim * dim + dim * n + 3 * dim * nc + dim * observed + n * n)
            + a_rows
            + events * (size_of::<EventFn>() + 2 * F64 * dim);
        let scanned = events + nf;
        let phi_out = usize::from(observed > 0);
        let stepping = F64
            * (dim * dim * (1 + phi_out + work_forms)
                + dim * scanned * (TAYLOR_TERMS + 3)
                + dim * observed);
        // `build`: the forces without contacts and M⁻¹ times them, the contacts' rows, the
        // constraint's blocks, and the spectral bound's matrices and eigen solve.
        let build_scratch = F64 * (4 * n * dim + 3 * nc * dim + 12 * n * n);
        // `stepping`: the powers Aᵏ/k! and exp(Aτ) formed from them; with energies, the
        // forms, a node's propagator and one product.
        let stepping_scratch = F64 * dim * dim * (TAYLOR_TERMS + 1 + if energies { 6 } else { 0 });
        Sizes {
            ops,
            stepping,
            build_scratch,
            stepping_scratch,
        }
    }

    /// A mode set with its propagators.
    pub(super) fn mode_set(&self) -> usize {
        self.ops + self.stepping
    }

    /// What a run holds at once: two mode sets with their propagators and the scratch of
    /// forming one.
    pub(super) fn working_set(&self) -> usize {
        2 * self.mode_set() + self.build_scratch.max(self.stepping_scratch)
    }
}

/// The bytes of mode-set matrices `exact` keeps on one thread: the cache of mode sets
/// (each stick/slip pattern's mode matrix, event functions and propagators) holds at most
/// this many, evicting the least recently used when a new one would not fit; a mode set
/// met again after its eviction is formed again, the same bits, so the budget changes a
/// run's time, never its answer. A thread keeps its last run's mode sets (those of its
/// last two buildings) for the next run, within the budget of that next run.
///
/// Beyond it a run holds its plan, its record, its outputs, O(dim·[`TAYLOR_TERMS`]) of
/// buffers and one use count per pattern met (at most [`MODE_CACHE`](super::MODE_CACHE)).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryBudget {
    /// Bytes.
    pub bytes: u64,
}

impl MemoryBudget {
    /// The budget of a run of `plan` (what [`Exact`](super::Exact) runs with):
    /// [`MODE_SETS_KEPT`] of its largest mode sets (with their propagators, bounded from
    /// its sizes), within [`MEMORY_FLOOR`] … [`MEMORY_CAP`]; never below the run's working
    /// set unless that exceeds the cap (the run is then refused). At 60 storeys with a
    /// massless damper on every floor this is about 140 MiB, at 120 storeys about 490 MiB.
    pub fn for_plan(plan: &Plan) -> MemoryBudget {
        let sizes = Sizes::of(plan);
        let kept = MODE_SETS_KEPT.saturating_mul(sizes.mode_set() as u64);
        let working = sizes.working_set() as u64;
        MemoryBudget {
            bytes: kept
                .clamp(MEMORY_FLOOR, MEMORY_CAP)
                .max(working.min(MEMORY_CAP)),
        }
    }

    /// No bound: every mode set met stays cached (what `exact` did before its budget).
    pub fn unbounded() -> MemoryBudget {
        MemoryBudget { bytes: u64::MAX }
    }

    /// The budget in bytes, as an address-space size.
    pub(super) fn as_usize(self) -> usize {
        usize::try_from(self.bytes).unwrap_or(usize::MAX)
    }
}

/// The bytes a run of `plan` holds at once (two of its mode sets with their propagators,
/// and the scratch of forming one): the least budget it can run within.
pub fn working_set_bytes(plan: &Plan) -> u64 {
    Sizes::of(plan).working_set() as u64
}

/// [`SimError::ExactMemory`] when a run of `plan` cannot hold its working set within
/// `budget`.
pub(super) fn check_memory(plan: &Plan, budget: MemoryBudget) -> Result<(), SimError> {
    let needed = working_set_bytes(plan);
    if needed <= budget.bytes {
        return Ok(());
    }
    Err(SimError::ExactMemory {
        needed,
        budget: budget.bytes,
        suggested_dt: plan.method.dt / 4.0,
    })
}
