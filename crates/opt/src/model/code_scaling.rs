//! Suites scaled to a code spectrum (`scale.code_spectrum`): the period range built from
//! the building, the record count the standard asks for, the suite's factor (one for all,
//! or each record's own first) and what the study keeps of it ([`CodeScaling`]).

use crate::base::error::OptError;
use crate::model::check::SuiteLimits;
use crate::model::check::short;
use crate::model::code_spectrum::{EN1998_MEAN_FROM, ScalingRule};
pub use crate::model::code_spectrum::{MIN_CODE_PAIRS, MIN_CODE_RECORDS};
use crate::model::config::{CodeSpectrumConfig, Hazard, MIN_STUDY_PGA_G};
use crate::model::objective::Statistic;
use serde::{Deserialize, Serialize};
use slipload_motion::{
    En1998Spectrum, G, Record, RecordPair, ScalingOptions, SpectrumTable, Target, TargetMatch,
    TargetSpectrum,
};
use slipload_sim::{Building, ScalingPeriods};
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
    /// S_DS, S_D1 (g) and T_L (s) of the design spectrum, as the study gives them (the
    /// ASCE 7-16 form; absent for the others).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sds_g: Option<f64>,
    /// S_D1, g.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sd1_g: Option<f64>,
    /// T_L, s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tl_s: Option<f64>,
    /// The table the study gives (before the hazard's factor), for the table form.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub table: Option<SpectrumTable>,
    /// The EN 1998-1 spectrum as resolved (a_g = γ_I·a_gR, S, T_B, T_C, T_D, ξ, η).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub en1998: Option<En1998Target>,
    /// The rule, when not ASCE 7-16's (`en1998`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rule: Option<ScalingRule>,
    /// With the EN 1998-1 rule: the scaled suite's mean PGA against a_g·S.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub zero_period: Option<ZeroPeriodCheck>,
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

/// The EN 1998-1 target of a suite, as code-check.json states it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct En1998Target {
    /// The ground type.
    pub ground_type: String,
    /// The spectrum type, 1 or 2.
    pub spectrum_type: u8,
    /// a_gR, g.
    pub agr_g: f64,
    /// γ_I.
    pub importance: f64,
    /// The spectrum (a_g = γ_I·a_gR).
    pub spectrum: En1998Spectrum,
}

/// The zero-period condition of EN 1998-1 §3.2.3.1.2(4)b on a scaled suite.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ZeroPeriodCheck {
    /// The scaled suite's mean PGA (pairs: the mean of their peak ground acceleration over
    /// every direction), g.
    pub mean_pga_g: f64,
    /// a_g·S, the target at T = 0, g.
    pub ag_s_g: f64,
    /// Whether it set the factor (the spectral condition alone would give less).
    pub binds: bool,
}

impl CodeScaling {
    /// The clause of the rule the suite was scaled by (its 90 % condition over the range):
    /// ASCE 7-16 §16.2.3, or EN 1998-1 §3.2.3.1.2 for the `en1998` rule.
    pub fn clause(&self) -> &'static str {
        match self.rule {
            Some(ScalingRule::En1998) => "EN 1998-1 §3.2.3.1.2",
            _ => "ASCE 7-16 §16.2.3",
        }
    }

    /// The target in words for code-check.md, with the clause the suite was scaled by.
    pub fn target_text(&self) -> String {
        let clause = self.clause();
        if let (Some(sds), Some(sd1), Some(tl)) = (self.sds_g, self.sd1_g, self.tl_s) {
            return format!("S_DS = {sds} g, S_D1 = {sd1} g, T_L = {tl} s; {clause}");
        }
        if let Some(t) = &self.table {
            let p = t.periods_s();
            return format!(
                "a table of {} periods from {} to {} s, interpolated linearly in ln T – ln Sa; {clause}",
                p.len(),
                p[0],
                p[p.len() - 1]
            );
        }
        if let Some(e) = &self.en1998 {
            let c = e.spectrum.corners;
            return format!(
                "EN 1998-1 §3.2.2.2 elastic spectrum, ground type {}, Type {}: a_g = γ_I·a_gR = {} × {} g, S = {}, T_B = {} s, T_C = {} s, T_D = {} s, ξ = {} %, η = {:.4}; {clause}",
                e.ground_type,
                e.spectrum_type,
                e.importance,
                e.agr_g,
                c.s,
                c.tb_s,
                c.tc_s,
                c.td_s,
                e.spectrum.damping_percent,
                e.spectrum.eta
            );
        }
        clause.to_string()
    }
}

/// With the EN 1998-1 rule and fewer than [`EN1998_MEAN_FROM`] accelerograms, the design
/// value is the most unfavourable response (§4.3.3.4.3(3), as the project reads it): a
/// criterion of suite `i` on another statistic is refused, naming it.
fn most_unfavourable(
    limits: Option<&SuiteLimits>,
    count: usize,
    path: &Path,
    i: usize,
) -> Result<(), OptError> {
    if count >= EN1998_MEAN_FROM {
        return Ok(());
    }
    let Some(l) = limits else { return Ok(()) };
    if let Some((k, c)) = l
        .criteria
        .iter()
        .enumerate()
        .find(|(_, c)| c.statistic != Statistic::Max)
    {
        return Err(OptError::invalid(
            path,
            format!("suites[{i}].limits.criteria[{k}].statistic"),
            format!(
                "is {:?}: with {count} accelerograms (fewer than {EN1998_MEAN_FROM}) EN 1998-1 §4.3.3.4.3(3) takes the most unfavourable response, not the {}; give \"max\", or at least {EN1998_MEAN_FROM} accelerograms",
                c.statistic.as_str(),
                c.statistic.as_str()
            ),
        ));
    }
    Ok(())
}

/// What a code-scaled suite's period range is built from: the bare frame's first period
/// and, where the braced frame has modes, its [`ScalingPeriods`] (a chain's, or a
/// building in plan's read along its principal directions).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ScalingBasis {
    /// T₁ of the bare frame, s (a plan: the larger first-mode period of x and y).
    pub t1_s: f64,
    /// The periods with the dampers stuck and the 90 %-mass modes.
    pub periods: Option<ScalingPeriods>,
}

impl ScalingBasis {
    /// A chain's.
    pub fn of(building: &Building) -> ScalingBasis {
        ScalingBasis {
            t1_s: building.t1(),
            periods: building.scaling_periods(),
        }
    }
}

/// The period range of a code-scaled suite: [0.2 T, 2 T] for a given T (`period_s`);
/// else from the building (ASCE 7-16 §16.2.3.1, docs/MODEL.md § Ground motions in code
/// form): the lower end the lesser of 0.2 × the first period with every damper stuck and
/// the period of the last mode needed for 90 % of the mass, the upper end 2 × the bare
/// frame's first period (the dampers slipping). Returns (T, range, stuck T₁, 90 %-mass
/// period).
fn scaling_range(
    basis: &ScalingBasis,
    period_s: Option<f64>,
) -> (f64, [f64; 2], Option<f64>, Option<f64>) {
    if let Some(t) = period_s {
        return (t, [0.2 * t, 2.0 * t], None, None);
    }
    let t1 = basis.t1_s;
    match basis.periods {
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
/// order); fewer than the rule's count (ASCE 7-16: 11 records, Ch. 16, or 7 pairs, Ch. 18;
/// EN 1998-1: 3 accelerograms, §3.2.3.1.2(4)a), or the study's `min_records`, is refused
/// with the number needed. By the EN 1998-1 rule the factor is also at least a_g·S over
/// the mean PGA (§3.2.3.1.2(4)b), and with fewer than 7 accelerograms every criterion of
/// the suite's `limits` must be a maximum ([`most_unfavourable`]).
pub(crate) fn scale_to_code(
    unscaled: &[Record],
    pairs: &[RecordPair],
    c: &CodeSpectrumConfig,
    limits: Option<&SuiteLimits>,
    basis: &ScalingBasis,
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
    let rule = c
        .rule()
        .map_err(|e| OptError::invalid(path, format!("suites[{i}].scale.code_spectrum.rule"), e))?;
    let (records_needed, pairs_needed) = rule.min_counts();
    let (count, what, standard, source_rule) = match (pairs.is_empty(), rule) {
        (true, ScalingRule::Asce7) => (
            unscaled.len(),
            "records",
            records_needed,
            "ASCE 7-16 Ch. 16",
        ),
        (false, ScalingRule::Asce7) => (pairs.len(), "pairs", pairs_needed, "ASCE 7-16 Ch. 18"),
        (true, ScalingRule::En1998) => (
            unscaled.len(),
            "records",
            records_needed,
            "EN 1998-1 §3.2.3.1.2(4)a",
        ),
        (false, ScalingRule::En1998) => (
            pairs.len(),
            "pairs",
            pairs_needed,
            "EN 1998-1 §3.2.3.1.2(4)a",
        ),
    };
    let needed = c.min_records.unwrap_or(standard);
    if count < needed {
        let source = match c.min_records {
            Some(_) => "the study's scale.code_spectrum.min_records".to_string(),
            None => format!(
                "{source_rule} asks for at least {standard} {what}; a study that follows another rule gives scale.code_spectrum.min_records"
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
    if rule == ScalingRule::En1998 {
        most_unfavourable(limits, count, path, i)?;
    }
    let hazard = c.hazard().map_err(|e| {
        OptError::invalid(path, format!("suites[{i}].scale.code_spectrum.hazard"), e)
    })?;
    let h = hazard.factor();
    let given = c.target(path, i)?;
    let target = given.scaled(h).map_err(|e| {
        OptError::invalid(
            path,
            format!("suites[{i}].scale.code_spectrum"),
            e.to_string(),
        )
    })?;
    let (period, range, stuck, mass_90) = scaling_range(basis, c.period_s);
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
    // the range inside the target's periods (a table's span, EN 1998-1's 4 s)
    if let Err(e) = slipload_motion::check_span(&target, range) {
        let field = match (&given, c.period_s) {
            (TargetSpectrum::Table(_), _) => "table.periods_s",
            (_, Some(_)) => "period_s",
            _ => "en1998",
        };
        return Err(OptError::invalid(
            path,
            format!("suites[{i}].scale.code_spectrum.{field}"),
            format!(
                "{e} (the range is built from the building's periods, docs/MODEL.md § Ground motions in code form)"
            ),
        ));
    }
    let options = ScalingOptions {
        per_record: c.per_record,
        zero_period_floor_m_s2: (rule == ScalingRule::En1998).then(|| target.sa_m_s2(0.0)),
    };
    let damping = c.damping();
    let (matched, scaled) = if pairs.is_empty() {
        let a = slipload_motion::scale_suite(unscaled, &target, range, damping, &options)?;
        let m = TargetMatch {
            factor: a.factor,
            controlling_period_s: a.controlling_period_s,
            periods_s: a.periods_s,
            mean_psa_m_s2: a.mean_psa_m_s2,
            target_psa_m_s2: a.target_psa_m_s2,
            zero_period: a.zero_period,
        };
        (m, a.suite.records)
    } else {
        let a = slipload_motion::scale_pairs(pairs, &target, range, damping, &options)?;
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
                    "scales {} to a PGA of {pga_g:.3e} g, below {MIN_STUDY_PGA_G} g: no dissipator slips and every design is the bare frame (check {})",
                    r.name(),
                    match given {
                        TargetSpectrum::Asce7(_) => "S_DS and S_D1",
                        TargetSpectrum::Table(_) => "the table's sa_g",
                        TargetSpectrum::En1998(_) => "agr_g",
                    }
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
    let asce = c.asce7();
    let (table, en1998) = match &given {
        TargetSpectrum::Asce7(_) => (None, None),
        TargetSpectrum::Table(t) => (Some(t.clone()), None),
        TargetSpectrum::En1998(spectrum) => (
            None,
            c.en1998.as_ref().map(|e| En1998Target {
                ground_type: e.ground_type.clone(),
                spectrum_type: e.spectrum_type,
                agr_g: e.agr_g,
                importance: e.importance.unwrap_or(1.0),
                spectrum: *spectrum,
            }),
        ),
    };
    let scaling = CodeScaling {
        record_factors,
        hazard,
        sds_g: asce.map(|x| x.0),
        sd1_g: asce.map(|x| x.1),
        tl_s: asce.map(|x| x.2),
        table,
        en1998,
        rule: (rule != ScalingRule::Asce7).then_some(rule),
        zero_period: a.zero_period.map(|z| ZeroPeriodCheck {
            mean_pga_g: z.mean_m_s2 * a.factor / G,
            ag_s_g: z.floor_m_s2 / G,
            binds: z.binds,
        }),
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
