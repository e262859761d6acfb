//! State shared by the integrators: the initial state, elastic–perfectly plastic element
//! state, slips, stored energies, and the recorders of histories and energies (so every
//! method reports the same quantities under the same names and definitions).

use crate::error::SimError;
use crate::friction::BoxQp;
use crate::friction::box_qp::Bound;
use crate::plan::{ContactKind, ContactRole, Plan};
use crate::response::{Energy, History, Peaks};
use nalgebra::{DMatrix, DVector};

/// Per-contact state of elastic–perfectly plastic elements: dissipator displacement,
/// velocity, acceleration (Newmark state of the condensed massless DOF).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct EppState {
    /// Dissipator displacement, m.
    pub(crate) u: f64,
    /// Dissipator velocity, m/s.
    pub(crate) v: f64,
    /// Dissipator acceleration, m/s².
    pub(crate) a: f64,
}

/// Slip rate w = Bᵀv for contact `c` given plan velocities and EPP state.
#[inline]
pub(crate) fn slip_rate(plan: &Plan, c: usize, v: &[f64], epp: &[EppState]) -> f64 {
    let ct = &plan.contacts[c];
    match ct.kind {
        ContactKind::Dof { dof } => ct.top.at(v) - v[dof],
        ContactKind::Epp => ct.top.at(v) - epp[c].v,
    }
}

/// Slip (floor minus dissipator displacement) of contact `c`.
#[inline]
pub(crate) fn slip(plan: &Plan, c: usize, u: &[f64], epp: &[EppState]) -> f64 {
    let ct = &plan.contacts[c];
    match ct.kind {
        ContactKind::Dof { dof } => ct.top.at(u) - u[dof],
        ContactKind::Epp => ct.top.at(u) - epp[c].u,
    }
}

/// Feeds the damper contacts' slip, slip rate `w` and friction force `f` at time `t` to
/// the per-damper recorder, when the plan's outputs ask for one (one branch otherwise).
#[inline]
#[allow(clippy::too_many_arguments)] // one observation of named quantities
pub(crate) fn observe_dampers(
    plan: &Plan,
    peaks: &mut Peaks,
    t: f64,
    u: &[f64],
    f: &[f64],
    w: &[f64],
    epp: &[EppState],
) {
    let Some(rec) = peaks.dampers.as_mut() else {
        return;
    };
    for (c, ct) in plan.contacts.iter().enumerate() {
        if ct.role == ContactRole::Damper {
            rec.observe(ct.slot, t, slip(plan, c, u, epp), w[c], f[c]);
        }
    }
}

/// |Base shear| = |Σ mᵢ(aᵢ + a_g) − P|, N, from M·r (`mr`, summing to `msum`), the
/// relative accelerations `a`, the ground acceleration and the harmonic force.
#[inline]
pub(crate) fn base_shear(mr: &[f64], msum: f64, a: &[f64], ag: f64, p: f64) -> f64 {
    signed_base_shear(mr, msum, a, ag, p).abs()
}

/// The base shear Σ mᵢ(aᵢ + a_g) − P with its sign, N ([`base_shear`]).
#[inline]
pub(crate) fn signed_base_shear(mr: &[f64], msum: f64, a: &[f64], ag: f64, p: f64) -> f64 {
    let mut vb = msum * ag - p;
    for (mi, ai) in mr.iter().zip(a) {
        vb += mi * ai;
    }
    vb
}

/// x̄ᵀ A x̄ with x̄ = (x0 + x1)/2, for a column-major square matrix, without allocating.
#[inline]
fn quad_avg(a: &DMatrix<f64>, x0: &[f64], x1: &[f64]) -> f64 {
    let n = x0.len();
    let mut total = 0.0;
    for (j, col) in a.as_slice().chunks_exact(n).enumerate() {
        let mut s = 0.0;
        for ((aij, p), q) in col.iter().zip(x0).zip(x1) {
            s += aij * 0.5 * (p + q);
        }
        total += s * 0.5 * (x0[j] + x1[j]);
    }
    total
}

/// Kinetic + strain energy (frame, braces with DOF, and EPP braces), J. No allocation.
pub(crate) fn stored_energy(plan: &Plan, u: &[f64], v: &[f64], epp: &[EppState]) -> (f64, f64) {
    debug_assert_eq!(u.len(), plan.dofs());
    let kinetic = 0.5 * quad_avg(&plan.mass, v, v);
    let strain = 0.5 * quad_avg(&plan.stiffness, u, u) + epp_strain(plan, u, epp);
    (kinetic, strain)
}

/// Strain energy of the elastic–perfectly plastic elements' braces, J.
#[inline]
pub(crate) fn epp_strain(plan: &Plan, u: &[f64], epp: &[EppState]) -> f64 {
    let mut strain = 0.0;
    for (c, ct) in plan.contacts.iter().enumerate() {
        if ct.kind == ContactKind::Epp {
            let uj = ct.bottom.at(u);
            let e = epp[c].u - uj;
            strain += 0.5 * ct.brace_stiffness * e * e;
        }
    }
    strain
}

/// A consistent initial state on the plan's DOFs.
pub(crate) struct Start {
    /// Displacements, m.
    pub(crate) u: Vec<f64>,
    /// Velocities, m/s.
    pub(crate) v: Vec<f64>,
    /// Accelerations, m/s².
    pub(crate) a: Vec<f64>,
    /// Friction forces, N.
    pub(crate) f: Vec<f64>,
    /// State of the elastic–perfectly plastic elements.
    pub(crate) epp: Vec<EppState>,
    /// Stuck (force strictly inside its bounds) per contact.
    pub(crate) stuck: Vec<bool>,
}

/// Consistent initial accelerations and friction forces.
///
/// Contacts whose dissipator has mass and whose initial slip rate is non-zero start
/// sliding at a bound; those with zero slip rate get their forces from the same box QP
/// at the acceleration level (Delassus BᵀM⁻¹B). A massless dissipator's force is its
/// brace force, which must lie within the bounds; its initial acceleration is taken
/// equal to its floor's (it enters only the first predictor, identically in reduced
/// and full plans).
pub(crate) fn initial_state(plan: &Plan) -> Result<Start, SimError> {
    let n = plan.dofs();
    let nc = plan.contacts.len();
    let u = plan.u0.clone();
    let v = plan.v0.clone();
    let ag0 = plan.ground_accel(0.0);
    let uu = DVector::from_column_slice(&u);
    let vv = DVector::from_column_slice(&v);
    let mut g = -(plan.mass_influence() * ag0) - &plan.damping * &vv - &plan.stiffness * &uu;
    if let Some(mr2) = plan.mass_influence2() {
        g -= mr2 * plan.ground2_accel(0.0);
    }
    if let Some(h) = &plan.harmonic {
        g[h.floor] += h.force(0.0);
    }
    let mut f = vec![0.0; nc];
    let mut known = vec![true; nc];
    let mut stuck = vec![false; nc];
    let mut epp = vec![EppState::default(); nc];
    for (c, ct) in plan.contacts.iter().enumerate() {
        let (uj, vj) = (ct.bottom.at(&u), ct.bottom.at(&v));
        let massless = match ct.kind {
            ContactKind::Epp => Some(plan.contact_x0[c]),
            ContactKind::Dof { dof } if plan.mass[(dof, dof)] == 0.0 => Some((u[dof], v[dof])),
            ContactKind::Dof { .. } => None,
        };
        if let Some((xd, vd)) = massless {
            let force = ct.brace_stiffness * (xd - uj) + ct.brace_damping * (vd - vj);
            let tol = 1e-12 * (ct.upper.abs().min(1e300) + ct.lower.abs().min(1e300) + force.abs());
            if force > ct.upper + tol || force < ct.lower - tol {
                let consistent = uj + force.clamp(ct.lower, ct.upper) / ct.brace_stiffness;
                return Err(SimError::Scene(format!(
                    "initial state: the massless dissipator of floor {} carries a brace force of {force:.6e} N, outside its friction bounds [{:.6e}, {:.6e}] N; a consistent initial dissipator displacement is {consistent:.9e} m",
                    ct.floor + 1,
                    ct.lower,
                    ct.upper
                )));
            }
            f[c] = force.clamp(ct.lower, ct.upper);
            stuck[c] = f[c] > ct.lower && f[c] < ct.upper;
            if ct.kind == ContactKind::Epp {
                epp[c] = EppState {
                    u: xd,
                    v: vd,
                    a: 0.0,
                };
            }
        } else if let ContactKind::Dof { dof } = ct.kind {
            let vf = ct.top.at(&v);
            let w0 = vf - v[dof];
            let tol = 1e-12 * (vf.abs() + v[dof].abs());
            if w0.abs() > tol {
                let bound = if w0 > 0.0 { ct.upper } else { ct.lower };
                if !bound.is_finite() {
                    return Err(SimError::Scene(format!(
                        "initial state: the locked dissipator of floor {} cannot slip, but its initial slip rate is {w0:.6e} m/s",
                        ct.floor + 1
                    )));
                }
                f[c] = bound;
            } else {
                known[c] = false;
                stuck[c] = true;
            }
        }
    }
    // −B F for the known forces.
    let apply = |g: &mut DVector<f64>, c: usize, force: f64| {
        let ct = &plan.contacts[c];
        ct.top.add(g.as_mut_slice(), -force);
        match ct.kind {
            ContactKind::Dof { dof } => g[dof] += force,
            ContactKind::Epp => ct.bottom.add(g.as_mut_slice(), force),
        }
    };
    for c in (0..nc).filter(|&c| known[c]) {
        apply(&mut g, c, f[c]);
    }
    let massive: Vec<usize> = (0..n).filter(|&d| plan.mass[(d, d)] > 0.0).collect();
    let ns = massive.len();
    let ms = DMatrix::from_fn(ns, ns, |i, j| plan.mass[(massive[i], massive[j])]);
    let chol = ms.cholesky().ok_or_else(|| SimError::NotPositiveDefinite {
        what: "mass matrix".into(),
        hint: String::new(),
    })?;
    let pos = |d: usize| massive.iter().position(|&x| x == d);
    let unknown: Vec<usize> = (0..nc).filter(|&c| !known[c]).collect();
    if !unknown.is_empty() {
        let mut bu = DMatrix::zeros(ns, unknown.len());
        for (k, &c) in unknown.iter().enumerate() {
            let ct = &plan.contacts[c];
            if let ContactKind::Dof { dof } = ct.kind
                && let Some(j) = pos(dof)
            {
                for (d, w) in ct.top.entries() {
                    if let Some(i) = pos(d) {
                        bu[(i, k)] = w;
                    }
                }
                bu[(j, k)] = -1.0;
            }
        }
        let gs = DVector::from_iterator(ns, massive.iter().map(|&d| g[d]));
        let y = chol.solve(&bu);
        let wa = bu.transpose() * &y;
        let wa = (&wa + wa.transpose()) * 0.5;
        let ba = bu.transpose() * chol.solve(&gs);
        let lo: Vec<f64> = unknown.iter().map(|&c| plan.contacts[c].lower).collect();
        let hi: Vec<f64> = unknown.iter().map(|&c| plan.contacts[c].upper).collect();
        let mut fu = vec![0.0; unknown.len()];
        let mut qp = BoxQp::new(wa.as_slice(), unknown.len())
            .map_err(|source| SimError::Friction { t: 0.0, source })?;
        qp.solve(ba.as_slice(), &lo, &hi, &mut fu)
            .map_err(|source| SimError::Friction { t: 0.0, source })?;
        for (k, &c) in unknown.iter().enumerate() {
            f[c] = fu[k];
            stuck[c] = qp.status(k) == Bound::Free;
            apply(&mut g, c, fu[k]);
        }
    }
    let gs = DVector::from_iterator(ns, massive.iter().map(|&d| g[d]));
    let a_s = chol.solve(&gs);
    let mut a = vec![0.0; n];
    for (i, &d) in massive.iter().enumerate() {
        a[d] = a_s[i];
    }
    for (c, ct) in plan.contacts.iter().enumerate() {
        match ct.kind {
            ContactKind::Dof { dof } if plan.mass[(dof, dof)] == 0.0 => a[dof] = ct.top.at(&a),
            ContactKind::Epp => epp[c].a = ct.top.at(&a),
            _ => {}
        }
    }
    Ok(Start {
        u,
        v,
        a,
        f,
        epp,
        stuck,
    })
}

/// Column names of the histories (the same for every method).
pub(crate) fn history_columns(plan: &Plan, energies: bool) -> History {
    let mut cols = vec!["t_s".to_string(), "ag_m_s2".to_string()];
    // A building in plan names its columns by what they measure (`x_3_rot_rad`,
    // `drift_D/3_m`, `F_D/3_N`): several lines share a storey.
    let labels = plan.labels.as_deref();
    match labels {
        None => cols.extend((1..=plan.points.len()).map(|i| format!("x{i}_m"))),
        Some(l) => cols.extend(l.points.iter().map(|p| {
            let unit = if p.ends_with("rot") { "rad" } else { "m" };
            format!("x_{}_{unit}", p.replace(' ', "_"))
        })),
    }
    // A yielding storey's plastic element: its position, force and slip rate (the
    // plastic drift rate), named xp, Fp, wp beside the dissipators' xd, F, w.
    let tag = |c: &crate::plan::Contact, damper: &str, storey: &str| match (c.role, labels) {
        (ContactRole::Damper, None) => format!("{damper}{}", c.floor + 1),
        (ContactRole::Storey, None) => format!("{storey}{}", c.floor + 1),
        (ContactRole::Damper, Some(l)) => format!("{damper}_{}", l.dampers[c.slot]),
        (ContactRole::Storey, Some(l)) => {
            format!("{storey}_{}", l.plastic[c.slot - plan.damper_slots])
        }
    };
    cols.extend(plan.contacts.iter().map(|c| tag(c, "xd", "xp") + "_m"));
    match labels {
        None => cols.extend((1..=plan.drifts.len()).map(|i| format!("drift{i}_m"))),
        Some(l) => cols.extend(
            l.drifts
                .iter()
                .map(|d| format!("drift_{}_m", d.replace(' ', "_"))),
        ),
    }
    cols.extend(plan.contacts.iter().map(|c| tag(c, "F", "Fp") + "_N"));
    cols.extend(plan.contacts.iter().map(|c| tag(c, "w", "wp") + "_m_s"));
    if energies {
        cols.extend(
            [
                "E_input_J",
                "E_kinetic_J",
                "E_strain_J",
                "E_viscous_J",
                "E_friction_J",
            ]
            .map(String::from),
        );
        if plan.has_yielding_storeys() {
            cols.push("E_plastic_J".into());
        }
    }
    let mut h = History {
        columns: cols,
        rows: Vec::new(),
    };
    h.rows.reserve((plan.steps + 1) * h.columns.len());
    h
}

/// Appends one history row (columns of [`history_columns`]).
#[allow(clippy::too_many_arguments)] // one row of named quantities
pub(crate) fn record_row(
    plan: &Plan,
    h: &mut History,
    t: f64,
    ag: f64,
    u: &[f64],
    f: &[f64],
    w: &[f64],
    epp: &[EppState],
    e: Option<EnergyRow>,
) {
    h.rows.push(t);
    h.rows.push(ag);
    h.rows.extend(plan.points.iter().map(|(p, _)| p.at(u)));
    for (c, ct) in plan.contacts.iter().enumerate() {
        h.rows.push(match ct.kind {
            ContactKind::Dof { dof } => u[dof],
            ContactKind::Epp => epp[c].u,
        });
    }
    for (top, bottom) in &plan.drifts {
        h.rows.push(top.at(u) - bottom.at(u));
    }
    h.rows.extend_from_slice(f);
    h.rows.extend_from_slice(w);
    if let Some(e) = e {
        push_energies(plan, h, &e);
    }
}

/// The energies of one history row: input, kinetic, strain, viscous, friction and plastic
/// dissipation (J).
pub(crate) type EnergyRow = [f64; 6];

/// Appends the energy columns of a history row (plastic only when a storey yields).
pub(crate) fn push_energies(plan: &Plan, h: &mut History, e: &EnergyRow) {
    let n = if plan.has_yielding_storeys() { 6 } else { 5 };
    h.rows.extend_from_slice(&e[..n]);
}

/// Energies accumulated step by step with step-averaged forces and velocities
/// (trapezoidal rule): input ∫(−a_g rᵀM + Pᵀ)u̇ dt, viscous ∫u̇ᵀCu̇ dt (plus the brace
/// dashpots of condensed dissipators), friction ∫Fᵀw dt.
#[derive(Debug, Clone, Default)]
pub(crate) struct EnergyAccumulator {
    /// Input energy so far, J.
    pub(crate) input: f64,
    /// Viscous dissipation so far, J.
    pub(crate) viscous: f64,
    /// Friction dissipation so far, J.
    pub(crate) friction: f64,
    /// Plastic dissipation of the yielding storeys so far, J.
    pub(crate) plastic: f64,
    /// Largest |balance error| / (|input| + initial) seen.
    pub(crate) balance_max_rel: f64,
    /// Area under the strain-energy history ∫ E_strain dt so far, J·s (trapezoidal).
    pub(crate) strain_area: f64,
    /// Strain energy at the end of the last step, J.
    strain_prev: f64,
    /// Kinetic and strain energy of the initial state, J.
    initial: (f64, f64),
}

/// One step's data for [`EnergyAccumulator::step`].
pub(crate) struct StepEnergyData<'a> {
    /// Time step, s.
    pub(crate) dt: f64,
    /// M r.
    pub(crate) mr: &'a [f64],
    /// Ground acceleration at the start and end of the step, m/s².
    pub(crate) ag: (f64, f64),
    /// A second ground component's M r₂ and accelerations at the step's start and end.
    pub(crate) second: Option<(&'a [f64], (f64, f64))>,
    /// Harmonic force at the start and end, N, and its floor.
    pub(crate) p: (f64, f64),
    /// Floor of the harmonic force.
    pub(crate) force_floor: Option<usize>,
    /// Velocities at the start and end.
    pub(crate) v: (&'a [f64], &'a [f64]),
    /// Friction forces at the start and end.
    pub(crate) f: (&'a [f64], &'a [f64]),
    /// Slip rates at the start and end.
    pub(crate) w: (&'a [f64], &'a [f64]),
    /// The end slip rate of an EPP element without a brace dashpot is its mean over the
    /// step (newmark's return mapping: its slip of the step / Δt), so its friction work is
    /// Δt·F̄·w₁; otherwise Δt·F̄·w̄ (the trapezoid, Newmark's own kinematics).
    pub(crate) epp_mean_rate: bool,
}

/// The quadratic forms of one step's energies, which each step loop evaluates with its
/// own storage of M, C and K.
#[derive(Debug, Clone, Copy)]
pub(crate) struct StepForms {
    /// v̄ᵀCv̄ with v̄ the step's mean velocity, W.
    pub(crate) cvv: f64,
    /// Kinetic energy at the end of the step, J.
    pub(crate) kinetic: f64,
    /// Strain energy at the end of the step (frame, braces with DOF and EPP braces), J.
    pub(crate) strain: f64,
}

impl StepForms {
    /// The forms from the plan's matrices (the loops with run-time sizes).
    pub(crate) fn of_plan(
        plan: &Plan,
        (v_old, v_now): (&[f64], &[f64]),
        u_now: &[f64],
        epp: &[EppState],
    ) -> StepForms {
        let (kinetic, strain) = stored_energy(plan, u_now, v_now, epp);
        StepForms {
            cvv: quad_avg(&plan.damping, v_old, v_now),
            kinetic,
            strain,
        }
    }
}

impl EnergyAccumulator {
    /// The run's energies at its end state (u, v, `epp`).
    pub(crate) fn finish(&self, plan: &Plan, u: &[f64], v: &[f64], epp: &[EppState]) -> Energy {
        let (ek, es) = stored_energy(plan, u, v, epp);
        Energy {
            input: self.input,
            kinetic: ek,
            strain: es,
            viscous: self.viscous,
            friction: self.friction,
            balance_error: self.input + self.initial_energy()
                - (ek + es + self.viscous + self.friction + self.plastic),
            plastic: plan.has_yielding_storeys().then_some(self.plastic),
        }
    }

    /// Starts from the initial state (u, v, `epp`): its stored energy is the balance's
    /// initial energy and the strain-energy area's first ordinate.
    pub(crate) fn start(plan: &Plan, u: &[f64], v: &[f64], epp: &[EppState]) -> Self {
        let (k0, s0) = stored_energy(plan, u, v, epp);
        EnergyAccumulator {
            strain_prev: s0,
            initial: (k0, s0),
            ..Default::default()
        }
    }

    /// Kinetic + strain energy of the initial state, J.
    pub(crate) fn initial_energy(&self) -> f64 {
        self.initial.0 + self.initial.1
    }

    /// The history row of the initial state (input, kinetic, strain, viscous, friction).
    pub(crate) fn initial_row(&self) -> EnergyRow {
        [0.0, self.initial.0, self.initial.1, 0.0, 0.0, 0.0]
    }

    /// Adds one step's increments, its quadratic forms `q` evaluated by the caller;
    /// returns the history row (input, kinetic, strain, viscous, friction) at the end of
    /// the step. `epp` is the elements' state at the end. Inlined, so that the fixed-size
    /// loop's compile-time lengths reach its loops.
    #[inline(always)]
    pub(crate) fn step(
        &mut self,
        plan: &Plan,
        d: &StepEnergyData<'_>,
        q: StepForms,
        epp: &[EppState],
    ) -> EnergyRow {
        let n = d.mr.len();
        let dt = d.dt;
        let (ag0, ag1) = d.ag;
        let (p0, p1) = d.p;
        let (v_old, v_now) = d.v;
        let (f_old, f_new) = d.f;
        let (w_old, w_new) = d.w;
        let ag_avg = 0.5 * (ag0 + ag1);
        let mut mrv = 0.0;
        for i in 0..n {
            mrv += d.mr[i] * 0.5 * (v_old[i] + v_now[i]);
        }
        let cvv = q.cvv;
        let mut d_input = -ag_avg * mrv;
        if let Some((mr2, (a0, a1))) = d.second {
            let mut m2v = 0.0;
            for i in 0..n {
                m2v += mr2[i] * 0.5 * (v_old[i] + v_now[i]);
            }
            d_input -= 0.5 * (a0 + a1) * m2v;
        }
        if let Some(f) = d.force_floor {
            d_input += 0.5 * (p0 + p1) * 0.5 * (v_old[f] + v_now[f]);
        }
        self.input += dt * d_input;
        self.viscous += dt * cvv;
        for c in 0..f_old.len() {
            let ct = &plan.contacts[c];
            let w_step = if d.epp_mean_rate && ct.is_algebraic() {
                w_new[c]
            } else {
                0.5 * (w_old[c] + w_new[c])
            };
            let work = dt * 0.5 * (f_old[c] + f_new[c]) * w_step;
            match ct.role {
                ContactRole::Damper => self.friction += work,
                ContactRole::Storey => self.plastic += work,
            }
            if ct.kind == ContactKind::Epp && ct.brace_damping > 0.0 {
                // Brace dashpot of a condensed dissipator: ė = v′ − v_below.
                let vj_old = ct.bottom.at(v_old);
                let vj_new = ct.bottom.at(v_now);
                let ed_old = (ct.top.at(v_old) - w_old[c]) - vj_old;
                let ed_new = epp[c].v - vj_new;
                let ed = 0.5 * (ed_old + ed_new);
                self.viscous += dt * ct.brace_damping * ed * ed;
            }
        }
        let (ek, es) = (q.kinetic, q.strain);
        self.strain_area += 0.5 * dt * (self.strain_prev + es);
        self.strain_prev = es;
        let bal = self.input + self.initial_energy()
            - (ek + es + self.viscous + self.friction + self.plastic);
        let scale = (self.input.abs() + self.initial_energy()).max(f64::MIN_POSITIVE);
        self.balance_max_rel = self.balance_max_rel.max(bal.abs() / scale);
        [
            self.input,
            ek,
            es,
            self.viscous,
            self.friction,
            self.plastic,
        ]
    }
}
