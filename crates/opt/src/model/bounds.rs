//! A property's bounds λ_min and λ_max (the study key `property_bounds.slip_load`, and
//! `brace_stiffness`): given as numbers, or built from their parts as the standard builds
//! them ([`Derivation`]), which the code check prints.

use crate::base::error::OptError;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Factors on a property: `lower ≤ 1 ≤ upper`, given as numbers or built from their
/// parts ([`Derivation`]); [`Factors::validate`] holds a study to one of the two.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Factors {
    /// λ_min (≤ 1), as a number.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lower: Option<f64>,
    /// λ_max (≥ 1), as a number.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub upper: Option<f64>,
    /// The parts λ_min and λ_max are built from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub derivation: Option<Derivation>,
}

impl Factors {
    /// λ_min and λ_max as numbers.
    pub fn numbers(lower: f64, upper: f64) -> Factors {
        Factors {
            lower: Some(lower),
            upper: Some(upper),
            derivation: None,
        }
    }

    /// (λ_min, λ_max): built from the derivation where there is one, else the numbers
    /// (1 for one left out, which [`Factors::validate`] refuses at load).
    pub fn bounds(&self) -> (f64, f64) {
        match &self.derivation {
            Some(d) => d.bounds(),
            None => (self.lower.unwrap_or(1.0), self.upper.unwrap_or(1.0)),
        }
    }

    /// Either both numbers or the derivation, its parts in range; then
    /// 0 < λ_min ≤ 1 ≤ λ_max, finite. Errors name the field under `prefix`
    /// (`property_bounds.slip_load`).
    pub fn validate(&self, path: &Path, prefix: &str) -> Result<(), OptError> {
        let field = |f: &str| format!("{prefix}.{f}");
        match (self.lower, self.upper, &self.derivation) {
            (Some(_), Some(_), None) => {}
            (None, None, Some(d)) => d.validate().map_err(|(f, msg)| {
                OptError::invalid(path, field(&format!("derivation.{f}")), msg)
            })?,
            (_, _, Some(_)) => {
                return Err(OptError::invalid(
                    path,
                    field("derivation"),
                    "give `lower` and `upper` (λ_min, λ_max) or their `derivation`, not both",
                ));
            }
            (l, _, None) => {
                return Err(OptError::invalid(
                    path,
                    field(if l.is_none() { "lower" } else { "upper" }),
                    "give both `lower` and `upper` (λ_min ≤ 1 ≤ λ_max), or their `derivation` (testing, aging_environment, specification)",
                ));
            }
        }
        let (lower, upper) = self.bounds();
        check_factor(path, &field("lower"), lower, true)?;
        check_factor(path, &field("upper"), upper, false)
    }
}

/// `v` in (0, 1] (`below`) or finite and ≥ 1.
fn in_range(v: f64, below: bool) -> Result<(), String> {
    let ok = v.is_finite() && v > 0.0 && if below { v <= 1.0 } else { v >= 1.0 };
    match (ok, below) {
        (true, _) => Ok(()),
        (false, true) => Err(format!("must be in (0, 1], got {v}")),
        (false, false) => Err(format!("must be finite and ≥ 1, got {v}")),
    }
}

fn check_factor(path: &Path, field: &str, v: f64, below: bool) -> Result<(), OptError> {
    in_range(v, below).map_err(|msg| OptError::invalid(path, field, msg))
}

/// One part of a property's bounds: its factors below and above the nominal value and
/// where they come from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Part {
    /// Factor of the part's lowest value (≤ 1).
    pub min: f64,
    /// Factor of its highest value (≥ 1).
    pub max: f64,
    /// Where the factors come from (a test report, a product approval), for the report.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
}

/// λ_max and λ_min built from their parts as ASCE 7-16 builds them for isolators
/// (§17.2.8.4, Eq. 17.2-1 and 17.2-2) and Ch. 18 for damping devices (§18.2.4.5):
/// λ_max = (1 + s (λ_ae,max − 1)) λ_test,max λ_spec,max and
/// λ_min = (1 − s (1 − λ_ae,min)) λ_test,min λ_spec,min, where s is the share of the
/// ageing and environment factor that counts (0.75 in the standard: not every
/// effect reaches its extreme at once). The standard also bounds the results (λ_max at
/// least, λ_min at most, a default value); the study gives those numbers
/// (`upper_at_least`, `lower_at_most`), which the report names as the study's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Derivation {
    /// λ_test: the spread of the prototype tests (heating, rate, scragging, between
    /// cycles).
    pub testing: Part,
    /// λ_ae: ageing (friction surface, bolt relaxation) and environment (temperature,
    /// contamination) over the design life.
    pub aging_environment: Part,
    /// λ_spec: the tolerance the procurement specification allows a unit from nominal.
    pub specification: Part,
    /// The share of the ageing and environment factor that counts (default 0.75).
    #[serde(default = "default_aging_share")]
    pub aging_share: f64,
    /// The least λ_max the study accepts (where the product is smaller, this governs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub upper_at_least: Option<f64>,
    /// The largest λ_min the study accepts (where the product is larger, this governs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lower_at_most: Option<f64>,
}

fn default_aging_share() -> f64 {
    0.75
}

impl Derivation {
    /// Each part's factors in (0, 1] and [1, ∞), the share in [0, 1], the study's
    /// bounds on the results in the same ranges; an error names the key under
    /// `derivation` and what was expected.
    fn validate(&self) -> Result<(), (String, String)> {
        let range = |name: String, v: f64, below: bool| in_range(v, below).map_err(|m| (name, m));
        for (name, p) in [
            ("testing", &self.testing),
            ("aging_environment", &self.aging_environment),
            ("specification", &self.specification),
        ] {
            range(format!("{name}.min"), p.min, true)?;
            range(format!("{name}.max"), p.max, false)?;
            // the source is printed as a line of code-check.md: one line of text
            if let Some(src) = &p.source
                && (src.trim().is_empty() || src.chars().any(char::is_control))
            {
                return Err((
                    format!("{name}.source"),
                    format!(
                        "{src:?} is blank or holds a control character: give the source on one line"
                    ),
                ));
            }
        }
        if !(0.0..=1.0).contains(&self.aging_share) {
            return Err((
                "aging_share".into(),
                format!(
                    "must be in [0, 1] (0.75 in ASCE 7-16), got {}",
                    self.aging_share
                ),
            ));
        }
        if let Some(v) = self.upper_at_least {
            range("upper_at_least".into(), v, false)?;
        }
        if let Some(v) = self.lower_at_most {
            range("lower_at_most".into(), v, true)?;
        }
        Ok(())
    }

    /// The products before the study's bounds: (λ_min, λ_max).
    pub fn products(&self) -> (f64, f64) {
        let s = self.aging_share;
        let upper = (1.0 + s * (self.aging_environment.max - 1.0))
            * self.testing.max
            * self.specification.max;
        let lower = (1.0 - s * (1.0 - self.aging_environment.min))
            * self.testing.min
            * self.specification.min;
        (lower, upper)
    }

    /// (λ_min, λ_max): the products, held to the study's bounds on them.
    pub fn bounds(&self) -> (f64, f64) {
        let (lower, upper) = self.products();
        (
            self.lower_at_most.map_or(lower, |b| lower.min(b)),
            self.upper_at_least.map_or(upper, |b| upper.max(b)),
        )
    }

    /// The derivation for the report, one line each bound and one a part's source.
    pub fn lines(&self, property: &str) -> Vec<String> {
        let (lower, upper) = self.products();
        let (lo, hi) = self.bounds();
        let s = self.aging_share;
        let (ae, t, sp) = (&self.aging_environment, &self.testing, &self.specification);
        let held = |v: f64, got: f64, bound: Option<f64>, word: &str| match bound {
            Some(b) if got != v => format!("; the study's {word} {b} governs: {got}"),
            Some(b) => format!(" ({word} {b}, the study's bound, holds)"),
            None => String::new(),
        };
        let mut out = vec![
            format!(
                "{property}: λ_max = (1 + {s} × ({} − 1)) × {} × {} = {upper:.4}{}",
                ae.max,
                t.max,
                sp.max,
                held(upper, hi, self.upper_at_least, "at least")
            ),
            format!(
                "{property}: λ_min = (1 − {s} × (1 − {})) × {} × {} = {lower:.4}{}",
                ae.min,
                t.min,
                sp.min,
                held(lower, lo, self.lower_at_most, "at most")
            ),
        ];
        for (name, p) in [
            ("testing", t),
            ("ageing and environment", ae),
            ("specification", sp),
        ] {
            if let Some(src) = &p.source {
                out.push(format!(
                    "{property}, {name} ({} to {}): {src}",
                    p.min, p.max
                ));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn factors(json: &str) -> Result<Factors, String> {
        let f: Factors = serde_json::from_str(json).map_err(|e| e.to_string())?;
        f.validate(Path::new("s.json"), "property_bounds.slip_load")
            .map_err(|e| e.to_string())?;
        Ok(f)
    }

    /// The bounds built from their parts, by hand: λ_max = (1 + 0.75 × 0.2) × 1.1 × 1.06
    /// = 1.3409, λ_min = (1 − 0.75 × 0.1) × 0.9 × 0.93 = 0.774225; the study's bounds
    /// govern only where they are wider.
    #[test]
    fn bounds_built_from_their_parts() {
        let parts = r#""testing": {"min": 0.9, "max": 1.1, "source": "prototype tests"},
            "aging_environment": {"min": 0.9, "max": 1.2},
            "specification": {"min": 0.93, "max": 1.06}"#;
        let f = factors(&format!(r#"{{"derivation": {{{parts}}}}}"#)).unwrap();
        assert!((f.bounds().1 - 1.15 * 1.1 * 1.06).abs() < 1e-15, "{f:?}");
        assert!((f.bounds().0 - 0.925 * 0.9 * 0.93).abs() < 1e-15, "{f:?}");
        let d = f.derivation.as_ref().unwrap();
        let lines = d.lines("slip load");
        assert!(
            lines[0].contains("(1 + 0.75 × (1.2 − 1)) × 1.1 × 1.06 = 1.3409"),
            "{lines:?}"
        );
        assert!(
            lines[1].contains("(1 − 0.75 × (1 − 0.9)) × 0.9 × 0.93 = 0.7742"),
            "{lines:?}"
        );
        assert!(
            lines
                .iter()
                .any(|l| l.contains("testing (0.9 to 1.1): prototype tests"))
        );
        // the study's floor on λ_max governs where the product is smaller; its cap on
        // λ_min holds where the product is already below it
        let f = factors(&format!(
            r#"{{"derivation": {{{parts}, "upper_at_least": 1.4, "lower_at_most": 0.85}}}}"#
        ))
        .unwrap();
        assert_eq!(f.bounds().1, 1.4);
        assert!((f.bounds().0 - 0.925 * 0.9 * 0.93).abs() < 1e-15);
        let lines = f.derivation.as_ref().unwrap().lines("slip load");
        assert!(
            lines[0].ends_with("the study's at least 1.4 governs: 1.4"),
            "{lines:?}"
        );
        assert!(
            lines[1].ends_with("(at most 0.85, the study's bound, holds)"),
            "{lines:?}"
        );
        // a share of 0: the ageing factor does not count
        let f = factors(&format!(
            r#"{{"derivation": {{{parts}, "aging_share": 0}}}}"#
        ))
        .unwrap();
        assert!((f.bounds().1 - 1.1 * 1.06).abs() < 1e-15);
    }

    #[test]
    fn bounds_given_twice_or_out_of_range_are_refused() {
        let parts = r#""testing": {"min": 0.9, "max": 1.1},
            "aging_environment": {"min": 0.9, "max": 1.2},
            "specification": {"min": 0.95, "max": 1.05}"#;
        let e = factors(&format!(
            r#"{{"lower": 0.9, "upper": 1.1, "derivation": {{{parts}}}}}"#
        ))
        .unwrap_err();
        assert!(e.contains("not both"), "{e}");
        let e = factors(r#"{"lower": 0.9}"#).unwrap_err();
        assert!(e.contains("give both `lower` and `upper`"), "{e}");
        let bad = parts.replace(r#""min": 0.95"#, r#""min": 1.05"#);
        let e = factors(&format!(r#"{{"derivation": {{{bad}}}}}"#)).unwrap_err();
        assert!(
            e.contains("property_bounds.slip_load.derivation.specification.min")
                && e.contains("must be in (0, 1], got 1.05"),
            "{e}"
        );
        let lined = parts.replace(
            r#""min": 0.9, "max": 1.1}"#,
            r#""min": 0.9, "max": 1.1, "source": "a\n## b"}"#,
        );
        let e = factors(&format!(r#"{{"derivation": {{{lined}}}}}"#)).unwrap_err();
        assert!(e.contains("derivation.testing.source"), "{e}");
        let e = factors(&format!(
            r#"{{"derivation": {{{parts}, "aging_share": 1.5}}}}"#
        ))
        .unwrap_err();
        assert!(e.contains("derivation.aging_share"), "{e}");
        let e = factors(&format!(r#"{{"derivation": {{{parts}, "tolerance": 1}}}}"#)).unwrap_err();
        assert!(e.contains("unknown field `tolerance`"), "{e}");
        // numbers as before: no derivation, the same bytes written back
        let f = factors(r#"{"lower": 0.85, "upper": 1.15}"#).unwrap();
        assert_eq!(
            serde_json::to_string(&f).unwrap(),
            r#"{"lower":0.85,"upper":1.15}"#
        );
    }
}
