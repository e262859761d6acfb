//! `delacruz` — the paper's algorithm (De la Cruz, López-Almansa & Oller 2007, Comput.
//! Struct. 85:30–42, §4), reconstructed from its structure; docs/MODEL.md § Integrators.
//!
//! # What is implemented
//!
//! **Time discretisation** (the paper's eqs. 11–14: accelerations linear within a step,
//! i.e. Newmark with γ = ½, β = ⅙). With the predictors
//! u* = uₖ + Δt vₖ + Δt²/3 aₖ and v* = vₖ + Δt/2 aₖ,
//! u_{k+1} = u* + Δt²/6 a_{k+1} and v_{k+1} = v* + Δt/2 a_{k+1}; the equation of motion
//! M a + C v + K u = −M r a_g + P − B F is imposed at t_{k+1}.
//!
//! **Stick/slip decision per floor at every instant** (the paper's rules 1 and 2).
//! A damper is either stuck (dissipator moving with its floor: a′ = a_floor, w = 0, its
//! friction force F the unknown reaction) or sliding in a direction s = ±1 (F = F⁺ or F⁻,
//! the dissipator moving under its own equation). The bounds may be asymmetric
//! (F⁻ ≤ 0 ≤ F⁺, the paper's §3).
//! - Rule 1 (stick → slip): when the force a stuck damper needs at t_{k+1} leaves
//!   [F⁻, F⁺], the damper slides from t_{k+1} at the bound it crossed, and the step is
//!   solved again with that damper sliding.
//! - Rule 2 (slip → stick): when a sliding damper's slip rate w changes sign (or reaches
//!   zero) during a step, it is stuck at t_{k+1}: the dissipator velocity and acceleration
//!   are set to its floor's (w_{k+1} = 0) and F_{k+1} is the force that keeps it stuck,
//!   kept within the bounds. If that force lies beyond the opposite bound, sliding
//!   continues in reverse — detected at t_{k+2} by rule 1, as in the paper.
//!
//! **Three nested fixed-point loops** (explicit iteration on the coupled problem):
//! - inner — structural (floor) accelerations: a_F ← M_FF⁻¹(q_F − (C v(a) + K u(a))_F −
//!   (B F)_F), with stuck dissipators following their floors; until max |Δa| ≤ ε_a;
//! - middle — friction forces of stuck dampers, from the dissipator's equation
//!   F = m′(a′ + a_g) + brace force (for a massless dissipator, F = brace force
//!   k′e + c′ė, algebraic), each followed by an inner loop; until max |ΔF| ≤ ε_f;
//! - outer — accelerations of sliding dissipators, a′ ← (q′ + F± − (C v(a) + K u(a))′)/m′,
//!   each followed by a middle loop; until max |Δa′| ≤ ε_a.
//!
//! Defaults, as the paper states: Δt = T₁/200 (the scene default), ε_a = |a_g|max/10⁵,
//! ε_f = μN/10⁵ (per damper; max(|F⁻|, F⁺) when asymmetric), with μN capped at the
//! building's inertial force Σm·|a_g|max (a huge slip load would otherwise make ε_f far
//! larger than the stuck forces it controls). Without a record ε_a takes
//! the largest of (harmonic amplitude / smallest floor mass), the initial floor
//! accelerations, ω₁²|x₀| and ω₁|ẋ₀| (ω₁ = 2π/T₁) as its scale, over 10⁵. Iteration
//! cap: 100 per loop invocation (the paper gives none). All settable (`method.eps_a`,
//! `method.eps_f`, `method.max_iterations`).
//!
//! **Conditional stability.** The loops are contractions only for small enough Δt: a
//! sliding dissipator's update has gain k′Δt²/(6m′) (so Δt < √(6m′/k′)), the structural
//! one about ω²Δt²/6, and linear acceleration itself is stable for Δt ≤ T_min·√3/π. When a
//! loop exceeds its cap, diverges (its correction grows four times in a row) or the state
//! stops being finite, the run ends with [`SimError::DelaCruzNotConverged`], naming the
//! step, the loop and a Δt = ½·min(√(6m′/k′), T_min·√3/π) (T_min of the frame with every
//! damper locked), for which every loop gain is at most about ½.
//!
//! **Massless dissipators** (m′ = 0): the paper's dissipator equations degenerate (no
//! acceleration to iterate on), yet its ten-storey case ran with Mᵈᵈ = 0. The principled
//! reduction is the plan's: a massless dissipator is an elastic–perfectly plastic contact
//! (`ContactKind::Epp`) whose brace force is the friction force — stuck, the brace
//! elongation e follows the storey drift and F = k′e + c′ė is found in the middle loop;
//! sliding, F = F± and e follows from F± = k′e + c′ė (e = F±/k′ without a dashpot,
//! trapezoidal in time with one). Unreduced plans that keep zero-mass dissipator DOFs are
//! refused (use `reduce: true`).
//!
//! **Energies** are accumulated with the same definitions and recorder as `newmark`
//! (trapezoidal rule on step-averaged forces and velocities). Linear acceleration does
//! not make that bookkeeping an identity: per step the strain term is off by
//! (β − ¼)Δt²(a_{k+1} − aₖ)ᵀK ū = −Δt²/12 Δaᵀ K ū, an oscillating (non-accumulating)
//! error within (ω_max Δt)²/12 of the energy in play. Each rule-2 projection changes the
//! dissipator's kinetic energy by ½m′(v′² − v_floor²), O(m′·w·v) with |w| no larger than
//! the step's change of slip rate; their sum is reported as
//! [`LoopIterations::projection_energy`]. So
//! |balance error − projection energy| ≤ (ω_max Δt)²/12 · (|input| + initial energy).

use crate::error::SimError;
use crate::integrator::method::Integrator;
use crate::integrator::state::{
    self, EnergyAccumulator, EppState, StepEnergyData, StepForms, history_columns, initial_state,
    record_row, slip,
};
use crate::plan::{ContactKind, Plan};
use crate::response::{Diagnostics, LoopIterations, Outcome, Peaks};
use crate::units::is_positive;
use nalgebra::{Cholesky, DMatrix, DVector, Dyn};

/// The paper's method: linear acceleration, stick/slip per floor at every step, three
/// nested fixed-point loops. Conditionally stable: see the module documentation.
#[derive(Debug, Clone, Copy, Default)]
pub struct DelaCruz;

/// Default iteration cap per loop invocation.
pub const DEFAULT_MAX_ITERATIONS: u32 = 100;

/// Consecutive growing corrections after which a loop is declared divergent.
const DIVERGING_AFTER: u32 = 4;

/// Stick/slip mode of a damper: 0 stuck, +1 sliding with w > 0 (F = F⁺), −1 with w < 0.
type Mode = i8;

/// Counts of one loop.
#[derive(Debug, Clone, Copy, Default)]
struct LoopCount {
    total: u64,
    calls: u64,
    max: u32,
}

impl LoopCount {
    fn add(&mut self, it: u32) {
        self.total += u64::from(it);
        self.calls += 1;
        self.max = self.max.max(it);
    }
    fn mean(&self) -> f64 {
        if self.calls == 0 {
            0.0
        } else {
            self.total as f64 / self.calls as f64
        }
    }
}

/// Which loop failed and after how many iterations.
#[derive(Debug, Clone, Copy)]
struct LoopFailure {
    name: &'static str,
    iterations: u32,
}

/// Tracks a loop's corrections to stop it at convergence, cap or divergence.
struct Watch {
    last: f64,
    growing: u32,
}

impl Watch {
    fn new() -> Self {
        Watch {
            last: f64::INFINITY,
            growing: 0,
        }
    }
    /// `Ok(true)` converged, `Ok(false)` go on, `Err` failed. `delta` is normalised so
    /// that convergence is `delta <= 1`.
    fn check(
        &mut self,
        delta: f64,
        it: u32,
        cap: u32,
        name: &'static str,
    ) -> Result<bool, LoopFailure> {
        let fail = LoopFailure {
            name,
            iterations: it,
        };
        if !delta.is_finite() {
            return Err(fail);
        }
        if delta <= 1.0 {
            return Ok(true);
        }
        if delta > self.last {
            self.growing += 1;
        } else {
            self.growing = 0;
        }
        self.last = delta;
        if it >= cap || self.growing >= DIVERGING_AFTER {
            return Err(fail);
        }
        Ok(false)
    }
}

/// Everything fixed for a run.
struct Setup {
    n: usize,
    nf: usize,
    dt: f64,
    /// Δt/2 C + Δt²/6 K: the part of C v + K u that depends on a_{k+1}.
    d: DMatrix<f64>,
    /// Cholesky factor of the floor mass block M_FF.
    mff: Cholesky<f64, Dyn>,
    /// M r.
    mr: DVector<f64>,
    eps_a: f64,
    /// Per contact.
    eps_f: Vec<f64>,
    cap: u32,
    suggested_dt: f64,
}

/// Largest ω² of the frame with every damper locked to its floor (generalised symmetric
/// eigenproblem K φ = ω² M φ, through the Cholesky factor of M).
fn locked_omega2_max(plan: &Plan) -> Option<f64> {
    let n = plan.dofs();
    let nf = plan.floors;
    let mut p = DMatrix::zeros(n, nf);
    for i in 0..nf {
        p[(i, i)] = 1.0;
    }
    for ct in &plan.contacts {
        if let ContactKind::Dof { dof } = ct.kind {
            p[(dof, ct.floor)] = 1.0;
        }
    }
    let mut k = p.transpose() * &plan.stiffness * &p;
    let m = p.transpose() * &plan.mass * &p;
    for ct in &plan.contacts {
        if ct.kind == ContactKind::Epp {
            let (i, kb) = (ct.floor, ct.brace_stiffness);
            k[(i, i)] += kb;
            if let Some(j) = ct.below() {
                k[(j, j)] += kb;
                k[(i, j)] -= kb;
                k[(j, i)] -= kb;
            }
        }
    }
    let l = m.cholesky()?.l();
    let li = l.try_inverse()?;
    let a = &li * k * li.transpose();
    let a = (&a + a.transpose()) * 0.5;
    a.symmetric_eigenvalues().iter().copied().reduce(f64::max)
}

/// A time step for which every loop contracts: ½·min(√(6m′/k′), T_min·√3/π).
fn suggested_dt(plan: &Plan) -> f64 {
    let mut lim = f64::INFINITY;
    for ct in &plan.contacts {
        if let ContactKind::Dof { dof } = ct.kind {
            let (m, k) = (plan.mass[(dof, dof)], plan.stiffness[(dof, dof)]);
            if m > 0.0 && k > 0.0 {
                lim = lim.min((6.0 * m / k).sqrt());
            }
        }
    }
    if let Some(w2) = locked_omega2_max(plan)
        && w2 > 0.0
    {
        let t_min = 2.0 * std::f64::consts::PI / w2.sqrt();
        lim = lim.min(t_min * 3f64.sqrt() / std::f64::consts::PI);
    }
    if lim.is_finite() {
        0.5 * lim
    } else {
        0.5 * plan.method.dt
    }
}

impl Setup {
    fn build(plan: &Plan, a0: &[f64]) -> Result<Setup, SimError> {
        let n = plan.dofs();
        let nf = plan.floors;
        let dt = plan.method.dt;
        // zero-mass dissipator DOFs were refused by Plan::check_method
        let d = &plan.damping * (0.5 * dt) + &plan.stiffness * (dt * dt / 6.0);
        let mff = plan
            .mass
            .view((0, 0), (nf, nf))
            .into_owned()
            .cholesky()
            .ok_or_else(|| SimError::NotPositiveDefinite {
                what: "floor mass matrix".into(),
                hint: String::new(),
            })?;
        let mr = plan.mass_influence();
        let min_floor_mass = (0..nf)
            .map(|i| plan.mass[(i, i)])
            .fold(f64::INFINITY, f64::min);
        let scale = match &plan.record {
            Some(r) if r.pga() > 0.0 => r.pga(),
            _ => {
                // No record: the accelerations the loads and the initial state call for
                // (harmonic amplitude over the lightest floor; initial accelerations; and
                // ω₁²|u₀|, ω₁|v₀| with ω₁ = 2π/T₁).
                let w1 = 2.0 * std::f64::consts::PI / plan.t1;
                let p = plan
                    .harmonic
                    .map_or(0.0, |h| h.amplitude.abs() / min_floor_mass);
                (0..nf).fold(p, |m, i| {
                    m.max(a0[i].abs())
                        .max(w1 * w1 * plan.u0[i].abs())
                        .max(w1 * plan.v0[i].abs())
                })
            }
        };
        let eps_a = plan.method.eps_a.unwrap_or(if scale > 0.0 {
            scale * 1e-5
        } else {
            f64::MIN_POSITIVE
        });
        // The paper's ε_f = μN/10⁵ assumes μN is of the order of the forces in play. A slip
        // load far above them (μN → ∞, a damper that never slips) would make the stuck-force
        // loop "converge" on forces 10⁵ times smaller than its tolerance, so the scale is
        // capped at the building's inertial force at the scale acceleration (Σm·a): the
        // paper's value whenever μN is below that force.
        let force_scale = mr.iter().sum::<f64>() * scale;
        let eps_f = plan
            .contacts
            .iter()
            .map(|ct| {
                plan.method.eps_f.unwrap_or_else(|| {
                    let mut b = [ct.lower.abs(), ct.upper.abs()]
                        .into_iter()
                        .filter(|x| x.is_finite())
                        .fold(0.0, f64::max);
                    if force_scale > 0.0 {
                        b = b.min(force_scale);
                    }
                    if b > 0.0 {
                        b * 1e-5
                    } else {
                        (plan.mass[(ct.floor, ct.floor)] * eps_a).max(f64::MIN_POSITIVE)
                    }
                })
            })
            .collect();
        Ok(Setup {
            n,
            nf,
            dt,
            d,
            mff,
            mr,
            eps_a,
            eps_f,
            cap: plan.method.max_iterations.unwrap_or(DEFAULT_MAX_ITERATIONS),
            suggested_dt: suggested_dt(plan),
        })
    }
}

/// Scratch and per-step data of one step's solve.
struct Step {
    /// Load at t_{k+1}: −M r a_g + P.
    q: Vec<f64>,
    /// C v* + K u*.
    gp: Vec<f64>,
    /// Predictors.
    up: Vec<f64>,
    vp: Vec<f64>,
    /// Floor residuals / new floor accelerations.
    r: DVector<f64>,
    /// Brace elongation e and rate ė of massless contacts at tₖ.
    e0: Vec<(f64, f64)>,
    /// … and at t_{k+1} (the current iterate).
    e1: Vec<(f64, f64)>,
}

/// (C v(a) + K u(a))_i = (C v* + K u*)_i + (D a)_i.
#[inline]
fn row_force(s: &Setup, st: &Step, i: usize, a: &[f64]) -> f64 {
    let mut x = st.gp[i];
    for (j, aj) in a.iter().enumerate() {
        x += s.d[(i, j)] * aj;
    }
    x
}

/// Drift (displacement, velocity) of a contact's storey at the end of the step.
#[inline]
fn storey(plan: &Plan, st: &Step, c: usize, a: &[f64], dt: f64) -> (f64, f64) {
    let ct = &plan.contacts[c];
    let uf = st.up[ct.floor] + dt * dt / 6.0 * a[ct.floor];
    let vf = st.vp[ct.floor] + 0.5 * dt * a[ct.floor];
    let (ub, vb) = ct.below().map_or((0.0, 0.0), |j| {
        (st.up[j] + dt * dt / 6.0 * a[j], st.vp[j] + 0.5 * dt * a[j])
    });
    (uf - ub, vf - vb)
}

struct Counters {
    inner: LoopCount,
    middle: LoopCount,
    outer: LoopCount,
}

/// Solves one step with the modes fixed: the three nested loops. `a` and `f` carry the
/// warm start in and the answer out.
#[allow(clippy::too_many_arguments)] // the step's state, kept in the caller's buffers
fn solve(
    plan: &Plan,
    s: &Setup,
    st: &mut Step,
    mode: &[Mode],
    u_k: &[f64],
    a: &mut [f64],
    f: &mut [f64],
    cnt: &mut Counters,
) -> Result<(), LoopFailure> {
    let nf = s.nf;
    let dt = s.dt;
    // Sliding dampers: their force is the bound; massless ones also fix e.
    for (c, ct) in plan.contacts.iter().enumerate() {
        if mode[c] != 0 {
            f[c] = if mode[c] > 0 { ct.upper } else { ct.lower };
            if ct.kind == ContactKind::Epp {
                let (e, ed) = st.e0[c];
                st.e1[c] = if ct.brace_damping > 0.0 {
                    // F = k′e + c′ė, trapezoidal in time.
                    let r = dt / (2.0 * ct.brace_damping);
                    let e1 = (e + 0.5 * dt * ed + r * f[c]) / (1.0 + r * ct.brace_stiffness);
                    (e1, (f[c] - ct.brace_stiffness * e1) / ct.brace_damping)
                } else {
                    (f[c] / ct.brace_stiffness, 0.0)
                };
            }
        }
    }
    let any_stuck = mode.contains(&0);
    let sliding_dofs = plan
        .contacts
        .iter()
        .zip(mode)
        .any(|(ct, m)| *m != 0 && matches!(ct.kind, ContactKind::Dof { .. }));
    let follow = |a: &mut [f64]| {
        for (c, ct) in plan.contacts.iter().enumerate() {
            if let ContactKind::Dof { dof } = ct.kind
                && mode[c] == 0
            {
                a[dof] = a[ct.floor];
            }
        }
    };
    let mut outer = Watch::new();
    let mut it_o = 0;
    loop {
        it_o += 1;
        // Middle loop: friction forces of stuck dampers.
        let mut middle = Watch::new();
        let mut it_m = 0;
        loop {
            it_m += 1;
            // Inner loop: floor accelerations.
            let mut inner = Watch::new();
            let mut it_i = 0;
            loop {
                it_i += 1;
                follow(a);
                for i in 0..nf {
                    let mut r = st.q[i] - row_force(s, st, i, a);
                    for (j, aj) in a.iter().enumerate().skip(nf) {
                        r -= plan.mass[(i, j)] * aj;
                    }
                    st.r[i] = r;
                }
                for (c, ct) in plan.contacts.iter().enumerate() {
                    st.r[ct.floor] -= f[c];
                    if ct.kind == ContactKind::Epp
                        && let Some(j) = ct.below()
                    {
                        st.r[j] += f[c];
                    }
                }
                s.mff.solve_mut(&mut st.r);
                let mut delta: f64 = 0.0;
                for (ai, ri) in a[..nf].iter_mut().zip(st.r.iter()) {
                    delta = delta.max((ri - *ai).abs());
                    *ai = *ri;
                }
                match inner.check(delta / s.eps_a, it_i, s.cap, "inner") {
                    Ok(true) => break,
                    Ok(false) => {}
                    Err(e) => {
                        cnt.inner.add(it_i);
                        return Err(e);
                    }
                }
            }
            cnt.inner.add(it_i);
            follow(a);
            if !any_stuck {
                break;
            }
            let mut delta: f64 = 0.0;
            for (c, ct) in plan.contacts.iter().enumerate() {
                if mode[c] != 0 {
                    continue;
                }
                let fc = match ct.kind {
                    ContactKind::Dof { dof } => {
                        let mut inertia = 0.0;
                        for (j, aj) in a.iter().enumerate() {
                            inertia += plan.mass[(dof, j)] * aj;
                        }
                        inertia + row_force(s, st, dof, a) - st.q[dof]
                    }
                    ContactKind::Epp => {
                        let (d1, dv1) = storey(plan, st, c, a, dt);
                        let d0 = u_k[ct.floor] - ct.below().map_or(0.0, |j| u_k[j]);
                        let e1 = st.e0[c].0 + (d1 - d0);
                        st.e1[c] = (e1, dv1);
                        ct.brace_stiffness * e1 + ct.brace_damping * dv1
                    }
                };
                delta = delta.max((fc - f[c]).abs() / s.eps_f[c]);
                f[c] = fc;
            }
            match middle.check(delta, it_m, s.cap, "middle") {
                Ok(true) => break,
                Ok(false) => {}
                Err(e) => {
                    cnt.middle.add(it_m);
                    return Err(e);
                }
            }
        }
        cnt.middle.add(it_m);
        if !sliding_dofs {
            break;
        }
        // Outer loop: accelerations of sliding dissipators.
        let mut delta: f64 = 0.0;
        for (c, ct) in plan.contacts.iter().enumerate() {
            let ContactKind::Dof { dof } = ct.kind else {
                continue;
            };
            if mode[c] == 0 {
                continue;
            }
            let mut r = st.q[dof] + f[c] - row_force(s, st, dof, a);
            for (j, aj) in a.iter().enumerate() {
                if j != dof {
                    r -= plan.mass[(dof, j)] * aj;
                }
            }
            let an = r / plan.mass[(dof, dof)];
            delta = delta.max((an - a[dof]).abs());
            a[dof] = an;
        }
        match outer.check(delta / s.eps_a, it_o, s.cap, "outer") {
            Ok(true) => break,
            Ok(false) => {}
            Err(e) => {
                cnt.outer.add(it_o);
                return Err(e);
            }
        }
    }
    cnt.outer.add(it_o);
    Ok(())
}

impl Integrator for DelaCruz {
    fn name(&self) -> &'static str {
        "delacruz"
    }

    fn run(&self, plan: &Plan) -> Result<Outcome, SimError> {
        let dt = plan.method.dt;
        if !is_positive(dt) {
            return Err(SimError::BadTimeStep { dt });
        }
        plan.check_method()?;
        let start = initial_state(plan)?;
        let s = Setup::build(plan, &start.a)?;
        let (n, nf, nc) = (s.n, s.nf, plan.contacts.len());
        let not_converged = |step: usize, t: f64, e: LoopFailure| SimError::DelaCruzNotConverged {
            step,
            t,
            loop_name: e.name,
            iterations: e.iterations,
            suggested_dt: s.suggested_dt,
        };

        let mut u = start.u.clone();
        let mut v = start.v.clone();
        let mut a = start.a.clone();
        let mut f = start.f.clone();
        let mut epp = start.epp;
        let mut mode: Vec<Mode> = plan
            .contacts
            .iter()
            .enumerate()
            .map(|(c, ct)| {
                if start.stuck[c] {
                    0
                } else if f[c] >= ct.upper {
                    1
                } else {
                    -1
                }
            })
            .collect();
        let below_u = |u: &[f64], c: usize| plan.contacts[c].below().map_or(0.0, |j| u[j]);
        let mut st = Step {
            q: vec![0.0; n],
            gp: vec![0.0; n],
            up: vec![0.0; n],
            vp: vec![0.0; n],
            r: DVector::zeros(nf),
            e0: (0..nc)
                .map(|c| (epp[c].u - below_u(&u, c), epp[c].v - below_u(&v, c)))
                .collect(),
            e1: vec![(0.0, 0.0); nc],
        };
        let slip_rate = |c: usize, v: &[f64], epp: &[EppState]| -> f64 {
            let ct = &plan.contacts[c];
            match ct.kind {
                ContactKind::Dof { dof } => v[ct.floor] - v[dof],
                ContactKind::Epp => v[ct.floor] - epp[c].v,
            }
        };
        let mut w: Vec<f64> = (0..nc).map(|c| slip_rate(c, &v, &epp)).collect();
        let mut cnt = Counters {
            inner: LoopCount::default(),
            middle: LoopCount::default(),
            outer: LoopCount::default(),
        };
        let mut resolves: u64 = 0;
        let mut projection_energy = 0.0;

        let energies = plan.outputs.energies;
        let mut acc = EnergyAccumulator::start(plan, &u, &v, &epp);
        let msum: f64 = s.mr.iter().sum();
        let hf = plan.harmonic.map(|h| h.floor);
        let base_shear =
            |a: &[f64], ag: f64, p: f64| state::base_shear(s.mr.as_slice(), msum, a, ag, p);
        let mut peaks = Peaks::for_plan(plan);
        debug_assert_eq!(peaks.drift.len(), nf);
        let mut ag0 = plan.ground_accel(0.0);
        let mut p0 = plan.force(0.0);
        peaks.observe_floors(&u, &a, ag0);
        peaks.observe_base_shear(base_shear(&a, ag0, p0));
        for c in 0..nc {
            let fl = plan.contacts[c].floor;
            peaks.observe_slip(fl, slip(plan, c, &u, &epp));
        }
        state::observe_dampers(plan, &mut peaks, 0.0, &u, &f, &w, &epp);
        let mut history = plan
            .outputs
            .histories
            .then(|| history_columns(plan, energies));
        if let Some(h) = history.as_mut() {
            let e = energies.then(|| acc.initial_row());
            record_row(plan, h, 0.0, ag0, &u, &f, &w, &epp, e);
        }

        let mut a_new = vec![0.0; n];
        let mut f_new = vec![0.0; nc];
        let mut f_dyn = vec![0.0; nc];
        let mut v_old = vec![0.0; n];
        let mut w_new = vec![0.0; nc];
        let mut mode_step = mode.clone();
        let (c_u, c_v) = (dt * dt / 3.0, 0.5 * dt);
        for step in 0..plan.steps {
            let t1 = (step + 1) as f64 * dt;
            let ag1 = plan.ground_accel(t1);
            let p1 = plan.force(t1);
            for i in 0..n {
                st.up[i] = u[i] + dt * v[i] + c_u * a[i];
                st.vp[i] = v[i] + c_v * a[i];
                st.q[i] = -s.mr[i] * ag1;
            }
            if let Some(fl) = hf {
                st.q[fl] += p1;
            }
            for i in 0..n {
                let mut g = 0.0;
                for j in 0..n {
                    g += plan.damping[(i, j)] * st.vp[j] + plan.stiffness[(i, j)] * st.up[j];
                }
                st.gp[i] = g;
            }
            // Solve with the modes of tₖ; rule 1 turns stuck dampers whose force left
            // its bounds into sliding ones and solves again (at most once per damper).
            mode_step.copy_from_slice(&mode);
            a_new.copy_from_slice(&a);
            f_new.copy_from_slice(&f);
            loop {
                solve(
                    plan, &s, &mut st, &mode_step, &u, &mut a_new, &mut f_new, &mut cnt,
                )
                .map_err(|e| not_converged(step + 1, t1, e))?;
                let mut switched = false;
                for (c, ct) in plan.contacts.iter().enumerate() {
                    if mode_step[c] == 0 {
                        if f_new[c] > ct.upper {
                            mode_step[c] = 1;
                            switched = true;
                        } else if f_new[c] < ct.lower {
                            mode_step[c] = -1;
                            switched = true;
                        }
                    }
                }
                if !switched {
                    break;
                }
                resolves += 1;
            }
            if energies {
                v_old.copy_from_slice(&v);
            }
            let mut finite = 0.0;
            for i in 0..n {
                a[i] = a_new[i];
                u[i] = st.up[i] + dt * dt / 6.0 * a[i];
                v[i] = st.vp[i] + 0.5 * dt * a[i];
                finite += u[i] + v[i] + a[i];
            }
            if !finite.is_finite() {
                return Err(not_converged(
                    step + 1,
                    t1,
                    LoopFailure {
                        name: "response",
                        iterations: 0,
                    },
                ));
            }
            f_dyn.copy_from_slice(&f_new);
            for (c, ct) in plan.contacts.iter().enumerate() {
                // Massless dissipators: x′ = x_below + e, v′ = v_below + ė.
                if ct.kind == ContactKind::Epp {
                    let (e, ed) = st.e1[c];
                    let (ub, vb) = ct.below().map_or((0.0, 0.0), |j| (u[j], v[j]));
                    epp[c] = EppState {
                        u: ub + e,
                        v: vb + ed,
                        a: 0.0,
                    };
                }
                w_new[c] = slip_rate(c, &v, &epp);
                let now = mode_step[c];
                // Rule 2: a damper sliding at tₖ whose slip rate reversed is stuck at t_{k+1}.
                if mode[c] != 0 && now == mode[c] && f64::from(now) * w_new[c] <= 0.0 {
                    match ct.kind {
                        ContactKind::Dof { dof } => {
                            projection_energy += 0.5
                                * plan.mass[(dof, dof)]
                                * (v[dof] * v[dof] - v[ct.floor] * v[ct.floor]);
                            v[dof] = v[ct.floor];
                            a[dof] = a[ct.floor];
                            let mut force = -st.q[dof];
                            for j in 0..n {
                                force += plan.mass[(dof, j)] * a[j]
                                    + plan.damping[(dof, j)] * v[j]
                                    + plan.stiffness[(dof, j)] * u[j];
                            }
                            f_new[c] = force.clamp(ct.lower, ct.upper);
                        }
                        ContactKind::Epp => {
                            let vb = ct.below().map_or(0.0, |j| v[j]);
                            let ed = v[ct.floor] - vb;
                            st.e1[c].1 = ed;
                            epp[c].v = vb + ed;
                            let e = st.e1[c].0;
                            f_new[c] = (ct.brace_stiffness * e + ct.brace_damping * ed)
                                .clamp(ct.lower, ct.upper);
                        }
                    }
                    w_new[c] = slip_rate(c, &v, &epp);
                    mode_step[c] = 0;
                }
                if mode_step[c] != mode[c] {
                    peaks.transitions[ct.floor] += 1;
                }
                peaks.observe_slip(ct.floor, slip(plan, c, &u, &epp));
            }
            state::observe_dampers(plan, &mut peaks, t1, &u, &f_new, &w_new, &epp);
            peaks.observe_floors(&u, &a, ag1);
            peaks.observe_base_shear(base_shear(&a, ag1, p1));
            let mut e_row = None;
            if energies {
                let data = StepEnergyData {
                    second: None,
                    dt,
                    mr: s.mr.as_slice(),
                    ag: (ag0, ag1),
                    p: (p0, p1),
                    force_floor: hf,
                    v: (&v_old, &v),
                    f: (&f, &f_dyn),
                    w: (&w, &w_new),
                    epp_mean_rate: false,
                };
                let q = StepForms::of_plan(plan, (&v_old, &v), &u, &epp);
                e_row = Some(acc.step(plan, &data, q, &epp));
            }
            if let Some(h) = history.as_mut() {
                record_row(plan, h, t1, ag1, &u, &f_new, &w_new, &epp, e_row);
            }
            f.copy_from_slice(&f_new);
            w.copy_from_slice(&w_new);
            mode.copy_from_slice(&mode_step);
            st.e0.copy_from_slice(&st.e1);
            ag0 = ag1;
            p0 = p1;
            if peaks.collapsed(t1) {
                break;
            }
        }
        let energy = energies.then(|| acc.finish(plan, &u, &v, &epp));
        let response = peaks.into_plan_response(plan, energy);
        Ok(Outcome {
            response,
            diagnostics: Diagnostics {
                qp_iterations_mean: 0.0,
                qp_iterations_max: 0,
                balance_error_max_relative: acc.balance_max_rel,
                initial_energy: acc.initial_energy(),
                loop_iterations: Some(LoopIterations {
                    inner_mean: cnt.inner.mean(),
                    inner_max: cnt.inner.max,
                    middle_mean: cnt.middle.mean(),
                    middle_max: cnt.middle.max,
                    outer_mean: cnt.outer.mean(),
                    outer_max: cnt.outer.max,
                    resolves,
                    projection_energy,
                }),
                strain_energy_area: acc.strain_area,
                ..Default::default()
            },
            history,
        })
    }
}
