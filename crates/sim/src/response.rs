//! Responses of one simulation (docs/MODEL.md § Outputs of a simulation) and the recorder
//! that accumulates them in place while stepping.
//!
//! Peaks are taken at the integration steps ("sampled peaks"); between steps the
//! continuous solution may exceed them slightly. `exact` reports the continuous drift
//! peaks in `Response::peak_drift` and the sampled ones in
//! `Diagnostics::sampled_peak_drift`.

use crate::kinematics::Kin;
use serde::{Deserialize, Serialize};

/// The five energies and the balance error, J (relative formulation).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Energy {
    /// Input energy ∫(−a_g rᵀM + Pᵀ) u̇ dt.
    pub input: f64,
    /// Kinetic energy ½ u̇ᵀ M u̇ at the end.
    pub kinetic: f64,
    /// Strain energy ½ uᵀ K u at the end (frame and braces).
    pub strain: f64,
    /// Viscous dissipation ∫ u̇ᵀ C u̇ dt.
    pub viscous: f64,
    /// Friction dissipation ∫ Fᵀ w dt (the dissipators).
    pub friction: f64,
    /// input + initial (kinetic + strain) − (kinetic + strain + viscous + friction
    /// [+ plastic]).
    pub balance_error: f64,
    /// Plastic (hysteretic) dissipation of the yielding storeys, ∫ Fₚ ẇₚ dt over their
    /// elastic–perfectly plastic parts; absent when no storey yields.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plastic: Option<f64>,
}

impl Energy {
    /// Friction dissipation over friction plus plastic dissipation (1 without yielding
    /// storeys, `None` when nothing was dissipated by either).
    pub fn friction_share(&self) -> Option<f64> {
        let total = self.friction + self.plastic.unwrap_or(0.0);
        (total > 0.0).then(|| self.friction / total)
    }
}

/// A run stopped because a storey's drift passed the collapse limit (a yielding storey,
/// often with P-Δ, ratcheting away): the peaks are those up to that instant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Collapse {
    /// Storey, 1 = the first.
    pub storey: usize,
    /// Time the limit was passed, s: the first output step at which the drift was past it
    /// (every method checks at its output steps; `Response::steps` counts the steps run).
    pub time: f64,
    /// The storey's drift then, m (signed).
    pub drift: f64,
    /// The limit, m.
    pub limit: f64,
}

/// The output contract of `simulate --format json` (SI units, arrays by storey).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Response {
    /// Method name.
    pub method: String,
    /// Time step, s.
    pub dt: f64,
    /// Number of steps.
    pub steps: usize,
    /// Wall-clock seconds of the (single-threaded) run.
    pub cpu_seconds: f64,
    /// Peak |interstorey drift| per storey, m.
    pub peak_drift: Vec<f64>,
    /// Peak drift / storey height per storey (when heights are given).
    pub peak_drift_ratio: Option<Vec<f64>>,
    /// Peak |floor displacement| relative to the ground, m.
    pub peak_displacement: Vec<f64>,
    /// Peak |absolute floor acceleration|, m/s².
    pub peak_abs_acceleration: Vec<f64>,
    /// |Interstorey drift| at the end, m.
    pub residual_drift: Vec<f64>,
    /// Peak |base shear|, N.
    pub peak_base_shear: f64,
    /// Peak |slip| (damper stroke) per storey, m (0 without a sliding damper).
    pub peak_slip: Vec<f64>,
    /// Stick↔slip transitions per storey.
    pub transitions: Vec<u64>,
    /// Energies, when asked for.
    pub energy: Option<Energy>,
    /// Peak ductility per storey, peak drift / yield drift (`null` for a storey that does
    /// not yield); absent when no storey yields.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_ductility: Option<Vec<Option<f64>>>,
    /// Peak |plastic drift| per storey (the slip of its plastic element), m; absent when no
    /// storey yields.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_plastic_drift: Option<Vec<f64>>,
    /// The collapse that stopped the run, if one did.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collapse: Option<Collapse>,
    /// Per-damper demands, one entry per storey (all zero for a storey without a sliding
    /// damper, as in `peak_slip`); present only when the scene's `outputs.dampers` asks.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dampers: Option<Vec<DamperDemand>>,
    /// The derivatives of the peaks with respect to the dampers' slip loads; present only
    /// when the scene's `outputs.sensitivities` asks.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sensitivity: Option<Sensitivity>,
    /// A building in plan: what each entry of the arrays above is (the arrays then run
    /// over its drifts, points and dampers instead of storeys and floors), and the
    /// torsional irregularity ratios. Absent for a chain.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub in_plan: Option<InPlan>,
}

/// What the arrays of a building in plan's [`Response`] hold.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InPlan {
    /// `peak_drift`, `peak_drift_ratio`, `residual_drift`, `peak_ductility`: one entry per
    /// drift named here (a line's storey, "A/3"; a plan edge's, "edge y=0 (x)/3").
    pub drifts: Vec<String>,
    /// `peak_displacement`, `peak_abs_acceleration`: one entry per point named here (a
    /// floor's centre of mass along x and y, "3 x", "3 y", in m and m/s², and its rotation,
    /// "3 rot", in rad and rad/s²).
    pub points: Vec<String>,
    /// `peak_slip`, `transitions`, `dampers`: one entry per damper named here ("A/3": line
    /// A, storey 3).
    pub dampers: Vec<String>,
    /// `peak_plastic_drift`: one entry per yielding storey of a line, named here.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub plastic: Vec<String>,
    /// Per storey, the torsional irregularity ratio along x and along y: the larger peak
    /// drift of the plan's two edges across the direction over their mean (1 for a floor
    /// that does not twist; ASCE 7-16 Table 12.3-1 calls a storey irregular past 1.2 and
    /// extremely irregular past 1.4). Peaks of the run, each edge's at its own time; 1
    /// where the edges' drifts along a direction are round-off beside the storey's
    /// largest (below 1e-9 of it: the ground does not move the storey that way). Absent
    /// when the plan's size is not given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torsional_irregularity: Option<Vec<[f64; 2]>>,
    /// The base's peak shears along the plan's x and y and its peak torque about the
    /// building's centre of mass ([`crate::plan::BaseRows`]): the inertia forces' resultant, each the
    /// largest magnitude over the output steps at its own time (the response's
    /// `peak_base_shear` is the shear along the first component).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_base: Option<BaseForces>,
}

/// A building in plan's peak base forces ([`InPlan::peak_base`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BaseForces {
    /// Peak |base shear along x|, N.
    pub shear_x_n: f64,
    /// Peak |base shear along y|, N.
    pub shear_y_n: f64,
    /// Peak |base torque about `torque_about_m`|, N·m.
    pub torque_nm: f64,
    /// The point the torque is taken about [x, y], m: the building's centre of mass (the
    /// floors' masses' centroid).
    pub torque_about_m: [f64; 2],
}

/// The derivatives of a run's peak responses with respect to each damper's slip load F
/// (its friction bounds ∓F), from the tangent of the `newmark` step (docs/MODEL.md §
/// Sensitivities). Each row holds one derivative per damper, in the order of `dampers`.
/// The step is a projection (the friction box QP), so the response is continuous and
/// piecewise smooth in F: the tangent is the derivative of the piece the run is on, and a
/// peak's derivative is the drift's at the step where the peak was reached.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sensitivity {
    /// The floor (from 0) of each damper, the columns' order.
    pub dampers: Vec<usize>,
    /// ∂(peak |drift|)/∂F per storey, m/N.
    pub peak_drift: Vec<Vec<f64>>,
    /// ∂(|drift| at the end)/∂F per storey, m/N.
    pub residual_drift: Vec<Vec<f64>>,
    /// ∂(peak |displacement|)/∂F per floor, m/N.
    pub peak_displacement: Vec<Vec<f64>>,
    /// ∂(peak |absolute acceleration|)/∂F per floor, m/s²/N.
    pub peak_abs_acceleration: Vec<Vec<f64>>,
    /// ∂(peak |base shear|)/∂F, N/N.
    pub peak_base_shear: Vec<f64>,
}

/// What one damper went through in a run: the figures a device is specified and
/// prototype-tested to (docs/MODEL.md § Per-damper demands). Sampled at the output steps,
/// as the other peaks are. The slip is the floor's displacement minus the dissipator's
/// (the slider's position on its brace), taken from its value at the start.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct DamperDemand {
    /// Largest slip displacement in the positive direction from the start, m (≥ 0).
    pub slip_max_pos_m: f64,
    /// Largest slip displacement in the negative direction from the start, as a positive
    /// magnitude, m (≥ 0).
    pub slip_max_neg_m: f64,
    /// Largest |slip rate|, m/s (a massless damper's rate is its mean over a step: its
    /// slip of the step / Δt).
    pub peak_slip_velocity_m_s: f64,
    /// Cumulative slip travel ∫|d(slip)|, m: the sum of |Δslip| over the output steps.
    pub cumulative_travel_m: f64,
    /// Slip episodes: each start of slipping from stick, and each reversal of the slip
    /// direction while slipping, counts one.
    pub slip_excursions: u64,
    /// Full cycles: one excursion each way, `slip_excursions / 2`.
    pub cycles: f64,
    /// Largest |friction force| of the slider, N.
    pub peak_force_n: f64,
    /// Energy the damper dissipated, ∫ F d(slip), J: the trapezoid rule in the slip
    /// between output steps (≥ 0 to round-off).
    pub energy_j: f64,
}

impl DamperDemand {
    /// The figures by name, in the order of the fields (for checks and tables).
    pub fn values(&self) -> [(&'static str, f64); 8] {
        [
            ("slip_max_pos_m", self.slip_max_pos_m),
            ("slip_max_neg_m", self.slip_max_neg_m),
            ("peak_slip_velocity_m_s", self.peak_slip_velocity_m_s),
            ("cumulative_travel_m", self.cumulative_travel_m),
            ("slip_excursions", self.slip_excursions as f64),
            ("cycles", self.cycles),
            ("peak_force_n", self.peak_force_n),
            ("energy_j", self.energy_j),
        ]
    }
}

/// One damper's running state in a [`DamperRecorder`].
#[derive(Debug, Clone, Copy, Default)]
struct DamperSlot {
    /// Whether the floor has a sliding damper (a contact of the plan).
    present: bool,
    /// Whether the first (initial) state has been observed.
    started: bool,
    /// Slip at the start, m.
    start: f64,
    /// Slip and friction force at the last observation.
    last_slip: f64,
    last_force: f64,
    /// Time of the last observation, s (a repeated observation of an instant is skipped).
    last_t: f64,
    /// Direction of the last step's slip: +1, −1, or 0 (stuck).
    dir: i8,
    /// Largest |Δslip| of one step so far, m.
    largest_step: f64,
    /// |Δslip| at or below which a step counts as stuck, m: 1e-9 of the damper's elastic
    /// brace deformation at its slip load (raised in `observe` to 1e-12 of the slip's
    /// value and to 1e-5 of the largest step's slip so far), far above the round-off of a
    /// stuck slip and far below any slip that moves a device.
    still: f64,
}

/// Accumulates [`DamperDemand`]s from the state at every output step (every method feeds
/// it the same way, so every method reports the same quantities under the same
/// definitions). Present in [`Peaks`] only when the plan's outputs ask for dampers.
#[derive(Debug, Clone)]
pub struct DamperRecorder {
    slots: Vec<DamperSlot>,
    demand: Vec<DamperDemand>,
}

impl DamperRecorder {
    /// A recorder for the damper contacts of `plan` (slots by floor).
    pub fn for_plan(plan: &crate::plan::Plan) -> Self {
        let n = plan.damper_slots;
        let mut slots = vec![DamperSlot::default(); n];
        for ct in &plan.contacts {
            if ct.role != crate::plan::ContactRole::Damper {
                continue;
            }
            let load = [ct.upper - ct.lower, ct.upper.abs(), ct.lower.abs()]
                .into_iter()
                .filter(|x| x.is_finite())
                .fold(0.0, f64::max);
            let still = if ct.brace_stiffness > 0.0 && ct.brace_stiffness.is_finite() {
                1e-9 * load / ct.brace_stiffness
            } else {
                0.0
            };
            slots[ct.slot] = DamperSlot {
                present: true,
                still,
                ..DamperSlot::default()
            };
        }
        DamperRecorder {
            slots,
            demand: vec![DamperDemand::default(); n],
        }
    }

    /// Records the damper of `floor` at time `t` (s): its slip (m), slip rate (m/s) and
    /// friction force (N). The first call is the initial state; a second call at the
    /// same instant is skipped.
    #[inline]
    pub fn observe(&mut self, floor: usize, t: f64, slip: f64, rate: f64, force: f64) {
        let (Some(s), Some(d)) = (self.slots.get_mut(floor), self.demand.get_mut(floor)) else {
            return;
        };
        if !s.present {
            return;
        }
        if !s.started {
            *s = DamperSlot {
                started: true,
                start: slip,
                last_slip: slip,
                last_force: force,
                last_t: t,
                dir: 0,
                ..*s
            };
        } else {
            if t <= s.last_t {
                return;
            }
            let ds = slip - s.last_slip;
            d.cumulative_travel_m += ds.abs();
            d.energy_j += 0.5 * (s.last_force + force) * ds;
            // the static threshold, the round-off of the slip's value itself, or 1e-5 of
            // the largest slip of a step so far (the micro-motion of a stuck slider whose
            // stiff brace rings is not an episode)
            let still = s
                .still
                .max(1e-12 * slip.abs().max(s.last_slip.abs()))
                .max(1e-5 * s.largest_step);
            if ds.abs() > s.largest_step {
                s.largest_step = ds.abs();
            }
            let dir = if ds > still {
                1
            } else if ds < -still {
                -1
            } else {
                0
            };
            if dir != 0 && dir != s.dir {
                d.slip_excursions += 1;
            }
            s.dir = dir;
            s.last_slip = slip;
            s.last_force = force;
            s.last_t = t;
            let from_start = slip - s.start;
            if from_start > d.slip_max_pos_m {
                d.slip_max_pos_m = from_start;
            }
            if -from_start > d.slip_max_neg_m {
                d.slip_max_neg_m = -from_start;
            }
        }
        if rate.abs() > d.peak_slip_velocity_m_s {
            d.peak_slip_velocity_m_s = rate.abs();
        }
        if force.abs() > d.peak_force_n {
            d.peak_force_n = force.abs();
        }
    }

    /// The demands, one per storey.
    pub fn finish(mut self) -> Vec<DamperDemand> {
        for d in &mut self.demand {
            d.cycles = d.slip_excursions as f64 / 2.0;
        }
        self.demand
    }
}

impl Response {
    /// The first response that is NaN or infinite, by name (`peak_drift[2]`,
    /// `energy.input`), with its value; `None` when every value is finite.
    pub fn first_non_finite(&self) -> Option<(String, f64)> {
        let vecs: [(&str, Option<&[f64]>); 6] = [
            ("peak_drift", Some(&self.peak_drift)),
            ("peak_drift_ratio", self.peak_drift_ratio.as_deref()),
            ("peak_displacement", Some(&self.peak_displacement)),
            ("peak_abs_acceleration", Some(&self.peak_abs_acceleration)),
            ("residual_drift", Some(&self.residual_drift)),
            ("peak_slip", Some(&self.peak_slip)),
        ];
        for (name, v) in vecs {
            if let Some(v) = v
                && let Some(i) = v.iter().position(|x| !x.is_finite())
            {
                return Some((format!("{name}[storey {}]", i + 1), v[i]));
            }
        }
        if !self.peak_base_shear.is_finite() {
            return Some(("peak_base_shear".into(), self.peak_base_shear));
        }
        if let Some(e) = &self.energy {
            for (name, v) in [
                ("input", e.input),
                ("kinetic", e.kinetic),
                ("strain", e.strain),
                ("viscous", e.viscous),
                ("friction", e.friction),
                ("balance_error", e.balance_error),
                ("plastic", e.plastic.unwrap_or(0.0)),
            ] {
                if !v.is_finite() {
                    return Some((format!("energy.{name}"), v));
                }
            }
        }
        for (i, d) in self.dampers.iter().flatten().enumerate() {
            for (name, v) in d.values() {
                if !v.is_finite() {
                    return Some((format!("dampers[storey {}].{name}", i + 1), v));
                }
            }
        }
        None
    }
}

/// Extra figures of a run that are not in the output contract.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Diagnostics {
    /// Friction QP iterations, mean per step.
    pub qp_iterations_mean: f64,
    /// Friction QP iterations, max in one step.
    pub qp_iterations_max: u32,
    /// Largest |balance error| / max(input + initial energy) over the steps (energies on).
    pub balance_error_max_relative: f64,
    /// Initial kinetic + strain energy, J.
    pub initial_energy: f64,
    /// `delacruz`: iterations of its three fixed-point loops (`None` for other methods).
    #[serde(default)]
    pub loop_iterations: Option<LoopIterations>,
    /// Peak |drift| per storey taken at the output steps only, m (`exact`, whose
    /// `Response::peak_drift` is the continuous peak located between steps).
    pub sampled_peak_drift: Option<Vec<f64>>,
    /// Mode changes (stick↔slip and slip reversals) located by `exact` (0 for others).
    pub events: u64,
    /// Area under the strain-energy history ∫ E_strain dt, J·s (trapezoidal at the steps;
    /// 0 unless energies are on). Filiatrault & Cherry (1988) compare it with the bare
    /// frame's in their relative performance index.
    #[serde(default)]
    pub strain_energy_area: f64,
    /// The run's arithmetic in multiply-adds of its dominant operations (products with
    /// the step operators, Taylor sums, event scans, observations), counted as the run
    /// goes: a measure of its cost that does not depend on the machine or its load, so a
    /// choice made from it is the same on every machine (`newmark`, `exact`; 0 for
    /// `delacruz`). `slipload bench` sets its time per unit beside it.
    #[serde(default)]
    pub work: u64,
    /// `exact`: the most bytes of stick/slip mode-set matrices its thread kept at once
    /// during the run, with the scratch of forming one: within its memory budget
    /// (`integrator::exact::MemoryBudget`). 0 for other methods.
    #[serde(default)]
    pub cache_peak_bytes: u64,
}

/// Iterations of `delacruz`'s three nested fixed-point loops, per invocation of each loop.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct LoopIterations {
    /// Inner loop (structural accelerations): mean iterations per invocation.
    pub inner_mean: f64,
    /// Inner loop: most iterations in one invocation.
    pub inner_max: u32,
    /// Middle loop (friction forces of stuck dampers): mean per invocation.
    pub middle_mean: f64,
    /// Middle loop: most in one invocation.
    pub middle_max: u32,
    /// Outer loop (accelerations of sliding dissipators): mean per invocation.
    pub outer_mean: f64,
    /// Outer loop: most in one invocation.
    pub outer_max: u32,
    /// Solves repeated because a stuck damper's force left its bounds (rule 1).
    pub resolves: u64,
    /// Kinetic energy removed by the rule-2 projections (a sliding dissipator whose slip
    /// rate reversed is given its floor's velocity), J: ½m′(v′² − v_floor²) summed. It is
    /// part of the balance error.
    pub projection_energy: f64,
}

/// Time histories, one column per quantity, one row per step.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct History {
    /// Column names with units.
    pub columns: Vec<String>,
    /// Row-major values.
    pub rows: Vec<f64>,
}

impl History {
    /// CSV text with a header line.
    pub fn to_csv(&self) -> String {
        // a plan's columns carry its lines', dampers' and points' names: user text
        let header: Vec<String> = self.columns.iter().map(|c| csv_field(c)).collect();
        let mut s = header.join(",");
        s.push('\n');
        let w = self.columns.len().max(1);
        for row in self.rows.chunks(w) {
            let line: Vec<String> = row.iter().map(|v| format!("{v:.9e}")).collect();
            s.push_str(&line.join(","));
            s.push('\n');
        }
        s
    }
    /// Values of column `name`.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let j = self.columns.iter().position(|c| c == name)?;
        let w = self.columns.len();
        Some(self.rows.chunks(w).map(|r| r[j]).collect())
    }
}

/// Everything one run produces.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The contract's responses.
    pub response: Response,
    /// Extra figures.
    pub diagnostics: Diagnostics,
    /// Histories, when asked for.
    pub history: Option<History>,
}

/// Running peaks, updated in place at every step (no allocation while stepping).
#[derive(Debug, Clone)]
pub struct Peaks {
    /// Peak |drift| per storey.
    pub drift: Vec<f64>,
    /// Peak |displacement| per floor.
    pub displacement: Vec<f64>,
    /// Peak |absolute acceleration| per floor.
    pub abs_acceleration: Vec<f64>,
    /// Last drift per storey (signed).
    pub last_drift: Vec<f64>,
    /// Peak |base shear|.
    pub base_shear: f64,
    /// Peak |slip| per slot: the damper of floor i at i, the plastic element of storey
    /// i + 1 at n + i (its slip is the plastic drift), so a step loop records either with
    /// one index and no branch.
    pub slip: Vec<f64>,
    /// Stick↔slip transitions per slot, likewise (a yielding storey's are not reported).
    pub transitions: Vec<u64>,
    /// Collapse drift per storey, when the plan sets one.
    pub collapse_limit: Option<Vec<f64>>,
    /// The first storey past its collapse limit.
    pub collapse: Option<Collapse>,
    /// Per-damper demands, when the plan's outputs ask for them.
    pub dampers: Option<DamperRecorder>,
    /// The drifts and points a plan that is not a chain measures (`None` for a chain,
    /// whose drifts are its storeys and points its floors).
    pub measures: Option<Box<Measures>>,
}

/// The drifts and points of a plan that is not a chain ([`crate::plan::Plan::drifts`],
/// [`crate::plan::Plan::points`]).
#[derive(Debug, Clone)]
pub struct Measures {
    /// Each drift's two points.
    pub drifts: Vec<(Kin, Kin)>,
    /// Each point and its ground influence.
    pub points: Vec<(Kin, f64)>,
    /// Each point's influence of the second ground component (zeros without one).
    pub points2: Vec<f64>,
    /// The base's rows ([`crate::plan::BaseRows`]), when the plan has them.
    pub base: Option<std::sync::Arc<crate::plan::BaseRows>>,
    /// Peak |base shear along x|, |along y| (N) and |base torque about the building's
    /// centre of mass| (N·m), each at its own time.
    pub base_peaks: [f64; 3],
}

impl Peaks {
    /// Zeroed peaks for `n` floors.
    pub fn new(n: usize) -> Self {
        Peaks {
            drift: vec![0.0; n],
            displacement: vec![0.0; n],
            abs_acceleration: vec![0.0; n],
            last_drift: vec![0.0; n],
            base_shear: 0.0,
            slip: vec![0.0; 2 * n],
            transitions: vec![0; 2 * n],
            collapse_limit: None,
            collapse: None,
            dampers: None,
            measures: None,
        }
    }

    /// Zeroed peaks for the drifts, points and contacts of `plan`, with its collapse
    /// limit.
    pub fn for_plan(plan: &crate::plan::Plan) -> Self {
        let (nd, np) = (plan.drifts.len(), plan.points.len());
        let slots = plan.damper_slots
            + plan
                .contacts
                .iter()
                .filter(|c| c.role == crate::plan::ContactRole::Storey)
                .map(|c| c.slot + 1 - plan.damper_slots)
                .max()
                .unwrap_or(0)
                .max(if plan.is_chain() { plan.floors } else { 0 });
        Peaks {
            drift: vec![0.0; nd],
            displacement: vec![0.0; np],
            abs_acceleration: vec![0.0; np],
            last_drift: vec![0.0; nd],
            slip: vec![0.0; slots],
            transitions: vec![0; slots],
            collapse_limit: plan.collapse_drift.clone(),
            dampers: plan.outputs.dampers.then(|| DamperRecorder::for_plan(plan)),
            measures: (!plan.is_chain()).then(|| {
                Box::new(Measures {
                    drifts: plan.drifts.clone(),
                    points: plan.points.clone(),
                    points2: plan
                        .second
                        .as_ref()
                        .map_or_else(|| vec![0.0; np], |g| g.points.clone()),
                    base: plan.base.clone(),
                    base_peaks: [0.0; 3],
                })
            }),
            ..Peaks::new(0)
        }
    }

    /// After [`Peaks::observe_floors`] at time `t`: whether a storey's drift has passed the
    /// collapse limit (the first such storey is recorded). Without a limit, false at the
    /// cost of one branch.
    #[inline]
    pub fn collapsed(&mut self, t: f64) -> bool {
        let Some(limit) = &self.collapse_limit else {
            return false;
        };
        if self.collapse.is_some() {
            return true;
        }
        for (i, (d, l)) in self.last_drift.iter().zip(limit).enumerate() {
            if d.abs() > *l {
                self.collapse = Some(Collapse {
                    storey: i + 1,
                    time: t,
                    drift: *d,
                    limit: *l,
                });
                return true;
            }
        }
        false
    }

    /// Keeps the larger |plastic drift| (m) of storey `floor + 1`.
    #[inline]
    pub fn observe_plastic(&mut self, floor: usize, s: f64) {
        let slot = self.drift.len() + floor;
        self.observe_slip(slot, s);
    }

    /// Records floor displacements `x` and relative accelerations `a` (first n entries
    /// used) with ground acceleration `ag`.
    #[inline]
    pub fn observe_floors(&mut self, x: &[f64], a: &[f64], ag: f64) {
        self.observe_floors2(x, a, ag, 0.0);
    }

    /// [`Peaks::observe_floors`] with a second ground component's acceleration `ag2`
    /// (a building in plan under both components; a chain has none).
    #[inline]
    pub fn observe_floors2(&mut self, x: &[f64], a: &[f64], ag: f64, ag2: f64) {
        if let Some(m) = &mut self.measures {
            if let Some(b) = &m.base {
                for (k, peak) in m.base_peaks.iter_mut().enumerate() {
                    let mut v = b.first[k] * ag + b.second[k] * ag2;
                    for (w, ai) in b.rows[k].iter().zip(a) {
                        v += w * ai;
                    }
                    if v.abs() > *peak {
                        *peak = v.abs();
                    }
                }
            }
            for (k, (top, bottom)) in m.drifts.iter().enumerate() {
                let d = top.at(x) - bottom.at(x);
                self.last_drift[k] = d;
                if d.abs() > self.drift[k] {
                    self.drift[k] = d.abs();
                }
            }
            for (k, ((p, r), r2)) in m.points.iter().zip(&m.points2).enumerate() {
                let (xa, aa) = (p.at(x).abs(), (p.at(a) + r * ag + r2 * ag2).abs());
                if xa > self.displacement[k] {
                    self.displacement[k] = xa;
                }
                if aa > self.abs_acceleration[k] {
                    self.abs_acceleration[k] = aa;
                }
            }
            return;
        }
        // Plain comparisons (a NaN never replaces a peak, as with `f64::max`) over zipped
        // slices: no bounds checks, nothing the step loop has to wait for.
        let mut below = 0.0;
        let rows = self
            .drift
            .iter_mut()
            .zip(&mut self.displacement)
            .zip(&mut self.abs_acceleration)
            .zip(&mut self.last_drift)
            .zip(x.iter().zip(a));
        for ((((pd, px), pa), ld), (&xi, &ai)) in rows {
            let d = xi - below;
            below = xi;
            *ld = d;
            let (d, xa, aa) = (d.abs(), xi.abs(), (ai + ag).abs());
            if d > *pd {
                *pd = d;
            }
            if xa > *px {
                *px = xa;
            }
            if aa > *pa {
                *pa = aa;
            }
        }
    }

    /// Keeps the larger |base shear| (N).
    #[inline]
    pub fn observe_base_shear(&mut self, v: f64) {
        if v.abs() > self.base_shear {
            self.base_shear = v.abs();
        }
    }

    /// Keeps the larger |slip| (m) of slot `floor` (from 0; n + i for storey i + 1's
    /// plastic element).
    #[inline]
    pub fn observe_slip(&mut self, floor: usize, s: f64) {
        if s.abs() > self.slip[floor] {
            self.slip[floor] = s.abs();
        }
    }

    /// Builds the contract's response of a run of `plan` (method, step, step count and
    /// storey heights come from the plan).
    pub fn into_plan_response(self, plan: &crate::plan::Plan, energy: Option<Energy>) -> Response {
        let yields = plan.yield_drift.iter().any(Option::is_some);
        let ductility = yields.then(|| {
            self.drift
                .iter()
                .zip(&plan.yield_drift)
                .map(|(d, y)| y.map(|y| d / y))
                .collect()
        });
        let n = plan.damper_slots;
        let plastic = yields.then(|| self.slip[n..].to_vec());
        let collapse = self.collapse;
        let base = self
            .measures
            .as_ref()
            .and_then(|m| m.base.as_ref().map(|b| (b.about, m.base_peaks)))
            .map(|(about, [x, y, t])| BaseForces {
                shear_x_n: x,
                shear_y_n: y,
                torque_nm: t,
                torque_about_m: about,
            });
        let mut r = self.into_response_slots(
            n,
            plan.method.name.as_str(),
            plan.method.dt,
            plan.steps,
            plan.storey_heights.as_deref(),
            energy,
        );
        r.peak_ductility = ductility;
        r.peak_plastic_drift = plastic;
        if let Some(c) = &collapse {
            // the steps actually run: the run stopped at the output step past the limit
            r.steps = ((c.time / plan.method.dt).round() as usize).min(plan.steps);
        }
        r.collapse = collapse;
        if let Some(labels) = &plan.labels {
            if let Some(c) = r.collapse.as_mut() {
                // the drift's index (from 1) becomes its storey's number
                c.storey = labels.drift_storeys[c.storey - 1] + 1;
            }
            // An edge pair whose drifts are round-off beside the storey's largest (a
            // direction the ground does not move) compares nothing: 1.
            let ratio = |a: f64, b: f64, scale: f64| {
                let mean = 0.5 * (a + b);
                if mean > 1e-9 * scale {
                    a.max(b) / mean
                } else {
                    1.0
                }
            };
            r.in_plan = Some(InPlan {
                drifts: labels.drifts.clone(),
                points: labels.points.clone(),
                dampers: labels.dampers.clone(),
                plastic: labels.plastic.clone(),
                peak_base: base,
                torsional_irregularity: labels.edges.as_ref().map(|edges| {
                    edges
                        .iter()
                        .map(|e| {
                            let d = |k: usize| r.peak_drift[e[k]];
                            let scale = (0..4).map(d).fold(0.0, f64::max);
                            [ratio(d(0), d(1), scale), ratio(d(2), d(3), scale)]
                        })
                        .collect()
                }),
            });
        }
        r
    }

    /// Builds the contract's response (a chain's: one damper slot per storey).
    pub fn into_response(
        self,
        method: &str,
        dt: f64,
        steps: usize,
        heights: Option<&[f64]>,
        energy: Option<Energy>,
    ) -> Response {
        let n = self.drift.len();
        self.into_response_slots(n, method, dt, steps, heights, energy)
    }

    /// Builds the contract's response with `n` damper slots.
    fn into_response_slots(
        self,
        n: usize,
        method: &str,
        dt: f64,
        steps: usize,
        heights: Option<&[f64]>,
        energy: Option<Energy>,
    ) -> Response {
        let ratio = heights.map(|h| self.drift.iter().zip(h).map(|(d, h)| d / h).collect());
        Response {
            method: method.to_string(),
            dt,
            steps,
            cpu_seconds: 0.0,
            peak_drift: self.drift,
            peak_drift_ratio: ratio,
            peak_displacement: self.displacement,
            peak_abs_acceleration: self.abs_acceleration,
            residual_drift: self.last_drift.iter().map(|d| d.abs()).collect(),
            peak_base_shear: self.base_shear,
            peak_slip: self.slip[..n].to_vec(),
            transitions: self.transitions[..n].to_vec(),
            energy,
            peak_ductility: None,
            peak_plastic_drift: None,
            collapse: None,
            dampers: self.dampers.map(DamperRecorder::finish),
            sensitivity: None,
            in_plan: None,
        }
    }
}

/// A CSV field: the text as it is, or quoted (its quotes doubled) where it holds a comma,
/// a quote or a line break, so a name read from a file stays one field.
pub fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}
