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
/// `records` its responses over every run of the study (records × property cases), `bare`
/// the bare frame's (for the relative performance index). A design that collapses on a
/// record of the study, or (a study with limits) misses a limit at some property case,
/// gets +∞ in every objective: it is dominated by every design that stands and passes, so
/// the front is made of passing designs. With the objective reading the worst property
/// case, each response objective is its largest over the cases.
pub fn objective_vector(
    study: &Study,
    loads: &[f64],
    records: &[RecordMetrics],
    bare: Option<&[RecordMetrics]>,
    suites: &[Range<usize>],
) -> Result<Vec<f64>, OptError> {
    let objectives = &study.objectives;
    let n = study.records.len();
    let failed = study.checks.has_limits() && !study.check_design(records)?.passes();
    if failed || records.iter().any(RecordMetrics::collapsed) {
        return Ok(vec![f64::INFINITY; objectives.len()]);
    }
    let cases = match study.checks.reading() {
        crate::model::check::BoundReading::Worst => study.checks.cases().len(),
        crate::model::check::BoundReading::Nominal => 1,
    };
    let mut worst = case_vector(study, loads, &records[..n], bare.map(|b| &b[..n]), suites)?;
    for c in 1..cases {
        let span = c * n..(c + 1) * n;
        let v = case_vector(
            study,
            loads,
            &records[span.clone()],
            bare.map(|b| &b[span]),
            suites,
        )?;
        for (w, x) in worst.iter_mut().zip(v) {
            *w = w.max(x);
        }
    }
    Ok(worst)
}

/// [`objective_vector`] at one property case (`records`, `bare`: its runs).
fn case_vector(
    study: &Study,
    loads: &[f64],
    records: &[RecordMetrics],
    bare: Option<&[RecordMetrics]>,
    suites: &[Range<usize>],
) -> Result<Vec<f64>, OptError> {
    let objectives = &study.objectives;
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
