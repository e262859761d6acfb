//! Fidelity: the method, time step and energies a batch of simulations runs at — the
//! sweep's and the reference check's, both read from the study. Part of a study's
//! fingerprint ([`crate::fingerprint`]) and of every check-journal key
//! ([`crate::evaluate::TaskJournal`]).

use crate::study::Study;
use slipload_sim::scene::MethodName;

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
}

impl Fidelity {
    /// The study's sweep fidelity (energies only when the objective needs them).
    pub fn sweep(study: &Study) -> Fidelity {
        Fidelity {
            method: study.config.fidelity.method,
            dt_s: study.config.fidelity.dt_s,
            dt_factor: 1.0,
            energies: study.needs_energies(),
        }
    }
    /// The study's reference check fidelity (energies on).
    pub fn check(study: &Study) -> Fidelity {
        Fidelity {
            method: study.config.fidelity.check_method,
            dt_s: study.config.fidelity.dt_s,
            dt_factor: study.config.fidelity.check_dt_factor,
            energies: true,
        }
    }

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
        )
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
