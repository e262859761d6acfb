//! The target of a suite scaled to a code spectrum (`scale.code_spectrum`) as the study
//! writes it: the ASCE 7-16 §11.4.6 design spectrum (`sds_g`, `sd1_g`, `tl_s`), a table of
//! periods and accelerations (`table`) or the EN 1998-1 §3.2.2.2 elastic spectrum
//! (`en1998`); the hazard level; and the rule the suite is scaled and counted by (`rule`:
//! ASCE 7-16 §16.2, or EN 1998-1 §3.2.3.1.2). Checked in full when the study loads
//! ([`CodeSpectrumConfig::validate`]), every refusal naming its field.

use crate::base::error::OptError;
use serde::{Deserialize, Serialize};
use slipload_motion::{
    DesignSpectrum, En1998Corners, En1998Spectrum, GroundType, MotionError, SpectrumTable,
    TargetSpectrum,
};
use std::path::Path;

/// The least number of single-component records of a suite scaled to a code spectrum,
/// unless the study says otherwise (ASCE 7-16 Ch. 16, as the project reads it: 11).
pub const MIN_CODE_RECORDS: usize = 11;
/// The least number of pairs of components of such a suite (ASCE 7-16 Ch. 18, as the
/// project reads it: 7).
pub const MIN_CODE_PAIRS: usize = 7;

/// The least number of accelerograms (single components or pairs) of a suite scaled by
/// the EN 1998-1 rule (§3.2.3.1.2(4)a, as the project reads it: 3).
pub const MIN_EN1998_ACCELEROGRAMS: usize = 3;

/// The number of accelerograms from which EN 1998-1 takes the mean response, not the
/// most unfavourable (§4.3.3.4.3(3), as the project reads it: 7).
pub const EN1998_MEAN_FROM: usize = 7;

/// The least target intensity a study may give, g (as `scale.pga_g` and the others).
const MIN_G: f64 = slipload_sim::scene::TARGET_PGA_BAND_G.0;

/// The target of a suite scaled to a code spectrum: one of its three forms, at a hazard
/// level, scaled and counted by a rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CodeSpectrumConfig {
    /// S_DS, g: the design spectral response acceleration at short periods (ASCE 7-16
    /// §11.4.5); with `sd1_g` and `tl_s`, the ASCE form.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sds_g: Option<f64>,
    /// S_D1, g: the design spectral response acceleration at 1 s (§11.4.5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sd1_g: Option<f64>,
    /// T_L, s: the long-period transition period (§11.4.6).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tl_s: Option<f64>,
    /// The hazard level the suite stands for, by name: `design` (the default) or `mce_r`
    /// ([`Hazard`]; read by [`CodeSpectrumConfig::hazard`]).
    #[serde(default)]
    pub hazard: Option<String>,
    /// The period T of the range [0.2 T, 2 T], s (default: a range built from the building,
    /// from its braced and bare first periods and its 90 %-mass modes).
    #[serde(default)]
    pub period_s: Option<f64>,
    /// The least number of records (single components) or pairs the study accepts in the
    /// suite (default: the rule's — 11 records or 7 pairs by ASCE 7-16, 3 by EN 1998-1): a
    /// study that follows another rule says so here.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_records: Option<usize>,
    /// Each record (pair) first fitted to the target by its own factor — the geometric
    /// mean of target/spectrum over the period range — then the suite by one common
    /// factor (default false: one factor for every record).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub per_record: bool,
    /// The target as a table of periods and accelerations.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub table: Option<TableConfig>,
    /// The target as the EN 1998-1 elastic spectrum.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub en1998: Option<Box<En1998Config>>,
    /// The scaling rule by name: `asce7` or `en1998` ([`ScalingRule`]; default `en1998`
    /// with the `en1998` form, else `asce7`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rule: Option<String>,
}

/// A target spectrum given as a table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TableConfig {
    /// The periods, s: ≥ 0, strictly increasing.
    pub periods_s: Vec<f64>,
    /// The 5 %-damped spectral acceleration at each, g.
    pub sa_g: Vec<f64>,
}

/// The EN 1998-1 horizontal elastic spectrum as the study gives it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct En1998Config {
    /// a_gR, g: the reference peak ground acceleration on type A ground (§3.2.1(3)).
    pub agr_g: f64,
    /// The ground type, `A` … `E` (Table 3.1).
    pub ground_type: String,
    /// The spectrum type, 1 or 2 (§3.2.2.2(2)P).
    pub spectrum_type: u8,
    /// γ_I, the importance factor: a_g = γ_I·a_gR (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub importance: Option<f64>,
    /// ξ, the viscous damping in percent (default 5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping_percent: Option<f64>,
    /// S (default: Table 3.2 or 3.3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub s: Option<f64>,
    /// T_B, s (default: Table 3.2 or 3.3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tb_s: Option<f64>,
    /// T_C, s (default: Table 3.2 or 3.3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tc_s: Option<f64>,
    /// T_D, s (default: Table 3.2 or 3.3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub td_s: Option<f64>,
}

/// A hazard level of a code-scaled suite.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Hazard {
    /// The design earthquake: the design spectrum of S_DS and S_D1 itself.
    #[default]
    Design,
    /// The risk-targeted maximum considered earthquake: 1.5 × the design spectrum
    /// (ASCE 7-16 §11.4.5: S_DS = 2/3 S_MS, S_D1 = 2/3 S_M1).
    MceR,
}

impl Hazard {
    /// The factor on the design spectrum: 1 for `design`, 1.5 for `mce_r`.
    pub fn factor(self) -> f64 {
        match self {
            Hazard::Design => 1.0,
            Hazard::MceR => 1.5,
        }
    }

    /// The level's name as a study file writes it.
    pub fn as_str(self) -> &'static str {
        match self {
            Hazard::Design => "design",
            Hazard::MceR => "mce_r",
        }
    }
}

/// The rule a code-scaled suite is scaled and counted by.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ScalingRule {
    /// ASCE 7-16 §16.2: 11 records (7 pairs), the scaled mean spectrum at least 90 % of
    /// the target over the range.
    #[default]
    Asce7,
    /// EN 1998-1 §3.2.3.1.2(4): at least 3 accelerograms, the mean PGA at least a_g·S
    /// (the target at T = 0), the mean spectrum at least 90 % of the target over the
    /// range; fewer than 7 take the most unfavourable response (§4.3.3.4.3(3)).
    En1998,
}

impl ScalingRule {
    /// The rule's name as a study file writes it.
    pub fn as_str(self) -> &'static str {
        match self {
            ScalingRule::Asce7 => "asce7",
            ScalingRule::En1998 => "en1998",
        }
    }

    /// The least number of single records and of pairs the rule asks for.
    pub fn min_counts(self) -> (usize, usize) {
        match self {
            ScalingRule::Asce7 => (MIN_CODE_RECORDS, MIN_CODE_PAIRS),
            ScalingRule::En1998 => (MIN_EN1998_ACCELEROGRAMS, MIN_EN1998_ACCELEROGRAMS),
        }
    }
}

/// A field's check: finite and > 0.
pub(crate) fn finite_positive(path: &Path, field: &str, v: f64) -> Result<(), OptError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(OptError::invalid(
            path,
            field,
            format!("must be finite and > 0, got {v}"),
        ))
    }
}

/// A suite's target intensity (g) within [`slipload_sim::scene::TARGET_PGA_BAND_G`]'s
/// least and [`slipload_motion::MAX_ABS_ACCEL_G`].
pub(crate) fn intensity_g(path: &Path, field: &str, v: f64) -> Result<(), OptError> {
    finite_positive(path, field, v)?;
    let max = slipload_motion::MAX_ABS_ACCEL_G;
    if !(MIN_G..=max).contains(&v) {
        return Err(OptError::invalid(
            path,
            field,
            format!(
                "{v:e} g is outside {MIN_G} … {max} g: below it no dissipator slips and every design is the bare frame, beyond it no ground has shaken (wrong units?)"
            ),
        ));
    }
    Ok(())
}

impl CodeSpectrumConfig {
    /// The hazard level named by `hazard` (`design` when absent); an unknown name is an
    /// error that lists the names.
    pub fn hazard(&self) -> Result<Hazard, String> {
        match self.hazard.as_deref() {
            None | Some("design") => Ok(Hazard::Design),
            Some("mce_r") => Ok(Hazard::MceR),
            Some(other) => Err(format!(
                "unknown hazard level {other:?}: expected \"design\" (the design earthquake) or \"mce_r\" (the risk-targeted maximum considered earthquake, 1.5 x design)"
            )),
        }
    }

    /// The rule named by `rule` (default: `en1998` with the `en1998` form, else `asce7`);
    /// an unknown name is an error that lists the names.
    pub fn rule(&self) -> Result<ScalingRule, String> {
        match self.rule.as_deref() {
            None if self.en1998.is_some() => Ok(ScalingRule::En1998),
            None | Some("asce7") => Ok(ScalingRule::Asce7),
            Some("en1998") => Ok(ScalingRule::En1998),
            Some(other) => Err(format!(
                "unknown scaling rule {other:?}: expected \"asce7\" (ASCE 7-16 §16.2) or \"en1998\" (EN 1998-1 §3.2.3.1.2)"
            )),
        }
    }

    /// S_DS, S_D1 (g) and T_L (s) of the ASCE form; `None` for a table or EN 1998-1.
    pub fn asce7(&self) -> Option<(f64, f64, f64)> {
        Some((self.sds_g?, self.sd1_g?, self.tl_s?))
    }

    /// The damping ratio of the target and of the records' spectra compared with it:
    /// ξ/100 of the EN 1998-1 form, else 0.05.
    pub fn damping(&self) -> f64 {
        match &self.en1998 {
            Some(e) => e.damping_percent.unwrap_or(5.0) / 100.0,
            None => 0.05,
        }
    }

    /// Checks every field of suite `i`'s code spectrum (see [`CodeSpectrumConfig::target`]
    /// for the forms), naming the field that fails.
    pub fn validate(&self, path: &Path, i: usize) -> Result<(), OptError> {
        let g = |k: &str| format!("suites[{i}].scale.code_spectrum.{k}");
        let hazard = self
            .hazard()
            .map_err(|e| OptError::invalid(path, g("hazard"), e))?;
        let rule = self
            .rule()
            .map_err(|e| OptError::invalid(path, g("rule"), e))?;
        if let Some(t) = self.period_s {
            finite_positive(path, &g("period_s"), t)?;
        }
        let target = self.target(path, i)?;
        if self.en1998.is_some() && hazard != Hazard::Design {
            return Err(OptError::invalid(
                path,
                g("hazard"),
                "the EN 1998-1 spectrum is taken as the study gives it (a_g = γ_I·a_gR): for another return period give its agr_g or importance, and leave hazard out (or \"design\")",
            ));
        }
        if rule == ScalingRule::En1998 {
            match &target {
                TargetSpectrum::Table(t) if t.periods_s()[0] != 0.0 => {
                    return Err(OptError::invalid(
                        path,
                        g("table.periods_s[0]"),
                        format!(
                            "is {} s: the en1998 rule holds the suite's mean PGA to the target at T = 0 (a_g·S, EN 1998-1 §3.2.3.1.2(4)b); begin the table at period 0",
                            self.table.as_ref().map_or(0.0, |t| t.periods_s[0])
                        ),
                    ));
                }
                TargetSpectrum::Asce7(_) => {
                    return Err(OptError::invalid(
                        path,
                        g("rule"),
                        "the en1998 rule takes the en1998 form, or a table that begins at period 0 (its value there is a_g·S): the ASCE 7-16 spectrum has no a_g·S",
                    ));
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// The target spectrum as the study gives it (before the hazard's factor): the ASCE
    /// 7-16 form of `sds_g`, `sd1_g` and `tl_s`; a `table`; or `en1998`, with S, T_B, T_C
    /// and T_D from EN 1998-1 Table 3.2 (Type 1) or 3.3 (Type 2) where the study gives
    /// none, a_g = γ_I·a_gR.
    ///
    /// Errors: [`OptError::Invalid`] naming the field for no form or more than one, a
    /// missing or bad value.
    pub fn target(&self, path: &Path, i: usize) -> Result<TargetSpectrum, OptError> {
        let g = |k: &str| format!("suites[{i}].scale.code_spectrum.{k}");
        let spectrum_err = |prefix: &str, e: MotionError| match e {
            MotionError::InvalidSpectrum {
                field,
                value,
                expected,
            } => OptError::invalid(
                path,
                g(&format!("{prefix}{field}")),
                format!("is {value}: expected {expected}"),
            ),
            other => OptError::invalid(path, g(prefix.trim_end_matches('.')), other.to_string()),
        };
        let asce = [
            ("sds_g", self.sds_g),
            ("sd1_g", self.sd1_g),
            ("tl_s", self.tl_s),
        ];
        let has_asce = asce.iter().any(|(_, v)| v.is_some());
        let forms = usize::from(has_asce)
            + usize::from(self.table.is_some())
            + usize::from(self.en1998.is_some());
        if forms != 1 {
            return Err(OptError::invalid(
                path,
                format!("suites[{i}].scale.code_spectrum"),
                format!(
                    "{}: give exactly one target — sds_g, sd1_g and tl_s (the ASCE 7-16 §11.4.6 spectrum), table {{ periods_s, sa_g }}, or en1998 {{ agr_g, ground_type, spectrum_type, … }} (EN 1998-1 §3.2.2.2)",
                    if forms == 0 {
                        "no target spectrum".to_string()
                    } else {
                        format!("{forms} target spectra")
                    }
                ),
            ));
        }
        if has_asce {
            let mut v = [0.0; 3];
            for (k, (key, value)) in asce.iter().enumerate() {
                let Some(x) = value else {
                    return Err(OptError::invalid(
                        path,
                        g(key),
                        "required with the ASCE 7-16 form (sds_g, sd1_g and tl_s together)",
                    ));
                };
                if k < 2 {
                    intensity_g(path, &g(key), *x)?;
                } else {
                    finite_positive(path, &g(key), *x)?;
                }
                v[k] = *x;
            }
            let d = DesignSpectrum::new(v[0], v[1], v[2]).map_err(|e| {
                OptError::invalid(
                    path,
                    format!("suites[{i}].scale.code_spectrum"),
                    e.to_string(),
                )
            })?;
            return Ok(TargetSpectrum::Asce7(d));
        }
        if let Some(t) = &self.table {
            let table = SpectrumTable::new(t.periods_s.clone(), t.sa_g.clone())
                .map_err(|e| spectrum_err("table.", e))?;
            return Ok(TargetSpectrum::Table(table));
        }
        let Some(e) = &self.en1998 else {
            return Err(OptError::invalid(
                path,
                format!("suites[{i}].scale.code_spectrum"),
                "no target spectrum",
            ));
        };
        intensity_g(path, &g("en1998.agr_g"), e.agr_g)?;
        let ground = GroundType::from_name(&e.ground_type).ok_or_else(|| {
            OptError::invalid(
                path,
                g("en1998.ground_type"),
                format!(
                    "unknown ground type {:?}: expected \"A\", \"B\", \"C\", \"D\" or \"E\" (EN 1998-1 Table 3.1; S1 and S2 need a special study and have no recommended spectrum: give it as a table)",
                    e.ground_type
                ),
            )
        })?;
        let recommended = En1998Corners::recommended(ground, e.spectrum_type).ok_or_else(|| {
            OptError::invalid(
                path,
                g("en1998.spectrum_type"),
                format!(
                    "is {}: expected 1 (Table 3.2) or 2 (Table 3.3, where the earthquakes that contribute most to the hazard have a surface-wave magnitude M_s ≤ 5.5; EN 1998-1 §3.2.2.2(2)P)",
                    e.spectrum_type
                ),
            )
        })?;
        let importance = e.importance.unwrap_or(1.0);
        if !(importance.is_finite() && importance > 0.0 && importance <= 3.0) {
            return Err(OptError::invalid(
                path,
                g("en1998.importance"),
                format!("must be an importance factor γ_I in (0, 3], got {importance}"),
            ));
        }
        let corners = En1998Corners {
            s: e.s.unwrap_or(recommended.s),
            tb_s: e.tb_s.unwrap_or(recommended.tb_s),
            tc_s: e.tc_s.unwrap_or(recommended.tc_s),
            td_s: e.td_s.unwrap_or(recommended.td_s),
        };
        let ag = importance * e.agr_g;
        intensity_g(path, &g("en1998.importance"), ag).map_err(|_| {
            OptError::invalid(
                path,
                g("en1998.importance"),
                format!(
                    "puts a_g = γ_I·a_gR = {ag} g outside {MIN_G} … {} g",
                    slipload_motion::MAX_ABS_ACCEL_G
                ),
            )
        })?;
        let spectrum = En1998Spectrum::new(ag, corners, e.damping_percent.unwrap_or(5.0))
            .map_err(|err| spectrum_err("en1998.", err))?;
        Ok(TargetSpectrum::En1998(spectrum))
    }
}
