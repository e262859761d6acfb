//! Nelder–Mead simplex (Nelder & Mead 1965; coefficients reflection 1, expansion 2,
//! contraction ½, shrink ½). Vertices are clamped into [0, 1]^d; a vertex that breaks a
//! linear constraint counts as +∞ without being simulated. Stops when the simplex is
//! smaller than the tolerance (max vertex distance to the best, ∞-norm) or the budget
//! is spent.

use super::{Evaluations, Point, clamp01};
use crate::error::OptError;
use crate::space::DesignSpace;
use crate::study::RefineConfig;

fn value(
    space: &DesignSpace,
    ev: &mut Evaluations<'_>,
    mut z: Vec<f64>,
) -> Result<Point, OptError> {
    clamp01(&mut z);
    if !space.is_feasible(&z) {
        return Ok(Point {
            z,
            f: f64::INFINITY,
        });
    }
    let f = ev.eval_one(&z)?;
    Ok(Point { z, f })
}

fn sort(s: &mut [Point]) {
    s.sort_by(|a, b| a.f.total_cmp(&b.f));
}

/// The Nelder–Mead refiner (see the module doc).
pub fn nelder_mead(
    space: &DesignSpace,
    start: &Point,
    ev: &mut Evaluations<'_>,
    cfg: &RefineConfig,
    budget: usize,
) -> Result<Point, OptError> {
    let d = space.dim();
    let r = cfg.initial_radius;
    let mut simplex = vec![start.clone()];
    for i in 0..d {
        let mut z = start.z.clone();
        z[i] += if z[i] + r <= 1.0 { r } else { -r };
        simplex.push(value(space, ev, z)?);
    }
    sort(&mut simplex);
    while ev.count() < budget {
        let size = simplex[1..]
            .iter()
            .map(|p| {
                p.z.iter()
                    .zip(&simplex[0].z)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        if size < cfg.tolerance {
            break;
        }
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
        sort(&mut simplex);
    }
    Ok(simplex[0].clone())
}
