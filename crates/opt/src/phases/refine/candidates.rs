//! The model refiner's candidate designs that read no model: the steps a poll points to
//! and the vertex of a line search's bracket ([`super::model`]).

use super::evaluations::{Point, clamp01};

/// The designs a poll around `c` points to (`polled`: coordinate, move, point): the
/// step of the separable quadratic through each coordinate's two moves (its gradient
/// and curvature by differences, the curvature at least |g|/(2Δ), so no coordinate moves
/// more than 2Δ), and the design that takes every move that lowered what the refiner
/// minimises, each whole and half way. On an objective with kinks (a peak over storeys
/// and records, the worst of the property cases) one floor moved alone often climbs
/// where floors moved together descend, and the interpolation model of the whole set
/// misleads; these steps read only the poll around the present centre (implicit
/// filtering's difference gradient at the scale Δ, Kelley 2011, and a combined
/// coordinate move).
pub(super) fn poll_candidates(
    c: &Point,
    polled: &[(usize, f64, Point)],
    delta: f64,
    separable: bool,
) -> Vec<Vec<f64>> {
    let d = c.z.len();
    let fc = c.objective();
    // each coordinate's moves: (offset, objective) — the objective whether the limits
    // pass or not, smooth across them
    let mut per: Vec<Vec<(f64, f64)>> = vec![Vec::new(); d];
    let mut gain = vec![(0.0, c.f); d];
    for (i, s, p) in polled {
        per[*i].push((*s, p.objective()));
        if p.f < gain[*i].1 {
            gain[*i] = (*s, p.f);
        }
    }
    let mut newton = vec![0.0; d];
    for (i, moves) in per.iter().enumerate() {
        let &[(a, fa), (b, fb)] = &moves[..] else {
            continue;
        };
        if !(fa.is_finite() && fb.is_finite() && fc.is_finite()) || a == b {
            continue;
        }
        // the parabola through (0, fc), (a, fa), (b, fb)
        let (da, db) = ((fa - fc) / a, (fb - fc) / b);
        let curvature = 2.0 * (da - db) / (a - b);
        let g = da - 0.5 * curvature * a;
        if g != 0.0 {
            newton[i] =
                (-g / curvature.max(g.abs() / (2.0 * delta))).clamp(-2.0 * delta, 2.0 * delta);
        }
    }
    let combined: Vec<f64> = gain.iter().map(|(s, _)| *s).collect();
    let mut out: Vec<Vec<f64>> = Vec::new();
    let gaining = combined.iter().filter(|s| **s != 0.0).count();
    // (one gaining move alone: the poll made it whole already, its half is new)
    for (step, useful) in [
        (&newton, separable && newton.iter().any(|s| *s != 0.0)),
        (&combined, gaining >= 1),
    ] {
        if !useful {
            continue;
        }
        for t in [1.0, 0.5] {
            let mut z: Vec<f64> = c.z.iter().zip(step).map(|(z, s)| z + t * s).collect();
            clamp01(&mut z);
            if z != c.z && !out.contains(&z) {
                out.push(z);
            }
        }
    }
    out
}

/// The vertex (in log α) of the parabola through three points of a bracket whose middle
/// point is the lowest; `None` when they are collinear.
pub(super) fn parabola_vertex(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> Option<f64> {
    let (x1, f1) = a;
    let (x2, f2) = b;
    let (x3, f3) = c;
    let num = (x2 - x1).powi(2) * (f2 - f3) - (x2 - x3).powi(2) * (f2 - f1);
    let den = (x2 - x1) * (f2 - f3) - (x2 - x3) * (f2 - f1);
    if !(den.abs() > 0.0 && den.is_finite() && num.is_finite()) {
        return None;
    }
    let v = x2 - 0.5 * num / den;
    (v > x1 && v < x3).then_some(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a separable quadratic f = Σ aᵢ (zᵢ − mᵢ)² with each mᵢ within 2Δ of the centre,
    /// the separable step of a poll lands on the minimum (to round-off: differences of a
    /// quadratic are exact), and the combined design takes every gaining move.
    #[test]
    fn a_polls_separable_step_lands_on_a_separable_quadratics_minimum() {
        let (a, m) = ([1.0, 4.0, 0.5], [0.42, 0.55, 0.6]);
        let f = |z: &[f64]| -> f64 { (0..3).map(|i| a[i] * (z[i] - m[i]).powi(2)).sum() };
        let (c, delta) = (vec![0.5, 0.5, 0.5], 0.05);
        let centre = Point::new(c.clone(), f(&c));
        let mut polled = Vec::new();
        for i in 0..3 {
            for s in [delta, -delta] {
                let mut z = c.clone();
                z[i] += s;
                polled.push((i, s, Point::new(z.clone(), f(&z))));
            }
        }
        let cands = poll_candidates(&centre, &polled, delta, true);
        // the separable step whole, then half way, then the combined moves
        let step = &cands[0];
        for i in 0..3 {
            assert!((step[i] - m[i]).abs() < 1e-12, "{step:?} vs {m:?}");
        }
        // floors 1 and 2 gain downward and upward by Δ; floor 3's minimum is 2Δ up
        let combined = [0.45, 0.55, 0.55];
        assert!(
            cands
                .iter()
                .any(|z| z.iter().zip(&combined).all(|(a, b)| (a - b).abs() < 1e-15))
        );
        // without the separable step (the first poll) only the combined moves
        assert_eq!(poll_candidates(&centre, &polled, delta, false).len(), 2);
    }
}
