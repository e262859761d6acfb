//! The global part of a front's search: a surrogate of each objective over every design
//! evaluated so far, and the designs it proposes.
//!
//! Each objective, normalised to the current front's ideal (0) and nadir (1) and clipped
//! at [`CLIP`] (so the designs far from the front — the bare frame's drifts — do not
//! bend the fit near it), is interpolated by a cubic radial basis function with a
//! polynomial tail (quadratic when there are at least twice as many designs as the
//! quadratic's terms, linear otherwise): s(z) = Σ λᵢ ‖z − zᵢ‖³ + p(z), with
//! Σ λᵢ q(zᵢ) = 0 for every q of the tail (Powell 1992; the surrogate of Regis &
//! Shoemaker's stochastic RBF method, 2007). A cubic spline of this kind reproduces its
//! tail's polynomials exactly.
//!
//! A proposal minimises an augmented Tchebycheff scalarisation of the surrogates,
//! g(z) = maxₘ wₘ (ŝₘ(z) − z*ₘ) + ρ Σₘ wₘ (ŝₘ(z) − z*ₘ), over a fixed candidate set:
//! a Halton set of the box ([`GLOBAL`] points, unshifted) and, around each front design,
//! a Halton ball at three radii (so a proposal can refine as well as jump to a separate
//! basin), minus the infeasible candidates and those within [`SEPARATION`] of a design
//! evaluated or proposed. The weights aim at each objective's end of the front (w = eₘ
//! plus a little of the others) and at the midpoints of its largest gaps (the ray from
//! the ideal through the midpoint).
//!
//! Everything is a function of the designs evaluated so far, in their order: no random
//! numbers, no threads; a resumed search proposes the same designs.

use crate::model::sampler::halton;
use crate::model::space::DesignSpace;
use nalgebra::{DMatrix, DVector};

/// Normalised objective values above this are clipped before the fit.
pub const CLIP: f64 = 2.0;
/// Halton points of the box in the candidate set.
pub const GLOBAL: usize = 8192;
/// Halton points of each ball around a front design.
const LOCAL: usize = 64;
/// Radii of the balls around the front designs (scaled variables).
const RADII: [f64; 3] = [0.1, 0.03, 0.01];
/// Most front designs that get balls of candidates (the first of the front, in its order).
const BALLS: usize = 64;
/// Most designs a fit uses (the best by non-dominated rank, ties by order).
pub const MAX_FIT: usize = 400;
/// Least distance (scaled, in every variable's max norm) of a proposal from any design
/// evaluated or already proposed.
pub const SEPARATION: f64 = 1e-3;
/// The augmentation of the Tchebycheff scalarisation.
const RHO: f64 = 0.05;
/// The weight of the other objectives in an end's scalarisation.
const END_WEIGHT: f64 = 0.01;

/// A cubic radial basis function interpolant with a polynomial tail.
#[derive(Debug, Clone)]
pub struct Rbf {
    centres: Vec<Vec<f64>>,
    lambda: Vec<f64>,
    /// Coefficients of the tail's terms ([`tail_terms`]).
    tail: Vec<f64>,
    quadratic: bool,
}

/// The tail's terms at `z`: 1, zⱼ, and (quadratic) zⱼ zₖ for j ≤ k.
fn tail_terms(z: &[f64], quadratic: bool, out: &mut Vec<f64>) {
    out.clear();
    out.push(1.0);
    out.extend_from_slice(z);
    if quadratic {
        for j in 0..z.len() {
            for k in j..z.len() {
                out.push(z[j] * z[k]);
            }
        }
    }
}

fn tail_len(d: usize, quadratic: bool) -> usize {
    1 + d + if quadratic { d * (d + 1) / 2 } else { 0 }
}

fn cube_dist(a: &[f64], b: &[f64]) -> f64 {
    let r2: f64 = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum();
    r2 * r2.sqrt()
}

impl Rbf {
    /// The interpolant of `values` at `points` (all of one dimension); `None` when there
    /// are too few points for a linear tail or the system is singular (points repeated
    /// or all on a hyperplane).
    pub fn fit(points: &[Vec<f64>], values: &[f64]) -> Option<Rbf> {
        let n = points.len();
        let d = points.first()?.len();
        if n != values.len() || n < d + 1 {
            return None;
        }
        let quadratic = n >= 2 * tail_len(d, true);
        let q = tail_len(d, quadratic);
        let size = n + q;
        let mut a = DMatrix::<f64>::zeros(size, size);
        let mut terms = Vec::with_capacity(q);
        for i in 0..n {
            for j in 0..n {
                a[(i, j)] = cube_dist(&points[i], &points[j]);
            }
            tail_terms(&points[i], quadratic, &mut terms);
            for (k, t) in terms.iter().enumerate() {
                a[(i, n + k)] = *t;
                a[(n + k, i)] = *t;
            }
        }
        let mut b = DVector::<f64>::zeros(size);
        for (i, v) in values.iter().enumerate() {
            b[i] = *v;
        }
        let x = a.lu().solve(&b)?;
        if x.iter().any(|v| !v.is_finite()) {
            return None;
        }
        Some(Rbf {
            centres: points.to_vec(),
            lambda: x.rows(0, n).iter().copied().collect(),
            tail: x.rows(n, q).iter().copied().collect(),
            quadratic,
        })
    }

    /// The interpolant's value at `z`.
    pub fn value(&self, z: &[f64]) -> f64 {
        let mut terms = Vec::with_capacity(self.tail.len());
        tail_terms(z, self.quadratic, &mut terms);
        let poly: f64 = terms.iter().zip(&self.tail).map(|(t, c)| t * c).sum();
        let radial: f64 = self
            .centres
            .iter()
            .zip(&self.lambda)
            .map(|(c, l)| l * cube_dist(z, c))
            .sum();
        poly + radial
    }
}

/// The candidate set: the box's Halton points, then a Halton ball at each radius around
/// each of `around` (up to `BALLS` of them), clipped to the box; only the feasible.
pub fn candidates(space: &DesignSpace, around: &[&[f64]]) -> Vec<Vec<f64>> {
    let d = space.dim();
    let zero = vec![0.0; d];
    let mut out: Vec<Vec<f64>> = halton(d, 0, GLOBAL, &zero);
    let ball = halton(d, GLOBAL as u64, LOCAL, &zero);
    for c in around.iter().take(BALLS) {
        for r in RADII {
            for u in &ball {
                out.push(
                    c.iter()
                        .zip(u)
                        .map(|(x, v)| (x + r * (2.0 * v - 1.0)).clamp(0.0, 1.0))
                        .collect(),
                );
            }
        }
    }
    out.retain(|z| space.is_feasible(z));
    out
}

/// The scalarisations' weights for a front of normalised objectives `norm` (in front
/// order) and its gaps (largest first, pairs of indices into `norm`): each objective's end
/// first, then the midpoints of up to `gaps_wanted` gaps.
pub fn weights(norm: &[Vec<f64>], gaps: &[(usize, usize)], gaps_wanted: usize) -> Vec<Vec<f64>> {
    let k = norm.first().map_or(0, Vec::len);
    let mut out: Vec<Vec<f64>> = (0..k)
        .map(|m| {
            (0..k)
                .map(|j| if j == m { 1.0 } else { END_WEIGHT })
                .collect()
        })
        .collect();
    for &(a, b) in gaps.iter().take(gaps_wanted) {
        let w: Vec<f64> = (0..k)
            .map(|m| 1.0 / (0.5 * (norm[a][m] + norm[b][m]) - IDEAL_SHIFT).max(1e-3))
            .collect();
        out.push(w);
    }
    out
}

/// The utopia point of the scalarisation: the front's ideal (0) less this, normalised.
const IDEAL_SHIFT: f64 = -0.01;

/// Up to one design per weight vector (in order): the candidate least in the
/// scalarisation of the surrogates `fits`, at least [`SEPARATION`] (in some variable)
/// from every design in `taken` and every design proposed before it. A weight whose
/// best candidate is taken gives the next best.
pub fn propose(
    fits: &[Rbf],
    candidates: &[Vec<f64>],
    weights: &[Vec<f64>],
    taken: &[Vec<f64>],
) -> Vec<Vec<f64>> {
    let far = |z: &[f64], q: &[f64]| z.iter().zip(q).any(|(a, b)| (a - b).abs() >= SEPARATION);
    let free: Vec<&Vec<f64>> = candidates
        .iter()
        .filter(|z| taken.iter().all(|q| far(z, q)))
        .collect();
    let predicted: Vec<Vec<f64>> = free
        .iter()
        .map(|z| fits.iter().map(|f| f.value(z)).collect())
        .collect();
    let mut out: Vec<Vec<f64>> = Vec::new();
    for w in weights {
        let score = |s: &[f64]| {
            let terms = s.iter().zip(w).map(|(v, wm)| wm * (v - IDEAL_SHIFT));
            let max = terms.clone().fold(f64::NEG_INFINITY, f64::max);
            max + RHO * terms.sum::<f64>()
        };
        let best = (0..free.len())
            .filter(|&i| out.iter().all(|q| far(free[i], q)))
            .min_by(|&a, &b| {
                score(&predicted[a])
                    .total_cmp(&score(&predicted[b]))
                    .then(a.cmp(&b))
            });
        if let Some(i) = best {
            out.push(free[i].clone());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
    use super::*;

    /// Three variables, slip loads 0–2000 kN, non-increasing with height (z₁ ≤ z₀,
    /// z₂ ≤ z₁).
    fn space() -> DesignSpace {
        DesignSpace {
            dampers: vec![0, 1, 2],
            offset: vec![0.0; 3],
            basis: DMatrix::from_diagonal_element(3, 3, 2.0e6),
            a: DMatrix::from_row_slice(2, 3, &[-1.0, 1.0, 0.0, 0.0, -1.0, 1.0]),
            b: vec![0.0, 0.0],
            names: vec!["floor1".into(), "floor2".into(), "floor3".into()],
            shape: None,
            profile: vec![1.0; 3],
        }
    }

    fn quadratic(z: &[f64]) -> f64 {
        1.5 - 2.0 * z[0] + 0.5 * z[1] + 3.0 * z[2] + 4.0 * z[0] * z[0] - z[0] * z[1]
            + 2.5 * z[1] * z[2]
            - 0.7 * z[2] * z[2]
    }

    /// Round-off of a solve of a few dozen unknowns with entries of order one.
    const ROUND_OFF: f64 = 1e-9;

    #[test]
    fn the_surrogate_reproduces_a_quadratic_exactly() {
        // 3 variables: the quadratic tail has 10 terms, so 20 points make it quadratic
        let points = halton(3, 0, 20, &[0.0; 3]);
        let values: Vec<f64> = points.iter().map(|z| quadratic(z)).collect();
        let fit = Rbf::fit(&points, &values).unwrap();
        for z in halton(3, 100, 50, &[0.0; 3]) {
            assert!((fit.value(&z) - quadratic(&z)).abs() < ROUND_OFF, "{z:?}");
        }
    }

    #[test]
    fn the_surrogate_interpolates_its_data_and_a_few_points_get_a_linear_tail() {
        // 8 points: too few for the quadratic tail; the cubic spline still interpolates
        let points = halton(3, 0, 8, &[0.0; 3]);
        let values: Vec<f64> = points
            .iter()
            .map(|z| (5.0 * z[0]).sin() + z[1] * z[2])
            .collect();
        let fit = Rbf::fit(&points, &values).unwrap();
        assert!(!fit.quadratic);
        for (z, v) in points.iter().zip(&values) {
            assert!((fit.value(z) - v).abs() < ROUND_OFF);
        }
        // and reproduces a linear function everywhere
        let linear: Vec<f64> = points.iter().map(|z| 1.0 + z[0] - 2.0 * z[2]).collect();
        let fit = Rbf::fit(&points, &linear).unwrap();
        let z = [0.3, 0.9, 0.05];
        assert!((fit.value(&z) - (1.0 + 0.3 - 0.1)).abs() < ROUND_OFF);
    }

    #[test]
    fn no_surrogate_from_too_few_or_repeated_points() {
        let points = halton(3, 0, 3, &[0.0; 3]);
        assert!(Rbf::fit(&points, &[1.0, 2.0, 3.0]).is_none());
        let mut points = halton(3, 0, 8, &[0.0; 3]);
        points[7] = points[0].clone();
        assert!(Rbf::fit(&points, &[1.0; 8]).is_none());
        // values not matching the points
        assert!(Rbf::fit(&halton(3, 0, 8, &[0.0; 3]), &[1.0; 7]).is_none());
    }

    #[test]
    fn proposals_are_deterministic_feasible_separated_and_aim_at_each_end() {
        let space = space();
        // two objectives: the distance to (0.8, 0.4, 0.1) and to (0.3, 0.3, 0.3)
        let a = [0.8, 0.4, 0.1];
        let b = [0.3, 0.3, 0.3];
        let dist =
            |z: &[f64], c: &[f64]| z.iter().zip(c).map(|(x, y)| (x - y).powi(2)).sum::<f64>();
        let evaluated: Vec<Vec<f64>> = halton(3, 500, 200, &[0.0; 3])
            .into_iter()
            .filter(|z| space.is_feasible(z))
            .collect();
        assert!(evaluated.len() >= 30);
        let fits: Vec<Rbf> = [a, b]
            .iter()
            .map(|c| {
                let v: Vec<f64> = evaluated.iter().map(|z| dist(z, c)).collect();
                Rbf::fit(&evaluated, &v).unwrap()
            })
            .collect();
        // balls around the design nearest each minimum (as around a front's ends)
        let nearest = |c: &[f64]| {
            evaluated
                .iter()
                .min_by(|p, q| dist(p, c).total_cmp(&dist(q, c)))
                .unwrap()
                .as_slice()
        };
        let around: Vec<&[f64]> = vec![nearest(&a), nearest(&b)];
        let cands = candidates(&space, &around);
        assert!(cands.iter().all(|z| space.is_feasible(z)));
        // ends, then three gap weights
        let norm = vec![vec![0.0, 1.0], vec![0.5, 0.5], vec![1.0, 0.0]];
        let w = weights(&norm, &[(0, 1), (1, 2)], 3);
        assert_eq!(w.len(), 4, "two ends and the two gaps there are");
        let out = propose(&fits, &cands, &w, &evaluated);
        assert_eq!(out.len(), 4);
        assert_eq!(out, propose(&fits, &cands, &w, &evaluated), "deterministic");
        for (i, z) in out.iter().enumerate() {
            assert!(space.is_feasible(z), "{z:?}");
            let far = |q: &[f64]| z.iter().zip(q).any(|(x, y)| (x - y).abs() >= SEPARATION);
            assert!(evaluated.iter().all(|q| far(q)), "{z:?} repeats a design");
            assert!(out[..i].iter().all(|q| far(q)), "{z:?} proposed twice");
        }
        // the surrogates are quadratics (exact): each end lands nearer its objective's
        // minimum than any design evaluated (the balls' candidates refine)
        assert!(dist(&out[0], &a) < dist(nearest(&a), &a), "{:?}", out[0]);
        assert!(dist(&out[1], &b) < dist(nearest(&b), &b), "{:?}", out[1]);
    }
}
