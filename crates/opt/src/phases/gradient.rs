//! The derivatives of a design's objective and limit ratios with respect to the scaled
//! variables z ([`Gradient`]), from the derivatives its runs carry
//! ([`RecordMetrics::tangent`]: the sensitivities of `newmark`).
//!
//! The objective and the limits are statistics of the runs' responses (a mean, a largest
//! value, a count) that the study computes one way only. Rather than a second, derived
//! copy of each, the responses of every run are moved along their derivative with respect
//! to one slip load, ±ε, and the study's own functions read both: the central difference
//! of a piecewise-linear statistic (a mean, a largest value away from a tie) is its
//! derivative exactly, of a smooth one to O(ε²), and no simulation is run. ε is 1e-6 of
//! the largest slip load (at least 1 N·1e3): the responses move by about 1e-7 of
//! themselves, far above round-off and far below any tie the statistics could cross.

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::model::study::Study;
use crate::phases::refine::Gradient;

/// Relative size of the move ε (see the module doc).
const MOVE: f64 = 1e-6;

/// The derivatives of the design `loads_n` (N per damper) whose runs are `rows` (`bare`:
/// the bare frame's), with the ratios of its check when `limits`; `None` when a run
/// carries no derivatives or one of them is not finite (a collapsed design's objective).
pub fn gradient(
    study: &Study,
    rows: &[RecordMetrics],
    bare: &[RecordMetrics],
    loads_n: &[f64],
    limits: bool,
) -> Result<Option<Gradient>, OptError> {
    if rows.is_empty() || rows.iter().any(|r| r.tangent.is_none()) {
        return Ok(None);
    }
    let cases = study.case_objectives(rows, bare, loads_n)?;
    let p = loads_n.len();
    let eps = MOVE * loads_n.iter().fold(1e3, |m: f64, v| m.max(v.abs()));
    let ratios = |rows: &[RecordMetrics]| -> Result<Vec<f64>, OptError> {
        Ok(if limits {
            study.check_design(rows)?.smooth_ratios()
        } else {
            Vec::new()
        })
    };
    // per damper: ∂(case objectives)/∂F and ∂(ratios)/∂F
    let mut d_cases = vec![vec![0.0; p]; cases.len()];
    let mut d_ratios: Vec<Vec<f64>> = Vec::new();
    for q in 0..p {
        let side = |s: f64| -> Result<(Vec<f64>, Vec<f64>), OptError> {
            let moved: Vec<RecordMetrics> = rows.iter().map(|r| r.moved(q, s * eps)).collect();
            let mut loads = loads_n.to_vec();
            loads[q] += s * eps;
            Ok((
                study.case_objectives(&moved, bare, &loads)?,
                ratios(&moved)?,
            ))
        };
        let ((cp, rp), (cm, rm)) = (side(1.0)?, side(-1.0)?);
        for (k, (a, b)) in cp.iter().zip(&cm).enumerate() {
            d_cases[k][q] = (a - b) / (2.0 * eps);
        }
        if d_ratios.is_empty() {
            d_ratios = vec![vec![0.0; p]; rp.len()];
        }
        for (l, (a, b)) in rp.iter().zip(&rm).enumerate() {
            d_ratios[l][q] = (a - b) / (2.0 * eps);
        }
    }
    // z → slip loads is affine (offset + basis z): ∂/∂z = basisᵀ ∂/∂F
    let basis = &study.space.basis;
    let to_z = |d: &[f64]| -> Vec<f64> {
        (0..basis.ncols())
            .map(|i| (0..p).map(|q| basis[(q, i)] * d[q]).sum())
            .collect()
    };
    let g = Gradient {
        cases,
        case_grads: d_cases.iter().map(|d| to_z(d)).collect(),
        ratio_grads: d_ratios.iter().map(|d| to_z(d)).collect(),
    };
    // a derivative that is not a number is none (a refiner then reads the design's value
    // alone): never a NaN in a step
    let finite = g.cases.iter().all(|v| v.is_finite())
        && g.case_grads
            .iter()
            .chain(&g.ratio_grads)
            .flatten()
            .all(|v| v.is_finite());
    Ok(finite.then_some(g))
}
