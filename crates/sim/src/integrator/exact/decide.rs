//! The contacts decided at an event: the box QP at the acceleration level (Delassus
//! B_UᵀM⁻¹B_U, as `newmark`'s initial state) gives each undecided dissipator with mass
//! its mode (free = stick, a bound = slide that way).

use super::cache::Cache;
use super::kernels::row_dot;
use super::model::{Mode, Model};
use crate::error::SimError;
use crate::friction::BoxQp;
use crate::friction::box_qp::Bound;
use nalgebra::{DMatrix, DVector};

impl Model<'_> {
    /// Modes decided by the acceleration-level box QP for the contacts in `decide`
    /// (all other contacts keep `modes`).
    pub(super) fn decide(
        &self,
        cache: &mut Cache,
        y: &DVector<f64>,
        modes: &mut [Mode],
        decide: &[usize],
        t: f64,
    ) -> Result<(), SimError> {
        if decide.is_empty() {
            return Ok(());
        }
        let plan = self.plan;
        let lay = &self.lay;
        let n = lay.n;
        // Forces of all non-decided contacts from the current modes.
        let mut tmp: Vec<Mode> = modes.to_vec();
        for &c in decide {
            tmp[c] = Mode::Upper; // placeholder: its force is excluded below
        }
        let ops = cache.operators(self, &tmp);
        let mut g = &self.f0 * y;
        for (c, _) in plan.contacts.iter().enumerate() {
            if decide.contains(&c) {
                continue;
            }
            let fc = row_dot(&ops.force, c, y);
            g.axpy(-fc, &self.bcols[c], 1.0);
        }
        let m = decide.len();
        let mut bu = DMatrix::zeros(n, m);
        for (k, &c) in decide.iter().enumerate() {
            bu.set_column(k, &self.bcols[c]);
        }
        let wa = bu.transpose() * &self.minv * &bu;
        let wa = (&wa + wa.transpose()) * 0.5;
        let b = bu.transpose() * (&self.minv * g);
        let lo: Vec<f64> = decide.iter().map(|&c| plan.contacts[c].lower).collect();
        let hi: Vec<f64> = decide.iter().map(|&c| plan.contacts[c].upper).collect();
        let mut f = vec![0.0; m];
        let mut qp =
            BoxQp::new(wa.as_slice(), m).map_err(|source| SimError::Friction { t, source })?;
        qp.solve(b.as_slice(), &lo, &hi, &mut f)
            .map_err(|source| SimError::Friction { t, source })?;
        for (k, &c) in decide.iter().enumerate() {
            modes[c] = match qp.status(k) {
                Bound::Free => Mode::Stuck,
                Bound::Upper => Mode::Upper,
                Bound::Lower => Mode::Lower,
            };
        }
        Ok(())
    }
}
