//! Nelder–Mead simplex (Nelder & Mead 1965; coefficients reflection 1, expansion 2,
//! contraction ½, shrink ½). Vertices are clamped into [0, 1]^d; a vertex that breaks a
//! linear constraint counts as +∞ without being simulated. Stops when the simplex is
//! smaller than the tolerance (max vertex distance to the best, ∞-norm) or the budget
//! is spent.

use super::evaluations::{Evaluations, Point, Refiner, clamp01};
use crate::base::error::OptError;
use crate::model::config::RefineConfig;
use crate::model::space::DesignSpace;
use serde::{Deserialize, Serialize};

fn value(
    space: &DesignSpace,
    ev: &mut Evaluations<'_>,
    mut z: Vec<f64>,
) -> Result<Point, OptError> {
    clamp01(&mut z);
    if !space.is_feasible(&z) {
        return Ok(Point::new(z, f64::INFINITY));
    }
    let f = ev.eval_one(&z)?;
    Ok(Point::new(z, f))
}

fn sort(s: &mut [Point]) {
    s.sort_by(|a, b| a.f.total_cmp(&b.f));
}

/// The Nelder–Mead refiner's state: the simplex, best vertex first.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NelderMead {
    /// Vertices, sorted by objective.
    pub simplex: Vec<Point>,
    /// Initial edge length, scaled variables.
    pub radius: f64,
    /// Stop when the simplex is smaller than this.
    pub tolerance: f64,
}

impl NelderMead {
    /// A refiner with the study's settings.
    pub fn new(cfg: &RefineConfig) -> Self {
        NelderMead {
            simplex: Vec::new(),
            radius: cfg.initial_radius,
            tolerance: cfg.tolerance,
        }
    }

    fn size(&self) -> f64 {
        self.simplex[1..]
            .iter()
            .map(|p| {
                p.z.iter()
                    .zip(&self.simplex[0].z)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max)
    }
}

impl Refiner for NelderMead {
    fn init(
        &mut self,
        space: &DesignSpace,
        start: &Point,
        ev: &mut Evaluations<'_>,
    ) -> Result<(), OptError> {
        let r = self.radius;
        self.simplex = vec![start.clone()];
        for i in 0..space.dim() {
            let mut z = start.z.clone();
            z[i] += if z[i] + r <= 1.0 { r } else { -r };
            self.simplex.push(value(space, ev, z)?);
        }
        sort(&mut self.simplex);
        Ok(())
    }

    fn next_iter(&mut self, space: &DesignSpace, ev: &mut Evaluations<'_>) -> Result<(), OptError> {
        let d = space.dim();
        let simplex = &mut self.simplex;
        let worst = simplex[d].clone();
        let centroid: Vec<f64> = (0..d)
            .map(|j| simplex[..d].iter().map(|p| p.z[j]).sum::<f64>() / d as f64)
            .collect();
        let along = |t: f64| -> Vec<f64> {
            centroid
                .iter()
                .zip(&worst.z)
                .map(|(c, w)| c + t * (c - w))
                .collect()
        };
        let xr = value(space, ev, along(1.0))?;
        if xr.f < simplex[0].f {
            let xe = value(space, ev, along(2.0))?;
            simplex[d] = if xe.f < xr.f { xe } else { xr };
        } else if xr.f < simplex[d - 1].f {
            simplex[d] = xr;
        } else {
            let xc = if xr.f < worst.f {
                value(space, ev, along(0.5))?
            } else {
                value(space, ev, along(-0.5))?
            };
            if xc.f < worst.f.min(xr.f) {
                simplex[d] = xc;
            } else {
                let best = simplex[0].z.clone();
                for vertex in simplex.iter_mut().skip(1) {
                    let z: Vec<f64> = best
                        .iter()
                        .zip(&vertex.z)
                        .map(|(b, v)| b + 0.5 * (v - b))
                        .collect();
                    *vertex = value(space, ev, z)?;
                }
            }
        }
        sort(simplex);
        Ok(())
    }

    fn terminate(&self) -> bool {
        self.size() < self.tolerance
    }

    fn best(&self) -> &Point {
        &self.simplex[0]
    }
}
