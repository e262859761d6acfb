//! Objectives: a weighted sum of suite statistics of per-record response metrics.
//!
//! With several suites, each term's statistic is taken per suite and the suites are
//! averaged with equal weight (a suite of 20 records does not outweigh one of 7).

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use serde::{Deserialize, Serialize};
use std::ops::Range;

/// A per-record response metric.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Metric {
    /// Peak interstorey drift ratio, max over the storeys (dimensionless).
    PeakDriftRatio,
    /// Peak absolute floor acceleration, max over the floors, m/s².
    PeakFloorAcceleration,
    /// Peak base shear, N.
    BaseShear,
    /// Residual drift ratio, max over the storeys.
    ResidualDriftRatio,
    /// E_friction / E_input (to maximise: the objective uses 1 − ratio).
    EnergyRatio,
    /// Filiatrault & Cherry (1988) relative performance index against the bare frame:
    /// RPI = ½ (SEA/SEA₀ + u_max/u_max,0), SEA = ∫ E_strain dt (strain energy of the
    /// frame and of the braces, as sim accumulates it), u_max the peak floor displacement
    /// (max over floors), index 0 = bare frame under the same record.
    Rpi,
    /// Peak storey ductility (peak drift / yield drift), max over the yielding storeys.
    PeakDuctility,
    /// Plastic (hysteretic) energy of the yielding storeys, J.
    HystereticEnergy,
    /// Friction share of the dissipated energy, E_friction / (E_friction + E_plastic) (to
    /// maximise: the objective uses 1 − share).
    FrictionShare,
}

impl Metric {
    /// Name as written.
    pub fn as_str(self) -> &'static str {
        match self {
            Metric::PeakDriftRatio => "peak_drift_ratio",
            Metric::PeakFloorAcceleration => "peak_floor_acceleration",
            Metric::BaseShear => "base_shear",
            Metric::ResidualDriftRatio => "residual_drift_ratio",
            Metric::EnergyRatio => "energy_ratio",
            Metric::Rpi => "rpi",
            Metric::PeakDuctility => "peak_ductility",
            Metric::HystereticEnergy => "hysteretic_energy",
            Metric::FrictionShare => "friction_share",
        }
    }

    /// The metric's value for one record (`bare`: the bare frame under the same record).
    /// Lower is better for every metric (the energy ratio enters as 1 − ratio).
    pub fn value(self, m: &RecordMetrics, bare: Option<&RecordMetrics>) -> Result<f64, OptError> {
        let need = |o: Option<f64>, what: &str| {
            o.ok_or_else(|| {
                OptError::Missing(format!("{} needs {what} (energies off)", self.as_str()))
            })
        };
        Ok(match self {
            Metric::PeakDriftRatio => m.peak_drift_ratio(),
            Metric::PeakFloorAcceleration => m.peak_floor_acceleration,
            Metric::BaseShear => m.peak_base_shear,
            Metric::ResidualDriftRatio => m.residual(),
            Metric::EnergyRatio => {
                let input = need(m.energy_input, "the input energy")?;
                let friction = need(m.energy_friction, "the friction energy")?;
                if input > 0.0 {
                    1.0 - friction / input
                } else {
                    1.0
                }
            }
            Metric::Rpi => {
                let b = bare.ok_or_else(|| {
                    OptError::Missing("rpi needs the bare frame's response".into())
                })?;
                let sea = need(m.strain_energy_area, "the strain-energy area")?;
                let sea0 = need(b.strain_energy_area, "the bare frame's strain-energy area")?;
                let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { 1.0 };
                0.5 * (ratio(sea, sea0) + ratio(m.peak_displacement, b.peak_displacement))
            }
            Metric::PeakDuctility => m.peak_ductility().ok_or_else(|| {
                OptError::Missing(
                    "peak_ductility needs a frame whose storeys yield (storey_yield in the building)"
                        .into(),
                )
            })?,
            Metric::HystereticEnergy => {
                need(m.energy_plastic, "yielding storeys (storey_yield) and energies")?
            }
            Metric::FrictionShare => {
                let friction = need(m.energy_friction, "the friction energy")?;
                let plastic = m.energy_plastic.unwrap_or(0.0);
                let total = friction + plastic;
                if total > 0.0 { plastic / total } else { 0.0 }
            }
        })
    }
}

/// A statistic over the records of a suite.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Statistic {
    /// Arithmetic mean.
    Mean,
    /// Median (mean of the middle two for an even count).
    Median,
    /// 84th percentile (linear interpolation between order statistics, rank p·(n−1)).
    P84,
    /// Maximum.
    Max,
}

impl Statistic {
    /// Name as written.
    pub fn as_str(self) -> &'static str {
        match self {
            Statistic::Mean => "mean",
            Statistic::Median => "median",
            Statistic::P84 => "p84",
            Statistic::Max => "max",
        }
    }

    /// The statistic of `values` (summed in order: deterministic). NaN for no values.
    pub fn of(self, values: &[f64]) -> f64 {
        if values.is_empty() {
            return f64::NAN;
        }
        match self {
            Statistic::Mean => values.iter().sum::<f64>() / values.len() as f64,
            Statistic::Max => values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            Statistic::Median => percentile(values, 0.5),
            Statistic::P84 => percentile(values, 0.84),
        }
    }
}

/// Percentile `p` ∈ [0, 1] by linear interpolation at rank p·(n−1).
pub fn percentile(values: &[f64], p: f64) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let pos = p * (v.len() - 1) as f64;
    let lo = pos.floor() as usize;
    let hi = pos.ceil() as usize;
    v[lo] + (pos - lo as f64) * (v[hi] - v[lo])
}

/// One term of an objective.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Term {
    /// The metric.
    pub metric: Metric,
    /// The statistic over each suite.
    pub statistic: Statistic,
    /// Weight (default 1).
    #[serde(default = "one")]
    pub weight: f64,
}

fn one() -> f64 {
    1.0
}

/// The dampers' cost: a price per kN of slip load and per device (a damper whose slip
/// load is above zero). As an objective it asks for the least dampers that meet the
/// study's limits: the sum Σ per_kn · Fᵢ/kN + per_device · #{Fᵢ > 0} over the design's
/// dampers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Cost {
    /// Price per kN of slip load (default 1: the objective is the total slip load in kN).
    #[serde(default = "one")]
    pub per_kn: f64,
    /// Price per device (default 0).
    #[serde(default)]
    pub per_device: f64,
}

impl Cost {
    /// The cost of slip loads `loads_n` (N).
    pub fn of(&self, loads_n: &[f64]) -> f64 {
        let kn: f64 = loads_n.iter().map(|f| f / 1e3).sum();
        let devices = loads_n.iter().filter(|f| **f > 0.0).count() as f64;
        self.per_kn * kn + self.per_device * devices
    }

    /// A short label: `total slip load (kN)`, or the prices.
    pub fn label(&self) -> String {
        if self.per_kn == 1.0 && self.per_device == 0.0 {
            return "total slip load (kN)".into();
        }
        let mut parts = Vec::new();
        if self.per_kn != 0.0 {
            parts.push(format!("{} per kN of slip load", self.per_kn));
        }
        if self.per_device != 0.0 {
            parts.push(format!("{} per device", self.per_device));
        }
        format!("cost ({})", parts.join(" + "))
    }
}

/// A weighted sum of terms, or the dampers' cost.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Objective {
    /// The terms (none for a cost objective).
    pub terms: Vec<Term>,
    /// The dampers' cost, for the objective "least dampers that meet the limits" (absent
    /// for a response objective).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cost: Option<Cost>,
}

impl Objective {
    /// Value of one term over the given suites: its statistic per suite, averaged over
    /// the suites. `records[i]` and `bare[i]` are record i's responses.
    pub fn term_value(
        term: &Term,
        records: &[RecordMetrics],
        bare: Option<&[RecordMetrics]>,
        suites: &[Range<usize>],
    ) -> Result<f64, OptError> {
        let mut sum = 0.0;
        for s in suites {
            let vals = s
                .clone()
                .map(|i| term.metric.value(&records[i], bare.map(|b| &b[i])))
                .collect::<Result<Vec<f64>, _>>()?;
            sum += term.statistic.of(&vals);
        }
        Ok(sum / suites.len() as f64)
    }

    /// Σ weight · term value; +∞ for a design that collapses on a record of the suites
    /// (it fails that record: it ranks after every design that stands, and refiners treat
    /// it as a rejected step).
    pub fn value(
        &self,
        records: &[RecordMetrics],
        bare: Option<&[RecordMetrics]>,
        suites: &[Range<usize>],
    ) -> Result<f64, OptError> {
        if suites
            .iter()
            .flat_map(|s| s.clone())
            .any(|i| records[i].collapsed())
        {
            return Ok(f64::INFINITY);
        }
        let mut f = 0.0;
        for t in &self.terms {
            f += t.weight * Objective::term_value(t, records, bare, suites)?;
        }
        if !f.is_finite() {
            return Err(OptError::NonFinite {
                design: "(the design evaluated)".into(),
                record: format!("{} records", records.len()),
                quantity: format!("objective {} = {f}", self.label()),
            });
        }
        Ok(f)
    }

    /// The cost part of the objective for slip loads `loads_n` (N): 0 without a cost.
    pub fn cost_value(&self, loads_n: &[f64]) -> f64 {
        self.cost.map_or(0.0, |c| c.of(loads_n))
    }

    /// A short label, e.g. `mean peak_drift_ratio`.
    pub fn label(&self) -> String {
        if let Some(c) = &self.cost {
            return c.label();
        }
        self.terms
            .iter()
            .map(|t| {
                let w = if t.weight == 1.0 {
                    String::new()
                } else {
                    format!("{} × ", t.weight)
                };
                format!("{w}{} {}", t.statistic.as_str(), t.metric.as_str())
            })
            .collect::<Vec<_>>()
            .join(" + ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_of_a_known_sample() {
        let v = [4.0, 1.0, 3.0, 2.0, 5.0];
        assert_eq!(Statistic::Mean.of(&v), 3.0);
        assert_eq!(Statistic::Median.of(&v), 3.0);
        assert_eq!(Statistic::Max.of(&v), 5.0);
        // rank 0.84·4 = 3.36 → 4 + 0.36·(5 − 4)
        assert!((Statistic::P84.of(&v) - 4.36).abs() < 1e-12);
        assert_eq!(Statistic::Median.of(&[1.0, 2.0]), 1.5);
    }
}
