//! Event and extremum search inside a substep: each scanned function is a scalar
//! polynomial in τ (its Taylor coefficients), scanned at [`SCAN_POINTS`] points and its
//! roots located by the Illinois method.

use super::params::{SCAN_POINTS, TAYLOR_TERMS};

/// Scalar polynomial Σ c_k τᵏ and its derivative.
#[inline]
pub(super) fn poly(c: &[f64], t: f64) -> (f64, f64) {
    let mut p = 0.0;
    let mut d = 0.0;
    for k in (0..c.len()).rev() {
        d = d * t + p;
        p = p * t + c[k];
    }
    (p, d)
}

/// Root of `f` in [a, b] with f(a)·f(b) ≤ 0 (Illinois), to ~1e-15 s.
pub(super) fn illinois(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let mut fa = f(a);
    let mut fb = f(b);
    if fa == 0.0 {
        return a;
    }
    if fb == 0.0 {
        return b;
    }
    let mut side = 0i8;
    for _ in 0..200 {
        let tol = 1e-15 + 4.0 * f64::EPSILON * b.abs();
        if (b - a).abs() <= tol {
            break;
        }
        let mut c = (a * fb - b * fa) / (fb - fa);
        if !(c > a.min(b) && c < a.max(b)) {
            c = 0.5 * (a + b);
        }
        let fc = f(c);
        if fc == 0.0 {
            return c;
        }
        if (fc > 0.0) == (fb > 0.0) {
            b = c;
            fb = fc;
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            fa = fc;
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        }
    }
    if fa.abs() < fb.abs() { a } else { b }
}

/// Σ_{k≥1} |c_k| lenᵏ, and the degree past which the terms add less than 1e-17 of
/// Σ_k |c_k| lenᵏ (the polynomial is scanned without them: a change far below round-off of
/// its values, and of its roots below the root finder's 1e-15 s).
pub(super) fn tail_and_degree(c: &[f64], len: f64) -> (f64, usize) {
    let mut terms = [0.0; TAYLOR_TERMS];
    let mut tail = 0.0;
    let mut tk = 1.0;
    for (k, ck) in c.iter().enumerate() {
        terms[k] = ck.abs() * tk;
        if k > 0 {
            tail += terms[k];
        }
        tk *= len;
    }
    let total = tail + terms[0];
    let mut dropped = 0.0;
    let mut degree = c.len() - 1;
    while degree > 1 && dropped + terms[degree] < 1e-17 * total {
        dropped += terms[degree];
        degree -= 1;
    }
    (tail, degree)
}

/// First τ in (0, len] where the polynomial goes below −thr (a crossing, or a minimum
/// between scan points), located at its zero (or at −thr when it started in (−thr, 0)).
pub(super) fn first_crossing(c: &[f64], len: f64, thr: f64) -> Option<f64> {
    let g0 = c[0];
    if g0 < -thr {
        // Already past: a contact recovering from round-off after its switch.
        return None;
    }
    // g(τ) ≥ g(0) − Σ_{k≥1} |c_k| τᵏ: nothing to find when that stays nonnegative.
    let (tail, degree) = tail_and_degree(c, len);
    if g0 - tail >= 0.0 {
        return None;
    }
    let c = &c[..=degree];
    let mut prev = (0.0, poly(c, 0.0));
    for j in 1..=SCAN_POINTS {
        let t = len * j as f64 / SCAN_POINTS as f64;
        let cur = (t, poly(c, t));
        let (ta, (ga, da)) = prev;
        let (tb, (gb, db)) = cur;
        let shift = if ga >= 0.0 { 0.0 } else { thr };
        if gb < -thr {
            return Some(illinois(|t| poly(c, t).0 + shift, ta, tb));
        }
        if da < 0.0 && db > 0.0 {
            let tm = illinois(|t| poly(c, t).1, ta, tb);
            if poly(c, tm).0 < -thr {
                return Some(illinois(|t| poly(c, t).0 + shift, ta, tm));
            }
        }
        prev = cur;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    pub(super) fn polynomial_and_derivative() {
        let c = [1.0, -2.0, 3.0];
        let (p, d) = poly(&c, 2.0);
        assert_eq!(p, 1.0 - 4.0 + 12.0);
        assert_eq!(d, -2.0 + 12.0);
    }

    #[test]
    pub(super) fn illinois_finds_a_simple_root_to_round_off() {
        let r = illinois(|t| t * t - 2.0, 0.0, 2.0);
        assert!((r - 2f64.sqrt()).abs() < 1e-14, "{r}");
    }

    #[test]
    pub(super) fn crossing_between_scan_points_is_found_from_the_minimum() {
        // g(τ) = (τ − 0.5)² − 1e-6 dips below zero between scan points 0.5 ± 0.001.
        let c = [0.25 - 1e-6, -1.0, 1.0];
        let t = first_crossing(&c, 1.0, 1e-12).expect("a crossing");
        assert!((t - (0.5 - 1e-3)).abs() < 1e-12, "{t}");
        // A graze within the threshold is no event.
        let c = [0.25 + 1e-13, -1.0, 1.0];
        assert!(first_crossing(&c, 1.0, 1e-12).is_none());
    }
}
