//! Fidelity: the method, time step and energies a batch of simulations runs at — the
//! sweep's and the reference check's, both read from the study. Part of a study's
//! fingerprint ([`crate::fingerprint`]) and of every check-journal key
//! ([`crate::evaluate::TaskJournal`]).

use crate::error::OptError;
use crate::evaluate::{DesignLoads, simulate_design};
use crate::study::Study;
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

/// The sweep's method: the one `fidelity.method` names; unnamed, `exact` where it costs
/// at most [`EXACT_SWEEP_COST`] times `newmark` on the study's building, else `newmark`.
/// The cost is each method's counted work (`Diagnostics::work`, multiply-adds of its
/// dominant operations) on a probe: the study's first record at the building file's own
/// slip loads, at the sweep's step and outputs. Counted work, not time, so the choice
/// (and every byte after it) is the same on every machine and under any load;
/// `slipload bench` reports each method's time per unit of work beside it. Where `exact`
/// refuses the probe (a chattering or too-stiff dissipator exceeds its budget), the sweep
/// is `newmark` and the reason says so.
pub fn choose_sweep_method(study: &Study) -> Result<SweepMethod, OptError> {
    if let Some(method) = study.config.fidelity.method {
        return Ok(SweepMethod {
            method,
            reason: "named by the study (fidelity.method)".into(),
        });
    }
    let probe = |method: MethodName| {
        let fid = Fidelity {
            method,
            dt_s: study.config.fidelity.dt_s,
            dt_factor: 1.0,
            energies: study.needs_energies(),
        };
        // the building file's design as written (a locked or asymmetric damper as such)
        simulate_design(
            study,
            &DesignLoads::file(study),
            0,
            &fid,
            "file (the sweep-method probe)",
        )
    };
    let record = study.records[0].name();
    let newmark = probe(MethodName::Newmark)?.diagnostics.work;
    let (method, reason) = match probe(MethodName::Exact) {
        Ok(exact) => {
            let ratio = exact.diagnostics.work as f64 / newmark.max(1) as f64;
            let method = if ratio <= EXACT_SWEEP_COST {
                MethodName::Exact
            } else {
                MethodName::Newmark
            };
            (
                method,
                format!(
                    "chosen: exact costs {ratio:.2} x newmark's work on a probe (record {record}, the building's own slip loads); the sweep runs exact where that is at most {EXACT_SWEEP_COST}"
                ),
            )
        }
        Err(e) => (
            MethodName::Newmark,
            format!("chosen: exact refused the probe (record {record}): {e}"),
        ),
    };
    Ok(SweepMethod { method, reason })
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
}

impl Fidelity {
    /// The study's sweep fidelity (energies only when the objective needs them).
    pub fn sweep(study: &Study) -> Fidelity {
        Fidelity {
            method: study.sweep_method.method,
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
