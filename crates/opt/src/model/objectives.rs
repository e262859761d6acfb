//! The objectives of a multi-objective study (the study's `objectives` list): each a
//! response metric with its statistic over the suites, or a property of the design
//! itself (the damper size), every one minimised.

use crate::base::error::OptError;
use crate::model::objective::{Metric, Statistic};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Fewest and most objectives of a front.
pub const OBJECTIVES: std::ops::RangeInclusive<usize> = 2..=4;

/// What one objective measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ParetoMetric {
    /// Peak interstorey drift ratio, max over the storeys.
    PeakDriftRatio,
    /// Peak absolute floor acceleration, max over the floors, m/s².
    PeakFloorAcceleration,
    /// Peak base shear, N.
    BaseShear,
    /// Residual drift ratio, max over the storeys.
    ResidualDriftRatio,
    /// Peak storey ductility (a frame whose storeys yield).
    PeakDuctility,
    /// 1 − E_friction / E_input (lower: more of the input dissipated by friction).
    EnergyRatio,
    /// Filiatrault–Cherry relative performance index against the bare frame.
    Rpi,
    /// Damper size: the sum of the slip loads, N (a property of the design: no
    /// statistic).
    DamperSize,
    /// Damper size relative to the floors: Σ slip load / (floor mass · g) over the
    /// dissipators (no statistic).
    DamperSizeRatio,
}

impl ParetoMetric {
    /// Name as written.
    pub fn as_str(self) -> &'static str {
        match self {
            ParetoMetric::DamperSize => "damper_size",
            ParetoMetric::DamperSizeRatio => "damper_size_ratio",
            other => other.response().map_or("", Metric::as_str),
        }
    }

    /// The response metric, for the metrics read from the simulations.
    pub fn response(self) -> Option<Metric> {
        Some(match self {
            ParetoMetric::PeakDriftRatio => Metric::PeakDriftRatio,
            ParetoMetric::PeakFloorAcceleration => Metric::PeakFloorAcceleration,
            ParetoMetric::BaseShear => Metric::BaseShear,
            ParetoMetric::ResidualDriftRatio => Metric::ResidualDriftRatio,
            ParetoMetric::PeakDuctility => Metric::PeakDuctility,
            ParetoMetric::EnergyRatio => Metric::EnergyRatio,
            ParetoMetric::Rpi => Metric::Rpi,
            ParetoMetric::DamperSize | ParetoMetric::DamperSizeRatio => return None,
        })
    }
}

/// One objective of the study's `objectives` list.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParetoObjective {
    /// The metric.
    pub metric: ParetoMetric,
    /// The statistic over each suite's records (response metrics; default mean), the
    /// suites then averaged with equal weight as the objective does.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub statistic: Option<Statistic>,
}

impl ParetoObjective {
    /// The statistic a response metric takes (mean when not given).
    pub fn statistic(&self) -> Statistic {
        self.statistic.unwrap_or(Statistic::Mean)
    }

    /// A short label: `mean peak_drift_ratio`, `damper_size`.
    pub fn label(&self) -> String {
        match self.metric.response() {
            Some(m) => format!("{} {}", self.statistic().as_str(), m.as_str()),
            None => self.metric.as_str().to_string(),
        }
    }

    /// A column name: `mean_peak_drift_ratio`, `damper_size`.
    pub fn column(&self) -> String {
        self.label().replace(' ', "_")
    }

    /// The unit the values are in (SI), for tables.
    pub fn unit(&self) -> &'static str {
        match self.metric {
            ParetoMetric::PeakFloorAcceleration => "m/s²",
            ParetoMetric::BaseShear | ParetoMetric::DamperSize => "N",
            _ => "",
        }
    }

    /// Whether this objective needs the energies accumulated.
    pub fn needs_energies(&self) -> bool {
        matches!(self.metric, ParetoMetric::EnergyRatio | ParetoMetric::Rpi)
    }

    /// Whether it needs the bare frame's responses (the relative performance index).
    pub fn needs_bare(&self) -> bool {
        self.metric == ParetoMetric::Rpi
    }
}

/// Checks a study's `objectives` list (and `pareto` settings) as written: 2 to 4
/// entries, no repeats, a statistic for the response metrics only. `yielding`: whether
/// the building's storeys yield (`peak_ductility` needs it; `None` before the building
/// is read).
pub fn validate(
    objectives: &[ParetoObjective],
    yielding: Option<bool>,
    path: &Path,
) -> Result<(), OptError> {
    if !OBJECTIVES.contains(&objectives.len()) {
        return Err(OptError::invalid(
            path,
            "objectives",
            format!(
                "a front takes 2 to 4 objectives, got {} (one objective is the study's `objective`: leave `objectives` out)",
                objectives.len()
            ),
        ));
    }
    for (i, o) in objectives.iter().enumerate() {
        let field = format!("objectives[{i}]");
        if o.metric.response().is_none() && o.statistic.is_some() {
            return Err(OptError::invalid(
                path,
                format!("{field}.statistic"),
                format!(
                    "{} is a property of the design, the same for every record: it takes no statistic (leave `statistic` out)",
                    o.metric.as_str()
                ),
            ));
        }
        if let Some(k) = objectives[..i]
            .iter()
            .position(|p| p.metric == o.metric && p.statistic() == o.statistic())
        {
            return Err(OptError::invalid(
                path,
                field,
                format!(
                    "repeats objectives[{k}] ({}): each objective once",
                    o.label()
                ),
            ));
        }
        if o.metric == ParetoMetric::PeakDuctility && yielding == Some(false) {
            return Err(OptError::invalid(
                path,
                format!("{field}.metric"),
                "peak_ductility needs a frame whose storeys yield (storey_yield in the building); this building is elastic",
            ));
        }
    }
    Ok(())
}

/// Settings of the front's search (the study's `pareto` object).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParetoConfig {
    /// Designs the search adds to the sweep's (default 100; each runs every record).
    #[serde(default = "default_designs")]
    pub designs: usize,
    /// Designs per generation (default 10).
    #[serde(default = "default_batch")]
    pub batch: usize,
    /// The first poll step of every design, in variables scaled to [0, 1] (default 0.2:
    /// a fifth of each slip load's range).
    #[serde(default = "default_radius")]
    pub initial_radius: f64,
}

fn default_designs() -> usize {
    100
}
fn default_batch() -> usize {
    10
}
fn default_radius() -> f64 {
    0.2
}

impl Default for ParetoConfig {
    fn default() -> Self {
        ParetoConfig {
            designs: default_designs(),
            batch: default_batch(),
            initial_radius: default_radius(),
        }
    }
}

/// Most designs a front's search may add (liftable with `--allow-large`).
pub const MAX_SEARCH_DESIGNS: usize = 100_000;

impl ParetoConfig {
    /// Checks the settings as written.
    pub fn validate(&self, path: &Path) -> Result<(), OptError> {
        if self.batch == 0 {
            return Err(OptError::invalid(
                path,
                "pareto.batch",
                "must be at least 1",
            ));
        }
        if self.designs > MAX_SEARCH_DESIGNS && !slipload_sim::limits::allow_large() {
            return Err(OptError::invalid(
                path,
                "pareto.designs",
                format!(
                    "{} designs is more than {MAX_SEARCH_DESIGNS} (a front needs hundreds; --allow-large lifts the limit)",
                    self.designs
                ),
            ));
        }
        let r = self.initial_radius;
        if !(r.is_finite() && r > 0.0 && r <= 1.0) {
            return Err(OptError::invalid(
                path,
                "pareto.initial_radius",
                format!("must be in (0, 1], got {r}"),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn o(metric: ParetoMetric, statistic: Option<Statistic>) -> ParetoObjective {
        ParetoObjective { metric, statistic }
    }

    #[test]
    fn validation_names_the_field() {
        let p = Path::new("s.json");
        let drift = o(ParetoMetric::PeakDriftRatio, Some(Statistic::Mean));
        let accel = o(ParetoMetric::PeakFloorAcceleration, None);
        assert!(validate(&[drift, accel], Some(false), p).is_ok());
        let e = validate(&[drift], None, p).unwrap_err().to_string();
        assert!(e.contains("`objectives`") && e.contains("2 to 4"), "{e}");
        let e = validate(&[drift, accel, accel, drift, drift], None, p)
            .unwrap_err()
            .to_string();
        assert!(e.contains("got 5"), "{e}");
        // mean is the default statistic: the same objective twice
        let e = validate(&[drift, o(ParetoMetric::PeakDriftRatio, None)], None, p)
            .unwrap_err()
            .to_string();
        assert!(e.contains("objectives[1]") && e.contains("repeats"), "{e}");
        let e = validate(
            &[drift, o(ParetoMetric::DamperSize, Some(Statistic::Max))],
            None,
            p,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("objectives[1].statistic"), "{e}");
        let duct = o(ParetoMetric::PeakDuctility, Some(Statistic::P84));
        let e = validate(&[drift, duct], Some(false), p)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("objectives[1].metric") && e.contains("yield"),
            "{e}"
        );
        assert!(validate(&[drift, duct], Some(true), p).is_ok());
    }

    #[test]
    fn labels_and_columns() {
        let a = o(ParetoMetric::PeakFloorAcceleration, Some(Statistic::P84));
        assert_eq!(a.label(), "p84 peak_floor_acceleration");
        assert_eq!(a.column(), "p84_peak_floor_acceleration");
        assert_eq!(o(ParetoMetric::DamperSize, None).label(), "damper_size");
    }
}
