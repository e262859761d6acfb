//! The mode sets of a run ([`Cache`]) over those a thread keeps for the last buildings it
//! ran, and each mode set as one run sees it ([`RunOps`]: whether this run has used it long
//! enough to step with its propagators, a decision of the run's own).

use super::model::{Mode, ModeOps, Model, Stepping, frame_steps};
use super::params::MODE_CACHE;
use crate::plan::{ContactKind, ContactRole, Plan};
use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::rc::Rc;

/// A mode set as one run sees it: the shared operators, and whether this run has used it
/// long enough to step with its propagators. That decision is the run's own, so a run's
/// substeps (and hence its bits) do not depend on what ran on the thread before it.
pub(super) struct RunOps {
    pub(super) ops: Rc<ModeOps>,
    /// Grid substeps taken with the Taylor sums so far in this run.
    uses: Cell<usize>,
    ready: Cell<bool>,
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
        if self.ready.get() {
            self.ops.stepping.get()
        } else {
            None
        }
    }

    /// Counts one grid substep taken with the Taylor sums; past `prepare_after` the
    /// propagators are formed (or taken from an earlier run) and used from then on.
    #[inline]
    pub(super) fn count_use(&self, model: &Model) {
        let u = self.uses.get() + 1;
        self.uses.set(u);
        if u > self.ops.prepare_after {
            self.ops.stepping.get_or_init(|| model.stepping(&self.ops));
            self.ready.set(true);
        }
    }
}

/// Mode sets of one run, over the mode sets of its building that earlier runs on this
/// thread formed.
pub(super) struct Cache {
    modes: HashMap<Vec<Mode>, Rc<RunOps>>,
    shared: Rc<RefCell<SharedModes>>,
}

/// Mode sets of one building, kept across runs.
type SharedModes = HashMap<Vec<Mode>, Rc<ModeOps>>;

/// A building's key ([`plan_key`]) and its mode sets.
type SharedPlan = (Vec<u64>, Rc<RefCell<SharedModes>>);

thread_local! {
    /// The mode sets of the last [`SHARED_PLANS`] buildings run on this thread, each under
    /// its [`plan_key`]: a suite of records on one design forms each mode set's operators
    /// and propagators once. What a run computes from them does not depend on whether they
    /// were found here ([`RunOps`]).
    static SHARED: RefCell<Vec<SharedPlan>> =
        const { RefCell::new(Vec::new()) };
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
        k.push(ct.below.map_or(0, |j| j as u64 + 1));
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
    k.push(plan.method.dt.to_bits());
    k.push(u64::from(plan.outputs.energies));
    k.push(frame_steps(plan) as u64);
    k
}

impl Cache {
    /// The run's cache over the thread's mode sets of `plan`'s building.
    pub(super) fn new(plan: &Plan) -> Cache {
        let key = plan_key(plan);
        let shared = SHARED.with(|s| {
            let mut s = s.borrow_mut();
            let found = s.iter().position(|(k, _)| *k == key);
            let entry = match found {
                Some(i) => s.remove(i),
                None => (key, Rc::new(RefCell::new(HashMap::new()))),
            };
            let shared = Rc::clone(&entry.1);
            s.insert(0, entry);
            s.truncate(SHARED_PLANS);
            shared
        });
        Cache {
            modes: HashMap::new(),
            shared,
        }
    }

    pub(super) fn get(&mut self, model: &Model, key: &[Mode]) -> Rc<RunOps> {
        if let Some(m) = self.modes.get(key) {
            return Rc::clone(m);
        }
        if self.modes.len() >= MODE_CACHE {
            self.modes.clear();
        }
        let ops = {
            let mut shared = self.shared.borrow_mut();
            match shared.get(key) {
                Some(ops) => Rc::clone(ops),
                None => {
                    if shared.len() >= MODE_CACHE {
                        shared.clear();
                    }
                    let ops = Rc::new(model.build(key));
                    shared.insert(key.to_vec(), Rc::clone(&ops));
                    ops
                }
            }
        };
        let run = Rc::new(RunOps {
            ops,
            uses: Cell::new(0),
            ready: Cell::new(false),
        });
        self.modes.insert(key.to_vec(), Rc::clone(&run));
        run
    }
}
