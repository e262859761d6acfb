//! The [`Exact`] integrator's run: the inputs of each record piece, the frames and their
//! substeps (grid or summed), the event and extremum scans, the events, the peaks at the
//! output steps, and the energies and histories (the method is in the module docs).

use super::cache::Cache;
use super::energy::Integrals;
use super::gauss::GAUSS;
use super::kernels::{col, dot, mat_vec, quadratic, row_dot};
use super::memory::{MemoryBudget, check_memory};
use super::model::{Mode, ModeOps, Model, Scale};
use super::modes::observed_peak;
use super::params::{
    GRAZE_REL, LEAD_TERMS, MAX_EVENTS, MAX_SUBSTEPS, SCAN_POINTS, SUBSTEP_PHASE, TAYLOR_TERMS,
};
use super::propagate::{lead_coefs, lead_terms, monotone, taylor};
use super::search::{first_crossing, illinois, poly, tail_and_degree};
use crate::error::SimError;
use crate::integrator::method::Integrator;
use crate::integrator::state::{
    EnergyRow, base_shear, history_columns, push_energies, signed_base_shear,
};
use crate::plan::{ContactKind, ContactRole, Plan};
use crate::response::{Diagnostics, Energy, History, Outcome, Peaks};
use crate::units::is_positive;
use nalgebra::DVector;
use slipload_motion::Record;
use std::cell::RefCell;
use std::sync::Arc;

/// Event-driven integrator, exact between events.
#[derive(Debug, Clone, Copy, Default)]
pub struct Exact;

/// Adds the history row of state `y` at time `t`.
fn history_row(
    model: &Model,
    ops: &ModeOps,
    h: &mut History,
    t: f64,
    y: &DVector<f64>,
    e: Option<EnergyRow>,
) {
    let plan = model.plan;
    let lay = &model.lay;
    h.rows.push(t);
    h.rows.push(y[lay.i_ag]);
    h.rows
        .extend(plan.points.iter().map(|(p, _)| p.at(y.as_slice())));
    for (c, ct) in plan.contacts.iter().enumerate() {
        h.rows.push(match (ct.kind, lay.epp_slot[c]) {
            (ContactKind::Dof { dof }, _) => y[dof],
            (_, Some(s)) => y[s],
            (ContactKind::Epp, None) => 0.0,
        });
    }
    for (top, bottom) in &plan.drifts {
        h.rows.push(top.at(y.as_slice()) - bottom.at(y.as_slice()));
    }
    for c in 0..plan.contacts.len() {
        h.rows.push(row_dot(&ops.force, c, y));
    }
    for c in 0..plan.contacts.len() {
        h.rows.push(row_dot(&ops.slip_rate, c, y));
    }
    if let Some(e) = e {
        push_energies(plan, h, &e);
    }
}

/// Ground acceleration at the start of [ta, tb] and its slope on it (0 after the record).
fn ground_segment(record: Option<&Arc<Record>>, ta: f64, tb: f64) -> (f64, f64) {
    match record {
        Some(r) => {
            let dur = r.duration();
            if ta >= dur - 1e-12 * r.dt() {
                return (0.0, 0.0);
            }
            let a0 = r.accel_at(ta);
            let a1 = r.accel_at(tb.min(dur));
            (a0, (a1 - a0) / (tb - ta))
        }
        None => (0.0, 0.0),
    }
}

/// End of the piece starting at `ta` (next record sample or record end, else `t_end`).
fn piece_end(plan: &Plan, ta: f64, t_end: f64) -> f64 {
    let first = piece_end_of(plan.record.as_ref(), ta, t_end);
    match &plan.second {
        Some(g) => first.min(piece_end_of(Some(&g.record), ta, t_end)),
        None => first,
    }
}

/// [`piece_end`] for one record.
fn piece_end_of(record: Option<&Arc<Record>>, ta: f64, t_end: f64) -> f64 {
    match record {
        Some(r) => {
            let rdt = r.dt();
            let dur = r.duration();
            if ta >= dur - 1e-12 * rdt {
                return t_end;
            }
            let mut k = (ta / rdt).floor() + 1.0;
            if k * rdt - ta <= 1e-9 * rdt {
                k += 1.0;
            }
            let ts = (k * rdt).min(dur);
            if ts < t_end - 1e-9 * rdt { ts } else { t_end }
        }
        None => t_end,
    }
}

/// Refuses a run that would need more than `MAX_SUBSTEPS` substeps of at most a phase of
/// `SUBSTEP_PHASE` of the fastest mode.
fn substep_budget(model: &Model, plan: &Plan) -> Result<(), SimError> {
    let rho = model.spectral_bound();
    let delta_max = if rho > 0.0 {
        SUBSTEP_PHASE / rho
    } else {
        f64::INFINITY
    };
    let duration = plan.steps as f64 * plan.method.dt;
    let needed = (duration / delta_max).ceil();
    if needed > MAX_SUBSTEPS as f64 {
        return Err(SimError::ExactBudget {
            what: "substeps".into(),
            t: 0.0,
            needed: needed as u64,
            limit: MAX_SUBSTEPS,
            hint: format!(
                "the fastest mode rings at {rho:.3e} rad/s (very light or very stiff dissipators); use newmark, or the massless limit (mass 0)"
            ),
        });
    }
    Ok(())
}

/// What [`Exact`] refuses before its first step beyond [`Plan::check_method`], without
/// stepping: a working set its memory budget ([`MemoryBudget::for_plan`]) cannot hold, a
/// model it cannot build, and a substep budget it would exceed.
pub(crate) fn check(plan: &Plan) -> Result<(), SimError> {
    check_memory(plan, MemoryBudget::for_plan(plan))?;
    let model = Model::new(plan)?;
    substep_budget(&model, plan)
}

impl Integrator for Exact {
    fn name(&self) -> &'static str {
        "exact"
    }

    /// Runs `plan` within its default memory budget ([`MemoryBudget::for_plan`]).
    fn run(&self, plan: &Plan) -> Result<Outcome, SimError> {
        self.run_within(plan, MemoryBudget::for_plan(plan))
    }
}

impl Exact {
    /// Runs `plan` keeping at most `budget` bytes of mode-set matrices on this thread
    /// ([`MemoryBudget`]); refused before the first step with
    /// [`SimError::ExactMemory`] when a run's working set does not fit it. The answer does
    /// not depend on the budget, to the last bit: only the time does.
    #[allow(clippy::too_many_lines)]
    pub fn run_within(&self, plan: &Plan, budget: MemoryBudget) -> Result<Outcome, SimError> {
        let dt = plan.method.dt;
        if !is_positive(dt) {
            return Err(SimError::BadTimeStep { dt });
        }
        plan.check_method()?;
        // from the plan's sizes alone, before anything is formed
        check_memory(plan, budget)?;
        let model = Model::new(plan)?;
        let lay = &model.lay;
        let (n, dim) = (lay.n, lay.dim);
        let nf = plan.drifts.len();
        let obs_contacts = plan.observed_contacts_offset();
        let nc = plan.contacts.len();
        substep_budget(&model, plan)?;
        let duration = plan.steps as f64 * dt;
        let energies = plan.outputs.energies;

        // Initial state.
        let mut y = DVector::zeros(dim);
        y.rows_mut(0, n).copy_from_slice(&plan.u0);
        y.rows_mut(n, n).copy_from_slice(&plan.v0);
        y[lay.i_one] = 1.0;
        for (c, s) in lay.epp_slot.iter().enumerate() {
            if let Some(s) = s {
                y[*s] = plan.contact_x0[c].0;
            }
        }
        let set_inputs = |y: &mut DVector<f64>, ta: f64, tb: f64| {
            let (a0, slope) = ground_segment(plan.record.as_ref(), ta, tb);
            y[lay.i_ag] = a0;
            y[lay.i_slope] = slope;
            if let (Some((i_ag2, i_slope2)), Some(g)) = (lay.second, &plan.second) {
                let (a0, slope) = ground_segment(Some(&g.record), ta, tb);
                y[i_ag2] = a0;
                y[i_slope2] = slope;
            }
            if let Some(h) = &plan.harmonic {
                let ph = h.omega * ta + h.phase;
                y[lay.i_sin] = ph.sin();
                y[lay.i_cos] = ph.cos();
            }
        };
        let first_end = piece_end(plan, 0.0, dt.min(duration.max(dt)));
        set_inputs(&mut y, 0.0, first_end);
        let mut v_ref = plan.v0[..n].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut modes = vec![Mode::Stuck; nc];
        let mut to_decide = Vec::new();
        for (c, ct) in plan.contacts.iter().enumerate() {
            match ct.kind {
                ContactKind::Epp => {
                    let s = lay.epp_slot[c].expect("EPP contacts have a slot");
                    let (uj, vj) = (
                        ct.bottom.at(y.as_slice()),
                        ct.bottom.at_offset(y.as_slice(), n),
                    );
                    let vd = plan.contact_x0[c].1;
                    let force = ct.brace_stiffness * (y[s] - uj) + ct.brace_damping * (vd - vj);
                    let tol = 1e-12
                        * (ct.upper.abs().min(1e300) + ct.lower.abs().min(1e300) + force.abs());
                    if force > ct.upper + tol || force < ct.lower - tol {
                        return Err(SimError::Scene(format!(
                            "initial state: the massless dissipator of floor {} carries a brace force of {force:.6e} N, outside its friction bounds [{:.6e}, {:.6e}] N",
                            ct.floor + 1,
                            ct.lower,
                            ct.upper
                        )));
                    }
                    let w = ct.top.at_offset(y.as_slice(), n) - vd;
                    modes[c] = if force >= ct.upper - tol && w > 0.0 {
                        Mode::Upper
                    } else if force <= ct.lower + tol && w < 0.0 {
                        Mode::Lower
                    } else {
                        Mode::Stuck
                    };
                }
                ContactKind::Dof { .. } if ct.lower == ct.upper => modes[c] = Mode::Upper,
                ContactKind::Dof { dof } => {
                    let vf = ct.top.at_offset(y.as_slice(), n);
                    let w0 = vf - y[n + dof];
                    let tol = 1e-12 * (vf.abs() + y[n + dof].abs());
                    if w0.abs() > tol {
                        let bound = if w0 > 0.0 { ct.upper } else { ct.lower };
                        if !bound.is_finite() {
                            return Err(SimError::Scene(format!(
                                "initial state: the locked dissipator of floor {} cannot slip, but its initial slip rate is {w0:.6e} m/s",
                                ct.floor + 1
                            )));
                        }
                        modes[c] = if w0 > 0.0 { Mode::Upper } else { Mode::Lower };
                    } else {
                        to_decide.push(c);
                    }
                }
            }
        }
        let mut cache = Cache::new(plan, budget);
        model.decide(&mut cache, &y, &mut modes, &to_decide, 0.0)?;
        let mut ops = cache.get(&model, &modes);
        let mut integ = Integrals::default();
        let (k0, s0) = model.stored(&y);
        let initial_energy = k0 + s0;
        // ∫ E_strain dt by the trapezoid rule at the output steps (as the step methods do).
        let mut strain_area = 0.0;
        let mut strain_prev = s0;
        // Project the initial velocities onto the stuck constraints (a no-op for
        // consistent initial states).
        let scratch = RefCell::new(DVector::zeros(n));
        let project = |y: &mut DVector<f64>, ops: &ModeOps| {
            if let Some(p) = &ops.proj {
                let mut v = scratch.borrow_mut();
                v.gemv(1.0, p, &y.rows(n, n), 0.0);
                y.rows_mut(n, n).copy_from(&*v);
            }
        };
        project(&mut y, &ops);
        // The same during the run, the kinetic energy it removes booked as friction work
        // (when energies are asked for).
        let project_counted = |y: &mut DVector<f64>, ops: &ModeOps, integ: &mut Integrals| {
            if energies {
                let (ke_before, _) = model.stored(y);
                project(y, ops);
                let (ke_after, _) = model.stored(y);
                integ.friction += ke_before - ke_after;
            } else {
                project(y, ops);
            }
        };

        // The run's arithmetic in multiply-adds of its dominant operations
        // (`Diagnostics::work`).
        let work = std::cell::Cell::new(0u64);
        let add = |w: usize| work.set(work.get() + w as u64);
        let mut peaks = Peaks::for_plan(plan);
        let mut cont_drift = vec![0.0; nf];
        let drift = |i: usize, y: &DVector<f64>| {
            let (top, bottom) = &plan.drifts[i];
            top.at(y.as_slice()) - bottom.at(y.as_slice())
        };
        let msum: f64 = plan.influence_mass();
        let cross = plan.cross_mass();
        let mut acc = DVector::zeros(dim);
        let observe =
            |peaks: &mut Peaks, ops: &ModeOps, y: &DVector<f64>, acc: &mut DVector<f64>, t: f64| {
                // Only the accelerations (rows n..2n of A y) are observed.
                add(n * dim + 4 * nf);
                for (i, ai) in acc.as_mut_slice()[n..2 * n].iter_mut().enumerate() {
                    *ai = dot(col(&ops.acc_rows, i), y.as_slice());
                }
                let ag = y[lay.i_ag];
                let p = plan
                    .harmonic
                    .as_ref()
                    .map_or(0.0, |h| h.amplitude * y[lay.i_sin]);
                match lay.second {
                    None => {
                        peaks.observe_floors(y.as_slice(), &acc.as_slice()[n..2 * n], ag);
                        peaks.observe_base_shear(base_shear(
                            model.mr.as_slice(),
                            msum,
                            &acc.as_slice()[n..2 * n],
                            ag,
                            p,
                        ));
                    }
                    Some((i_ag2, _)) => {
                        let ag2 = y[i_ag2];
                        peaks.observe_floors2(y.as_slice(), &acc.as_slice()[n..2 * n], ag, ag2);
                        let v = signed_base_shear(
                            model.mr.as_slice(),
                            msum,
                            &acc.as_slice()[n..2 * n],
                            ag,
                            p,
                        ) + cross * ag2;
                        peaks.observe_base_shear(v.abs());
                    }
                }
                for (c, ct) in plan.contacts.iter().enumerate() {
                    let other = match (ct.kind, lay.epp_slot[c]) {
                        (ContactKind::Dof { dof }, _) => y[dof],
                        (_, Some(s)) => y[s],
                        (ContactKind::Epp, None) => 0.0,
                    };
                    let slip = ct.top.at(y.as_slice()) - other;
                    peaks.observe_slip(ct.slot, slip);
                    if ct.role == ContactRole::Damper
                        && let Some(rec) = peaks.dampers.as_mut()
                    {
                        let force = row_dot(&ops.force, c, y);
                        let rate = row_dot(&ops.slip_rate, c, y);
                        rec.observe(ct.slot, t, slip, rate, force);
                    }
                }
            };
        observe(&mut peaks, &ops, &y, &mut acc, 0.0);
        cont_drift.copy_from_slice(&peaks.drift);

        let mut history = plan
            .outputs
            .histories
            .then(|| history_columns(plan, energies));
        if let Some(h) = history.as_mut() {
            let e = energies.then_some([0.0, k0, s0, 0.0, 0.0, 0.0]);
            history_row(&model, &ops, h, 0.0, &y, e);
        }

        // Work buffers.
        let mut p: Vec<DVector<f64>> = vec![DVector::zeros(dim); TAYLOR_TERMS];
        let mut coef = vec![0.0; TAYLOR_TERMS];
        let mut dcoef = [0.0; TAYLOR_TERMS];
        let mut ynode = DVector::zeros(dim);
        let mut yabs = DVector::zeros(dim);
        let mut at_end = vec![false; nf];
        let mut far = vec![0.0; dim];
        let mut yobs = DVector::zeros(dim);
        let eval = |p: &[DVector<f64>], t: f64, out: &mut DVector<f64>| {
            add(TAYLOR_TERMS * dim);
            out.copy_from(&p[TAYLOR_TERMS - 1]);
            for k in (0..TAYLOR_TERMS - 1).rev() {
                *out *= t;
                *out += &p[k];
            }
        };
        let mut events: u64 = 0;
        let mut same_instant: u32 = 0;
        let mut last_event_t = f64::NEG_INFINITY;
        let mut balance_max_rel: f64 = 0.0;

        // Frames of q output steps (q = 1 unless the run asks for peaks only: then a frame
        // is a record interval, `modes::frame_steps`); the output steps inside a frame are
        // observed from the substep that reaches them, where a sampled peak can change.
        let q = model.frame_steps;
        'frames: for frame in 0..plan.steps.div_ceil(q) {
            let first = frame * q;
            let last = (first + q).min(plan.steps);
            let t_step_end = last as f64 * dt;
            let mut ta = first as f64 * dt;
            let step_start = ta;
            let full = last - first == q;
            let mut next_out = first + 1;
            while ta < t_step_end {
                let tb = piece_end(plan, ta, t_step_end);
                set_inputs(&mut y, ta, tb);
                // A piece that is a whole frame runs on its mode set's grid
                // ta + j·h (h = qΔt/m): a substep from one grid point to the next is one
                // product with the cached exp(A h), and its scans start with a bound that
                // rules most of them out. Substeps off the grid (after an event, or in
                // pieces cut by record samples) sum the Taylor series for their length.
                let whole = full && ta == step_start && tb == t_step_end;
                let mut t = ta;
                let mut on_grid = whole.then_some(0usize);
                while t < tb {
                    let rem = tb - t;
                    // (length, grid index reached, whether it starts on the grid)
                    let (len, reach, regular) = if whole {
                        let m = ops.per_step;
                        match on_grid {
                            Some(j) => (ops.h, Some(j + 1), true),
                            None => {
                                let j = (((t - ta) / ops.h).floor() as usize + 1).min(m);
                                let tn = if j >= m { tb } else { ta + j as f64 * ops.h };
                                if tn <= t {
                                    // Already at that grid point (to round-off).
                                    on_grid = Some(j);
                                    t = tn;
                                    continue;
                                }
                                (tn - t, Some(j), false)
                            }
                        }
                    } else {
                        let len = if rem <= ops.delta_max * (1.0 + 1e-12) {
                            rem
                        } else {
                            rem / (rem / ops.delta_max).ceil()
                        };
                        (len, None, false)
                    };
                    // A grid substep of a mode set that has lasted uses its propagators;
                    // any other substep sums the Taylor coefficients p_k = Aᵏ y / k!.
                    if regular && ops.prepared().is_none() {
                        cache.count_use(&model, &ops);
                    }
                    // Bounds: a prepared mode set's tails hold for any substep no longer
                    // than its grid interval (every term grows with τ), so substeps off
                    // the grid (after an event) are ruled out by the same tests.
                    let bounds = ops.prepared().filter(|_| len <= ops.h * (1.0 + 1e-12));
                    // The propagator itself only on a whole grid interval.
                    let fast = if regular { bounds } else { None };
                    if bounds.is_some() {
                        for (a, b) in yabs.iter_mut().zip(y.iter()) {
                            *a = b.abs();
                        }
                    }
                    // The Taylor coefficients p_k = Aᵏ y / k! of the substep, formed when
                    // its end is not one product with the propagator (or when a scan
                    // needs them and there are no Taylor rows).
                    let mut summed = fast.is_none();
                    if summed {
                        taylor(&ops.a_rows, &y, &mut p);
                        add(TAYLOR_TERMS * ops.a_rows.nnz());
                    }
                    let nev = ops.events.len();
                    // the exclusion tests of the event functions and drifts
                    add((nev + nf) * dim);
                    let coefs =
                        |f: usize, y: &DVector<f64>, p: &[DVector<f64>], coef: &mut [f64]| {
                            add(TAYLOR_TERMS * (dim + 2 * SCAN_POINTS));
                            if let Some(st) = bounds {
                                for (k, c) in coef.iter_mut().enumerate() {
                                    *c = dot(col(&st.rows, f * TAYLOR_TERMS + k), y.as_slice());
                                }
                            } else if f < nev {
                                let row = &ops.events[f].row;
                                for (c, pk) in coef.iter_mut().zip(p) {
                                    *c = row.dot(pk);
                                }
                            } else {
                                let i = f - nev;
                                for (c, pk) in coef.iter_mut().zip(p) {
                                    *c = drift(i, pk);
                                }
                            }
                        };
                    // On a summed substep without the mode set's bounds, the sizes of the
                    // far Taylor terms, q_j = Σ_{k≥L} |p_k,j| lenᵏ: with |row| they bound
                    // an event function's far part, so its leading coefficients alone
                    // (L dot products, not all of them) can rule it out.
                    let far_ready = bounds.is_none() && summed && !ops.events.is_empty();
                    if far_ready {
                        far.fill(0.0);
                        let mut lk = len.powi(LEAD_TERMS as i32);
                        for pk in &p[LEAD_TERMS..] {
                            for (q, v) in far.iter_mut().zip(pk.iter()) {
                                *q += v.abs() * lk;
                            }
                            lk *= len;
                        }
                    }
                    // Earliest event.
                    let mut tau_end = len;
                    let mut fired: Option<usize> = None;
                    for (e, ef) in ops.events.iter().enumerate() {
                        if far_ready {
                            let row = ef.row.as_slice();
                            let g0 = dot(row, p[0].as_slice());
                            let mut low = g0;
                            let mut lk = 1.0;
                            for pk in &p[1..LEAD_TERMS] {
                                lk *= len;
                                low += (dot(row, pk.as_slice()) * lk).min(0.0);
                            }
                            if g0 >= 0.0 && low >= dot(ops.event_abs[e].as_slice(), far.as_slice())
                            {
                                // g(τ) ≥ g(0) + Σ_{k<L} min(0, c_k lenᵏ) − Σ_j |row_j| q_j ≥ 0.
                                continue;
                            }
                        }
                        if let Some(st) = bounds {
                            let g0 = dot(ef.row.as_slice(), y.as_slice());
                            if g0 >= dot(col(&st.tails, e), yabs.as_slice()) {
                                // g(τ) ≥ g(0) − Σ|y_j|·tail_j ≥ 0 on the whole substep.
                                continue;
                            }
                            if g0 >= 0.0
                                && lead_terms(&lead_coefs(st, e, &y), len)
                                    .iter()
                                    .fold(g0, |low, t| low + t.min(0.0))
                                    >= dot(col(&st.tails_far, e), yabs.as_slice())
                            {
                                // g(τ) ≥ Σ_{k<L} min(0, c_k lenᵏ) − Σ|y_j|·tail_far_j ≥ 0
                                // (the leading terms formed exactly).
                                continue;
                            }
                        }
                        coefs(e, &y, &p, &mut coef);
                        let thr = match ef.scale {
                            Scale::Force(b) => GRAZE_REL * b,
                            Scale::Velocity => GRAZE_REL * v_ref,
                        };
                        if let Some(te) = first_crossing(&coef, tau_end, thr)
                            && te <= tau_end
                        {
                            tau_end = te;
                            fired = Some(e);
                        }
                    }
                    // Output steps inside the frame that this substep reaches (a frame of
                    // several output steps). A sampled peak can change there only where an
                    // observed function's bound on the substep, |g(0)| + Σ|y_j|·tail_j,
                    // exceeds it; where one does, each output step inside is observed from
                    // exp(AΔt) (a grid substep) or the Taylor coefficients, and one at the
                    // substep's end once the end state is known. Past a collapse limit the
                    // substep ends at that output step and the run stops there.
                    let mut stop = false;
                    let mut end_out = None;
                    if next_out < last {
                        let t_sub = t + tau_end;
                        let tol = 1e-9 * dt;
                        let mut upto = next_out;
                        while upto < last && upto as f64 * dt <= t_sub + tol {
                            upto += 1;
                        }
                        let at_end =
                            upto > next_out && ((upto - 1) as f64 * dt - t_sub).abs() <= tol;
                        let inner = if at_end { upto - 1 } else { upto };
                        if upto > next_out && bounds.is_some() {
                            add(2 * ops.obs_rows.ncols() * dim);
                        }
                        let quiet = upto > next_out
                            && ops.obs_rows.ncols() > 0
                            && bounds.is_some_and(|st| {
                                (0..ops.obs_rows.ncols()).all(|o| {
                                    // A stuck contact's slip does not change.
                                    (o >= obs_contacts && modes[o - obs_contacts] == Mode::Stuck)
                                        || dot(col(&ops.obs_rows, o), y.as_slice()).abs()
                                            + dot(col(&st.obs_tails, o), yabs.as_slice())
                                            <= observed_peak(plan, &peaks, o)
                                })
                            });
                        if !quiet {
                            let chain = bounds
                                .and_then(|st| st.phi_out.as_ref())
                                .filter(|_| regular);
                            if chain.is_some() {
                                yobs.copy_from(&y);
                            } else if inner > next_out && !summed {
                                taylor(&ops.a_rows, &y, &mut p);
                                add(TAYLOR_TERMS * ops.a_rows.nnz());
                                summed = true;
                            }
                            for j in next_out..inner {
                                let tj = j as f64 * dt;
                                let tau = (tj - t).clamp(0.0, tau_end);
                                if let Some(po) = chain {
                                    mat_vec(po, yobs.as_slice(), ynode.as_mut_slice());
                                    add(dim * dim);
                                    std::mem::swap(&mut yobs, &mut ynode);
                                } else {
                                    eval(&p, tau, &mut yobs);
                                }
                                observe(&mut peaks, &ops, &yobs, &mut acc, tj);
                                if peaks.collapsed(tj) {
                                    if !summed {
                                        taylor(&ops.a_rows, &y, &mut p);
                                        add(TAYLOR_TERMS * ops.a_rows.nnz());
                                        summed = true;
                                    }
                                    tau_end = tau;
                                    fired = None;
                                    stop = true;
                                    break;
                                }
                            }
                            if at_end && !stop {
                                end_out = Some(upto - 1);
                            }
                        }
                        next_out = upto;
                    }
                    // Drift extrema inside (0, tau_end]; a drift that is monotone there
                    // has its peak at the end, taken once the end state is known.
                    at_end.fill(false);
                    for i in 0..nf {
                        if let Some(st) = bounds {
                            let d0 = drift(i, &y);
                            if d0.abs() + dot(col(&st.tails, nev + i), yabs.as_slice())
                                <= cont_drift[i]
                            {
                                continue;
                            }
                            let lead = lead_coefs(st, nev + i, &y);
                            if lead_terms(&lead, len)
                                .iter()
                                .fold(d0.abs(), |high, t| high + t.abs())
                                + dot(col(&st.tails_far, nev + i), yabs.as_slice())
                                <= cont_drift[i]
                            {
                                continue;
                            }
                            if monotone(
                                &lead,
                                len,
                                dot(col(&st.rate_tails_far, nev + i), yabs.as_slice()),
                            ) {
                                at_end[i] = true;
                                continue;
                            }
                        }
                        coefs(nev + i, &y, &p, &mut coef);
                        let (tail, degree) = tail_and_degree(&coef, tau_end);
                        if coef[0].abs() + tail <= cont_drift[i] {
                            continue;
                        }
                        let coef = &coef[..=degree];
                        for k in 1..=degree {
                            dcoef[k - 1] = coef[k] * k as f64;
                        }
                        let dcoef = &dcoef[..degree];
                        let mut prev = (0.0, poly(dcoef, 0.0).0);
                        for j in 1..=SCAN_POINTS {
                            let tj = tau_end * j as f64 / SCAN_POINTS as f64;
                            let dj = poly(dcoef, tj).0;
                            if (prev.1 > 0.0 && dj < 0.0) || (prev.1 < 0.0 && dj > 0.0) {
                                let tm = illinois(|t| poly(dcoef, t).0, prev.0, tj);
                                cont_drift[i] = cont_drift[i].max(poly(coef, tm).0.abs());
                            }
                            prev = (tj, dj);
                        }
                        cont_drift[i] = cont_drift[i].max(poly(coef, tau_end).0.abs());
                    }
                    if let (Some(st), None, false) = (fast, fired, stop) {
                        if let Some([wi, wv, wf, wp]) = &st.work {
                            add(4 * dim * dim);
                            // One grid interval: its work is a quadratic form of y.
                            integ.input += quadratic(wi, &y, &mut ynode);
                            integ.viscous += quadratic(wv, &y, &mut ynode);
                            integ.friction += quadratic(wf, &y, &mut ynode);
                            if model.storeys {
                                integ.plastic += quadratic(wp, &y, &mut ynode);
                            }
                        }
                        mat_vec(&st.phi, y.as_slice(), ynode.as_mut_slice());
                        add(dim * dim);
                        std::mem::swap(&mut y, &mut ynode);
                    } else {
                        if !summed {
                            // A grid substep cut by an event.
                            taylor(&ops.a_rows, &y, &mut p);
                            add(TAYLOR_TERMS * ops.a_rows.nnz());
                            summed = true;
                        }
                        if energies {
                            model.integrate_powers(
                                &ops,
                                &mut integ,
                                tau_end,
                                &mut ynode,
                                |g, out| {
                                    add(3 * dim * dim / 2);
                                    eval(&p, GAUSS[g].0 * tau_end, out);
                                },
                            );
                        }
                        eval(&p, tau_end, &mut y);
                    }
                    debug_assert!(summed || fast.is_some());
                    // The monotone drifts' peaks, at the end of the substep.
                    for (i, c) in cont_drift.iter_mut().enumerate() {
                        if at_end[i] {
                            *c = c.max(drift(i, &y).abs());
                        }
                    }
                    if let Some(j) = end_out {
                        observe(&mut peaks, &ops, &y, &mut acc, j as f64 * dt);
                        stop = peaks.collapsed(j as f64 * dt);
                    }
                    if stop {
                        break 'frames;
                    }
                    match (fired, reach) {
                        (None, Some(j)) => {
                            t = if j >= ops.per_step {
                                tb
                            } else {
                                ta + j as f64 * ops.h
                            };
                            on_grid = Some(j);
                        }
                        (None, None) if len == rem => t = tb,
                        _ => {
                            t += tau_end;
                            on_grid = None;
                        }
                    }
                    for i in 0..plan.frame_dofs {
                        v_ref = v_ref.max(y[n + i].abs());
                    }
                    if !y.iter().all(|x| x.is_finite()) {
                        return Err(SimError::NonFinite {
                            step: next_out,
                            t,
                            hint: "exact: the state became non-finite".into(),
                        });
                    }
                    let Some(e) = fired else { continue };
                    // Event: decide the new modes.
                    events += 1;
                    add(2 * dim * dim);
                    if events > MAX_EVENTS {
                        return Err(SimError::ExactBudget {
                            what: "stick-slip events".into(),
                            t,
                            needed: events,
                            limit: MAX_EVENTS,
                            hint: "the dissipators chatter; use newmark, or the massless limit"
                                .into(),
                        });
                    }
                    let c_fired = ops.events[e].contact;
                    if t - last_event_t <= 1e-14 * t.max(1.0) {
                        same_instant += 1;
                        if same_instant > 4 * nc as u32 + 16 {
                            return Err(SimError::ExactZeno {
                                t,
                                events: same_instant,
                                floor: plan.contacts[c_fired].floor + 1,
                            });
                        }
                    } else {
                        same_instant = 0;
                    }
                    last_event_t = t;
                    let old = modes.clone();
                    // Every function at (or past) zero and heading down fires with it.
                    acc.gemv(1.0, &ops.a, &y, 0.0);
                    let mut decide: Vec<usize> = Vec::new();
                    for (k, ef) in ops.events.iter().enumerate() {
                        let g = ef.row.dot(&y);
                        let gd = ef.row.dot(&acc);
                        let thr = match ef.scale {
                            Scale::Force(b) => GRAZE_REL * b,
                            Scale::Velocity => GRAZE_REL * v_ref,
                        };
                        let fires = k == e || (g <= thr && gd < 0.0);
                        if !fires {
                            continue;
                        }
                        let c = ef.contact;
                        let ct = &plan.contacts[c];
                        match old[c] {
                            Mode::Stuck => {
                                // Which bound: the force row sign tells.
                                let fc = row_dot(&ops.force, c, &y);
                                modes[c] = if (fc - ct.upper).abs() <= (fc - ct.lower).abs() {
                                    Mode::Upper
                                } else {
                                    Mode::Lower
                                };
                                if let (Some(s), true) = (lay.epp_slot[c], ct.brace_damping == 0.0)
                                {
                                    // Snap the brace onto the bound (a root-finding residual).
                                    let bound = if modes[c] == Mode::Upper {
                                        ct.upper
                                    } else {
                                        ct.lower
                                    };
                                    let uj = ct.bottom.at(y.as_slice());
                                    let e_old = y[s] - uj;
                                    let e_new = bound / ct.brace_stiffness;
                                    let released =
                                        0.5 * ct.brace_stiffness * (e_old * e_old - e_new * e_new);
                                    match ct.role {
                                        ContactRole::Damper => integ.friction += released,
                                        ContactRole::Storey => integ.plastic += released,
                                    }
                                    y[s] = uj + e_new;
                                }
                            }
                            Mode::Upper | Mode::Lower => match ct.kind {
                                ContactKind::Epp => modes[c] = Mode::Stuck,
                                ContactKind::Dof { .. } => {
                                    if !decide.contains(&c) {
                                        decide.push(c);
                                    }
                                }
                            },
                        }
                    }
                    if !decide.is_empty() {
                        for (c, ct) in plan.contacts.iter().enumerate() {
                            if matches!(ct.kind, ContactKind::Dof { .. })
                                && modes[c] == Mode::Stuck
                                && old[c] == Mode::Stuck
                                && !decide.contains(&c)
                            {
                                decide.push(c);
                            }
                        }
                        decide.sort_unstable();
                        model.decide(&mut cache, &y, &mut modes, &decide, t)?;
                    }
                    for c in 0..nc {
                        if (modes[c] == Mode::Stuck) != (old[c] == Mode::Stuck)
                            && plan.contacts[c].role == ContactRole::Damper
                        {
                            peaks.transitions[plan.contacts[c].slot] += 1;
                        }
                    }
                    ops = cache.get(&model, &modes);
                    project_counted(&mut y, &ops, &mut integ);
                }
                ta = tb;
            }
            // The frame's last output step. Re-impose B_Sᵀv = 0 on the stuck contacts: the
            // projected dynamics keep it only to round-off, which accumulates over many
            // substeps on very stiff braces (the kinetic energy removed, ~ε², goes to
            // friction).
            if ops.proj.is_some() {
                project_counted(&mut y, &ops, &mut integ);
            }
            observe(&mut peaks, &ops, &y, &mut acc, t_step_end);
            let mut e_row = None;
            if energies {
                let (ek, es) = model.stored(&y);
                strain_area += 0.5 * dt * (strain_prev + es);
                strain_prev = es;
                let bal = integ.input + initial_energy
                    - (ek + es + integ.viscous + integ.friction + integ.plastic);
                let scale = (integ.input.abs() + initial_energy).max(f64::MIN_POSITIVE);
                balance_max_rel = balance_max_rel.max(bal.abs() / scale);
                e_row = Some([
                    integ.input,
                    ek,
                    es,
                    integ.viscous,
                    integ.friction,
                    integ.plastic,
                ]);
            }
            if let Some(h) = history.as_mut() {
                history_row(&model, &ops, h, t_step_end, &y, e_row);
            }
            if peaks.collapsed(t_step_end) {
                break;
            }
        }
        for (c, s) in cont_drift.iter_mut().zip(&peaks.drift) {
            *c = c.max(*s);
        }
        let energy = energies.then(|| {
            let (ek, es) = model.stored(&y);
            Energy {
                input: integ.input,
                kinetic: ek,
                strain: es,
                viscous: integ.viscous,
                friction: integ.friction,
                balance_error: integ.input + initial_energy
                    - (ek + es + integ.viscous + integ.friction + integ.plastic),
                plastic: model.storeys.then_some(integ.plastic),
            }
        });
        let sampled = peaks.drift.clone();
        peaks.drift = cont_drift;
        let response = peaks.into_plan_response(plan, energy);
        Ok(Outcome {
            response,
            diagnostics: Diagnostics {
                balance_error_max_relative: balance_max_rel,
                initial_energy,
                sampled_peak_drift: Some(sampled),
                events,
                strain_energy_area: strain_area,
                work: work.get(),
                cache_peak_bytes: cache.peak_bytes() as u64,
                ..Default::default()
            },
            history,
        })
    }
}
