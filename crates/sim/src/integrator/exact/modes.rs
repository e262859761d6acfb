//! Contacts and mode sets: the augmented state's layout, each mode set's operators
//! (mode matrix, force and slip-rate rows, event functions, spectral bound), their cache,
//! and the acceleration-level box QP that decides contacts at an event.

use super::propagate::Stepping;
use super::{MODE_CACHE, SUBSTEP_PHASE};
use crate::error::SimError;
use crate::friction::BoxQp;
use crate::friction::box_qp::Bound;
use crate::plan::{ContactKind, ContactRole, Plan};
use crate::response::Peaks;
use nalgebra::{DMatrix, DVector};
use std::cell::{Cell, OnceCell, RefCell};
use std::collections::HashMap;
use std::rc::Rc;

/// State of one contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Mode {
    Stuck,
    Upper,
    Lower,
}

/// Positions in the augmented state.
pub(super) struct Layout {
    pub(super) n: usize,
    /// State index of x′ for elastic–perfectly plastic contacts.
    pub(super) epp_slot: Vec<Option<usize>>,
    pub(super) i_ag: usize,
    pub(super) i_slope: usize,
    pub(super) i_sin: usize,
    pub(super) i_cos: usize,
    pub(super) i_one: usize,
    pub(super) dim: usize,
}

#[derive(Clone, Copy, PartialEq)]
pub(super) enum Scale {
    Force(f64),
    Velocity,
}

/// g(y) = row·y ≥ 0 while the mode is consistent.
pub(super) struct EventFn {
    pub(super) contact: usize,
    pub(super) row: DVector<f64>,
    pub(super) scale: Scale,
}

/// A square matrix by rows, nonzeros only (compressed sparse rows).
pub(super) struct SparseRows {
    /// Row i's entries are `start[i]..start[i + 1]` of `col` and `val`.
    start: Vec<usize>,
    col: Vec<usize>,
    val: Vec<f64>,
}

impl SparseRows {
    /// Stored entries.
    pub(super) fn nnz(&self) -> usize {
        self.val.len()
    }

    pub(super) fn of(m: &DMatrix<f64>) -> SparseRows {
        let mut start = vec![0];
        let (mut col, mut val) = (Vec::new(), Vec::new());
        for i in 0..m.nrows() {
            for j in 0..m.ncols() {
                if m[(i, j)] != 0.0 {
                    col.push(j);
                    val.push(m[(i, j)]);
                }
            }
            start.push(col.len());
        }
        SparseRows { start, col, val }
    }

    /// out = scale · (M x), each row summed in column order.
    #[inline]
    pub(super) fn mul_into(&self, scale: f64, x: &[f64], out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            let (a, b) = (self.start[i], self.start[i + 1]);
            let mut s = 0.0;
            for (j, v) in self.col[a..b].iter().zip(&self.val[a..b]) {
                s += v * x[*j];
            }
            *o = scale * s;
        }
    }

    /// out = scale · (rᵀ M) (a row vector times the matrix), as a column.
    pub(super) fn row_mul_into(&self, scale: f64, r: &[f64], out: &mut [f64]) {
        out.fill(0.0);
        for (i, ri) in r.iter().enumerate() {
            if *ri == 0.0 {
                continue;
            }
            for k in self.start[i]..self.start[i + 1] {
                out[self.col[k]] += ri * self.val[k];
            }
        }
        for o in out.iter_mut() {
            *o *= scale;
        }
    }
}

/// Everything fixed for one mode set.
pub(super) struct ModeOps {
    pub(super) a: DMatrix<f64>,
    /// `a` by rows, its nonzeros only ([`SparseRows`]): the velocity rows are one entry,
    /// the generators' one or none, the elements' few; only the acceleration rows are
    /// full. Products with it cost n·dim instead of dim².
    pub(super) a_rows: SparseRows,
    /// The acceleration rows n..2n of `a`, stored transposed (dim × n: column i is the
    /// acceleration of DOF i as a row on y), for the peaks at every output step.
    pub(super) acc_rows: DMatrix<f64>,
    /// Friction force of each contact as a row on y, stored transposed (dim × contacts:
    /// column c is contact c's row, contiguous for [`row_dot`]).
    pub(super) force: DMatrix<f64>,
    /// Slip rate of each contact as a row on y, transposed likewise.
    pub(super) slip_rate: DMatrix<f64>,
    /// ẋ′ rows of elastic–perfectly plastic contacts (zero rows for others), transposed
    /// likewise.
    pub(super) xdot: DMatrix<f64>,
    pub(super) events: Vec<EventFn>,
    /// |row| of each event function, componentwise: with the far Taylor terms' sizes it
    /// bounds the part of g past its leading coefficients on a summed substep.
    pub(super) event_abs: Vec<DVector<f64>>,
    /// The M-orthogonal projector of the velocities onto B_Sᵀv = 0 for the stuck contacts
    /// with a DOF, I − M⁻¹B_S W_S⁻¹B_Sᵀ (n × n); `None` when none sticks.
    pub(super) proj: Option<DMatrix<f64>>,
    /// The sampled peaks' quantities as rows on y, transposed (dim × functions), in the
    /// order of [`observed_peak`]: storey drifts, floor displacements, absolute floor
    /// accelerations, base shear, then each contact's slip. Formed only when a grid
    /// substep holds several output steps and testing them costs less than observing
    /// those (dim × 0 otherwise: every output step is observed).
    pub(super) obs_rows: DMatrix<f64>,
    /// Longest substep, [`SUBSTEP_PHASE`]/ρ (ρ this mode set's spectral bound).
    pub(super) delta_max: f64,
    /// Substeps per frame of q output steps ([`frame_steps`]), m, and the grid interval
    /// h = qΔt/m: m = q⌈Δt/δ_max⌉ where an output step is longer than δ_max, else
    /// q/s with s the largest divisor of q such that sΔt ≤ δ_max. Output steps are
    /// grid points either way.
    pub(super) per_step: usize,
    /// Output steps per grid substep, s (0 when a substep is shorter than an output step).
    pub(super) out_steps: usize,
    pub(super) h: f64,
    /// How many grid substeps taken with the Taylor sums make the mode set worth its
    /// propagators in a run (forming them costs about dim + scanned functions substeps).
    pub(super) prepare_after: usize,
    /// The grid propagators ([`Model::stepping`]), formed the first time a run's use of
    /// the mode set reaches `prepare_after` (and kept for later runs of the same
    /// building, [`Cache`]).
    pub(super) stepping: OnceCell<Stepping>,
}

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

/// Run-wide model data.
pub(super) struct Model<'a> {
    pub(super) plan: &'a Plan,
    pub(super) lay: Layout,
    pub(super) minv: DMatrix<f64>,
    /// L⁻¹ of the mass matrix's Cholesky factor M = LLᵀ.
    pub(super) linv: DMatrix<f64>,
    pub(super) mr: DVector<f64>,
    /// Contact columns of B.
    pub(super) bcols: Vec<DVector<f64>>,
    /// Forces without contacts as rows on y (n × dim).
    pub(super) f0: DMatrix<f64>,
    pub(super) omega_h: f64,
    /// Whether a storey yields (the plastic work is then kept apart from friction).
    pub(super) storeys: bool,
    /// Output steps per frame, q ([`frame_steps`]): a frame of qΔt is the interval a mode
    /// set's grid divides.
    pub(super) frame_steps: usize,
}

/// Output steps per frame: the record's sample interval in output steps when the run asks
/// for peaks only (no histories, no energies) and Δt divides that interval, else 1. A
/// frame is one record interval, the span a mode set's grid divides; the output steps
/// inside it are observed only where a peak can change there (the observed functions'
/// bounds, [`ModeOps::obs_rows`]), so a fine output step costs no substeps of its own.
/// Histories and energies need the state at every output step: their frames are the
/// output steps.
pub(super) fn frame_steps(plan: &Plan) -> usize {
    let Some(r) = plan.record.as_ref() else {
        return 1;
    };
    if plan.outputs.histories || plan.outputs.energies {
        return 1;
    }
    let (rdt, dt) = (r.dt(), plan.method.dt);
    let q = (rdt / dt).round();
    if (2.0..=1e6).contains(&q) && (q * dt - rdt).abs() <= 1e-9 * rdt {
        q as usize
    } else {
        1
    }
}

impl<'a> Model<'a> {
    pub(super) fn new(plan: &'a Plan) -> Result<Model<'a>, SimError> {
        let n = plan.dofs();
        let mut epp_slot = vec![None; plan.contacts.len()];
        let mut next = 2 * n;
        for (c, ct) in plan.contacts.iter().enumerate() {
            match ct.kind {
                ContactKind::Epp => {
                    epp_slot[c] = Some(next);
                    next += 1;
                }
                // zero-mass DOFs are refused by Plan::check_method before a run
                ContactKind::Dof { .. } => {}
            }
        }
        let lay = Layout {
            n,
            epp_slot,
            i_ag: next,
            i_slope: next + 1,
            i_sin: next + 2,
            i_cos: next + 3,
            i_one: next + 4,
            dim: next + 5,
        };
        let chol = plan
            .mass
            .clone()
            .cholesky()
            .ok_or_else(|| SimError::NotPositiveDefinite {
                what: "mass matrix".into(),
                hint: " (exact needs every DOF to carry mass)".into(),
            })?;
        let minv = chol.inverse();
        let linv = chol
            .l()
            .try_inverse()
            .expect("the Cholesky factor of an SPD matrix is invertible");
        let mr = plan.mass_influence();
        let bm = plan.contact_matrix();
        let bcols = (0..plan.contacts.len())
            .map(|c| bm.column(c).into_owned())
            .collect();
        let dim = lay.dim;
        let mut f0 = DMatrix::zeros(n, dim);
        f0.view_mut((0, 0), (n, n)).copy_from(&(-&plan.stiffness));
        f0.view_mut((0, n), (n, n)).copy_from(&(-&plan.damping));
        for i in 0..n {
            f0[(i, lay.i_ag)] = -mr[i];
        }
        let mut omega_h = 0.0;
        if let Some(h) = &plan.harmonic {
            f0[(h.floor, lay.i_sin)] = h.amplitude;
            omega_h = h.omega;
        }
        Ok(Model {
            plan,
            lay,
            minv,
            linv,
            mr,
            bcols,
            f0,
            omega_h,
            storeys: plan.has_yielding_storeys(),
            frame_steps: frame_steps(plan),
        })
    }

    /// Bound ρ on |λ(A)| for every mode set: ν_max + ω_max over all-stuck elastic
    /// braces (constraints only lower both), k′/c′ of sliding damped massless
    /// dissipators, and the harmonic frequency. Used for the run's substep budget.
    pub(super) fn spectral_bound(&self) -> f64 {
        self.bound(None)
    }

    /// Bound ρ on |λ(A)| of one mode set. A nonzero eigenvalue λ of the mode matrix has
    /// an eigenvector u in null(B_Sᵀ) (the stuck dissipators with mass move with their
    /// floors) with λ²uᴴMu + λuᴴC_mu + uᴴK_mu = 0, so |λ| ≤ ν + ω with ν, ω² the largest
    /// Rayleigh quotients of C_m and K_m over M on that subspace (M-orthogonal projection
    /// keeps the quotients of the unconstrained matrices there). K_m, C_m carry the braces
    /// of stuck massless dissipators; a sliding damped one adds its rate k′/c′. `None`:
    /// the bound over every mode set (no constraints, every brace, every rate).
    pub(super) fn bound(&self, modes: Option<&[Mode]>) -> f64 {
        let plan = self.plan;
        let mut k = plan.stiffness.clone();
        let mut c = plan.damping.clone();
        let mut maxwell: f64 = 0.0;
        let mut stuck_cols = Vec::new();
        for (i, ct) in plan.contacts.iter().enumerate() {
            let mode = modes.map(|m| m[i]);
            match ct.kind {
                ContactKind::Epp => {
                    if matches!(mode, None | Some(Mode::Stuck)) {
                        add_link(&mut k, ct.floor, ct.below, ct.brace_stiffness);
                        add_link(&mut c, ct.floor, ct.below, ct.brace_damping);
                    }
                    if !matches!(mode, Some(Mode::Stuck)) && ct.brace_damping > 0.0 {
                        maxwell = maxwell.max(ct.brace_stiffness / ct.brace_damping);
                    }
                }
                ContactKind::Dof { .. } => {
                    // A contact with F⁻ = F⁺ never sticks (its force is fixed).
                    if mode == Some(Mode::Stuck) && ct.lower != ct.upper {
                        stuck_cols.push(&self.linv * &self.bcols[i]);
                    }
                }
            }
        }
        let n = self.lay.n;
        // Orthogonal projector onto the complement of L⁻¹B_S (y = Lᵀu coordinates).
        let proj = if stuck_cols.is_empty() {
            None
        } else {
            let d = DMatrix::from_columns(&stuck_cols);
            let dtd = d.transpose() * &d;
            dtd.cholesky()
                .map(|ch| DMatrix::identity(n, n) - &d * ch.solve(&d.transpose()))
        };
        let top = |m: &DMatrix<f64>| -> f64 {
            let mut s = &self.linv * m * self.linv.transpose();
            if let Some(p) = &proj {
                s = p * s * p;
            }
            let s = (&s + s.transpose()) * 0.5;
            s.symmetric_eigenvalues()
                .iter()
                .fold(0.0f64, |a, &x| a.max(x.abs()))
        };
        top(&k).sqrt() + top(&c) + maxwell + self.omega_h
    }

    pub(super) fn build(&self, modes: &[Mode]) -> ModeOps {
        let plan = self.plan;
        let lay = &self.lay;
        let (n, dim) = (lay.n, lay.dim);
        let nc = plan.contacts.len();
        let mut f = self.f0.clone();
        let mut force = DMatrix::zeros(nc, dim);
        let mut xdot = DMatrix::zeros(nc, dim);
        let mut stuck = Vec::new();
        for (c, ct) in plan.contacts.iter().enumerate() {
            match (modes[c], ct.kind) {
                (Mode::Upper, _) => force[(c, lay.i_one)] = ct.upper,
                (Mode::Lower, _) => force[(c, lay.i_one)] = ct.lower,
                (Mode::Stuck, ContactKind::Dof { .. }) => stuck.push(c),
                (Mode::Stuck, ContactKind::Epp) => {
                    let s = lay.epp_slot[c].expect("EPP contacts have a slot");
                    force[(c, s)] += ct.brace_stiffness;
                    force[(c, n + ct.floor)] += ct.brace_damping;
                    if let Some(j) = ct.below {
                        force[(c, j)] -= ct.brace_stiffness;
                        force[(c, n + j)] -= ct.brace_damping;
                    }
                }
            }
            if let Some(s) = lay.epp_slot[c] {
                match modes[c] {
                    Mode::Stuck => xdot[(c, n + ct.floor)] = 1.0,
                    Mode::Upper | Mode::Lower => {
                        if let Some(j) = ct.below {
                            xdot[(c, n + j)] = 1.0;
                        }
                        if ct.brace_damping > 0.0 {
                            let bound = force[(c, lay.i_one)];
                            let r = 1.0 / ct.brace_damping;
                            xdot[(c, lay.i_one)] += bound * r;
                            xdot[(c, s)] -= ct.brace_stiffness * r;
                            if let Some(j) = ct.below {
                                xdot[(c, j)] += ct.brace_stiffness * r;
                            }
                        }
                    }
                }
            }
            if !(modes[c] == Mode::Stuck && matches!(ct.kind, ContactKind::Dof { .. })) {
                // f −= b_c ⊗ force_c
                let row = force.row(c).into_owned();
                for i in 0..n {
                    let b = self.bcols[c][i];
                    if b != 0.0 {
                        for j in 0..dim {
                            f[(i, j)] -= b * row[j];
                        }
                    }
                }
            }
        }
        let minv_f = &self.minv * &f;
        let (acc, proj) = if stuck.is_empty() {
            (minv_f, None)
        } else {
            let s = stuck.len();
            let mut bs = DMatrix::zeros(n, s);
            for (k, &c) in stuck.iter().enumerate() {
                bs.set_column(k, &self.bcols[c]);
            }
            let y = &self.minv * &bs;
            let ws = bs.transpose() * &y;
            let ws = (&ws + ws.transpose()) * 0.5;
            let wsinv = ws
                .cholesky()
                .expect("B_SᵀM⁻¹B_S is SPD: contact columns are independent")
                .inverse();
            let lam = &wsinv * (bs.transpose() * &minv_f);
            for (k, &c) in stuck.iter().enumerate() {
                force.set_row(c, &lam.row(k));
            }
            let proj = DMatrix::identity(n, n) - &y * &wsinv * bs.transpose();
            (minv_f - &y * &lam, Some(proj))
        };
        let mut a = DMatrix::zeros(dim, dim);
        for i in 0..n {
            a[(i, n + i)] = 1.0;
        }
        a.view_mut((n, 0), (n, dim)).copy_from(&acc);
        let mut slip_rate = DMatrix::zeros(nc, dim);
        for (c, ct) in plan.contacts.iter().enumerate() {
            slip_rate[(c, n + ct.floor)] = 1.0;
            match (ct.kind, lay.epp_slot[c]) {
                (ContactKind::Dof { dof }, _) => slip_rate[(c, n + dof)] -= 1.0,
                (ContactKind::Epp, Some(s)) => {
                    a.set_row(s, &xdot.row(c));
                    let r = slip_rate.row(c) - xdot.row(c);
                    slip_rate.set_row(c, &r);
                }
                (ContactKind::Epp, None) => unreachable!("EPP contacts have a slot"),
            }
        }
        a[(lay.i_ag, lay.i_slope)] = 1.0;
        a[(lay.i_sin, lay.i_cos)] = self.omega_h;
        a[(lay.i_cos, lay.i_sin)] = -self.omega_h;
        let mut events = Vec::new();
        for (c, ct) in plan.contacts.iter().enumerate() {
            if ct.lower == ct.upper {
                // Zero-width bounds (μN = 0 kept in an unreduced plan): the force is that
                // value whatever the contact does; no events.
                continue;
            }
            let bound_scale = Scale::Force(
                [ct.upper, ct.lower]
                    .iter()
                    .filter(|b| b.is_finite())
                    .fold(0.0f64, |m, b| m.max(b.abs())),
            );
            match modes[c] {
                Mode::Stuck => {
                    if ct.upper.is_finite() {
                        let mut row = -force.row(c).transpose();
                        row[lay.i_one] += ct.upper;
                        events.push(EventFn {
                            contact: c,
                            row,
                            scale: bound_scale,
                        });
                    }
                    if ct.lower.is_finite() {
                        let mut row = force.row(c).transpose();
                        row[lay.i_one] -= ct.lower;
                        events.push(EventFn {
                            contact: c,
                            row,
                            scale: bound_scale,
                        });
                    }
                }
                Mode::Upper => events.push(EventFn {
                    contact: c,
                    row: slip_rate.row(c).transpose(),
                    scale: Scale::Velocity,
                }),
                Mode::Lower => events.push(EventFn {
                    contact: c,
                    row: -slip_rate.row(c).transpose(),
                    scale: Scale::Velocity,
                }),
            }
        }
        let dt = plan.method.dt;
        let rho = self.bound(Some(modes));
        let delta_max = if rho > 0.0 {
            SUBSTEP_PHASE / rho
        } else {
            f64::INFINITY
        };
        // Substeps per output step; where one output step is shorter than δ_max, the
        // frame of q output steps is cut into substeps of s output steps each, s the
        // largest divisor of q with s·Δt ≤ δ_max, so output steps are grid points.
        let per_out = if delta_max.is_finite() {
            ((dt / delta_max) * (1.0 - 1e-12)).ceil().max(1.0) as usize
        } else {
            1
        };
        let q = self.frame_steps;
        let (per_step, out_steps) = if per_out > 1 || q == 1 {
            (q * per_out, usize::from(per_out == 1))
        } else {
            let s = (1..=q)
                .rev()
                .find(|&s| q.is_multiple_of(s) && s as f64 * dt <= delta_max * (1.0 - 1e-12))
                .unwrap_or(1);
            (q / s, s)
        };
        let prepare_after = dim + events.len() + plan.floors;
        let acc_rows = a.rows(n, n).transpose();
        // The observed functions' bounds are worth testing on a substep when they cost
        // less than the output steps inside it they can spare (a product with exp(A Δt)
        // and the observation, each).
        let obs_rows = if out_steps >= 2
            && 2 * (3 * plan.floors + 1 + nc) * dim < (out_steps - 1) * (dim + n) * dim
        {
            self.observed_rows(&acc_rows)
        } else {
            DMatrix::zeros(dim, 0)
        };
        let a_rows = SparseRows::of(&a);
        let event_abs = events.iter().map(|e| e.row.abs()).collect();
        ModeOps {
            event_abs,
            obs_rows,
            a_rows,
            a,
            acc_rows,
            force: force.transpose(),
            slip_rate: slip_rate.transpose(),
            xdot: xdot.transpose(),
            events,
            proj,
            delta_max,
            per_step,
            out_steps,
            h: (q as f64 * dt) / per_step as f64,
            prepare_after,
            stepping: OnceCell::new(),
        }
    }
}

pub(super) fn add_link(m: &mut DMatrix<f64>, i: usize, j: Option<usize>, k: f64) {
    m[(i, i)] += k;
    if let Some(j) = j {
        m[(j, j)] += k;
        m[(i, j)] -= k;
        m[(j, i)] -= k;
    }
}

/// Contact `r`'s row on y, stored as column `r` of `m` (a [`ModeOps`] row set), times `y`,
/// summed in order without allocating.
#[inline]
pub(super) fn row_dot(m: &DMatrix<f64>, r: usize, y: &DVector<f64>) -> f64 {
    let mut s = 0.0;
    let rows = m.nrows();
    for (mj, yj) in m.as_slice()[r * rows..(r + 1) * rows]
        .iter()
        .zip(y.as_slice())
    {
        s += mj * yj;
    }
    s
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

/// The current sampled peak of observed function `o` (the order of
/// [`ModeOps::obs_rows`]).
#[inline]
pub(super) fn observed_peak(plan: &Plan, peaks: &Peaks, o: usize) -> f64 {
    let nf = plan.floors;
    match o {
        _ if o < nf => peaks.drift[o],
        _ if o < 2 * nf => peaks.displacement[o - nf],
        _ if o < 3 * nf => peaks.abs_acceleration[o - 2 * nf],
        _ if o == 3 * nf => peaks.base_shear,
        _ => {
            let ct = &plan.contacts[o - 3 * nf - 1];
            match ct.role {
                ContactRole::Damper => peaks.slip[ct.floor],
                ContactRole::Storey => peaks.slip[nf + ct.floor],
            }
        }
    }
}

impl Model<'_> {
    /// The rows of [`ModeOps::obs_rows`] from the mode set's acceleration rows
    /// (`acc_rows`, dim × n): the same quantities the output steps observe.
    fn observed_rows(&self, acc_rows: &DMatrix<f64>) -> DMatrix<f64> {
        let plan = self.plan;
        let lay = &self.lay;
        let (n, nf, dim) = (lay.n, plan.floors, lay.dim);
        let mut rows = DMatrix::zeros(dim, 3 * nf + 1 + plan.contacts.len());
        for i in 0..nf {
            rows[(i, i)] = 1.0;
            if i > 0 {
                rows[(i - 1, i)] = -1.0;
            }
            rows[(i, nf + i)] = 1.0;
            let mut a = acc_rows.column(i).into_owned();
            a[lay.i_ag] += 1.0;
            rows.set_column(2 * nf + i, &a);
        }
        // Base shear Σ mᵢ(aᵢ + a_g) − p over every DOF (as `base_shear`).
        let mut v = DVector::zeros(dim);
        for i in 0..n {
            v.axpy(self.mr[i], &acc_rows.column(i), 1.0);
        }
        v[lay.i_ag] += self.mr.iter().sum::<f64>();
        if let Some(h) = &plan.harmonic {
            v[lay.i_sin] -= h.amplitude;
        }
        rows.set_column(3 * nf, &v);
        for (c, ct) in plan.contacts.iter().enumerate() {
            let col = 3 * nf + 1 + c;
            rows[(ct.floor, col)] = 1.0;
            match (ct.kind, lay.epp_slot[c]) {
                (ContactKind::Dof { dof }, _) => rows[(dof, col)] -= 1.0,
                (_, Some(s)) => rows[(s, col)] -= 1.0,
                (ContactKind::Epp, None) => {}
            }
        }
        rows
    }

    /// Modes decided by the acceleration-level box QP for the contacts in `decide`
    /// (all other contacts keep `modes`).
    pub(super) fn decide(
        &self,
        cache: &mut Cache,
        y: &DVector<f64>,
        modes: &mut [Mode],
        decide: &[usize],
        t: f64,
    ) -> Result<(), SimError> {
        if decide.is_empty() {
            return Ok(());
        }
        let plan = self.plan;
        let lay = &self.lay;
        let n = lay.n;
        // Forces of all non-decided contacts from the current modes.
        let mut tmp: Vec<Mode> = modes.to_vec();
        for &c in decide {
            tmp[c] = Mode::Upper; // placeholder: its force is excluded below
        }
        let ops = cache.get(self, &tmp);
        let mut g = &self.f0 * y;
        for (c, _) in plan.contacts.iter().enumerate() {
            if decide.contains(&c) {
                continue;
            }
            let fc = row_dot(&ops.force, c, y);
            g.axpy(-fc, &self.bcols[c], 1.0);
        }
        let m = decide.len();
        let mut bu = DMatrix::zeros(n, m);
        for (k, &c) in decide.iter().enumerate() {
            bu.set_column(k, &self.bcols[c]);
        }
        let wa = bu.transpose() * &self.minv * &bu;
        let wa = (&wa + wa.transpose()) * 0.5;
        let b = bu.transpose() * (&self.minv * g);
        let lo: Vec<f64> = decide.iter().map(|&c| plan.contacts[c].lower).collect();
        let hi: Vec<f64> = decide.iter().map(|&c| plan.contacts[c].upper).collect();
        let mut f = vec![0.0; m];
        let mut qp =
            BoxQp::new(wa.as_slice(), m).map_err(|source| SimError::Friction { t, source })?;
        qp.solve(b.as_slice(), &lo, &hi, &mut f)
            .map_err(|source| SimError::Friction { t, source })?;
        for (k, &c) in decide.iter().enumerate() {
            modes[c] = match qp.status(k) {
                Bound::Free => Mode::Stuck,
                Bound::Upper => Mode::Upper,
                Bound::Lower => Mode::Lower,
            };
        }
        Ok(())
    }
}
