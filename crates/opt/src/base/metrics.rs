//! Per-record responses of one design: what the sweep journals and the objective reads.

use serde::{Deserialize, Serialize};
use slipload_sim::Outcome;

/// The responses of one (design, record) simulation that studies use (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordMetrics {
    /// Peak |drift| / storey height per storey.
    pub drift_ratio: Vec<f64>,
    /// |Drift| / storey height at the end, per storey.
    pub residual_drift_ratio: Vec<f64>,
    /// Peak |absolute floor acceleration| over all floors, m/s².
    pub peak_floor_acceleration: f64,
    /// Peak |base shear|, N.
    pub peak_base_shear: f64,
    /// Peak |floor displacement| over all floors (relative to the ground), m.
    pub peak_displacement: f64,
    /// Peak |slip| (damper stroke) per storey, m.
    pub stroke: Vec<f64>,
    /// Input energy, J (energies on).
    pub energy_input: Option<f64>,
    /// Friction dissipation, J (energies on).
    pub energy_friction: Option<f64>,
    /// ∫ E_strain dt, J·s (energies on).
    pub strain_energy_area: Option<f64>,
    /// Peak ductility (peak drift / yield drift) per storey, 0 for a storey without a
    /// yield law; absent for an elastic frame.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ductility: Option<Vec<f64>>,
    /// Plastic (hysteretic) energy of the yielding storeys, J (energies on; absent for an
    /// elastic frame).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub energy_plastic: Option<f64>,
    /// The run stopped on the collapse limit: (storey from 1, time in s). The design fails
    /// this record.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collapse: Option<(usize, f64)>,
    /// Per-damper demands per storey (zero for a storey without a damper), when the run
    /// recorded them (a study with limits, at the check fidelity).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dampers: Option<Vec<slipload_sim::response::DamperDemand>>,
    /// The derivatives of these responses with respect to the design's slip loads, when
    /// the run computed them (the `sqp` refiner's evaluations).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangent: Option<MetricTangents>,
}

/// The derivatives of one run's responses with respect to the design's slip loads (N),
/// one per damper of the design space in its order, at the run's property case (a bound
/// case's factor on the slip loads included): what the `sqp` refiner reads, from the
/// run's [`slipload_sim::response::Sensitivity`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MetricTangents {
    /// ∂(peak drift ratio)/∂F per storey, one per damper, 1/N.
    pub drift_ratio: Vec<Vec<f64>>,
    /// ∂(residual drift ratio)/∂F per storey, 1/N.
    pub residual_drift_ratio: Vec<Vec<f64>>,
    /// ∂(peak absolute floor acceleration)/∂F at the floor of the peak, m/s²/N.
    pub peak_floor_acceleration: Vec<f64>,
    /// ∂(peak base shear)/∂F.
    pub peak_base_shear: Vec<f64>,
    /// ∂(peak floor displacement)/∂F at the floor of the peak, m/N.
    pub peak_displacement: Vec<f64>,
}

/// Index of the first largest value (0 for an empty slice).
fn argmax(v: &[f64]) -> usize {
    let mut at = 0;
    for (i, x) in v.iter().enumerate() {
        if *x > v[at] {
            at = i;
        }
    }
    at
}

impl RecordMetrics {
    /// From a simulation outcome; `heights` are the storey heights, m.
    pub fn from_outcome(out: &Outcome, heights: &[f64]) -> RecordMetrics {
        let r = &out.response;
        let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
        let energy = r.energy;
        RecordMetrics {
            drift_ratio: r
                .peak_drift
                .iter()
                .zip(heights)
                .map(|(d, h)| d / h)
                .collect(),
            residual_drift_ratio: r
                .residual_drift
                .iter()
                .zip(heights)
                .map(|(d, h)| d / h)
                .collect(),
            peak_floor_acceleration: max(&r.peak_abs_acceleration),
            peak_base_shear: r.peak_base_shear,
            peak_displacement: max(&r.peak_displacement),
            stroke: r.peak_slip.clone(),
            energy_input: energy.map(|e| e.input),
            energy_friction: energy.map(|e| e.friction),
            strain_energy_area: energy.map(|_| out.diagnostics.strain_energy_area),
            ductility: r
                .peak_ductility
                .as_ref()
                .map(|mu| mu.iter().map(|m| m.unwrap_or(0.0)).collect()),
            energy_plastic: energy.and_then(|e| e.plastic),
            collapse: r.collapse.map(|c| (c.storey, c.time)),
            dampers: r.dampers.clone(),
            tangent: None,
        }
    }

    /// With the derivatives of the run's sensitivities (when it computed them): the
    /// design's damper k sits on floor `dampers[k]`, and the run's slip loads are the
    /// design's times `factor` (its property case). A damper the run does not carry
    /// has derivative 0.
    pub fn with_tangents(
        mut self,
        out: &Outcome,
        heights: &[f64],
        dampers: &[usize],
        factor: f64,
    ) -> RecordMetrics {
        let r = &out.response;
        let Some(s) = &r.sensitivity else {
            return self;
        };
        let col: Vec<Option<usize>> = dampers
            .iter()
            .map(|f| s.dampers.iter().position(|g| g == f))
            .collect();
        let pick = |row: &[f64]| -> Vec<f64> {
            col.iter()
                .map(|c| c.map_or(0.0, |c| factor * row[c]))
                .collect()
        };
        let per_storey = |rows: &[Vec<f64>]| -> Vec<Vec<f64>> {
            rows.iter()
                .zip(heights)
                .map(|(row, h)| pick(row).into_iter().map(|v| v / h).collect())
                .collect()
        };
        self.tangent = Some(MetricTangents {
            drift_ratio: per_storey(&s.peak_drift),
            residual_drift_ratio: per_storey(&s.residual_drift),
            peak_floor_acceleration: pick(
                &s.peak_abs_acceleration[argmax(&r.peak_abs_acceleration)],
            ),
            peak_base_shear: pick(&s.peak_base_shear),
            peak_displacement: pick(&s.peak_displacement[argmax(&r.peak_displacement)]),
        });
        self
    }

    /// These responses moved by `eps` times their derivative with respect to damper `k`
    /// (unchanged where the run carries no derivatives): what a statistic of the
    /// responses is differentiated through.
    pub fn moved(&self, k: usize, eps: f64) -> RecordMetrics {
        let mut m = self.clone();
        if let Some(t) = &self.tangent {
            for (v, row) in m.drift_ratio.iter_mut().zip(&t.drift_ratio) {
                *v += eps * row[k];
            }
            for (v, row) in m
                .residual_drift_ratio
                .iter_mut()
                .zip(&t.residual_drift_ratio)
            {
                *v += eps * row[k];
            }
            m.peak_floor_acceleration += eps * t.peak_floor_acceleration[k];
            m.peak_base_shear += eps * t.peak_base_shear[k];
            m.peak_displacement += eps * t.peak_displacement[k];
        }
        m
    }

    /// The envelope of two runs of one ground motion (a pair at two orientations,
    /// [`crate::model::orientation`]): each response its larger value, and with it its
    /// derivative (ties keep `self`'s). A damper's largest slips each way are both the
    /// larger of the four (the response to the opposite orientation is the mirror, which
    /// swaps them); its other demands, the energies and the ductilities are each the
    /// larger; a collapse of either run is the envelope's (`self`'s first).
    pub fn envelope(mut self, other: &RecordMetrics) -> RecordMetrics {
        let take = |a: &mut f64, b: f64| -> bool {
            let more = b > *a;
            if more {
                *a = b;
            }
            more
        };
        let mut tangent = self.tangent.take();
        let theirs = other.tangent.as_ref();
        for (s, (v, w)) in self
            .drift_ratio
            .iter_mut()
            .zip(&other.drift_ratio)
            .enumerate()
        {
            if take(v, *w)
                && let (Some(t), Some(o)) = (tangent.as_mut(), theirs)
            {
                t.drift_ratio[s].clone_from(&o.drift_ratio[s]);
            }
        }
        for (s, (v, w)) in self
            .residual_drift_ratio
            .iter_mut()
            .zip(&other.residual_drift_ratio)
            .enumerate()
        {
            if take(v, *w)
                && let (Some(t), Some(o)) = (tangent.as_mut(), theirs)
            {
                t.residual_drift_ratio[s].clone_from(&o.residual_drift_ratio[s]);
            }
        }
        if take(
            &mut self.peak_floor_acceleration,
            other.peak_floor_acceleration,
        ) && let (Some(t), Some(o)) = (tangent.as_mut(), theirs)
        {
            t.peak_floor_acceleration
                .clone_from(&o.peak_floor_acceleration);
        }
        if take(&mut self.peak_base_shear, other.peak_base_shear)
            && let (Some(t), Some(o)) = (tangent.as_mut(), theirs)
        {
            t.peak_base_shear.clone_from(&o.peak_base_shear);
        }
        if take(&mut self.peak_displacement, other.peak_displacement)
            && let (Some(t), Some(o)) = (tangent.as_mut(), theirs)
        {
            t.peak_displacement.clone_from(&o.peak_displacement);
        }
        self.tangent = tangent;
        for (v, w) in self.stroke.iter_mut().zip(&other.stroke) {
            take(v, *w);
        }
        let larger = |a: Option<f64>, b: Option<f64>| match (a, b) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
        self.energy_input = larger(self.energy_input, other.energy_input);
        self.energy_friction = larger(self.energy_friction, other.energy_friction);
        self.strain_energy_area = larger(self.strain_energy_area, other.strain_energy_area);
        self.energy_plastic = larger(self.energy_plastic, other.energy_plastic);
        if let (Some(mu), Some(nu)) = (self.ductility.as_mut(), other.ductility.as_ref()) {
            for (v, w) in mu.iter_mut().zip(nu) {
                take(v, *w);
            }
        }
        if self.collapse.is_none() {
            self.collapse = other.collapse;
        }
        if let (Some(ds), Some(es)) = (self.dampers.as_mut(), other.dampers.as_ref()) {
            for (d, e) in ds.iter_mut().zip(es) {
                let slip = d
                    .slip_max_pos_m
                    .max(d.slip_max_neg_m)
                    .max(e.slip_max_pos_m)
                    .max(e.slip_max_neg_m);
                d.slip_max_pos_m = slip;
                d.slip_max_neg_m = slip;
                take(&mut d.peak_slip_velocity_m_s, e.peak_slip_velocity_m_s);
                take(&mut d.cumulative_travel_m, e.cumulative_travel_m);
                d.slip_excursions = d.slip_excursions.max(e.slip_excursions);
                take(&mut d.cycles, e.cycles);
                take(&mut d.peak_force_n, e.peak_force_n);
                take(&mut d.energy_j, e.energy_j);
            }
        }
        self
    }

    /// Largest peak ductility over the storeys (`None` for an elastic frame).
    pub fn peak_ductility(&self) -> Option<f64> {
        self.ductility
            .as_ref()
            .map(|mu| mu.iter().copied().fold(0.0, f64::max))
    }

    /// Whether the run stopped on the collapse limit.
    pub fn collapsed(&self) -> bool {
        self.collapse.is_some()
    }

    /// Largest peak drift ratio over the storeys.
    pub fn peak_drift_ratio(&self) -> f64 {
        self.drift_ratio.iter().copied().fold(0.0, f64::max)
    }

    /// Largest residual drift ratio over the storeys.
    pub fn residual(&self) -> f64 {
        self.residual_drift_ratio
            .iter()
            .copied()
            .fold(0.0, f64::max)
    }

    /// The first value that is NaN or infinite, by name; `None` when all are finite.
    pub fn first_non_finite(&self) -> Option<String> {
        let vecs = [
            ("drift_ratio", &self.drift_ratio),
            ("residual_drift_ratio", &self.residual_drift_ratio),
            ("stroke", &self.stroke),
        ];
        for (name, v) in vecs {
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return Some(format!("{name}[storey {}] = {}", i + 1, v[i]));
            }
        }
        let scalars = [
            (
                "peak_floor_acceleration",
                Some(self.peak_floor_acceleration),
            ),
            ("peak_base_shear", Some(self.peak_base_shear)),
            ("peak_displacement", Some(self.peak_displacement)),
            ("energy_input", self.energy_input),
            ("energy_friction", self.energy_friction),
            ("strain_energy_area", self.strain_energy_area),
            ("energy_plastic", self.energy_plastic),
            ("peak_ductility", self.peak_ductility()),
        ];
        for (name, v) in scalars {
            if let Some(v) = v
                && !v.is_finite()
            {
                return Some(format!("{name} = {v}"));
            }
        }
        for (i, d) in self.dampers.iter().flatten().enumerate() {
            if let Some((name, v)) = d.values().into_iter().find(|(_, v)| !v.is_finite()) {
                return Some(format!("damper {name}[storey {}] = {v}", i + 1));
            }
        }
        None
    }

    /// Every value is finite.
    pub fn is_finite(&self) -> bool {
        let opt = |o: Option<f64>| o.is_none_or(f64::is_finite);
        self.drift_ratio.iter().all(|v| v.is_finite())
            && self.residual_drift_ratio.iter().all(|v| v.is_finite())
            && self.stroke.iter().all(|v| v.is_finite())
            && self.peak_floor_acceleration.is_finite()
            && self.peak_base_shear.is_finite()
            && self.peak_displacement.is_finite()
            && opt(self.energy_input)
            && opt(self.energy_friction)
            && opt(self.strain_energy_area)
            && opt(self.energy_plastic)
            && opt(self.peak_ductility())
            && self
                .dampers
                .iter()
                .flatten()
                .all(|d| d.values().iter().all(|(_, v)| v.is_finite()))
    }
}
