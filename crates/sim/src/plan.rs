//! Plans: a scene compiled into only the effects that matter (docs/MODEL.md § Scenes and plans).
//!
//! Degrees of freedom are the floors (0..N) followed by the dissipators that keep one.
//! With `reduce` on:
//! - a floor without a dissipator, or whose slip load is zero, has no dissipator DOF and
//!   no brace (a bare storey: the μN = 0 limit of docs/MODEL.md § The model);
//! - a locked dissipator (μN = ∞) is merged into its floor: its mass is added to the
//!   floor and its brace joins floors i−1 and i directly (a braced storey);
//! - a massless dissipator (m′ = 0) becomes an elastic–perfectly plastic element between
//!   floors i−1 and i: no DOF, its brace elongation carried as internal state;
//! - every other dissipator keeps its DOF and a friction contact with its floor.
//!
//! With `reduce` off every dissipator keeps its DOF and contact (the full 2N model, with
//! zero masses where m′ = 0): tests compare both.

use crate::building::{Building, Dissipator};
use crate::error::SimError;
use crate::kinematics::{Kin, add_between};
use crate::scene::{Harmonic, MethodName, MethodSettings, OutputsConfig, Scene};
use nalgebra::{DMatrix, DVector};
use slipload_motion::Record;
use std::fmt::Write as _;
use std::sync::Arc;

/// How a contact's dissipator side is modelled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactKind {
    /// The dissipator is a DOF (`dof`), joined by its brace to the floor below.
    Dof {
        /// Index of the dissipator DOF.
        dof: usize,
    },
    /// Massless dissipator condensed into an elastic–perfectly plastic element.
    Epp,
}

/// What a contact models.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactRole {
    /// A friction dissipator on its brace.
    Damper,
    /// The elastic–perfectly plastic part (1−α)k, yielding at (1−α)Fy, of a storey whose
    /// shear–drift law is bilinear: `floor` is the storey's top floor, `below` its bottom.
    Storey,
}

/// One friction contact between floor `floor` and its dissipator (or, for a
/// [`ContactRole::Storey`] contact, the plastic element of storey `floor + 1`).
///
/// The contact acts along kinematic vectors ([`Kin`]): its friction force acts between
/// the point `top` (the floor it is on) and its dissipator; its brace (or plastic
/// element) joins the dissipator to the point `bottom` (the floor below, or the ground).
/// In a chain `top` is floor `floor`'s DOF and `bottom` the floor below's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// What the contact models.
    pub role: ContactRole,
    /// Index of the storey (0-based, its top floor) the contact is in: names it in
    /// messages and columns.
    pub floor: usize,
    /// Where its slip peak and transitions go in [`crate::response::Peaks`]: a damper's
    /// index among the plan's damper slots, or [`Plan::damper_slots`] + the index of a
    /// yielding storey's plastic element. In a chain a damper's slot is its floor and a
    /// plastic element's the floor count + its floor.
    pub slot: usize,
    /// The point on the floor the friction acts at.
    pub top: Kin,
    /// The point the brace starts from ([`Kin::GROUND`] for the ground).
    pub bottom: Kin,
    /// Dissipator model.
    pub kind: ContactKind,
    /// Lower friction bound F⁻, N.
    pub lower: f64,
    /// Upper friction bound F⁺, N.
    pub upper: f64,
    /// Brace stiffness k′, N/m.
    pub brace_stiffness: f64,
    /// Brace damping c′, N·s/m.
    pub brace_damping: f64,
}

impl Contact {
    /// The floor below in a chain: the bottom point's DOF (`None` for the ground). Read by
    /// the chain-only step loops alone ([`Plan::is_chain`]), where the top point is the
    /// DOF `floor`.
    #[inline]
    pub fn below(&self) -> Option<usize> {
        self.bottom.as_dof()
    }

    /// An elastic–perfectly plastic element without a brace dashpot (c′ = 0): its condensed
    /// massless DOF is algebraic (the brace force k′e is the friction force), which
    /// `newmark` steps by the return mapping (docs/MODEL.md § Integrators).
    pub fn is_algebraic(&self) -> bool {
        self.kind == ContactKind::Epp && self.brace_damping == 0.0
    }
}

/// What each floor carries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FloorLink {
    /// No dissipator in the model.
    None,
    /// Friction contact number `.0`.
    Contact(usize),
    /// Locked dissipator, merged into the floor.
    Locked,
}

/// What a plan that is not a chain measures, by name: its drifts, points and damper
/// slots (a chain's are its storeys, floors and floors' dampers, by number).
#[derive(Debug, Clone, PartialEq)]
pub struct Labels {
    /// One name per drift ([`Plan::drifts`]).
    pub drifts: Vec<String>,
    /// The storey (0-based) of each drift.
    pub drift_storeys: Vec<usize>,
    /// One name per point ([`Plan::points`]).
    pub points: Vec<String>,
    /// One name per damper slot.
    pub dampers: Vec<String>,
    /// One name per yielding storey's plastic element, in slot order.
    pub plastic: Vec<String>,
    /// Per storey, the drifts at the plan's four edges — along x at its least and largest
    /// y, along y at its least and largest x — when the plan's size is known: the
    /// torsional irregularity ratio compares them.
    pub edges: Option<Vec<[usize; 4]>>,
}

/// A second horizontal ground component applied with the first (a building in plan under
/// both components of a pair at once): its record, its influence on the DOFs and on the
/// measured points.
#[derive(Debug, Clone)]
pub struct SecondGround {
    /// The record, m/s².
    pub record: Arc<Record>,
    /// Its ground influence r₂ on the DOFs (the load is −M·r₂·a_g₂).
    pub influence: DVector<f64>,
    /// Its influence on each point of [`Plan::points`].
    pub points: Vec<f64>,
}

/// What a building in plan's base carries: its shear along x and y and its torque about
/// the building's centre of mass, each a row of weights on the absolute accelerations.
/// Row k is M·e_k for the base's rigid motion e_k (a unit translation along x, along y, a
/// unit rotation about that centre: every floor's origin moving with it, a damper's DOF
/// by its line's share), so the base's reaction is e_kᵀ M (a + r₁ a_g₁ + r₂ a_g₂): the
/// inertia forces' resultant, as a chain's base shear Σ mᵢ(aᵢ + a_g) is.
#[derive(Debug, Clone)]
pub struct BaseRows {
    /// The point the torque is taken about [x, y], m: the floors' masses' centroid.
    pub about: [f64; 2],
    /// M·e_x, M·e_y, M·e_θ on the plan's DOFs (kg, kg, kg·m).
    pub rows: [DVector<f64>; 3],
    /// Each row times the first component's influence r₁: its ground acceleration's share.
    pub first: [f64; 3],
    /// Each row times the second component's influence r₂ (zeros without one).
    pub second: [f64; 3],
}

/// A compiled scene.
#[derive(Debug, Clone)]
pub struct Plan {
    /// Scene name.
    pub name: String,
    /// Number of floors N.
    pub floors: usize,
    /// Mass matrix on the plan's DOFs, kg.
    pub mass: DMatrix<f64>,
    /// Damping matrix, N·s/m.
    pub damping: DMatrix<f64>,
    /// Stiffness matrix, N/m.
    pub stiffness: DMatrix<f64>,
    /// Friction contacts.
    pub contacts: Vec<Contact>,
    /// Number of damper slots of [`crate::response::Peaks`] (a chain: one per floor);
    /// yielding storeys' plastic elements take the slots after them.
    pub damper_slots: usize,
    /// The drifts the responses measure, each between two points (`top`, `bottom`): a
    /// chain's storeys, floor i's DOF over floor i − 1's (the ground's for the first).
    pub drifts: Vec<(Kin, Kin)>,
    /// The points whose displacement and absolute acceleration the responses measure (a
    /// chain's floors), with each point's ground influence (the component of a unit
    /// ground displacement along the point's direction; 1 in a chain).
    pub points: Vec<(Kin, f64)>,
    /// The ground influence r on the DOFs: the displacement of each DOF under a unit
    /// ground displacement (1 everywhere in a chain); the ground's load is −M·r·a_g.
    pub influence: DVector<f64>,
    /// Whether the plan is a chain of floors ([`Plan::is_chain`]).
    pub chain: bool,
    /// The names of what a plan that is not a chain measures (`None` for a chain).
    pub labels: Option<Arc<Labels>>,
    /// Number of the structure's own DOFs (the floors' DOFs, before the dissipators').
    pub frame_dofs: usize,
    /// Per floor: its dissipator's model.
    pub links: Vec<FloorLink>,
    /// Storey heights, m.
    pub storey_heights: Option<Vec<f64>>,
    /// Ground record, m/s².
    pub record: Option<Arc<Record>>,
    /// A second ground component applied with `record` (`None` for a chain).
    pub second: Option<SecondGround>,
    /// A building in plan's base shears and torque as rows on the accelerations (`None`
    /// for a chain, whose base shear is its own sum).
    pub base: Option<Arc<BaseRows>>,
    /// Harmonic floor force.
    pub harmonic: Option<Harmonic>,
    /// Initial displacements on the plan's DOFs, m.
    pub u0: Vec<f64>,
    /// Initial velocities on the plan's DOFs, m/s.
    pub v0: Vec<f64>,
    /// Initial dissipator displacement and velocity per contact (used by EPP contacts).
    pub contact_x0: Vec<(f64, f64)>,
    /// Method and time step.
    pub method: MethodSettings,
    /// Number of steps.
    pub steps: usize,
    /// What to compute.
    pub outputs: OutputsConfig,
    /// Fundamental period of the bare frame, s.
    pub t1: f64,
    /// Yield drift Fy/k of each storey that yields.
    pub yield_drift: Vec<Option<f64>>,
    /// Drift of each storey (m) past which the run stops with a collapse, when set.
    pub collapse_drift: Option<Vec<f64>>,
    /// One line per decision, for `slipload explain`.
    pub notes: Vec<String>,
}

/// Ground accelerations at successive steps ([`Plan::ground_steps`]).
#[derive(Debug, Clone)]
pub struct GroundSteps<'a>(Option<slipload_motion::StepSampler<'a>>);

impl GroundSteps<'_> {
    /// The ground acceleration at the next step, m/s² (0 without a record).
    #[inline]
    pub fn next_accel(&mut self) -> f64 {
        self.0.as_mut().map_or(0.0, |s| s.next_accel())
    }
}

/// The step and duration are usable and the run is within [`crate::limits`]: checked
/// before anything is allocated.
fn check_steps(scene: &Scene) -> Result<(), SimError> {
    check_step_count(scene.method.dt, scene.duration)
}

/// [`check_steps`] on a step `dt` and a `duration` (s): also a plan in plan's.
pub(crate) fn check_step_count(dt: f64, duration: f64) -> Result<(), SimError> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(SimError::BadTimeStep { dt });
    }
    if !(duration.is_finite() && duration > 0.0) {
        return Err(SimError::Scene(format!(
            "duration {duration} s must be positive and finite"
        )));
    }
    if dt > duration * (1.0 + 1e-9) {
        return Err(SimError::StepTooLong {
            dt,
            what: "the simulated duration".into(),
            span: duration,
            consequence: "the run would be one step that ends past the duration, and its peaks would miss the response in between; give a step of at most the duration (the default is T1/400)".into(),
        });
    }
    let steps = duration / dt;
    crate::limits::check(
        &format!("{duration} s at dt = {dt:e} s"),
        steps,
        crate::limits::MAX_STEPS,
        &|v| format!("{} integration steps", crate::limits::count(v)),
    )
}

impl Plan {
    /// Compiles a scene.
    pub fn compile(scene: &Scene) -> Result<Plan, SimError> {
        check_steps(scene)?;
        let b: &Building = &scene.building;
        let n = b.floors();
        let reduce = scene.reduce;
        let mut notes = Vec::new();
        // `bilinear` ignores dissipator inertia: brace + damper become one EPP spring.
        let bilinear = scene.method.name == MethodName::Bilinear;
        let dissipators: Vec<Option<Dissipator>> = b
            .dissipators
            .iter()
            .map(|d| {
                d.map(|d| {
                    if bilinear {
                        Dissipator { mass: 0.0, ..d }
                    } else {
                        d
                    }
                })
            })
            .collect();
        if bilinear && b.dissipators.iter().flatten().any(|d| d.mass > 0.0) {
            notes.push("method bilinear: dissipator masses ignored (m' -> 0), each brace + damper is one elastic-perfectly plastic spring".into());
        }
        // A damper at zero slip load is a bare storey, unless the run carries the
        // derivatives with respect to the slip loads: then it stays a contact whose bounds
        // are zero (the derivative at F = 0 is the one-sided one of a damper that slips).
        let drop_free = |d: &Dissipator| d.is_free() && !scene.outputs.sensitivities;
        // First pass: which floors keep a dissipator DOF.
        let mut dof_of = vec![None; n];
        let mut n_dof = n;
        for (f, d) in dissipators.iter().enumerate() {
            let Some(d) = d else { continue };
            let keep = !reduce || !(drop_free(d) || d.is_locked() || d.mass == 0.0);
            if keep {
                dof_of[f] = Some(n_dof);
                n_dof += 1;
            }
        }
        let mut mass = DMatrix::zeros(n_dof, n_dof);
        let ends = |f: usize| (Kin::dof(f), Kin::floor_or_ground(f.checked_sub(1)));
        let mut damping = DMatrix::zeros(n_dof, n_dof);
        let mut stiffness = DMatrix::zeros(n_dof, n_dof);
        mass.view_mut((0, 0), (n, n)).copy_from(&b.mass);
        damping.view_mut((0, 0), (n, n)).copy_from(&b.damping);
        stiffness.view_mut((0, 0), (n, n)).copy_from(&b.stiffness);
        let mut contacts = Vec::new();
        let mut links = vec![FloorLink::None; n];
        let mut contact_x0 = Vec::new();
        let ic = &scene.initial;
        let mut u0: Vec<f64> = ic.floor_displacement.clone();
        let mut v0: Vec<f64> = ic.floor_velocity.clone();
        u0.resize(n_dof, 0.0);
        v0.resize(n_dof, 0.0);
        for (f, d) in dissipators.iter().enumerate() {
            let storey = f + 1;
            let Some(d) = d else {
                notes.push(format!("floor {storey}: no dissipator"));
                continue;
            };
            if reduce && drop_free(d) {
                notes.push(format!("floor {storey}: slip load 0 -> brace disconnected, no dissipator DOF (bare storey)"));
                continue;
            }
            let (top, bottom) = ends(f);
            if reduce && d.is_locked() {
                mass[(f, f)] += d.mass;
                add_between(&mut stiffness, &top, &bottom, d.brace_stiffness);
                add_between(&mut damping, &top, &bottom, d.brace_damping);
                links[f] = FloorLink::Locked;
                notes.push(format!(
                    "floor {storey}: locked -> dissipator merged into the floor (m' = {} kg added), brace k' = {:.6e} N/m joins floors {} and {storey}",
                    d.mass, d.brace_stiffness, f
                ));
                continue;
            }
            let kind = match dof_of[f] {
                Some(dof) => {
                    mass[(dof, dof)] = d.mass;
                    add_between(&mut stiffness, &Kin::dof(dof), &bottom, d.brace_stiffness);
                    add_between(&mut damping, &Kin::dof(dof), &bottom, d.brace_damping);
                    u0[dof] = ic.dissipator_displacement[f];
                    v0[dof] = ic.dissipator_velocity[f];
                    notes.push(format!(
                        "floor {storey}: friction contact, dissipator DOF {dof} (m' = {} kg, k' = {:.6e} N/m, c' = {} N*s/m), bounds [{:.6e}, {:.6e}] N{}",
                        d.mass,
                        d.brace_stiffness,
                        d.brace_damping,
                        d.lower,
                        d.upper,
                        if d.mass == 0.0 { " (massless DOF kept: unreduced plan)" } else { "" }
                    ));
                    ContactKind::Dof { dof }
                }
                None => {
                    notes.push(format!(
                        "floor {storey}: m' = 0 -> elastic-perfectly plastic element between floors {f} and {storey} (k' = {:.6e} N/m, c' = {} N*s/m, bounds [{:.6e}, {:.6e}] N), no DOF",
                        d.brace_stiffness, d.brace_damping, d.lower, d.upper
                    ));
                    ContactKind::Epp
                }
            };
            links[f] = FloorLink::Contact(contacts.len());
            let (mut xd0, vd0) = (ic.dissipator_displacement[f], ic.dissipator_velocity[f]);
            let had_mass = b.dissipators[f].is_some_and(|orig| orig.mass > 0.0);
            if bilinear && had_mass && kind == ContactKind::Epp {
                // Ignoring m′ is the limit m′ → 0, in which a dissipator displaced beyond
                // its slip load slides instantly until its brace force is on the bound.
                let (xj, vj) = (bottom.at(&u0), bottom.at(&v0));
                let viscous = d.brace_damping * (vd0 - vj);
                let force = d.brace_stiffness * (xd0 - xj) + viscous;
                let clamped = force.clamp(d.lower, d.upper);
                if clamped != force {
                    xd0 = xj + (clamped - viscous) / d.brace_stiffness;
                    notes.push(format!(
                        "floor {storey}: bilinear (m' -> 0): initial dissipator displacement moved to {xd0:.9e} m so the brace force {force:.6e} N sits on the slip load {clamped:.6e} N (instant slide)"
                    ));
                }
            }
            contact_x0.push((xd0, vd0));
            contacts.push(Contact {
                role: ContactRole::Damper,
                floor: f,
                slot: f,
                top,
                bottom,
                kind,
                lower: d.lower,
                upper: d.upper,
                brace_stiffness: d.brace_stiffness,
                brace_damping: d.brace_damping,
            });
        }
        // Yielding storeys: the spring k of storey i splits into an elastic αk, which stays
        // in K, and an elastic–perfectly plastic (1−α)k yielding at (1−α)Fy, which is a
        // contact between floors i−1 and i like a massless dissipator. Appended after the
        // dissipators, so a building without them compiles to the same contacts.
        for (f, y) in b.storey_yield.iter().enumerate() {
            let Some(y) = y else { continue };
            let storey = f + 1;
            let (top, bottom) = ends(f);
            let kp = (1.0 - y.post_yield_ratio) * y.stiffness;
            let fp = (1.0 - y.post_yield_ratio) * y.yield_shear;
            add_between(&mut stiffness, &top, &bottom, -kp);
            // Unstressed plastic element: it starts stuck with the storey's elastic force;
            // a storey displaced beyond yield at rest has yielded to its bound.
            let uj = bottom.at(&u0);
            let force = kp * (top.at(&u0) - uj);
            let clamped = force.clamp(-fp, fp);
            let x0 = uj + clamped / kp;
            if clamped != force {
                notes.push(format!(
                    "storey {storey}: initial drift {:.6e} m is beyond yield ({:.6e} m): starts yielded, plastic drift {:.6e} m",
                    u0[f] - uj,
                    y.yield_drift(),
                    u0[f] - x0
                ));
            }
            notes.push(format!(
                "storey {storey}: yields (k = {:.6e} N/m, Fy = {:.6e} N, yield drift {:.6e} m, alpha = {}) -> elastic {:.6e} N/m in K + elastic-perfectly plastic element between floors {f} and {storey} (k = {kp:.6e} N/m, bounds +-{fp:.6e} N), no DOF",
                y.stiffness,
                y.yield_shear,
                y.yield_drift(),
                y.post_yield_ratio,
                y.post_yield_ratio * y.stiffness,
            ));
            contact_x0.push((x0, v0[f]));
            contacts.push(Contact {
                role: ContactRole::Storey,
                floor: f,
                slot: n + f,
                top,
                bottom,
                kind: ContactKind::Epp,
                lower: -fp,
                upper: fp,
                brace_stiffness: kp,
                brace_damping: 0.0,
            });
        }
        // P-Δ: the linearised geometric stiffness −Pᵢ/hᵢ of every storey.
        if let (Some(p), Some(h)) = (&b.gravity_loads, &b.storey_heights) {
            for (f, (pi, hi)) in p.iter().zip(h).enumerate() {
                let (top, bottom) = ends(f);
                add_between(&mut stiffness, &top, &bottom, -pi / hi);
            }
            notes.push(format!(
                "P-Delta: geometric stiffness -P/h per storey, P = [{}] N over h = [{}] m",
                p.iter()
                    .map(|v| format!("{v:.6e}"))
                    .collect::<Vec<_>>()
                    .join(", "),
                h.iter()
                    .map(|v| format!("{v}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
            if b.storey_yield.iter().any(Option::is_some) {
                // What P-Δ leaves of a yielded storey: its tangent αk − P/h.
                let tangents: Vec<String> = b
                    .storey_yield
                    .iter()
                    .zip(p.iter().zip(h))
                    .map(|(y, (pi, hi))| match y {
                        Some(y) => format!("{:.4e}", y.post_yield_ratio * y.stiffness - pi / hi),
                        None => "elastic".into(),
                    })
                    .collect();
                notes.push(format!(
                    "P-Delta: post-yield tangent alpha*k - P/h per storey [{}] N/m (negative: a yielded storey loses stiffness and can ratchet to the collapse limit)",
                    tangents.join(", ")
                ));
            }
        }
        if let Some(limit) = &b.collapse_drift {
            notes.push(format!(
                "collapse limit: a storey drift past [{}] m stops the run and reports the collapse (storey, time, drift)",
                limit
                    .iter()
                    .map(|v| format!("{v:.4}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        // The initial stiffness (every contact stuck, its brace or plastic element
        // elastic) must be positive definite (it is for valid buildings; a check here
        // turns a modelling slip into an error instead of a wrong answer). Yielded, a
        // storey with P-Δ may lose stiffness: that is the instability the run reports.
        let mut initial = stiffness.clone();
        for ct in contacts.iter().filter(|c| c.kind == ContactKind::Epp) {
            add_between(&mut initial, &ct.top, &ct.bottom, ct.brace_stiffness);
        }
        if initial.cholesky().is_none() {
            return Err(SimError::NotPositiveDefinite {
                what: "assembled stiffness matrix".into(),
                hint: if b.gravity_loads.is_some() {
                    " (with P-Delta: the gravity loads exceed what the elastic frame carries)"
                        .into()
                } else {
                    " (check the frame stiffness and the brace stiffnesses)".into()
                },
            });
        }
        let steps = scene.steps();
        if scene.outputs.histories {
            // t, a_g, x and drift per floor, x′, F and w per contact, five energies
            let cols = 2 + 2 * n + 3 * contacts.len() + if scene.outputs.energies { 5 } else { 0 };
            let values = (steps as f64 + 1.0) * cols as f64;
            crate::limits::check(
                &format!(
                    "time histories of {} steps x {cols} columns",
                    crate::limits::count(steps as f64 + 1.0)
                ),
                values * crate::limits::HISTORY_BYTES_PER_VALUE,
                crate::limits::MAX_HISTORY_BYTES,
                &crate::limits::bytes,
            )?;
        }
        let dampers = contacts
            .iter()
            .filter(|c| c.role == ContactRole::Damper)
            .count();
        notes.push(format!(
            "{}, {} ({} with DOF, {} elastic-perfectly plastic)",
            counted(n_dof, "DOF", "DOFs")
                + &format!(
                    " ({} + {})",
                    counted(n, "floor", "floors"),
                    counted(n_dof - n, "dissipator", "dissipators")
                ),
            counted(dampers, "friction contact", "friction contacts"),
            contacts
                .iter()
                .filter(|c| matches!(c.kind, ContactKind::Dof { .. }))
                .count(),
            contacts
                .iter()
                .filter(|c| c.kind == ContactKind::Epp && c.role == ContactRole::Damper)
                .count()
        ));
        let storeys = contacts
            .iter()
            .filter(|c| c.role == ContactRole::Storey)
            .count();
        if storeys > 0 {
            notes.push(format!(
                "{} as elastic-perfectly plastic elements (no DOF)",
                counted(storeys, "yielding storey", "yielding storeys")
            ));
        }
        notes.push(format!(
            "method {} (alpha = {}), dt = {:.6e} s (T1/{:.1}, bare T1 = {:.4} s), {} steps over {:.4} s",
            scene.method.name.as_str(),
            scene.method.alpha,
            scene.method.dt,
            b.t1() / scene.method.dt,
            b.t1(),
            steps,
            steps as f64 * scene.method.dt
        ));
        match &scene.record {
            Some(r) => notes.push(format!(
                "ground motion: {} ({} samples at dt = {} s, PGA = {:.4} m/s^2)",
                r.name(),
                r.len(),
                r.dt(),
                r.pga()
            )),
            None => notes.push("ground motion: none".into()),
        }
        notes.extend(scene.notes.iter().cloned());
        if let Some(h) = &scene.harmonic {
            notes.push(format!(
                "harmonic force on floor {}: {:.6e} N at {} rad/s",
                h.floor + 1,
                h.amplitude,
                h.omega
            ));
        }
        notes.push(format!(
            "outputs: peaks{}{}{}",
            if scene.outputs.energies {
                ", energies"
            } else {
                " (energies off: not accumulated)"
            },
            if scene.outputs.histories {
                ", histories"
            } else {
                " (no histories: memory independent of duration)"
            },
            if scene.outputs.dampers {
                ", per-damper demands"
            } else {
                ""
            }
        ));
        Ok(Plan {
            name: scene.name.clone(),
            floors: n,
            influence: DVector::from_element(n_dof, 1.0),
            mass,
            damping,
            stiffness,
            contacts,
            damper_slots: n,
            drifts: (0..n).map(ends).collect(),
            points: (0..n).map(|f| (Kin::dof(f), 1.0)).collect(),
            chain: true,
            labels: None,
            frame_dofs: n,
            links,
            storey_heights: b.storey_heights.clone(),
            record: scene.record.clone(),
            second: None,
            base: None,
            harmonic: scene.harmonic,
            u0,
            v0,
            contact_x0,
            method: scene.method,
            steps,
            outputs: scene.outputs,
            t1: b.t1(),
            yield_drift: b
                .storey_yield
                .iter()
                .map(|y| y.map(|y| y.yield_drift()))
                .collect(),
            collapse_drift: b.collapse_drift.clone(),
            notes,
        })
    }

    /// What the plan's method cannot model, refused before its first step. Every
    /// integrator calls it as its run starts, and `explain` through
    /// [`crate::simulate::check`], so both refuse the same scenes with the same words:
    /// - `delacruz`: yielding storeys (its three-level iteration is written for
    ///   dissipators on braces; a storey's own plastic element is not among the cases it
    ///   resolves), and zero-mass dissipator DOFs (unreduced plans), where its dissipator
    ///   equation degenerates;
    /// - `exact`: zero-mass dissipator DOFs, which it cannot integrate (it needs M⁻¹).
    pub fn check_method(&self) -> Result<(), SimError> {
        let name = self.method.name;
        if !self.chain {
            if name == MethodName::Delacruz {
                return Err(SimError::Scene(
                    "delacruz steps a chain of floors (its loops run floor by floor); a building in plan runs with exact (the reference), newmark, hht or bilinear".into(),
                ));
            }
            if self.outputs.sensitivities {
                return Err(SimError::Scene(
                    "outputs.sensitivities: the derivatives with respect to the slip loads are computed for a chain of floors; a building in plan runs without them".into(),
                ));
            }
        }
        if self.outputs.sensitivities && matches!(name, MethodName::Delacruz | MethodName::Exact) {
            return Err(SimError::Scene(format!(
                "outputs.sensitivities: the derivatives with respect to the slip loads are computed by newmark, hht and bilinear, not by {}",
                name.as_str()
            )));
        }
        if name == MethodName::Delacruz && self.has_yielding_storeys() {
            return Err(SimError::Scene(
                "delacruz does not model yielding storeys; use exact (the reference) or newmark, which treat a storey's plastic element like a massless dissipator".into(),
            ));
        }
        let massless_dof = self
            .contacts
            .iter()
            .find(|ct| matches!(ct.kind, ContactKind::Dof { dof } if self.mass[(dof, dof)] <= 0.0));
        match (name, massless_dof) {
            (MethodName::Delacruz, Some(ct)) => Err(SimError::Scene(format!(
                "delacruz: the dissipator of floor {} is a zero-mass DOF of an unreduced plan, where the method's dissipator equation degenerates; set \"reduce\": true to model it as an elastic-perfectly plastic contact",
                ct.floor + 1
            ))),
            (MethodName::Exact, Some(ct)) => Err(SimError::Scene(format!(
                "exact: the dissipator of floor {} has zero mass but keeps a DOF (unreduced plan); compile the scene with \"reduce\": true so it becomes the equivalent elastic-perfectly plastic element",
                ct.floor + 1
            ))),
            _ => Ok(()),
        }
    }

    /// Whether a storey yields (its plastic element is a [`ContactRole::Storey`] contact).
    pub fn has_yielding_storeys(&self) -> bool {
        self.contacts.iter().any(|c| c.role == ContactRole::Storey)
    }

    /// Number of DOFs.
    pub fn dofs(&self) -> usize {
        self.mass.nrows()
    }

    /// Ground acceleration at `t`, m/s².
    #[inline]
    pub fn ground_accel(&self, t: f64) -> f64 {
        self.record.as_ref().map_or(0.0, |r| r.accel_at(t))
    }

    /// Ground accelerations at the steps `t = dt, 2dt, …` of the plan's method, one per
    /// [`GroundSteps::next_accel`] call: the values of [`Plan::ground_accel`] without a
    /// division per step.
    pub fn ground_steps(&self) -> GroundSteps<'_> {
        GroundSteps(self.record.as_ref().map(|r| r.steps(self.method.dt)))
    }

    /// The second ground component's acceleration at `t`, m/s² (0 without one).
    #[inline]
    pub fn ground2_accel(&self, t: f64) -> f64 {
        self.second.as_ref().map_or(0.0, |g| g.record.accel_at(t))
    }

    /// The second component's accelerations at the steps, as [`Plan::ground_steps`].
    pub fn ground2_steps(&self) -> GroundSteps<'_> {
        GroundSteps(self.second.as_ref().map(|g| g.record.steps(self.method.dt)))
    }

    /// M·r₂ of the second component, kg.
    pub fn mass_influence2(&self) -> Option<DVector<f64>> {
        self.second.as_ref().map(|g| &self.mass * &g.influence)
    }

    /// r₁ᵀ·M·r₂: the base shear along the first component's direction per unit
    /// acceleration of the second (0 without one), kg.
    pub fn cross_mass(&self) -> f64 {
        self.second
            .as_ref()
            .map_or(0.0, |g| self.influence.dot(&(&self.mass * &g.influence)))
    }

    /// Harmonic force at `t`, N (0 without one).
    #[inline]
    pub fn force(&self, t: f64) -> f64 {
        self.harmonic.as_ref().map_or(0.0, |h| h.force(t))
    }

    /// The influence matrix B (DOFs × contacts): column c is top − e(dissipator) for a
    /// contact with DOF, top − bottom for an elastic–perfectly plastic one (in a chain
    /// e(floor) − e(dissipator) and e(floor) − e(floor below)).
    pub fn contact_matrix(&self) -> DMatrix<f64> {
        let mut bm = DMatrix::zeros(self.dofs(), self.contacts.len());
        for (c, ct) in self.contacts.iter().enumerate() {
            self.contact_column(ct, &mut bm.column_mut(c));
        }
        bm
    }

    /// Column `c` of [`Plan::contact_matrix`] written into `col` (zeros on entry).
    pub fn contact_column(&self, ct: &Contact, col: &mut nalgebra::DVectorViewMut<'_, f64>) {
        let slice = col.as_mut_slice();
        ct.top.add(slice, 1.0);
        match ct.kind {
            ContactKind::Dof { dof } => slice[dof] -= 1.0,
            ContactKind::Epp => ct.bottom.add(slice, -1.0),
        }
    }

    /// Where the contacts start among `exact`'s observed functions: after the drifts, the
    /// points' displacements and accelerations, and the base shear.
    pub fn observed_contacts_offset(&self) -> usize {
        self.drifts.len() + 2 * self.points.len() + 1
    }

    /// Whether every element is a chain's: its points single DOFs of weight 1 (or the
    /// ground), the ground influence 1 on every DOF and the drifts the storeys'. The
    /// chain-only step loops (`newmark`'s banded and fixed-size loops, `delacruz`) run
    /// such plans alone.
    pub fn is_chain(&self) -> bool {
        self.chain
    }

    /// The half-bandwidth of the plan's operators: the largest |i − j| of a non-zero entry
    /// of M, C or K, or of two DOFs a friction contact joins (an elastic–perfectly plastic
    /// contact joins its floor and the floor below; a contact with DOF its floor and its
    /// dissipator). 1 for a shear building (storey stiffness, Rayleigh or storey damping)
    /// with massless dissipators; a condensed frame matrix or modal damping is full
    /// (n − 1). The banded step of `newmark` runs in O(N·bandwidth) per step on it.
    pub fn half_bandwidth(&self) -> usize {
        let n = self.dofs();
        let mut p = 0;
        for a in [&self.mass, &self.damping, &self.stiffness] {
            for j in 0..n {
                for i in j + p + 1..n {
                    if a[(i, j)] != 0.0 || a[(j, i)] != 0.0 {
                        p = i - j;
                    }
                }
            }
        }
        for ct in &self.contacts {
            let other = match ct.kind {
                ContactKind::Dof { dof } => Some(dof),
                ContactKind::Epp => ct.bottom.max_dof(),
            };
            let ends: Vec<usize> = ct.top.entries().map(|(i, _)| i).chain(other).collect();
            for &i in &ends {
                for &j in &ends {
                    p = p.max(i.abs_diff(j));
                }
            }
        }
        p
    }

    /// M·r, with r the ground influence ([`Plan::influence`]; 1 on every DOF of a chain:
    /// all displacements are relative to the ground), kg.
    pub fn mass_influence(&self) -> DVector<f64> {
        &self.mass * &self.influence
    }

    /// rᵀ·M·r: the mass the ground accelerates (a chain's total mass), kg.
    pub fn influence_mass(&self) -> f64 {
        let mr = self.mass_influence();
        if self.chain {
            mr.iter().sum()
        } else {
            self.influence.dot(&mr)
        }
    }

    /// Human-readable description of the plan.
    pub fn explain(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "plan for {}", self.name);
        for n in &self.notes {
            let _ = writeln!(s, "  {n}");
        }
        s
    }
}

/// "1 friction contact", "2 friction contacts": a count with its noun in the right number.
fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}
