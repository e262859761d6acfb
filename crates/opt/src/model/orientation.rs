//! How a planar model runs a pair of horizontal components (`suites[].pairs`): each
//! component as its own run (`components`, the default), the pair rotated over a grid of
//! orientations with each orientation a run (`angles`), or the same grid with the largest
//! response over the orientations taken per pair (`worst`) — docs/MODEL.md § Ground
//! motions in code form.
//!
//! Contract: the grid is θ = 0, s, 2s, … < 180° for the step s (default
//! [`DEFAULT_STEP_DEG`]), a_θ = a₁ cos θ + a₂ sin θ
//! ([`slipload_motion::RecordPair::rotated_deg`]); s divides 90°, so both recorded
//! components are on the grid to the bit (θ = 0° and 90°). Half a turn is enough: the
//! planar model's response to −a is the mirror of its response to a (the frame, its yield
//! laws and the friction law are odd in the displacement), so θ + 180° gives the peaks of
//! θ. `worst` runs every orientation and keeps, per response, its largest value over them
//! ([`crate::base::metrics::RecordMetrics::envelope`]): one ground motion, one row of the
//! statistics.

use crate::base::error::OptError;
use serde::{Deserialize, Serialize};
use slipload_motion::{Record, RecordPair};
use std::path::Path;

/// The step between orientations when the study gives none, degrees.
pub const DEFAULT_STEP_DEG: f64 = 30.0;

/// `suites[].pairs` as written.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PairsConfig {
    /// `components` (each component a run, the default), `angles` (the pair at each
    /// orientation of the grid, each a run) or `worst` (per pair, each response's largest
    /// over the orientations).
    pub run: String,
    /// The step between orientations, degrees: a divisor of 90 (default 30: 0°, 30°, …,
    /// 150°).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step_deg: Option<f64>,
}

/// How the pairs of a suite run, resolved.
#[derive(Debug, Clone, PartialEq)]
pub enum PairRun {
    /// Each component a run (the pair as recorded).
    Components,
    /// Each orientation (degrees) a run.
    Angles(Vec<f64>),
    /// Every orientation (degrees) run, each response's largest kept per pair.
    Worst(Vec<f64>),
}

impl PairRun {
    /// What the report says of it, e.g. "each pair at 6 orientations (0°, 30°, …, 150°),
    /// the largest response over them per pair".
    pub fn describe(&self) -> String {
        let grid = |a: &[f64]| {
            let shown: Vec<String> = a.iter().map(|d| format!("{d}°")).collect();
            format!("{} orientations ({})", a.len(), shown.join(", "))
        };
        match self {
            PairRun::Components => {
                "each component of a pair as its own run (the pair as recorded)".into()
            }
            PairRun::Angles(a) => format!(
                "each pair rotated to {} (a_θ = a₁ cos θ + a₂ sin θ), each orientation a run",
                grid(a)
            ),
            PairRun::Worst(a) => format!(
                "each pair rotated to {} (a_θ = a₁ cos θ + a₂ sin θ), each response the largest over them (one row per pair)",
                grid(a)
            ),
        }
    }

    /// The runs of `pair` and, for `worst`, every orientation whose responses envelope
    /// into its one run (that run is the first orientation, named for the pair): (runs,
    /// orientations).
    pub fn runs_of(&self, pair: &RecordPair) -> Result<(Vec<Record>, Vec<Record>), OptError> {
        Ok(match self {
            PairRun::Components => (vec![pair.first().clone(), pair.second().clone()], vec![]),
            PairRun::Angles(a) => (
                a.iter()
                    .map(|&d| pair.rotated_deg(d))
                    .collect::<Result<_, _>>()?,
                vec![],
            ),
            PairRun::Worst(a) => {
                let all: Vec<Record> = a
                    .iter()
                    .map(|&d| pair.rotated_deg(d))
                    .collect::<Result<_, _>>()?;
                let Some(first) = all.first() else {
                    return Ok((vec![], vec![]));
                };
                let named = first.clone().with_name(format!(
                    "{} (worst of {} orientations)",
                    pair.name(),
                    a.len()
                ));
                (vec![named], all)
            }
        })
    }
}

impl PairsConfig {
    /// The resolved run of suite `i`'s pairs; a bad `run` or step names its field.
    pub fn resolve(&self, path: &Path, i: usize) -> Result<PairRun, OptError> {
        let step = self.step_deg.unwrap_or(DEFAULT_STEP_DEG);
        let grid = || -> Result<Vec<f64>, OptError> {
            let per_quarter = 90.0 / step;
            if !(step.is_finite() && step > 0.0 && step <= 90.0)
                || (per_quarter - per_quarter.round()).abs() > 1e-9
            {
                return Err(OptError::invalid(
                    path,
                    format!("suites[{i}].pairs.step_deg"),
                    format!(
                        "{step}: the step between orientations divides 90° (90, 45, 30, 15, 10, 5, …), so both recorded components are among them"
                    ),
                ));
            }
            let n = 2 * per_quarter.round() as usize;
            Ok((0..n).map(|k| k as f64 * 180.0 / n as f64).collect())
        };
        match self.run.as_str() {
            "components" => {
                if self.step_deg.is_some() {
                    return Err(OptError::invalid(
                        path,
                        format!("suites[{i}].pairs.step_deg"),
                        "a step between orientations is for `angles` or `worst`; `components` runs the pair as recorded",
                    ));
                }
                Ok(PairRun::Components)
            }
            "angles" => Ok(PairRun::Angles(grid()?)),
            "worst" => Ok(PairRun::Worst(grid()?)),
            other => Err(OptError::invalid(
                path,
                format!("suites[{i}].pairs.run"),
                format!("{other:?}: expected \"components\", \"angles\" or \"worst\""),
            )),
        }
    }
}
