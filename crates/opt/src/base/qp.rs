//! Convex QPs of the trust-region refiner, solved by clarabel:
//! min ½ xᵀPx + qᵀx subject to lo ≤ x ≤ hi and A x ≤ b, with P symmetric positive
//! semidefinite (only its upper triangle is passed: clarabel drops a lower one).

use crate::base::error::OptError;
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
};
use nalgebra::DMatrix;

/// P with every eigenvalue below `floor` raised to `floor` (P symmetric): the nearest
/// (Frobenius) symmetric matrix with spectrum ≥ floor.
pub fn clip_to_psd(p: &DMatrix<f64>, floor: f64) -> DMatrix<f64> {
    let sym = (p + p.transpose()) * 0.5;
    let eig = sym.symmetric_eigen();
    let lam = eig.eigenvalues.map(|l| l.max(floor));
    let v = &eig.eigenvectors;
    v * DMatrix::from_diagonal(&lam) * v.transpose()
}

fn csc_from_columns(
    rows: usize,
    cols: usize,
    entry: impl Fn(usize, usize) -> f64,
    upper_only: bool,
) -> CscMatrix<f64> {
    let mut colptr = vec![0];
    let mut rowval = Vec::new();
    let mut nzval = Vec::new();
    for j in 0..cols {
        for i in 0..rows {
            if upper_only && i > j {
                break;
            }
            let v = entry(i, j);
            if v != 0.0 {
                rowval.push(i);
                nzval.push(v);
            }
        }
        colptr.push(rowval.len());
    }
    CscMatrix::new(rows, cols, colptr, rowval, nzval)
}

/// Solves the QP; the answer is clamped into [lo, hi] (an interior-point answer sits a
/// hair inside its bounds). Errors when clarabel does not report `Solved`/`AlmostSolved`.
pub fn solve(
    p: &DMatrix<f64>,
    q: &[f64],
    lo: &[f64],
    hi: &[f64],
    a: &DMatrix<f64>,
    b: &[f64],
) -> Result<Vec<f64>, OptError> {
    solve_with_duals(p, q, lo, hi, a, b).map(|(x, _)| x)
}

/// As [`solve`], with the multipliers (≥ 0) of the rows A x ≤ b.
pub fn solve_with_duals(
    p: &DMatrix<f64>,
    q: &[f64],
    lo: &[f64],
    hi: &[f64],
    a: &DMatrix<f64>,
    b: &[f64],
) -> Result<(Vec<f64>, Vec<f64>), OptError> {
    let n = q.len();
    let m = a.nrows();
    let pc = csc_from_columns(n, n, |i, j| p[(i, j)], true);
    let ac = csc_from_columns(
        2 * n + m,
        n,
        |i, j| {
            if i < n {
                if i == j { 1.0 } else { 0.0 }
            } else if i < 2 * n {
                if i - n == j { -1.0 } else { 0.0 }
            } else {
                a[(i - 2 * n, j)]
            }
        },
        false,
    );
    let rhs: Vec<f64> = hi
        .iter()
        .copied()
        .chain(lo.iter().map(|l| -l))
        .chain(b.iter().copied())
        .collect();
    let cones = [NonnegativeConeT(2 * n + m)];
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .build()
        .map_err(|e| OptError::Subproblem(e.to_string()))?;
    let mut solver = DefaultSolver::new(&pc, q, &ac, &rhs, &cones, settings)
        .map_err(|e| OptError::Subproblem(format!("{e:?}")))?;
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => Ok((
            solver
                .solution
                .x
                .iter()
                .zip(lo.iter().zip(hi))
                .map(|(x, (l, h))| x.clamp(*l, *h))
                .collect(),
            solver.solution.z[2 * n..]
                .iter()
                .map(|v| v.max(0.0))
                .collect(),
        )),
        other => Err(OptError::Subproblem(format!("clarabel status {other:?}"))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_qp_with_a_full_hessian_matches_the_closed_form() {
        // min ½xᵀPx − (1,1)ᵀx, P = [[4,1],[1,2]], box [0, 10]²: unconstrained optimum
        // P⁻¹(1,1) = (1/7, 3/7) is inside the box.
        let p = DMatrix::from_row_slice(2, 2, &[4.0, 1.0, 1.0, 2.0]);
        let x = solve(
            &p,
            &[-1.0, -1.0],
            &[0.0, 0.0],
            &[10.0, 10.0],
            &DMatrix::zeros(0, 2),
            &[],
        )
        .unwrap();
        // interior-point accuracy ~1e-8 (clarabel's default tolerances)
        assert!(
            (x[0] - 1.0 / 7.0).abs() < 1e-6 && (x[1] - 3.0 / 7.0).abs() < 1e-6,
            "{x:?}"
        );
    }

    #[test]
    fn linear_constraint_binds() {
        // min ½|x|² − 2(x₀ + x₁) with x₀ + x₁ ≤ 1: optimum (½, ½)
        let p = DMatrix::identity(2, 2);
        let a = DMatrix::from_row_slice(1, 2, &[1.0, 1.0]);
        let x = solve(&p, &[-2.0, -2.0], &[-5.0, -5.0], &[5.0, 5.0], &a, &[1.0]).unwrap();
        assert!(
            (x[0] - 0.5).abs() < 1e-6 && (x[1] - 0.5).abs() < 1e-6,
            "{x:?}"
        );
    }

    #[test]
    fn clipping_keeps_psd_part() {
        let p = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, -3.0]);
        let c = clip_to_psd(&p, 0.0);
        assert!((c[(0, 0)] - 1.0).abs() < 1e-12 && c[(1, 1)].abs() < 1e-12);
    }
}
