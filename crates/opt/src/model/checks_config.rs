//! The study keys of the checks around the response history: the frame's strength
//! without dampers (`frame_strength`), the design wind (`wind`) and the drift the
//! deformation-sensitive nonstructural components are designed for (`nonstructural`).

use crate::base::error::OptError;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The study key `frame_strength`: what the equivalent-lateral-force demand of the frame
/// without dampers needs beyond the design spectrum (taken from the study's first suite
/// scaled to a code spectrum).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrameStrengthConfig {
    /// The response modification coefficient R of the seismic force-resisting system
    /// (ASCE 7-16 Table 12.2-1).
    pub response_modification: f64,
    /// The importance factor I_e (Table 1.5-2); default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub importance: Option<f64>,
    /// The fraction of the demand the frame without dampers must reach; default 0.75
    /// (1 for an irregular structure, which the study states).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fraction: Option<f64>,
    /// The period of the demand, s; default the bare frame's first period.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub period_s: Option<f64>,
}

/// The study key `wind`: the design wind's storey shears, which no damper may slip under
/// (design practice: a slip load at its lower property bound of at least `factor` × its
/// storey's wind shear).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WindConfig {
    /// The design wind's storey shear of each storey, kN, bottom to top.
    pub storey_shears_kn: Vec<f64>,
    /// The margin over the wind shear; default 1.3.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub factor: Option<f64>,
}

/// The study key `nonstructural`: the storey drift ratio the deformation-sensitive
/// nonstructural components are designed for, and the flag a storey gets when the
/// design's drift passes `factor` × it (docs/MODEL.md § The 150 % drift flag).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NonstructuralConfig {
    /// The drift ratio the components are designed for, every storey's (or
    /// `drift_ratios`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drift_ratio: Option<f64>,
    /// The drift ratio the components are designed for, per storey, bottom to top.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drift_ratios: Option<Vec<f64>>,
    /// The multiple of it that flags a storey; default 1.5.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub factor: Option<f64>,
}

impl NonstructuralConfig {
    /// The designed-for drift ratio of each of `storeys` storeys (as validated).
    pub fn designed(&self, storeys: usize) -> Vec<f64> {
        match (&self.drift_ratios, self.drift_ratio) {
            (Some(v), _) => v.clone(),
            (None, Some(v)) => vec![v; storeys],
            (None, None) => Vec::new(),
        }
    }
}

/// Checks the study key against the building's `storeys`: positive finite drifts below 1
/// (one, or one per storey) and a factor of at least 1.
pub fn validate_nonstructural(
    c: &NonstructuralConfig,
    storeys: usize,
    path: &Path,
) -> Result<(), OptError> {
    let bad = |field: String, why: String| Err(OptError::invalid(path, field, why));
    let ok = |v: f64| v.is_finite() && v > 0.0 && v < 1.0;
    match (c.drift_ratio, &c.drift_ratios) {
        (Some(_), Some(_)) | (None, None) => {
            return bad(
                "nonstructural".into(),
                "give `drift_ratio` (one for every storey) or `drift_ratios` (one per storey), one of them".into(),
            );
        }
        (Some(v), None) if !ok(v) => {
            return bad(
                "nonstructural.drift_ratio".into(),
                format!("{v}: a storey drift ratio (drift / storey height) in (0, 1), e.g. 0.01"),
            );
        }
        (None, Some(v)) => {
            if v.len() != storeys {
                return bad(
                    "nonstructural.drift_ratios".into(),
                    format!(
                        "{} values for a building of {storeys} storeys: one per storey, bottom to top",
                        v.len()
                    ),
                );
            }
            if let Some((s, x)) = v.iter().enumerate().find(|(_, x)| !ok(**x)) {
                return bad(
                    format!("nonstructural.drift_ratios[{s}]"),
                    format!("{x}: a storey drift ratio in (0, 1)"),
                );
            }
        }
        _ => {}
    }
    if let Some(f) = c.factor
        && !(f.is_finite() && f >= 1.0)
    {
        return bad(
            "nonstructural.factor".into(),
            format!("{f}: a multiple of the designed-for drift, at least 1 (default 1.5)"),
        );
    }
    Ok(())
}
