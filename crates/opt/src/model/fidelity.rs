//! Fidelity: the method, time step and energies a batch of simulations runs at — the
//! sweep's and the reference check's, both read from the study
//! ([`Fidelity::sweep`], [`Fidelity::check`], defined beside the study);
//! the sweep's method and why it was chosen ([`SweepMethod`], chosen by
//! [`crate::eval::probe`]). Part of a study's
//! fingerprint ([`crate::model::fingerprint`]) and of every check-journal key
//! ([`crate::eval::evaluate::TaskJournal`]).

use slipload_sim::scene::MethodName;

/// Largest cost of `exact` on a study's building, in `newmark`'s, at which the study
/// sweeps with `exact` when its file names no method: at about twice the time, a sweep at
/// the reference's accuracy is worth it (the finalists' check then has nothing to correct).
pub const EXACT_SWEEP_COST: f64 = 2.0;

/// The method a study sweeps and refines with, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepMethod {
    /// The method.
    pub method: MethodName,
    /// Why it was chosen, in a sentence (the manifest and `optimize` report it).
    pub reason: String,
}

/// Method and accuracy of a batch of simulations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fidelity {
    /// Method.
    pub method: MethodName,
    /// Time step, s; `None`: sim's default for each record ([`slipload_sim::scene::default_dt`]).
    pub dt_s: Option<f64>,
    /// Factor on that time step (1 for the sweep, `check_dt_factor` for the check).
    pub dt_factor: f64,
    /// Accumulate energies (E_friction/E_input, strain-energy area).
    pub energies: bool,
    /// Record the per-damper demands (a study with limits, at the check fidelity: the
    /// device table reads them).
    pub dampers: bool,
    /// Compute the derivatives of the responses with respect to the slip loads (the
    /// `sqp` refiner's evaluations; `newmark`, `hht` and `bilinear` only).
    pub sensitivities: bool,
}

impl Fidelity {
    /// A text that tells fidelities apart (method, step bits, factor bits, energies).
    pub fn tag(&self) -> String {
        format!(
            "{} dt={} x{:016x} energies={}",
            self.method.as_str(),
            self.dt_s.map_or_else(
                || "default".to_string(),
                |d| format!("{:016x}", d.to_bits())
            ),
            self.dt_factor.to_bits(),
            self.energies
        ) + if self.dampers { " dampers" } else { "" }
            + if self.sensitivities {
                " sensitivities"
            } else {
                ""
            }
    }
}

/// HHT α of a study's runs: −0.05 for `hht`, 0 otherwise.
pub fn hht_alpha(method: MethodName) -> f64 {
    if method == MethodName::Hht {
        -0.05
    } else {
        0.0
    }
}
