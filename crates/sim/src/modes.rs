//! Undamped modes of a structure: the generalised symmetric eigenproblem K φ = ω² M φ,
//! solved through the Cholesky factor of M (L⁻¹ K L⁻ᵀ ψ = ω² ψ, φ = L⁻ᵀ ψ), so the shapes
//! come out mass-normalised (φᵀ M φ = I).

use nalgebra::{DMatrix, DVector};

/// Natural circular frequencies (rad/s, ascending) and mass-normalised mode shapes (columns).
#[derive(Debug, Clone)]
pub struct Modes {
    /// ω_k, rad/s, ascending.
    pub omega: DVector<f64>,
    /// Mode shapes as columns, φᵀMφ = I.
    pub shapes: DMatrix<f64>,
}

impl Modes {
    /// Solves K φ = ω² M φ. Returns `None` when M is not positive definite or K has a
    /// negative eigenvalue (an unstable structure).
    pub fn compute(m: &DMatrix<f64>, k: &DMatrix<f64>) -> Option<Modes> {
        let n = m.nrows();
        let chol = m.clone().cholesky()?;
        let l = chol.l();
        let linv = l.clone().try_inverse()?;
        let a = &linv * k * linv.transpose();
        let a = (&a + a.transpose()) * 0.5;
        let eig = a.symmetric_eigen();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
        let mut omega = DVector::zeros(n);
        let mut psi = DMatrix::zeros(n, n);
        for (col, &i) in order.iter().enumerate() {
            let lam = eig.eigenvalues[i];
            if lam.is_nan() || lam <= 0.0 {
                return None;
            }
            omega[col] = lam.sqrt();
            psi.set_column(col, &eig.eigenvectors.column(i));
        }
        let shapes = linv.transpose() * psi;
        Some(Modes { omega, shapes })
    }

    /// Natural periods, s (descending).
    pub fn periods(&self) -> Vec<f64> {
        self.omega
            .iter()
            .map(|w| 2.0 * std::f64::consts::PI / w)
            .collect()
    }

    /// Damping matrix with modal ratios ζ_k: C = M Φ diag(2 ζ_k ω_k) Φᵀ M.
    pub fn damping_matrix(&self, m: &DMatrix<f64>, zeta: &[f64]) -> DMatrix<f64> {
        let n = self.omega.len();
        let d = DMatrix::from_fn(n, n, |i, j| {
            if i == j {
                2.0 * zeta[i] * self.omega[i]
            } else {
                0.0
            }
        });
        let mp = m * &self.shapes;
        let c = &mp * d * mp.transpose();
        (&c + c.transpose()) * 0.5
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_storey_shear_building_closed_form() {
        // m = 1, k = 1 on both storeys: ω² = (3 ∓ √5)/2.
        let m = DMatrix::identity(2, 2);
        let k = DMatrix::from_row_slice(2, 2, &[2.0, -1.0, -1.0, 1.0]);
        let modes = Modes::compute(&m, &k).unwrap();
        let s5 = 5f64.sqrt();
        assert!((modes.omega[0] - ((3.0 - s5) / 2.0).sqrt()).abs() < 1e-14);
        assert!((modes.omega[1] - ((3.0 + s5) / 2.0).sqrt()).abs() < 1e-14);
        let orth = modes.shapes.transpose() * &m * &modes.shapes;
        assert!((orth - DMatrix::identity(2, 2)).norm() < 1e-13);
    }

    #[test]
    fn modal_damping_reproduces_ratios() {
        let m = DMatrix::from_diagonal(&DVector::from_vec(vec![2.0, 1.0, 1.5]));
        let k = DMatrix::from_row_slice(3, 3, &[5.0, -2.0, 0.0, -2.0, 3.0, -1.0, 0.0, -1.0, 1.0]);
        let modes = Modes::compute(&m, &k).unwrap();
        let zeta = [0.02, 0.05, 0.1];
        let c = modes.damping_matrix(&m, &zeta);
        let cm = modes.shapes.transpose() * c * &modes.shapes;
        for i in 0..3 {
            assert!((cm[(i, i)] - 2.0 * zeta[i] * modes.omega[i]).abs() < 1e-12);
        }
    }
}
