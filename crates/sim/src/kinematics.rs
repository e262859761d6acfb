//! Kinematic vectors: how a one-dimensional element (a friction contact, a yielding
//! storey's plastic element, a drift that is measured) reads the structure's DOFs
//! (docs/MODEL.md § Buildings in plan).
//!
//! An element acts between two points, `top` and `bottom`, each a weighted sum of at most
//! three DOFs ([`Kin`]): in a chain of floors a point is one floor's DOF (weight 1) or the
//! ground (no DOF); in a plan it is the component along a line's direction of the motion
//! of a rigid floor at the line, cos φ·uₓ + sin φ·u_y + r·θ (three DOFs). The integrators
//! read and load every element through these vectors, so the chain and the plan are two
//! instances of one structure. A chain's point reads its DOF exactly (no product, no sum),
//! so a chain gives the same bits as before the structure was generalised.

/// A point an element acts at: Σₖ wₖ·`x[iₖ]` over at most three DOFs; the ground when
/// empty.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kin {
    idx: [usize; 3],
    w: [f64; 3],
    len: u8,
    /// A single DOF of weight 1 (the chain's case): read without a product.
    unit: bool,
}

impl Kin {
    /// The ground: no DOF, reads 0.
    pub const GROUND: Kin = Kin {
        idx: [0; 3],
        w: [0.0; 3],
        len: 0,
        unit: false,
    };

    /// One DOF of weight 1.
    pub const fn dof(i: usize) -> Kin {
        Kin {
            idx: [i, 0, 0],
            w: [1.0, 0.0, 0.0],
            len: 1,
            unit: true,
        }
    }

    /// A floor (`Some`) or the ground (`None`), as a chain names the floor below.
    pub const fn floor_or_ground(f: Option<usize>) -> Kin {
        match f {
            Some(i) => Kin::dof(i),
            None => Kin::GROUND,
        }
    }

    /// A weighted sum of DOFs (entries of weight 0 dropped). At most three entries.
    ///
    /// # Panics
    /// With more than three non-zero entries (a programming error: points in plan read
    /// three DOFs).
    pub fn weighted(entries: &[(usize, f64)]) -> Kin {
        let mut k = Kin::GROUND;
        for &(i, w) in entries.iter().filter(|(_, w)| *w != 0.0) {
            assert!(k.len < 3, "a kinematic vector reads at most three DOFs");
            k.idx[k.len as usize] = i;
            k.w[k.len as usize] = w;
            k.len += 1;
        }
        k.unit = k.len == 1 && k.w[0] == 1.0;
        k
    }

    /// Whether this is the ground.
    #[inline]
    pub fn is_ground(&self) -> bool {
        self.len == 0
    }

    /// The DOF when this is one DOF of weight 1 (the chain's case).
    #[inline]
    pub fn as_dof(&self) -> Option<usize> {
        self.unit.then_some(self.idx[0])
    }

    /// The (DOF, weight) entries.
    pub fn entries(&self) -> impl Iterator<Item = (usize, f64)> + '_ {
        (0..self.len as usize).map(|k| (self.idx[k], self.w[k]))
    }

    /// Σₖ wₖ·`x[iₖ]`; exactly `x[i]` for one DOF of weight 1, 0 for the ground.
    #[inline(always)]
    pub fn at(&self, x: &[f64]) -> f64 {
        self.at_offset(x, 0)
    }

    /// Σₖ wₖ·`x[off + iₖ]` (a state vector whose block starts at `off`).
    #[inline(always)]
    pub fn at_offset(&self, x: &[f64], off: usize) -> f64 {
        if self.unit {
            return x[off + self.idx[0]];
        }
        let mut s = 0.0;
        for k in 0..self.len as usize {
            s += self.w[k] * x[off + self.idx[k]];
        }
        s
    }

    /// `x[iₖ]` += s·wₖ (a force `s` along the point's direction); `x[i]` += s for one DOF of
    /// weight 1.
    #[inline(always)]
    pub fn add(&self, x: &mut [f64], s: f64) {
        self.add_offset(x, 0, s);
    }

    /// `x[off + iₖ]` += s·wₖ.
    #[inline(always)]
    pub fn add_offset(&self, x: &mut [f64], off: usize, s: f64) {
        if self.unit {
            x[off + self.idx[0]] += s;
            return;
        }
        for k in 0..self.len as usize {
            x[off + self.idx[k]] += s * self.w[k];
        }
    }

    /// The largest DOF index read, if any.
    pub fn max_dof(&self) -> Option<usize> {
        self.entries().map(|(i, _)| i).max()
    }
}

/// Adds the element stiffness k·(a − b)(a − b)ᵀ of a spring between the points `a` and
/// `b` to the column-major square matrix `m` (its order `n`).
pub fn add_between(m: &mut nalgebra::DMatrix<f64>, a: &Kin, b: &Kin, k: f64) {
    let v: Vec<(usize, f64)> = a
        .entries()
        .chain(b.entries().map(|(i, w)| (i, -w)))
        .collect();
    for &(i, wi) in &v {
        for &(j, wj) in &v {
            m[(i, j)] += k * wi * wj;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_unit_point_reads_its_dof_and_the_ground_reads_zero() {
        let x = [1.5, -2.0, 3.25];
        assert_eq!(Kin::dof(1).at(&x), -2.0);
        assert_eq!(Kin::GROUND.at(&x), 0.0);
        assert_eq!(Kin::weighted(&[(2, 1.0)]).as_dof(), Some(2));
        let p = Kin::weighted(&[(0, 0.5), (1, 0.0), (2, -2.0)]);
        assert_eq!(p.entries().count(), 2);
        assert_eq!(p.at(&x), 0.75 - 6.5);
        let mut y = [0.0; 3];
        p.add(&mut y, 2.0);
        assert_eq!(y, [1.0, 0.0, -4.0]);
    }

    #[test]
    fn a_spring_between_two_points_is_symmetric_and_reads_their_difference() {
        let a = Kin::weighted(&[(0, 0.6), (1, 0.8), (2, 3.0)]);
        let b = Kin::GROUND;
        let mut m = nalgebra::DMatrix::zeros(3, 3);
        add_between(&mut m, &a, &b, 2.0);
        let x = nalgebra::DVector::from_vec(vec![0.1, -0.3, 0.02]);
        let d = a.at(x.as_slice());
        // xᵀKx = k d²
        assert!(((x.transpose() * &m * &x)[(0, 0)] - 2.0 * d * d).abs() < 1e-15);
        assert_eq!(m, m.transpose());
    }
}
