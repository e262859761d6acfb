//! The strength of the frame without its dampers (`frame_strength`): ASCE 7-16 §18.2.1.1
//! asks the seismic force-resisting system of a structure with a damping system to have at
//! least 75 % of the strength it would need without one (100 % where the structure is
//! irregular; the study gives the fraction). The demand is the equivalent lateral force
//! of a frame without dampers (ASCE 7-16 §12.8):
//!
//! - C_s = S_DS / (R/I_e) (Eq. 12.8-2), at most S_D1 / (T R/I_e) for T ≤ T_L and
//!   S_D1 T_L / (T² R/I_e) beyond (Eq. 12.8-3, 12.8-4), at least max(0.044 S_DS I_e, 0.01)
//!   (Eq. 12.8-5); Eq. 12.8-6 (sites with S₁ ≥ 0.6 g) needs S₁, which the study does not
//!   give, and is not applied;
//! - V = C_s W, W the floors' weight (Eq. 12.8-1);
//! - F_x = V w_x h_x^k / Σ w_i h_i^k, k = 1 for T ≤ 0.5 s, 2 for T ≥ 2.5 s, linear
//!   between (Eq. 12.8-11, 12.8-12); the storey shear V_x = Σ_{i ≥ x} F_i.
//!
//! T is the bare frame's first period unless the study gives one (the standard caps the
//! computed period at C_u T_a, which needs the structure type: a study that follows it
//! gives `period_s`). S_DS, S_D1 and T_L are the first code-scaled suite's. Each storey's
//! strength is its yield shear (the building's `storey_yield`), the nominal strength the
//! model uses; a storey without a yield law is elastic in the model and is not checked.

use crate::model::config::ScaleConfig;
use crate::model::study::Study;
use serde::Serialize;
use slipload_motion::G;
use std::fmt::Write as _;

/// One storey's strength against its share of the demand.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StoreyStrength {
    /// Storey (from 1).
    pub storey: usize,
    /// The fraction of the equivalent-lateral-force storey shear, kN.
    pub required_kn: f64,
    /// The storey's yield shear, kN (`None`: elastic in the model, not checked).
    pub strength_kn: Option<f64>,
}

/// The check of the frame's strength without dampers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrameStrength {
    /// The seismic response coefficient C_s.
    pub cs: f64,
    /// The period it was taken at, s.
    pub period_s: f64,
    /// The weight W, kN.
    pub weight_kn: f64,
    /// The base shear V = C_s W, kN.
    pub base_shear_kn: f64,
    /// The distribution exponent k.
    pub k: f64,
    /// The fraction of the demand required.
    pub fraction: f64,
    /// One line per storey, bottom to top.
    pub storeys: Vec<StoreyStrength>,
}

impl FrameStrength {
    /// The check of `study`'s frame, where the study asks for it (`frame_strength`) and
    /// its building has storey heights and a code-scaled suite (checked when it loads).
    pub fn of(study: &Study) -> Option<FrameStrength> {
        let cfg = study.config.frame_strength?;
        // S_DS, S_D1, T_L of the first suite scaled to the ASCE form (a study without one
        // is refused when it loads)
        let (sds_g, sd1_g, tl_s) = study.config.suites.iter().find_map(|s| match &s.scale {
            Some(ScaleConfig::CodeSpectrum(c)) => c.asce7(),
            _ => None,
        })?;
        let b = &study.building;
        let heights = b.storey_heights.as_ref()?;
        let (ie, fraction) = (cfg.importance.unwrap_or(1.0), cfg.fraction.unwrap_or(0.75));
        let t = cfg.period_s.unwrap_or_else(|| b.t1());
        let r = cfg.response_modification / ie;
        let cap = if t <= tl_s {
            sd1_g / (t * r)
        } else {
            sd1_g * tl_s / (t * t * r)
        };
        let cs = (sds_g / r).min(cap).max((0.044 * sds_g * ie).max(0.01));
        let n = b.floors();
        let w: Vec<f64> = (0..n).map(|i| b.mass[(i, i)] * G).collect();
        let weight: f64 = w.iter().sum();
        let v = cs * weight;
        let k = if t <= 0.5 {
            1.0
        } else if t >= 2.5 {
            2.0
        } else {
            1.0 + (t - 0.5) / 2.0
        };
        let mut h = 0.0;
        let whk: Vec<f64> = (0..n)
            .map(|i| {
                h += heights[i];
                w[i] * h.powf(k)
            })
            .collect();
        let total: f64 = whk.iter().sum();
        let storeys = (0..n)
            .map(|x| {
                let shear = v * whk[x..].iter().sum::<f64>() / total;
                StoreyStrength {
                    storey: x + 1,
                    required_kn: fraction * shear / 1e3,
                    strength_kn: b
                        .storey_yield
                        .get(x)
                        .copied()
                        .flatten()
                        .map(|y| y.yield_shear / 1e3),
                }
            })
            .collect();
        Some(FrameStrength {
            cs,
            period_s: t,
            weight_kn: weight / 1e3,
            base_shear_kn: v / 1e3,
            k,
            fraction,
            storeys,
        })
    }

    /// The least ratio strength / required over the storeys checked, with its storey
    /// (`None`: no storey has a yield law).
    pub fn least(&self) -> Option<(f64, usize)> {
        self.storeys
            .iter()
            .filter_map(|s| s.strength_kn.map(|c| (c / s.required_kn, s.storey)))
            .fold(None, |m: Option<(f64, usize)>, x| match m {
                Some(m) if m.0 <= x.0 => Some(m),
                _ => Some(x),
            })
    }

    /// The check as a section of `code-check.md`.
    pub fn to_markdown(&self) -> String {
        let mut s = String::from("## Frame strength without dampers\n\n");
        let _ = writeln!(
            s,
            "ASCE 7-16 §18.2.1.1: each storey's yield shear against {} % of the equivalent-lateral-force storey shear of the frame without a damping system (§12.8): C_s = {:.4} at T = {:.3} s, W = {:.0} kN, V = {:.0} kN, k = {:.3} (Eq. 12.8-6 not applied).\n",
            100.0 * self.fraction,
            self.cs,
            self.period_s,
            self.weight_kn,
            self.base_shear_kn,
            self.k
        );
        s.push_str("| storey | required (kN) | yield shear (kN) | ratio | verdict |\n|---:|---:|---:|---:|---|\n");
        for st in &self.storeys {
            let _ = match st.strength_kn {
                Some(c) => writeln!(
                    s,
                    "| {} | {:.0} | {:.0} | {:.2} | {} |",
                    st.storey,
                    st.required_kn,
                    c,
                    c / st.required_kn,
                    if c >= st.required_kn {
                        "pass"
                    } else {
                        "**FAIL**"
                    }
                ),
                None => writeln!(
                    s,
                    "| {} | {:.0} | — | — | elastic in the model: not checked |",
                    st.storey, st.required_kn
                ),
            };
        }
        s.push('\n');
        s
    }
}
