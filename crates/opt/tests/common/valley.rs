//! The analytic narrow valley the refiner tests run on (`tests/refiner_model.rs`,
//! `tests/refiner_sqp.rs`), with its gradient.

use nalgebra::{DMatrix, DVector};

/// The minimum: a profile falling from 0.62 at the first variable to 0.26 at the last
/// (slip loads that fall with height), so a start along the storey-shear-like profile
/// below is near but not at it.
pub fn minimum(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| 0.62 - 0.36 * i as f64 / (n - 1) as f64)
        .collect()
}

/// A narrow valley: f(z) = 1 + Σ λₖ (qₖᵀu)² + (uᵀu)², u = z − z*, where q₀ is the
/// profile direction (every variable together, the valley's floor: λ₀ = 0.1) and the
/// other qₖ an orthonormal basis of the rest with λₖ from 1 to 30 (moving one variable
/// against the others is steep). f* = 1 at z*. Not a quadratic (the quartic term), so no
/// model is exact. The ten-storey check example's objective, relative to its optimum,
/// has curvatures of the same order: about 1 along the profile (every slip load × 1.03
/// costs 0.1 %) and about 14 for one floor (−450 kN, 0.15 of the range, costs 32 %).
pub struct Valley {
    q: DMatrix<f64>,
    lambda: Vec<f64>,
    pub star: Vec<f64>,
}

impl Valley {
    pub fn new(n: usize) -> Valley {
        // Gram–Schmidt on the profile direction, then a fixed set of dense vectors
        let mut cols: Vec<DVector<f64>> = vec![DVector::from_element(n, 1.0).normalize()];
        // (a fixed linear congruential sequence: dense vectors in general position)
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        while cols.len() < n {
            let mut v = DVector::from_fn(n, |_, _| next());
            for c in &cols {
                v -= c * c.dot(&v);
            }
            if v.norm() > 1e-6 {
                cols.push(v.normalize());
            }
        }
        let q = DMatrix::from_columns(&cols);
        let lambda = (0..n)
            .map(|k| {
                if k == 0 {
                    0.1
                } else {
                    1.0 + 29.0 * (k - 1) as f64 / (n - 1).max(2) as f64
                }
            })
            .collect();
        Valley {
            q,
            lambda,
            star: minimum(n),
        }
    }

    pub fn f(&self, z: &[f64]) -> f64 {
        let u = DVector::from_iterator(z.len(), z.iter().zip(&self.star).map(|(a, b)| a - b));
        let w = self.q.transpose() * &u;
        let quad: f64 = w.iter().zip(&self.lambda).map(|(w, l)| l * w * w).sum();
        1.0 + quad + u.dot(&u).powi(2)
    }

    /// ∇f = 2 Q Λ Qᵀu + 4 (uᵀu) u.
    pub fn gradient(&self, z: &[f64]) -> Vec<f64> {
        let u = DVector::from_iterator(z.len(), z.iter().zip(&self.star).map(|(a, b)| a - b));
        let w = self.q.transpose() * &u;
        let lw = DVector::from_iterator(w.len(), w.iter().zip(&self.lambda).map(|(w, l)| l * w));
        let g = &self.q * lw * 2.0 + &u * (4.0 * u.dot(&u));
        g.iter().copied().collect()
    }
}
