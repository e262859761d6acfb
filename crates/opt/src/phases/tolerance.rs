//! The widest specification tolerance a recommended design affords: the procurement
//! specification's band ±t on every slip load (λ_spec = 1 ± t in the bounds' derivation,
//! [`crate::model::check::Derivation`]) at which the design still meets every limit at
//! its lower- and upper-bound cases. Found by re-checking the design (every case and
//! record at the check fidelity) while the band widens (doubling from the study's own)
//! and then by bisection, to [`PRECISION`]. It assumes that a design that passes at a
//! band passes at every narrower one — wider bounds spread the cases further from the
//! nominal design — and the report says so.

use crate::base::error::OptError;
use crate::eval::evaluate::run_designs;
use crate::model::check::{Derivation, Part};
use crate::model::fidelity::Fidelity;
use crate::model::study::Study;
use serde::Serialize;

/// The band is found to this half-width (0.25 % of the slip load).
pub const PRECISION: f64 = 0.0025;

/// The widest band searched: λ_spec,min = 0.5.
pub const WIDEST: f64 = 0.5;

/// The widest specification tolerance of one design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Tolerance {
    /// The study's own band: the larger of 1 − λ_spec,min and λ_spec,max − 1.
    pub study_band: f64,
    /// The widest band ±t (searched to [`PRECISION`]) at which the design passes; `None`
    /// when it fails even at t = 0.
    pub widest_band: Option<f64>,
    /// The narrowest band found to fail, with the verdict there (`None`: it passes up to
    /// [`WIDEST`]).
    pub fails_at: Option<(f64, String)>,
    /// Checks of the design made (each one run of every case and record).
    pub checks: usize,
    /// Simulations they ran.
    pub simulations: usize,
}

impl Tolerance {
    /// The line for the report.
    pub fn text(&self) -> String {
        let pct = |t: f64| format!("±{:.2} %", 100.0 * t);
        let found = match self.widest_band {
            Some(t) => format!(
                "the widest specification tolerance the design affords is {} on every slip load (the study's {})",
                pct(t),
                pct(self.study_band)
            ),
            None => format!(
                "the design fails even with no specification tolerance (the study's {})",
                pct(self.study_band)
            ),
        };
        let beyond = match &self.fails_at {
            Some((t, verdict)) => format!("; at {} it fails: {verdict}", pct(*t)),
            None => format!("; it passes up to {}, the widest searched", pct(WIDEST)),
        };
        format!(
            "{found}{beyond} (λ_spec = 1 ± t in the bounds' derivation, the other parts as given; by re-checking the design at its bound cases, {} checks, {} simulations, widening then bisecting to {}, on the assumption that a narrower band passes where a wider one does)",
            self.checks,
            self.simulations,
            pct(PRECISION)
        )
    }
}

/// The study's slip-load bounds as built from their parts, which the search needs (`None`:
/// the study gives them as numbers, or has none).
pub fn derivation(study: &Study) -> Option<&Derivation> {
    study
        .checks
        .property_bounds
        .as_ref()
        .and_then(|b| b.slip_load.derivation.as_ref())
}

/// The widest tolerance of the design `loads_n` (N) of `study`, where the study builds
/// its slip-load bounds from their parts ([`derivation`]); `None` otherwise.
pub fn widest(
    study: &Study,
    loads_n: &[f64],
    tick: &(dyn Fn() + Sync),
) -> Result<Option<Tolerance>, OptError> {
    let Some(derivation) = derivation(study).cloned() else {
        return Ok(None);
    };
    let spec = &derivation.specification;
    let study_band = (1.0 - spec.min).max(spec.max - 1.0);
    let fid = Fidelity::check(study);
    let mut checks = 0;
    let mut simulations = 0;
    // the verdict at band t: Ok(()) passes, Err(verdict) fails
    let mut check = |t: f64| -> Result<Result<(), String>, OptError> {
        let banded = with_band(study, &derivation, t);
        let runs = run_designs(&banded, &[loads_n.to_vec()], &fid, tick)?;
        checks += 1;
        simulations += banded.runs();
        let c = banded.check_design(&runs[0])?;
        Ok(if c.passes() { Ok(()) } else { Err(c.verdict()) })
    };
    // (a passing band, a failing band with its verdict)
    let (mut pass, mut fail): (Option<f64>, Option<(f64, String)>) = (None, None);
    match check(study_band)? {
        Ok(()) => pass = Some(study_band),
        Err(v) => {
            fail = Some((study_band, v));
            match check(0.0)? {
                Ok(()) => pass = Some(0.0),
                Err(v) => fail = Some((0.0, v)),
            }
        }
    }
    // widen from a passing band until one fails or the widest is reached
    while let (Some(p), None) = (pass, &fail) {
        if p >= WIDEST {
            break;
        }
        let t = (2.0 * p).clamp(PRECISION, WIDEST);
        match check(t)? {
            Ok(()) => pass = Some(t),
            Err(v) => fail = Some((t, v)),
        }
    }
    // bisect between them
    while let (Some(p), Some((f, _))) = (pass, &fail) {
        if f - p <= PRECISION {
            break;
        }
        let t = 0.5 * (p + f);
        match check(t)? {
            Ok(()) => pass = Some(t),
            Err(v) => fail = Some((t, v)),
        }
    }
    Ok(Some(Tolerance {
        study_band,
        widest_band: pass,
        fails_at: fail,
        checks,
        simulations,
    }))
}

/// `study` with its slip-load specification band ±t (the other parts as given).
fn with_band(study: &Study, derivation: &Derivation, t: f64) -> Study {
    let mut s = study.clone();
    let d = Derivation {
        specification: Part {
            min: 1.0 - t,
            max: 1.0 + t,
            source: None,
        },
        ..derivation.clone()
    };
    if let Some(b) = s.checks.property_bounds.as_mut() {
        b.slip_load.derivation = Some(d);
    }
    s
}
