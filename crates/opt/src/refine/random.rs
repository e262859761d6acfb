//! Adaptive random search: draws uniformly in a box of half-width r around the best
//! point (clipped to [0, 1]^d, constraints by rejection); r grows ×1.5 (to at most ½)
//! after a success and shrinks ×0.7 after two failures in a row. Seeded, deterministic.
//! The baseline the model-based refiner should beat.

use super::{Evaluations, Point};
use crate::error::OptError;
use crate::sampler::SplitMix;
use crate::space::DesignSpace;
use crate::study::RefineConfig;

/// The random-search refiner (see the module doc).
pub fn random_search(
    space: &DesignSpace,
    start: &Point,
    ev: &mut Evaluations<'_>,
    cfg: &RefineConfig,
    budget: usize,
) -> Result<Point, OptError> {
    let mut rng = SplitMix::new(cfg.seed);
    let mut best = start.clone();
    let mut r = cfg.initial_radius;
    let mut fails = 0;
    while ev.count() < budget && r >= cfg.tolerance {
        let mut z = None;
        for _ in 0..100 {
            let cand: Vec<f64> = best
                .z
                .iter()
                .map(|c| (c + r * (2.0 * rng.uniform() - 1.0)).clamp(0.0, 1.0))
                .collect();
            if space.is_feasible(&cand) {
                z = Some(cand);
                break;
            }
        }
        let Some(z) = z else { break };
        let f = ev.eval_one(&z)?;
        if f < best.f {
            best = Point { z, f };
            r = (1.5 * r).min(0.5);
            fails = 0;
        } else {
            fails += 1;
            if fails >= 2 {
                r *= 0.7;
                fails = 0;
            }
        }
    }
    Ok(best)
}
