//! The integration methods a scene names ([`MethodName`]: the options each reads), their
//! resolved settings ([`MethodSettings`]) and the default time step ([`default_dt`]).

use serde::{Deserialize, Serialize};

/// The integration methods.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MethodName {
    /// Newmark average acceleration (γ = ½, β = ¼) with exact implicit friction.
    #[default]
    Newmark,
    /// HHT-α (default α = −0.05) with exact implicit friction.
    Hht,
    /// What frame programs (DRAIN-2D, SAP2000, OpenSees) do: each brace + damper as one
    /// elastic–perfectly plastic spring, dissipator mass ignored, stepped by `newmark`.
    Bilinear,
    /// The paper's method (De la Cruz, López-Almansa & Oller 2007, §4): linear
    /// acceleration, stick/slip decided per floor at every step, three nested fixed-point
    /// loops. Conditionally stable.
    Delacruz,
    /// Event-driven reference: each stick/slip mode integrated exactly (matrix
    /// exponential series), every stick↔slip event located by root finding.
    Exact,
}

impl MethodName {
    /// The name as written in configs and on the command line.
    pub fn as_str(self) -> &'static str {
        match self {
            MethodName::Newmark => "newmark",
            MethodName::Hht => "hht",
            MethodName::Bilinear => "bilinear",
            MethodName::Delacruz => "delacruz",
            MethodName::Exact => "exact",
        }
    }
}

impl MethodName {
    /// Every method, in the order the docs list them.
    pub const ALL: [MethodName; 5] = [
        MethodName::Newmark,
        MethodName::Hht,
        MethodName::Delacruz,
        MethodName::Exact,
        MethodName::Bilinear,
    ];

    /// The `method` fields (beyond `name`) this method reads; any other is refused.
    pub fn options(self) -> &'static [&'static str] {
        match self {
            MethodName::Newmark | MethodName::Bilinear | MethodName::Exact => &["dt"],
            MethodName::Hht => &["dt", "alpha"],
            MethodName::Delacruz => &["dt", "eps_a", "eps_f", "max_iterations"],
        }
    }
}

impl std::str::FromStr for MethodName {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "newmark" => Ok(MethodName::Newmark),
            "hht" => Ok(MethodName::Hht),
            "bilinear" => Ok(MethodName::Bilinear),
            "delacruz" => Ok(MethodName::Delacruz),
            "exact" => Ok(MethodName::Exact),
            other => Err(format!(
                "unknown method {other:?}: expected newmark, hht, bilinear, delacruz or exact"
            )),
        }
    }
}

/// Method and settings, resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MethodSettings {
    /// Method.
    pub name: MethodName,
    /// Time step, s (resolved).
    pub dt: f64,
    /// HHT α (0 for Newmark).
    pub alpha: f64,
    /// `delacruz` acceleration tolerance, m/s² (`None`: |a_g|max/10⁵).
    pub eps_a: Option<f64>,
    /// `delacruz` friction-force tolerance, N (`None`: μN/10⁵ per damper).
    pub eps_f: Option<f64>,
    /// `delacruz` iteration cap per loop (`None`: 100).
    pub max_iterations: Option<u32>,
}

/// Steps per bare-frame fundamental period of the default time step ([`default_dt`]).
pub const DEFAULT_STEPS_PER_PERIOD: f64 = 400.0;

/// Default time step of `method`: T₁/400 of the bare frame (the paper's own T₁/200 for
/// `delacruz`), rounded down so that it divides the record's sample interval (the record is
/// then sampled at steps, not between them, and never more coarsely than it was recorded)
/// — or, without a record, so that it divides the duration (the run ends exactly at it).
///
/// T₁/400 because the step-by-step methods must stay within 1 % of `exact` on every
/// storey's peak drift at their default: over the embedded synthetic suite (10 records,
/// 15 s, 0.4 g) `newmark` at T₁/200 was up to 1.4 % off on the benchmark building and 4.3 %
/// on the ten-storey one (higher modes and the stiff braced state carry the error, not T₁);
/// at T₁/400, 0.40 % and 0.90 % (`scripts/accuracy-study.sh`, results/accuracy/).
pub fn default_dt(method: MethodName, t1: f64, record_dt: Option<f64>, duration: f64) -> f64 {
    let per_period = match method {
        MethodName::Delacruz => 200.0,
        _ => DEFAULT_STEPS_PER_PERIOD,
    };
    let target = t1 / per_period;
    let divide = |span: f64| span / (span / target).ceil().max(1.0);
    match record_dt {
        Some(rdt) => divide(rdt),
        None => divide(duration),
    }
}
