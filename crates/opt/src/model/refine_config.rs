//! The study key `refine`: which refiner, from how many starts, with what budget
//! ([`RefineConfig`]), held to its bands by [`super::config::StudyConfig`]'s validation.

use serde::{Deserialize, Serialize};

/// Refiners.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RefineMethod {
    /// The default: `sqp` where the study can be differentiated (its objective and limits
    /// read peak or residual drift, floor acceleration or base shear, and its sweep method
    /// computes sensitivities), else `model`. Resolved when the study loads
    /// ([`RefineMethod::resolve`]); a refiner never sees it.
    Auto,
    /// Profile line searches, then a trust region on a least-change quadratic
    /// interpolation model (the refiner for many slip loads; `phases::refine::ModelSearch`).
    Model,
    /// A trust-region SQP on the derivatives of the runs (`newmark`'s sensitivities): the
    /// cases of the worst reading and the limits as constraints (`phases::refine::Sqp`).
    Sqp,
    /// Trust region on a fitted quadratic model, subproblem solved by clarabel.
    TrustRegion,
    /// Nelder–Mead simplex.
    NelderMead,
    /// Adaptive random search.
    Random,
}

impl std::str::FromStr for RefineMethod {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "auto" => Ok(RefineMethod::Auto),
            "model" => Ok(RefineMethod::Model),
            "sqp" => Ok(RefineMethod::Sqp),
            "trust-region" => Ok(RefineMethod::TrustRegion),
            "nelder-mead" => Ok(RefineMethod::NelderMead),
            "random" => Ok(RefineMethod::Random),
            o => Err(format!(
                "unknown refiner {o:?}: expected auto, model, sqp, trust-region, nelder-mead or random"
            )),
        }
    }
}

impl RefineMethod {
    /// The refiner `auto` stands for: `sqp` when `differentiable`, else `model`; any
    /// other refiner is itself.
    pub fn resolve(self, differentiable: bool) -> RefineMethod {
        match self {
            RefineMethod::Auto if differentiable => RefineMethod::Sqp,
            RefineMethod::Auto => RefineMethod::Model,
            m => m,
        }
    }

    /// The name as written.
    pub fn as_str(self) -> &'static str {
        match self {
            RefineMethod::Auto => "auto",
            RefineMethod::Model => "model",
            RefineMethod::Sqp => "sqp",
            RefineMethod::TrustRegion => "trust-region",
            RefineMethod::NelderMead => "nelder-mead",
            RefineMethod::Random => "random",
        }
    }
}

/// Refinement settings.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RefineConfig {
    /// Refiner (default `auto`: `sqp` where the study can be differentiated, else `model`).
    #[serde(default = "default_refiner")]
    pub method: RefineMethod,
    /// Refine from this many of the best sweep points (default 2).
    #[serde(default = "default_starts")]
    pub starts: usize,
    /// Most design evaluations per start (default 40).
    #[serde(default = "default_max_evals")]
    pub max_evaluations: usize,
    /// Run the starts side by side, each with its own `max_evaluations` and the sweep's
    /// designs, independent of the others (default false: one after the other, a later
    /// start seeing the earlier ones' designs and taking what they left of the budget).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub parallel_starts: bool,
    /// Stop when the step (trust radius, simplex size) falls below this, in variables
    /// scaled to [0, 1] (default 2e-3).
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// Initial trust radius / simplex size, scaled (default 0.15).
    #[serde(default = "default_radius")]
    pub initial_radius: f64,
    /// Designs verified at reference accuracy (default 3).
    #[serde(default = "default_finalists")]
    pub finalists: usize,
    /// Seed of the random refiner (default 1).
    #[serde(default = "default_seed")]
    pub seed: u64,
}

fn default_refiner() -> RefineMethod {
    RefineMethod::Auto
}
fn default_starts() -> usize {
    2
}
fn default_max_evals() -> usize {
    40
}
fn default_tolerance() -> f64 {
    2e-3
}
fn default_radius() -> f64 {
    0.15
}
fn default_finalists() -> usize {
    3
}

impl Default for RefineConfig {
    fn default() -> Self {
        RefineConfig {
            method: default_refiner(),
            starts: default_starts(),
            max_evaluations: default_max_evals(),
            parallel_starts: false,
            tolerance: default_tolerance(),
            initial_radius: default_radius(),
            finalists: default_finalists(),
            seed: default_seed(),
        }
    }
}

/// The random refiner's default seed (the sweep's default too).
fn default_seed() -> u64 {
    1
}
