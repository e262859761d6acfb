//! What a `newmark` run fixes before its first step: the operators of the dense step
//! ([`Operators`]: A⁻¹K, A⁻¹C, the friction columns G and the Delassus matrix W) and the
//! Newmark constants of a step ([`StepConstants`]), which the banded step shares.

use crate::error::SimError;
use crate::plan::{ContactKind, Plan};
use nalgebra::{DMatrix, DVector};

/// Operators fixed for a run.
pub(super) struct Operators {
    pub(super) n: usize,
    pub(super) alpha: f64,
    pub(super) beta: f64,
    pub(super) gamma: f64,
    /// [−A⁻¹K, −A⁻¹C], n × 2n, applied to the weighted predictors ((1+α)ũ − αu,
    /// (1+α)ṽ − αv) with ũ = u + Δt v + (½−β)Δt² a, ṽ = v + (1−γ)Δt a.
    pub(super) q: DMatrix<f64>,
    /// A⁻¹ M r.
    pub(super) h: DVector<f64>,
    /// A⁻¹ e(force floor), when a harmonic force acts.
    pub(super) hp: Option<(usize, DVector<f64>)>,
    /// (1+α) A⁻¹ B, n × nc.
    pub(super) g: DMatrix<f64>,
    /// Delassus matrix, nc × nc.
    pub(super) w: DMatrix<f64>,
    /// κ = k′βΔt/γ + c′ for elastic–perfectly plastic contacts (0 otherwise).
    pub(super) kappa: Vec<f64>,
    /// M r.
    pub(super) mr: DVector<f64>,
    /// M r₂ and A⁻¹ M r₂ of a second ground component, when the plan has one.
    pub(super) second: Option<(DVector<f64>, DVector<f64>)>,
}

impl Operators {
    pub(super) fn build(plan: &Plan) -> Result<Operators, SimError> {
        let n = plan.dofs();
        let dt = plan.method.dt;
        let alpha = plan.method.alpha;
        let gamma = 0.5 - alpha;
        let beta = (1.0 - alpha) * (1.0 - alpha) / 4.0;
        let (m, c, k) = (&plan.mass, &plan.damping, &plan.stiffness);
        let a = m + (c * (gamma * dt) + k * (beta * dt * dt)) * (1.0 + alpha);
        let chol = a.cholesky().ok_or_else(|| SimError::NotPositiveDefinite {
            what: "Newmark iteration matrix M + γΔtC + βΔt²K".into(),
            hint: " (a mass, damping or stiffness matrix is invalid)".into(),
        })?;
        let mut q = DMatrix::zeros(n, 2 * n);
        q.view_mut((0, 0), (n, n)).copy_from(&(-chol.solve(k)));
        q.view_mut((0, n), (n, n)).copy_from(&(-chol.solve(c)));
        let mr = plan.mass_influence();
        let h = chol.solve(&mr);
        let second = plan.mass_influence2().map(|mr2| {
            let h2 = chol.solve(&mr2);
            (mr2, h2)
        });
        let hp = plan.harmonic.map(|hm| {
            let mut e = DVector::zeros(n);
            e[hm.floor] = 1.0;
            (hm.floor, chol.solve(&e))
        });
        let bm = plan.contact_matrix();
        let g = chol.solve(&bm) * (1.0 + alpha);
        let mut w = bm.transpose() * &g * (gamma * dt);
        let kappa: Vec<f64> = plan
            .contacts
            .iter()
            .map(|ct| match ct.kind {
                ContactKind::Epp => ct.brace_stiffness * beta * dt / gamma + ct.brace_damping,
                ContactKind::Dof { .. } => 0.0,
            })
            .collect();
        for (i, kp) in kappa.iter().enumerate() {
            if *kp > 0.0 {
                w[(i, i)] += 1.0 / kp;
            }
        }
        let w = (&w + w.transpose()) * 0.5;
        Ok(Operators {
            n,
            alpha,
            beta,
            gamma,
            q,
            h,
            hp,
            g,
            w,
            kappa,
            mr,
            second,
        })
    }
}

/// The Newmark constants of a run's step.
#[derive(Debug, Clone, Copy)]
pub(super) struct StepConstants {
    pub(super) dt: f64,
    /// (½ − β)Δt² and (1 − γ)Δt: the predictors' weights of the acceleration.
    pub(super) c_u: f64,
    pub(super) c_v: f64,
    /// γΔt, βΔt², βΔt/γ and 1/(γΔt).
    pub(super) gdt: f64,
    pub(super) bdt2: f64,
    pub(super) bg: f64,
    pub(super) inv_gdt: f64,
}

impl StepConstants {
    pub(super) fn new(dt: f64, beta: f64, gamma: f64) -> StepConstants {
        StepConstants {
            dt,
            c_u: (0.5 - beta) * dt * dt,
            c_v: (1.0 - gamma) * dt,
            gdt: gamma * dt,
            bdt2: beta * dt * dt,
            bg: beta * dt / gamma,
            inv_gdt: 1.0 / (gamma * dt),
        }
    }
}
