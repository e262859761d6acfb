//! Refiners: from a good sweep point to a better one with few design evaluations
//! (each evaluation is one simulation per record of the study).
//!
//! All refiners work in the scaled variables z ∈ [0, 1]^d of the [`DesignSpace`] and call
//! the objective through [`Evaluations`], which remembers every point evaluated (sweep
//! points included) and counts the new ones, so the refiners can be compared by the
//! number of evaluations they need.
//!
//! [`DesignSpace`]: crate::DesignSpace

mod evaluations;
mod nelder_mead;
mod random;
mod trust_region;

pub use evaluations::{Evaluations, Hook, Oracle, Point, Refiner};
pub use nelder_mead::NelderMead;
pub use random::RandomSearch;
pub use trust_region::TrustRegion;

use crate::base::error::OptError;
use crate::model::config::{RefineConfig, RefineMethod};
use crate::model::space::DesignSpace;

/// Drives a refiner: `init`, then `next_iter` while the budget of new evaluations
/// (counted over the whole [`Evaluations`]) lasts and `terminate` is false.
pub fn run(
    refiner: &mut dyn Refiner,
    space: &DesignSpace,
    start: &Point,
    ev: &mut Evaluations<'_>,
    budget: usize,
) -> Result<Point, OptError> {
    refiner.init(space, start, ev)?;
    while ev.count() < budget && !refiner.terminate() {
        refiner.next_iter(space, ev)?;
    }
    Ok(refiner.best().clone())
}

/// Runs `method` from `start` until `budget` new evaluations have been made in total
/// (counting those before the call) or the method's own test stops it.
pub fn refine(
    method: RefineMethod,
    space: &DesignSpace,
    start: &Point,
    ev: &mut Evaluations<'_>,
    cfg: &RefineConfig,
    budget: usize,
) -> Result<Point, OptError> {
    let mut r: Box<dyn Refiner> = match method {
        RefineMethod::TrustRegion => Box::new(TrustRegion::new(cfg, budget)),
        RefineMethod::NelderMead => Box::new(NelderMead::new(cfg)),
        RefineMethod::Random => Box::new(RandomSearch::new(cfg)),
    };
    run(r.as_mut(), space, start, ev, budget)
}
