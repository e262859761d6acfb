//! Contract: the front tools of `slipload_opt::phases::pareto` find the known analytic front of
//! synthetic problems — ZDT1 on a box (two objectives, front f₂ = 1 − √f₁) and the
//! DTLZ2 sphere (three objectives, front the unit sphere's octant) — and their exact
//! hypervolume converges to the analytic one from below.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::phases::pareto::{
    crowding_distance, first_front, hypervolume, knee, nondominated_ranks,
};

/// ZDT1 (Zitzler, Deb & Thiele 2000) with `x` in [0, 1]^d: f₁ = x₁,
/// g = 1 + 9 · mean(x₂…), f₂ = g (1 − √(f₁/g)). Its front is g = 1: x₂… = 0.
fn zdt1(x: &[f64]) -> Vec<f64> {
    let f1 = x[0];
    let g = 1.0 + 9.0 * x[1..].iter().sum::<f64>() / (x.len() - 1) as f64;
    vec![f1, g * (1.0 - (f1 / g).sqrt())]
}

#[test]
fn zdt1_front_of_a_grid_is_the_analytic_front() {
    // a 41 × 5 × 5 grid of the box: the front is exactly the 41 designs with x₂ = x₃ = 0
    let n = 40;
    let mut xs = Vec::new();
    for i in 0..=n {
        for j in 0..5 {
            for k in 0..5 {
                xs.push(vec![i as f64 / n as f64, j as f64 / 4.0, k as f64 / 4.0]);
            }
        }
    }
    let f: Vec<Vec<f64>> = xs.iter().map(|x| zdt1(x)).collect();
    let front = first_front(&f);
    assert_eq!(front.len(), n + 1);
    for &i in &front {
        assert_eq!((xs[i][1], xs[i][2]), (0.0, 0.0), "design {i} on the front");
        // on the analytic front f₂ = 1 − √f₁ (to round-off)
        assert!((f[i][1] - (1.0 - f[i][0].sqrt())).abs() < 1e-15);
    }
    // every design off the front is dominated: rank > 1
    let ranks = nondominated_ranks(&f);
    assert!(
        ranks
            .iter()
            .enumerate()
            .all(|(i, &r)| (r == 1) == front.contains(&i))
    );

    // the hypervolume against (1, 1): analytic ∫₀¹ √f₁ df₁ = 2/3. The staircase of
    // n + 1 equally spaced front points is a Riemann sum of an increasing function of
    // total variation 1, so it lies below 2/3 by at most 1/n
    let pts: Vec<Vec<f64>> = front.iter().map(|&i| f[i].clone()).collect();
    let hv = hypervolume(&f, &[1.0, 1.0]);
    assert_eq!(
        hv,
        hypervolume(&pts, &[1.0, 1.0]),
        "dominated points add nothing"
    );
    assert!(hv < 2.0 / 3.0 && hv > 2.0 / 3.0 - 1.0 / n as f64, "{hv}");

    // crowding on the front: the ends are infinite, the rest finite and positive
    let cd = crowding_distance(&pts);
    let (lo, hi) = (0, pts.len() - 1); // sorted by f₁ already (x₁ increasing)
    assert!(cd[lo].is_infinite() && cd[hi].is_infinite());
    assert!(cd[1..hi].iter().all(|d| d.is_finite() && *d > 0.0));

    // the knee of f₂ = 1 − √f₁ normalised to [0, 1]²: least f₁ + 1 − √f₁, at f₁ = 1/4
    let k = knee(&pts).unwrap();
    assert_eq!(pts[k][0], 0.25);
}

#[test]
fn dtlz2_sphere_hypervolume_converges_to_the_analytic_value() {
    // points on the unit sphere's octant: each on the front, none dominates another;
    // the region they dominate up to (1, 1, 1) tends to the cube minus the ball's
    // octant, 1 − π/6, from below
    let analytic = 1.0 - std::f64::consts::PI / 6.0;
    let mut last = 0.0;
    let mut errors = Vec::new();
    for n in [8, 16, 32] {
        let mut pts = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                let a = std::f64::consts::FRAC_PI_2 * i as f64 / n as f64;
                let b = std::f64::consts::FRAC_PI_2 * j as f64 / n as f64;
                pts.push(vec![a.cos() * b.cos(), a.cos() * b.sin(), a.sin()]);
            }
        }
        let ranks = nondominated_ranks(&pts);
        assert!(
            ranks.iter().all(|&r| r == 1),
            "every sphere point is on the front"
        );
        let hv = hypervolume(&pts, &[1.0, 1.0, 1.0]);
        assert!(
            hv < analytic && hv > last,
            "n = {n}: {hv} (analytic {analytic})"
        );
        last = hv;
        errors.push(analytic - hv);
    }
    // the staircase misses a layer of thickness O(1/n) over the sphere: the error halves
    // (to within a quarter) when n doubles — first-order convergence to 1 − π/6
    for w in errors.windows(2) {
        let ratio = w[1] / w[0];
        assert!((0.375..0.625).contains(&ratio), "errors {errors:?}");
    }
}

#[test]
fn four_objectives_slice_like_three() {
    // a fourth objective equal for every point scales the 3-D hypervolume by its span
    let pts = vec![
        vec![0.2, 0.5, 0.7],
        vec![0.6, 0.1, 0.4],
        vec![0.3, 0.3, 0.3],
        vec![0.9, 0.8, 0.05],
    ];
    let three = hypervolume(&pts, &[1.0, 1.0, 1.0]);
    let four: Vec<Vec<f64>> = pts
        .iter()
        .map(|p| {
            let mut q = p.clone();
            q.push(0.5);
            q
        })
        .collect();
    let hv4 = hypervolume(&four, &[1.0, 1.0, 1.0, 2.0]);
    assert!(
        (hv4 - 1.5 * three).abs() < 1e-14,
        "{hv4} vs {}",
        1.5 * three
    );
}
