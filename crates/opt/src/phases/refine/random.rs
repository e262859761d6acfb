//! Adaptive random search: draws uniformly in a box of half-width r around the best
//! point (clipped to [0, 1]^d, constraints by rejection); r grows ×1.5 (to at most ½)
//! after a success and shrinks ×0.7 after two failures in a row. Seeded, deterministic.
//! The baseline the model-based refiner should beat.

use super::evaluations::{Evaluations, Point, Refiner};
use crate::base::error::OptError;
use crate::model::config::RefineConfig;
use crate::model::sampler::SplitMix;
use crate::model::space::DesignSpace;
use serde::{Deserialize, Serialize};

/// The random-search refiner's state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RandomSearch {
    /// The generator (its whole state is one u64).
    pub rng: SplitMix,
    /// Best point so far.
    pub best: Point,
    /// Half-width of the sampling box, scaled variables.
    pub radius: f64,
    /// Stop when the radius falls below this.
    pub tolerance: f64,
    /// Failures in a row.
    pub fails: u32,
    /// No feasible point found in 100 draws.
    pub stalled: bool,
}

impl RandomSearch {
    /// A refiner with the study's settings (seed `refine.seed`).
    pub fn new(cfg: &RefineConfig) -> Self {
        RandomSearch {
            rng: SplitMix::new(cfg.seed),
            best: Point::new(Vec::new(), f64::INFINITY),
            radius: cfg.initial_radius,
            tolerance: cfg.tolerance,
            fails: 0,
            stalled: false,
        }
    }
}

impl Refiner for RandomSearch {
    fn init(
        &mut self,
        _space: &DesignSpace,
        start: &Point,
        _ev: &mut Evaluations<'_>,
    ) -> Result<(), OptError> {
        self.best = start.clone();
        Ok(())
    }

    fn next_iter(&mut self, space: &DesignSpace, ev: &mut Evaluations<'_>) -> Result<(), OptError> {
        let mut z = None;
        for _ in 0..100 {
            let cand: Vec<f64> = self
                .best
                .z
                .iter()
                .map(|c| (c + self.radius * (2.0 * self.rng.uniform() - 1.0)).clamp(0.0, 1.0))
                .collect();
            if space.is_feasible(&cand) {
                z = Some(cand);
                break;
            }
        }
        let Some(z) = z else {
            self.stalled = true;
            return Ok(());
        };
        let f = ev.eval_one(&z)?;
        if f < self.best.f {
            self.best = Point::new(z, f);
            self.radius = (1.5 * self.radius).min(0.5);
            self.fails = 0;
        } else {
            self.fails += 1;
            if self.fails >= 2 {
                self.radius *= 0.7;
                self.fails = 0;
            }
        }
        Ok(())
    }

    fn terminate(&self) -> bool {
        self.stalled || self.radius < self.tolerance
    }

    fn best(&self) -> &Point {
        &self.best
    }
}
