//! Energies: the input, viscous and friction powers as quadratic forms of the augmented
//! state, their Gauss–Legendre work over a substep, and the stored energies.

use super::gauss::GAUSS;
use super::kernels::row_dot;
use super::model::{ModeOps, Model};
use crate::plan::{ContactKind, ContactRole};
use nalgebra::{DMatrix, DVector};

/// Running integrals.
#[derive(Default, Clone, Copy)]
pub(super) struct Integrals {
    pub(super) input: f64,
    pub(super) viscous: f64,
    pub(super) friction: f64,
    /// The yielding storeys' plastic work (their contacts' share of the friction power).
    pub(super) plastic: f64,
}

/// The powers at one state: input, viscous, friction (dissipators) and plastic (yielding
/// storeys), W.
pub(super) type Powers = [f64; 4];

impl Model<'_> {
    /// The symmetric matrices Q_p with p(y) = yᵀ Q_p y of the input, viscous, friction and
    /// plastic powers of [`Model::powers`] (each is a quadratic form of the augmented
    /// state: the ground acceleration, the harmonic force and the constant slip forces are
    /// states).
    pub(super) fn power_forms(&self, ops: &ModeOps) -> [DMatrix<f64>; 4] {
        let lay = &self.lay;
        let (n, dim) = (lay.n, lay.dim);
        let plan = self.plan;
        let mut input = DMatrix::zeros(dim, dim);
        let mut viscous = DMatrix::zeros(dim, dim);
        let mut friction = DMatrix::zeros(dim, dim);
        let mut plastic = DMatrix::zeros(dim, dim);
        // −a_g (M r · v), and the harmonic force's F sin · v_floor.
        for i in 0..n {
            input[(lay.i_ag, n + i)] -= self.mr[i];
        }
        if let (Some((i_ag2, _)), Some(m2)) = (lay.second, &self.mr2) {
            for i in 0..n {
                input[(i_ag2, n + i)] -= m2[i];
            }
        }
        if let Some(h) = &plan.harmonic {
            input[(lay.i_sin, n + h.floor)] += h.amplitude;
        }
        // vᵀ C v.
        for j in 0..n {
            for i in 0..n {
                viscous[(n + i, n + j)] += plan.damping[(i, j)];
            }
        }
        for (c, ct) in plan.contacts.iter().enumerate() {
            // (force row · y)(slip-rate row · y).
            let f = ops.force.column(c);
            let w = ops.slip_rate.column(c);
            match ct.role {
                ContactRole::Damper => friction.ger(1.0, &f, &w, 1.0),
                ContactRole::Storey => plastic.ger(1.0, &f, &w, 1.0),
            }
            if ct.kind == ContactKind::Epp && ct.brace_damping > 0.0 {
                // c′ (ẋ′ − v_below)².
                let mut e = ops.xdot.column(c).into_owned();
                ct.bottom.add_offset(e.as_mut_slice(), n, -1.0);
                viscous.ger(ct.brace_damping, &e, &e, 1.0);
            }
        }
        [input, viscous, friction, plastic].map(|q| (&q + q.transpose()) * 0.5)
    }

    pub(super) fn powers(&self, ops: &ModeOps, y: &DVector<f64>) -> Powers {
        let lay = &self.lay;
        let n = lay.n;
        let plan = self.plan;
        let v = &y.as_slice()[n..2 * n];
        let mut mrv = 0.0;
        let mut viscous = 0.0;
        for i in 0..n {
            mrv += self.mr[i] * v[i];
            let mut cv = 0.0;
            for (j, vj) in v.iter().enumerate() {
                cv += plan.damping[(i, j)] * vj;
            }
            viscous += v[i] * cv;
        }
        let mut input = -y[lay.i_ag] * mrv;
        if let (Some((i_ag2, _)), Some(m2)) = (lay.second, &self.mr2) {
            let m2v: f64 = m2.iter().zip(v.iter()).map(|(m, v)| m * v).sum();
            input -= y[i_ag2] * m2v;
        }
        if let Some(h) = &plan.harmonic {
            input += h.amplitude * y[lay.i_sin] * v[h.floor];
        }
        let mut friction = 0.0;
        let mut plastic = 0.0;
        for (c, ct) in plan.contacts.iter().enumerate() {
            let p = row_dot(&ops.force, c, y) * row_dot(&ops.slip_rate, c, y);
            match ct.role {
                ContactRole::Damper => friction += p,
                ContactRole::Storey => plastic += p,
            }
            if ct.kind == ContactKind::Epp && ct.brace_damping > 0.0 {
                let vb = ct.bottom.at(v);
                let ed = row_dot(&ops.xdot, c, y) - vb;
                viscous += ct.brace_damping * ed * ed;
            }
        }
        [input, viscous, friction, plastic]
    }

    /// Adds the input, viscous and friction work over a substep of length `len` by
    /// 6-point Gauss–Legendre ([`GAUSS`]); `node(g, out)` writes the state at the g-th node.
    pub(super) fn integrate_powers(
        &self,
        ops: &ModeOps,
        integ: &mut Integrals,
        len: f64,
        ynode: &mut DVector<f64>,
        mut node: impl FnMut(usize, &mut DVector<f64>),
    ) {
        let (mut di, mut dv, mut df, mut dp) = (0.0, 0.0, 0.0, 0.0);
        for (g, (_, w)) in GAUSS.iter().enumerate() {
            node(g, ynode);
            let [pi, pv, pf, pp] = self.powers(ops, ynode);
            di += w * pi;
            dv += w * pv;
            df += w * pf;
            dp += w * pp;
        }
        integ.input += di * len;
        integ.viscous += dv * len;
        integ.friction += df * len;
        integ.plastic += dp * len;
    }

    pub(super) fn stored(&self, y: &DVector<f64>) -> (f64, f64) {
        let plan = self.plan;
        let n = self.lay.n;
        let u = y.rows(0, n);
        let v = y.rows(n, n);
        // Quadratic forms without temporaries (called at every output step).
        let quad = |m: &DMatrix<f64>, x: &nalgebra::DVectorView<f64>| -> f64 {
            let mut q = 0.0;
            for (j, xj) in x.iter().enumerate() {
                q += xj * m.column(j).dot(x);
            }
            q
        };
        let kinetic = 0.5 * quad(&plan.mass, &v);
        let mut strain = 0.5 * quad(&plan.stiffness, &u);
        for (c, ct) in plan.contacts.iter().enumerate() {
            if let Some(s) = self.lay.epp_slot[c] {
                let e = y[s] - ct.bottom.at(u.as_slice());
                strain += 0.5 * ct.brace_stiffness * e * e;
            }
        }
        (kinetic, strain)
    }
}

#[cfg(test)]
mod tests {
    use super::super::model::Mode;
    use super::*;
    use crate::plan::Plan;

    #[test]
    pub(super) fn power_forms_are_the_powers() {
        // Two storeys: a massless dissipator with a damped brace (its c′ term), one with
        // mass (a Lagrange multiplier while stuck), a harmonic force and Rayleigh damping.
        // For every mode set, yᵀ Q_p y must be the power itself at any augmented state, to
        // round-off of the sums (relative to their absolute terms, ~1e-15).
        let text = r#"{ "building": { "floor_masses": [4.0e5, 3.0e5], "storey_stiffness": [2.0e8, 1.5e8],
                "damping": { "rayleigh": { "alpha": 0.2, "beta": 1e-3 } },
                "dissipators": [
                  { "floor": 1, "brace_stiffness": 4.0e8, "mass": 0, "brace_damping": 3e5, "slip_load": 4e5 },
                  { "floor": 2, "brace_stiffness": 3.0e8, "mass": 350, "brace_damping": 0, "slip_load": 2e5 } ] },
              "excitation": { "harmonic": { "floor": 2, "amplitude": 1e5, "omega": 9.0 } },
              "duration": 1.0, "method": { "name": "exact", "dt": 0.01 }, "outputs": { "energies": true } }"#;
        let scene = crate::scene::Scene::from_json(
            text,
            std::path::Path::new("inline.json"),
            &crate::scene::SceneOverrides::default(),
        )
        .unwrap();
        let plan = Plan::compile(&scene).unwrap();
        let model = Model::new(&plan).unwrap();
        let dim = model.lay.dim;
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut uniform = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        use Mode::{Lower, Stuck, Upper};
        for modes in [
            [Stuck, Stuck],
            [Upper, Lower],
            [Lower, Stuck],
            [Stuck, Upper],
        ] {
            let ops = model.build(&modes);
            let forms = model.power_forms(&ops);
            for _ in 0..20 {
                let y = DVector::from_fn(dim, |_, _| uniform());
                let [pi, pv, pf, pp] = model.powers(&ops, &y);
                for (q, p, what) in [
                    (&forms[0], pi, "input"),
                    (&forms[1], pv, "viscous"),
                    (&forms[2], pf, "friction"),
                    (&forms[3], pp, "plastic"),
                ] {
                    let from_form = (q * &y).dot(&y);
                    let scale = (q.abs() * y.abs()).dot(&y.abs());
                    assert!(
                        (from_form - p).abs() <= 1e-13 * scale,
                        "{modes:?} {what}: form {from_form:e}, power {p:e}, scale {scale:e}"
                    );
                }
            }
        }
    }
}
