//! The objective vector of a design under a study's `objectives`: each response
//! objective's statistic over the suites, or the damper size of its slip loads.

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::model::objective::{Objective, Term};
use crate::model::objectives::ParetoMetric;
use crate::model::study::Study;
use slipload_motion::G;
use std::ops::Range;

/// The objective vector of one design: `loads` its slip loads (N per dissipator),
/// `records` its responses over every record of the study, `bare` the bare frame's (for
/// the relative performance index). A design that collapses on a record of the study
/// gets +∞ in every objective (it is dominated by every design that stands).
pub fn objective_vector(
    study: &Study,
    loads: &[f64],
    records: &[RecordMetrics],
    bare: Option<&[RecordMetrics]>,
    suites: &[Range<usize>],
) -> Result<Vec<f64>, OptError> {
    let objectives = &study.objectives;
    if records.iter().any(RecordMetrics::collapsed) {
        return Ok(vec![f64::INFINITY; objectives.len()]);
    }
    objectives
        .iter()
        .map(|o| match o.metric.response() {
            Some(metric) => Objective::term_value(
                &Term {
                    metric,
                    statistic: o.statistic(),
                    weight: 1.0,
                },
                records,
                bare,
                suites,
            ),
            None => Ok(damper_size(study, o.metric, loads)),
        })
        .collect()
}

/// The damper size of a design: Σ slip load (N), or Σ slip load / (floor mass · g).
pub fn damper_size(study: &Study, metric: ParetoMetric, loads: &[f64]) -> f64 {
    match metric {
        ParetoMetric::DamperSizeRatio => study
            .space
            .dampers
            .iter()
            .zip(loads)
            .map(|(&f, s)| s / (study.building.mass.row(f).sum() * G))
            .sum(),
        _ => loads.iter().sum(),
    }
}
