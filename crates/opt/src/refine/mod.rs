//! Refiners: from a good sweep point to a better one with few design evaluations
//! (each evaluation is one simulation per record of the study).
//!
//! All refiners work in the scaled variables z ∈ [0, 1]^d of the [`DesignSpace`] and call
//! the objective through [`Evaluations`], which remembers every point evaluated (sweep
//! points included) and counts the new ones, so the refiners can be compared by the
//! number of evaluations they need.
//!
//! [`DesignSpace`]: crate::DesignSpace

mod nelder_mead;
mod random;
mod trust_region;

pub use nelder_mead::nelder_mead;
pub use random::random_search;
pub use trust_region::trust_region;

use crate::error::OptError;
use crate::space::DesignSpace;
use crate::study::{RefineConfig, RefineMethod};
use std::collections::HashMap;

/// One evaluated design.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Scaled variables.
    pub z: Vec<f64>,
    /// Objective.
    pub f: f64,
}

/// The batch objective: objective values of several scaled points.
pub type Oracle<'a> = dyn FnMut(&[Vec<f64>]) -> Result<Vec<f64>, OptError> + 'a;

/// Every evaluation so far, with a cache keyed by the exact bits of z.
pub struct Evaluations<'a> {
    oracle: Box<Oracle<'a>>,
    cache: HashMap<Vec<u64>, f64>,
    /// Points known before refining (not counted).
    pub known: Vec<Point>,
    /// New evaluations, in order.
    pub log: Vec<Point>,
}

fn key(z: &[f64]) -> Vec<u64> {
    z.iter().map(|v| v.to_bits()).collect()
}

impl<'a> Evaluations<'a> {
    /// Starts with points already evaluated (the sweep's).
    pub fn new(oracle: Box<Oracle<'a>>, known: Vec<Point>) -> Self {
        let cache = known.iter().map(|p| (key(&p.z), p.f)).collect();
        Evaluations {
            oracle,
            cache,
            known,
            log: Vec::new(),
        }
    }

    /// Objective at each point; only points never seen are evaluated (in one batch).
    pub fn eval(&mut self, zs: &[Vec<f64>]) -> Result<Vec<f64>, OptError> {
        let mut fresh: Vec<Vec<f64>> = Vec::new();
        for z in zs {
            if !self.cache.contains_key(&key(z)) && !fresh.contains(z) {
                fresh.push(z.clone());
            }
        }
        if !fresh.is_empty() {
            let fs = (self.oracle)(&fresh)?;
            for (z, f) in fresh.into_iter().zip(fs) {
                self.cache.insert(key(&z), f);
                self.log.push(Point { z, f });
            }
        }
        Ok(zs
            .iter()
            .map(|z| *self.cache.get(&key(z)).expect("evaluated above"))
            .collect())
    }

    /// Objective at one point.
    pub fn eval_one(&mut self, z: &[f64]) -> Result<f64, OptError> {
        Ok(self.eval(&[z.to_vec()])?[0])
    }

    /// Number of new evaluations.
    pub fn count(&self) -> usize {
        self.log.len()
    }

    /// Every point seen (known, then new).
    pub fn all(&self) -> impl Iterator<Item = &Point> {
        self.known.iter().chain(self.log.iter())
    }

    /// The best point seen (first of equals).
    pub fn best(&self) -> Option<Point> {
        let mut best: Option<&Point> = None;
        for p in self.all() {
            if best.is_none_or(|b| p.f < b.f) {
                best = Some(p);
            }
        }
        best.cloned()
    }
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
    match method {
        RefineMethod::TrustRegion => trust_region(space, start, ev, cfg, budget),
        RefineMethod::NelderMead => nelder_mead(space, start, ev, cfg, budget),
        RefineMethod::Random => random_search(space, start, ev, cfg, budget),
    }
}

/// z clamped into [0, 1]^d.
pub(crate) fn clamp01(z: &mut [f64]) {
    for v in z {
        *v = v.clamp(0.0, 1.0);
    }
}
