//! The mode sets of a run ([`Cache`]) over those a thread keeps for the last buildings it
//! ran, within a byte budget ([`MemoryBudget`]), and each mode set as one run sees it
//! ([`RunOps`]: whether this run has used it long enough to step with its propagators, a
//! decision of the run's own).
//!
//! Policy: the thread's mode sets are kept, least recently used first out, while their
//! bytes ([`ModeOps::bytes`]) and those of the one being formed (bounded before it is,
//! [`Sizes`], with the scratch of forming it) fit the budget; a mode set a run holds is
//! never evicted. A run counts its own use of every mode set it meets (no matrices), so
//! when it steps with a mode set's propagators does not depend on what the cache kept:
//! an evicted mode set met again is formed again, with its propagators if the run had
//! reached them, from the same arithmetic on the same inputs, hence the same bits.

use super::memory::{MemoryBudget, Sizes};
use super::model::{Mode, ModeOps, Model, Stepping, frame_steps};
use super::params::MODE_CACHE;
use crate::plan::{ContactKind, ContactRole, Plan};
use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::rc::Rc;

/// One run's use of one mode set.
#[derive(Default)]
struct Visit {
    /// Grid substeps taken with the Taylor sums so far in this run.
    uses: Cell<usize>,
    ready: Cell<bool>,
}

/// A mode set as one run sees it: the shared operators, and whether this run has used it
/// long enough to step with its propagators. That decision is the run's own, so a run's
/// substeps (and hence its bits) do not depend on what ran on the thread before it, nor
/// on what the cache evicted.
pub(super) struct RunOps {
    pub(super) ops: Rc<ModeOps>,
    visit: Rc<Visit>,
}

impl std::ops::Deref for RunOps {
    type Target = ModeOps;
    fn deref(&self) -> &ModeOps {
        &self.ops
    }
}

impl RunOps {
    /// The grid propagators, once this run has used the mode set for `prepare_after`
    /// grid substeps.
    #[inline]
    pub(super) fn prepared(&self) -> Option<&Stepping> {
        if self.visit.ready.get() {
            self.ops.stepping.get()
        } else {
            None
        }
    }
}

/// A mode set the thread keeps: its matrices, their bytes, and when it was last asked for.
struct Kept {
    ops: Rc<ModeOps>,
    bytes: usize,
    last: u64,
}

/// Mode sets of one building, kept across runs.
type SharedModes = HashMap<Vec<Mode>, Kept>;

/// The mode sets a thread keeps, over its last [`SHARED_PLANS`] buildings.
#[derive(Default)]
struct Store {
    /// (id, [`plan_key`], mode sets), most recent building first.
    plans: Vec<(u64, Vec<u64>, SharedModes)>,
    next_id: u64,
    /// Bytes of every kept mode set.
    bytes: usize,
    /// Ticks of [`Kept::last`].
    clock: u64,
}

impl Store {
    fn modes(&mut self, id: u64) -> &mut SharedModes {
        &mut self
            .plans
            .iter_mut()
            .find(|p| p.0 == id)
            .expect("a run's building stays kept while it runs")
            .2
    }

    /// Evicts the least recently used mode sets no run holds until `incoming` more bytes
    /// fit `budget` (or none is left to evict).
    fn make_room(&mut self, incoming: usize, budget: usize) {
        while self.bytes.saturating_add(incoming) > budget {
            let oldest = self
                .plans
                .iter()
                .enumerate()
                .flat_map(|(p, (_, _, m))| m.iter().map(move |(k, e)| (p, k, e)))
                .filter(|(_, _, e)| Rc::strong_count(&e.ops) == 1)
                .min_by_key(|(_, _, e)| e.last)
                .map(|(p, k, _)| (p, k.clone()));
            let Some((p, key)) = oldest else { return };
            let gone = self.plans[p].2.remove(&key).expect("found above");
            self.bytes -= gone.bytes;
        }
    }
}

thread_local! {
    /// The mode sets of the last [`SHARED_PLANS`] buildings run on this thread, each under
    /// its [`plan_key`]: a suite of records on one design forms each mode set's operators
    /// and propagators once (while the budget holds them). What a run computes from them
    /// does not depend on whether they were found here ([`RunOps`]).
    static SHARED: RefCell<Store> = RefCell::new(Store::default());
}

/// Drops the mode sets this thread keeps between runs: for a thread that ran `exact` once
/// and will not run it again soon (a study's sweep-method probe, on the thread that loads
/// the study, while the study's runs go to other threads), so that what it kept is not
/// held beside every worker's budget.
pub fn release_thread_cache() {
    SHARED.with(|s| *s.borrow_mut() = Store::default());
}

/// Buildings whose mode sets a thread keeps.
const SHARED_PLANS: usize = 2;

/// Everything a mode set's operators and propagators are formed from, as bits: the
/// matrices (the mass influence M·1 follows from M), the contacts, the harmonic force's floor, amplitude and frequency, the output
/// step, whether energies are asked for and the frame ([`frame_steps`]). Equal keys give
/// equal operators.
fn plan_key(plan: &Plan) -> Vec<u64> {
    let mut k: Vec<u64> = Vec::with_capacity(8 + 3 * plan.mass.len() + 8 * plan.contacts.len());
    k.extend([
        plan.floors as u64,
        plan.dofs() as u64,
        plan.contacts.len() as u64,
    ]);
    for m in [&plan.mass, &plan.damping, &plan.stiffness] {
        k.extend(m.iter().map(|x| x.to_bits()));
    }
    for ct in &plan.contacts {
        k.push(match ct.role {
            ContactRole::Damper => 0,
            ContactRole::Storey => 1,
        });
        k.push(ct.floor as u64);
        for point in [&ct.top, &ct.bottom] {
            k.push(point.entries().count() as u64);
            for (i, w) in point.entries() {
                k.extend([i as u64, w.to_bits()]);
            }
        }
        k.push(match ct.kind {
            ContactKind::Epp => 0,
            ContactKind::Dof { dof } => dof as u64 + 1,
        });
        k.extend([ct.lower, ct.upper, ct.brace_stiffness, ct.brace_damping].map(f64::to_bits));
    }
    match &plan.harmonic {
        Some(h) => k.extend([1, h.floor as u64, h.amplitude.to_bits(), h.omega.to_bits()]),
        None => k.push(0),
    }
    match &plan.second {
        Some(g) => {
            k.push(1);
            k.extend(g.influence.iter().map(|x| x.to_bits()));
        }
        None => k.push(0),
    }
    k.push(plan.method.dt.to_bits());
    k.push(u64::from(plan.outputs.energies));
    k.push(frame_steps(plan) as u64);
    k
}

/// Mode sets of one run, over the mode sets of its building that the thread keeps.
pub(super) struct Cache {
    /// The building's id in the thread's store.
    id: u64,
    budget: usize,
    sizes: Sizes,
    /// This run's use of each mode set it has met (no matrices; restarted when it holds
    /// [`MODE_CACHE`]).
    visits: HashMap<Vec<Mode>, Rc<Visit>>,
    /// Most bytes of mode sets kept at once during the run, with the scratch of forming one.
    peak: usize,
}

impl Cache {
    /// The run's cache over the thread's mode sets of `plan`'s building, which it brings
    /// within `budget` (an earlier run may have kept more).
    pub(super) fn new(plan: &Plan, budget: MemoryBudget) -> Cache {
        let key = plan_key(plan);
        let budget = budget.as_usize();
        let (id, kept) = SHARED.with(|s| {
            let mut s = s.borrow_mut();
            let entry = match s.plans.iter().position(|p| p.1 == key) {
                Some(i) => s.plans.remove(i),
                None => {
                    s.next_id += 1;
                    (s.next_id, key, HashMap::new())
                }
            };
            let id = entry.0;
            s.plans.insert(0, entry);
            while s.plans.len() > SHARED_PLANS {
                let (_, _, gone) = s.plans.pop().expect("more than SHARED_PLANS");
                s.bytes -= gone.values().map(|e| e.bytes).sum::<usize>();
            }
            s.make_room(0, budget);
            (id, s.bytes)
        });
        Cache {
            id,
            budget,
            sizes: Sizes::of(plan),
            visits: HashMap::new(),
            peak: kept,
        }
    }

    /// Most bytes of mode sets the thread kept at once during the run, with the scratch
    /// of forming one (within the budget).
    pub(super) fn peak_bytes(&self) -> usize {
        self.peak
    }

    /// This run's use of mode set `key`, met now.
    fn visit(&mut self, key: &[Mode]) -> Rc<Visit> {
        if let Some(v) = self.visits.get(key) {
            return Rc::clone(v);
        }
        if self.visits.len() >= MODE_CACHE {
            self.visits.clear();
        }
        let v = Rc::new(Visit::default());
        self.visits.insert(key.to_vec(), Rc::clone(&v));
        v
    }

    /// Mode set `key` as this run sees it, with its propagators once the run has reached
    /// them.
    pub(super) fn get(&mut self, model: &Model, key: &[Mode]) -> RunOps {
        let visit = self.visit(key);
        let ops = self.kept(model, key, visit.ready.get());
        RunOps { ops, visit }
    }

    /// Mode set `key`'s operators (its force rows decide contacts at an event), met by the
    /// run as [`Cache::get`] meets it, without forming its propagators.
    pub(super) fn operators(&mut self, model: &Model, key: &[Mode]) -> Rc<ModeOps> {
        self.visit(key);
        self.kept(model, key, false)
    }

    /// Counts one grid substep taken with the Taylor sums; past `prepare_after` the
    /// propagators are formed (or taken from an earlier run) and used from then on.
    #[inline]
    pub(super) fn count_use(&mut self, model: &Model, ops: &RunOps) {
        let u = ops.visit.uses.get() + 1;
        ops.visit.uses.set(u);
        if u > ops.prepare_after {
            if ops.stepping.get().is_none() {
                SHARED.with(|s| self.form_stepping(&mut s.borrow_mut(), model, &ops.ops));
            }
            ops.visit.ready.set(true);
        }
    }

    /// Forms the propagators of `ops`, a kept mode set a run holds, making room for them.
    fn form_stepping(&mut self, s: &mut Store, model: &Model, ops: &Rc<ModeOps>) {
        s.make_room(
            self.sizes.stepping + self.sizes.stepping_scratch,
            self.budget,
        );
        self.peak = self
            .peak
            .max(s.bytes + self.sizes.stepping + self.sizes.stepping_scratch);
        let stepping = model.stepping(ops);
        let added = stepping.bytes();
        if ops.stepping.set(stepping).is_ok() {
            s.bytes += added;
            let kept = s
                .modes(self.id)
                .values_mut()
                .find(|e| Rc::ptr_eq(&e.ops, ops))
                .expect("a mode set a run holds stays kept");
            kept.bytes += added;
        }
        self.peak = self.peak.max(s.bytes);
    }

    /// Mode set `key` from the thread's store, formed (with its propagators when
    /// `with_stepping`) if the store does not hold it.
    fn kept(&mut self, model: &Model, key: &[Mode], with_stepping: bool) -> Rc<ModeOps> {
        SHARED.with(|s| {
            let mut s = s.borrow_mut();
            s.clock += 1;
            let now = s.clock;
            if let Some(e) = s.modes(self.id).get_mut(key) {
                e.last = now;
                let ops = Rc::clone(&e.ops);
                if with_stepping && ops.stepping.get().is_none() {
                    self.form_stepping(&mut s, model, &ops);
                }
                return ops;
            }
            let incoming = self.sizes.ops
                + if with_stepping {
                    self.sizes.stepping
                } else {
                    0
                };
            let scratch = if with_stepping {
                self.sizes.build_scratch.max(self.sizes.stepping_scratch)
            } else {
                self.sizes.build_scratch
            };
            s.make_room(incoming + scratch, self.budget);
            self.peak = self.peak.max(s.bytes + incoming + scratch);
            let ops = model.build(key);
            if with_stepping {
                let stepping = model.stepping(&ops);
                let _ = ops.stepping.set(stepping);
            }
            let ops = Rc::new(ops);
            let bytes = ops.bytes();
            s.bytes += bytes;
            s.modes(self.id).insert(
                key.to_vec(),
                Kept {
                    ops: Rc::clone(&ops),
                    bytes,
                    last: now,
                },
            );
            self.peak = self.peak.max(s.bytes);
            ops
        })
    }
}
