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
        }
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
