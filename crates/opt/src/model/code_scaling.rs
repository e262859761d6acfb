//! Suites scaled to a code spectrum (`scale.code_spectrum`): the period range built from
//! the building, the record count the standard asks for, the suite's factor (one for all,
//! or each record's own first) and what the study keeps of it ([`CodeScaling`]).

use crate::base::error::OptError;
use crate::model::check::short;
use crate::model::config::{CodeSpectrumConfig, Hazard, MIN_STUDY_PGA_G};
use serde::{Deserialize, Serialize};
use slipload_motion::{DesignSpectrum, G, Record, RecordPair, TargetMatch};
use slipload_sim::Building;
use std::path::Path;

/// A suite scaled to a code spectrum (ASCE 7-16 §16.2.3): one factor for every record,
/// the smallest that puts the suite's mean 5 %-damped spectrum at or above 90 % of the
/// target at every period of the range ([`slipload_motion::scale_suite_over_range`]): by
/// default from the lesser of 0.2 × the first period with the dampers stuck and the period
/// of the last mode needed for 90 % of the mass, to 2 × the bare frame's first period
/// (docs/MODEL.md § Ground motions in code form); [0.2 T, 2 T] for a given `period_s`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CodeScaling {
    /// The hazard level.
    pub hazard: Hazard,
    /// S_DS, S_D1 (g) and T_L (s) of the design spectrum, as the study gives them.
    pub sds_g: f64,
    /// S_D1, g.
    pub sd1_g: f64,
    /// T_L, s.
    pub tl_s: f64,
    /// T, s: the period the range's upper end is built on (2 T): the bare frame's first
    /// period, or the study's `period_s`.
    pub period_s: f64,
    /// The period range, s.
    pub range_s: [f64; 2],
    /// The first period with every damper stuck (the braced frame), s, when the range was
    /// built from the building (no `period_s`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stuck_period_s: Option<f64>,
    /// The period of the last mode needed for 90 % of the mass (the shorter of the bare and
    /// the braced frame's), s, when the range was built from the building.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass_90_period_s: Option<f64>,
    /// The number of pairs, when the suite is pairs of components scaled by their mean
    /// maximum-direction (RotD100) spectrum (`mean_sa_g` is then that mean); absent for
    /// single components.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pairs: Option<usize>,
    /// The suite's factor (every record × this).
    pub factor: f64,
    /// The period where the scaled mean spectrum meets 90 % of the target, s.
    pub controlling_period_s: f64,
    /// The periods the spectra are compared at, s (log-spaced over the range).
    pub periods_s: Vec<f64>,
    /// The scaled suite's mean 5 %-damped pseudo-spectral acceleration there, g.
    pub mean_sa_g: Vec<f64>,
    /// The target spectrum there (the design spectrum × the hazard's factor), g.
    pub target_sa_g: Vec<f64>,
    /// With `per_record`: each record's factor (its own fit to the target times the
    /// suite's `factor`; both components of a pair alike), in the suite's order; empty
    /// otherwise.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub record_factors: Vec<f64>,
}

/// The least number of single-component records of a suite scaled to a code spectrum,
/// unless the study says otherwise (ASCE 7-16 Ch. 16, as the project reads it: 11).
pub const MIN_CODE_RECORDS: usize = 11;
/// The least number of pairs of components of such a suite (ASCE 7-16 Ch. 18, as the
/// project reads it: 7).
pub const MIN_CODE_PAIRS: usize = 7;

/// The period range of a code-scaled suite: [0.2 T, 2 T] for a given T (`period_s`);
/// else from the building (ASCE 7-16 §16.2.3.1, docs/MODEL.md § Ground motions in code
/// form): the lower end the lesser of 0.2 × the first period with every damper stuck and
/// the period of the last mode needed for 90 % of the mass, the upper end 2 × the bare
/// frame's first period (the dampers slipping). Returns (T, range, stuck T₁, 90 %-mass
/// period).
fn scaling_range(
    building: &Building,
    period_s: Option<f64>,
) -> (f64, [f64; 2], Option<f64>, Option<f64>) {
    if let Some(t) = period_s {
        return (t, [0.2 * t, 2.0 * t], None, None);
    }
    let t1 = building.t1();
    match building.scaling_periods() {
        Some(p) => {
            let lower = (0.2 * p.stuck_t1_s).min(p.mass_90_period_s);
            (
                t1,
                [lower, 2.0 * t1],
                Some(p.stuck_t1_s),
                Some(p.mass_90_period_s),
            )
        }
        None => (t1, [0.2 * t1, 2.0 * t1], None, None),
    }
}

/// Scales the records of suite `i` by one factor to the code spectrum `c` over its range
/// ([`scaling_range`]), refusing a factor that puts a record below [`MIN_STUDY_PGA_G`].
///
/// A suite is either single components (scaled by their mean spectrum) or pairs (scaled
/// by their mean maximum-direction spectrum, both components of a pair run as records, in
/// order); fewer than the standard's count (11 records, ASCE 7-16 Ch. 16; 7 pairs, Ch. 18),
/// or the study's `min_records`, is refused with the number needed.
pub(crate) fn scale_to_code(
    unscaled: &[Record],
    pairs: &[RecordPair],
    c: &CodeSpectrumConfig,
    building: &Building,
    path: &Path,
    i: usize,
) -> Result<(Vec<Record>, CodeScaling), OptError> {
    if !unscaled.is_empty() && !pairs.is_empty() {
        return Err(OptError::invalid(
            path,
            format!("suites[{i}].records"),
            format!(
                "names {} single records and {} pairs: a suite scaled to a code spectrum is single components (scaled by their spectra) or pairs (by their maximum-direction spectra), not both; make two suites",
                unscaled.len(),
                pairs.len()
            ),
        ));
    }
    let (count, what, standard, rule) = if pairs.is_empty() {
        (
            unscaled.len(),
            "records",
            MIN_CODE_RECORDS,
            "ASCE 7-16 Ch. 16",
        )
    } else {
        (pairs.len(), "pairs", MIN_CODE_PAIRS, "ASCE 7-16 Ch. 18")
    };
    let needed = c.min_records.unwrap_or(standard);
    if count < needed {
        let source = match c.min_records {
            Some(_) => "the study's scale.code_spectrum.min_records".to_string(),
            None => format!(
                "{rule} asks for at least {standard} {what}; a study that follows another rule gives scale.code_spectrum.min_records"
            ),
        };
        return Err(OptError::invalid(
            path,
            format!("suites[{i}].records"),
            format!(
                "{count} {what}: at least {needed} needed ({source}); add {} more",
                needed - count
            ),
        ));
    }
    let hazard = c.hazard().map_err(|e| {
        OptError::invalid(path, format!("suites[{i}].scale.code_spectrum.hazard"), e)
    })?;
    let h = hazard.factor();
    let target = DesignSpectrum::new(c.sds_g * h, c.sd1_g * h, c.tl_s).map_err(|e| {
        OptError::invalid(
            path,
            format!("suites[{i}].scale.code_spectrum"),
            e.to_string(),
        )
    })?;
    let (period, range, stuck, mass_90) = scaling_range(building, c.period_s);
    // a period the study gives: the range's lower end must be one the records resolve
    // (a response spectrum below twice a record's sample interval reads the sampling, not
    // the ground motion)
    if let Some(t) = c.period_s {
        let coarsest = unscaled
            .iter()
            .chain(pairs.iter().flat_map(|p| [p.first(), p.second()]))
            .max_by(|a, b| a.dt().total_cmp(&b.dt()));
        if let Some(r) = coarsest
            && range[0] < 2.0 * r.dt()
        {
            return Err(OptError::invalid(
                path,
                format!("suites[{i}].scale.code_spectrum.period_s"),
                format!(
                    "{t} s puts the range's lower end, 0.2 T = {} s, below twice the sample interval of {} ({} s): its spectrum is not resolved there; give T of at least {} s, or leave period_s out (the range is then built from the building)",
                    short(range[0]),
                    r.name(),
                    r.dt(),
                    short(10.0 * r.dt())
                ),
            ));
        }
    }
    let (matched, scaled) = if pairs.is_empty() {
        let a = if c.per_record {
            slipload_motion::scale_suite_over_range_each(unscaled, &target, range, 0.05)?
        } else {
            slipload_motion::scale_suite_over_range(unscaled, &target, range, 0.05)?
        };
        let m = TargetMatch {
            factor: a.factor,
            controlling_period_s: a.controlling_period_s,
            periods_s: a.periods_s,
            mean_psa_m_s2: a.mean_psa_m_s2,
            target_psa_m_s2: a.target_psa_m_s2,
            zero_period: None,
        };
        (m, a.suite.records)
    } else {
        let a = if c.per_record {
            slipload_motion::scale_pairs_over_range_each(pairs, &target, range, 0.05)?
        } else {
            slipload_motion::scale_pairs_over_range(pairs, &target, range, 0.05)?
        };
        let records = a
            .pairs
            .into_iter()
            .flat_map(|p| [p.first().clone(), p.second().clone()])
            .collect();
        (a.matched, records)
    };
    let a = matched;
    for r in &scaled {
        let pga_g = r.pga() / G;
        if pga_g < MIN_STUDY_PGA_G {
            return Err(OptError::invalid(
                path,
                format!("suites[{i}].scale.code_spectrum"),
                format!(
                    "scales {} to a PGA of {pga_g:.3e} g, below {MIN_STUDY_PGA_G} g: no dissipator slips and every design is the bare frame (check S_DS and S_D1)",
                    r.name()
                ),
            ));
        }
    }
    // each record's factor from its own scale before and after (pairs: both components)
    let record_factors = if c.per_record {
        let before = unscaled
            .iter()
            .chain(pairs.iter().flat_map(|p| [p.first(), p.second()]))
            .map(|r| r.scale_factor());
        scaled
            .iter()
            .zip(before)
            .map(|(r, b)| r.scale_factor() / b)
            .collect()
    } else {
        Vec::new()
    };
    let scaling = CodeScaling {
        record_factors,
        hazard,
        sds_g: c.sds_g,
        sd1_g: c.sd1_g,
        tl_s: c.tl_s,
        period_s: period,
        range_s: range,
        stuck_period_s: stuck,
        mass_90_period_s: mass_90,
        factor: a.factor,
        controlling_period_s: a.controlling_period_s,
        pairs: (!pairs.is_empty()).then_some(pairs.len()),
        mean_sa_g: a.mean_psa_m_s2.iter().map(|m| m * a.factor / G).collect(),
        target_sa_g: a.target_psa_m_s2.iter().map(|t| t / G).collect(),
        periods_s: a.periods_s,
    };
    Ok((scaled, scaling))
}
