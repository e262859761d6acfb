//! The step loop of `newmark` for a compile-time DOF count `N` and contact count `NC`.
//!
//! Same step as the general loop (`dense.rs`) — the same operators and
//! predictors, the products summed in another order (round-off apart, the same numbers) —
//! with every vector and operator a fixed-size array, so the products unroll and nothing
//! is bounds-checked, and with the friction QP answered from its stick/slip pattern
//! ([`PatternQp`]) before the general active-set solver is asked. It records peaks and,
//! when asked, energies (their quadratic forms on fixed-size copies of M, C and K, the
//! bookkeeping shared with the general loop); runs that ask for histories take the
//! general loop, which the `peaks_only_loop` tests hold it equal to.

// Index loops over compile-time sizes read as the formulas they compute, and unroll.
#![allow(clippy::needless_range_loop)]

use super::link::{EppPred, Link};
use super::operators::{Operators, StepConstants};
use super::outcome::{non_finite, outcome};
use crate::error::SimError;
use crate::friction::BoxQp;
use crate::friction::box_qp::Bound;
use crate::friction::pattern::PatternQp;
use crate::integrator::state::{
    EnergyAccumulator, EppState, StepEnergyData, StepForms, base_shear, epp_strain, initial_state,
    slip_rate as contact_slip_rate,
};
use crate::kinematics::Kin;
use crate::plan::Plan;
use crate::response::{Outcome, Peaks};

/// Fixed-size copies of the run's operators.
struct Ops<const N: usize, const NC: usize> {
    /// Columns of −A⁻¹K and −A⁻¹C.
    qu: [[f64; N]; N],
    qv: [[f64; N]; N],
    /// A⁻¹ M r.
    h: [f64; N],
    /// A⁻¹ e(force floor) (zeros without a harmonic force).
    hp: [f64; N],
    /// Columns of (1+α) A⁻¹ B.
    g: [[f64; N]; NC],
    /// M r.
    mr: [f64; N],
}

impl<const N: usize, const NC: usize> Ops<N, NC> {
    fn new(ops: &Operators) -> Ops<N, NC> {
        let mut o = Ops {
            qu: [[0.0; N]; N],
            qv: [[0.0; N]; N],
            h: [0.0; N],
            hp: [0.0; N],
            g: [[0.0; N]; NC],
            mr: [0.0; N],
        };
        for j in 0..N {
            for i in 0..N {
                o.qu[j][i] = ops.q[(i, j)];
                o.qv[j][i] = ops.q[(i, N + j)];
            }
        }
        for c in 0..NC {
            for i in 0..N {
                o.g[c][i] = ops.g[(i, c)];
            }
        }
        o.h.copy_from_slice(ops.h.as_slice());
        if let Some((_, hp)) = &ops.hp {
            o.hp.copy_from_slice(hp.as_slice());
        }
        o.mr.copy_from_slice(ops.mr.as_slice());
        o
    }
}

/// Fixed-size copies (columns) of the matrices the energies read.
struct EnergyMatrices<const N: usize> {
    m: [[f64; N]; N],
    c: [[f64; N]; N],
    k: [[f64; N]; N],
}

impl<const N: usize> EnergyMatrices<N> {
    fn new(plan: &Plan) -> EnergyMatrices<N> {
        let cols = |a: &nalgebra::DMatrix<f64>| {
            let mut o = [[0.0; N]; N];
            for (j, col) in o.iter_mut().enumerate() {
                for (i, x) in col.iter_mut().enumerate() {
                    *x = a[(i, j)];
                }
            }
            o
        };
        EnergyMatrices {
            m: cols(&plan.mass),
            c: cols(&plan.damping),
            k: cols(&plan.stiffness),
        }
    }

    /// One step's quadratic forms: v̄ᵀCv̄ over the step (v̄ the mean of `v_old` and `v`),
    /// and the kinetic and strain energies at its end.
    #[inline(always)]
    fn forms(
        &self,
        plan: &Plan,
        (v_old, v): (&[f64; N], &[f64; N]),
        u: &[f64; N],
        epp: &[EppState],
    ) -> StepForms {
        let mut vm = [0.0; N];
        for i in 0..N {
            vm[i] = 0.5 * (v_old[i] + v[i]);
        }
        StepForms {
            cvv: dot(&mul(&self.c, &vm), &vm),
            kinetic: 0.5 * dot(&mul(&self.m, v), v),
            strain: 0.5 * dot(&mul(&self.k, u), u) + epp_strain(plan, u, epp),
        }
    }
}

/// Whether the fixed loop can run `plan`: no histories and no per-damper demands (its
/// loop holds no code for either), every contact with a finite box of positive width (the
/// pattern solver's premise).
pub(super) fn applies(plan: &Plan) -> bool {
    plan.is_chain()
        && !plan.outputs.histories
        && !plan.outputs.dampers
        && !plan.outputs.sensitivities
        && plan
            .contacts
            .iter()
            .all(|c| c.lower.is_finite() && c.upper.is_finite() && c.lower < c.upper)
}

/// Runs the fixed-size loop for `N` DOFs and `NC` contacts (the caller matched them),
/// recording energies when `E` (the caller matched it to the plan's outputs: a peaks-only
/// run's loop holds no energy code at all).
pub(super) fn run<const N: usize, const NC: usize, const E: bool>(
    plan: &Plan,
    ops: &Operators,
    links: &[Link],
) -> Result<Outcome, SimError> {
    debug_assert!(ops.n == N && plan.contacts.len() == NC && links.len() == NC);
    debug_assert_eq!(E, plan.outputs.energies);
    let o = Ops::<N, NC>::new(ops);
    let dt = plan.method.dt;
    let (alpha, beta, gamma) = (ops.alpha, ops.beta, ops.gamma);
    let k = StepConstants::new(dt, beta, gamma);
    let (c_u, c_v, gdt, bdt2) = (k.c_u, k.c_v, k.gdt, k.bdt2);
    let msum: f64 = ops.mr.iter().sum();
    let mut lo = [0.0; NC];
    let mut hi = [0.0; NC];
    let mut link = [Link {
        top: Kin::GROUND,
        other: Kin::GROUND,
        epp: false,
        algebraic: false,
        k_over_kappa: 0.0,
        slot: 0,
    }; NC];
    for c in 0..NC {
        lo[c] = plan.contacts[c].lower;
        hi[c] = plan.contacts[c].upper;
        link[c] = links[c];
    }
    let hhht = alpha != 0.0 && NC > 0;
    let forced = ops.hp.is_some();

    let start = initial_state(plan)?;
    let mut u = [0.0; N];
    let mut v = [0.0; N];
    let mut a = [0.0; N];
    u.copy_from_slice(&start.u);
    v.copy_from_slice(&start.v);
    a.copy_from_slice(&start.a);
    let mut f_old = [0.0; NC];
    f_old.copy_from_slice(&start.f);
    let mut epp = [EppState::default(); NC];
    epp.copy_from_slice(&start.epp);
    let mut stuck = [false; NC];
    stuck.copy_from_slice(&start.stuck);
    let energies = E.then(|| EnergyMatrices::<N>::new(plan));
    let mut acc = EnergyAccumulator::start(plan, &start.u, &start.v, &start.epp);
    let force_floor = ops.hp.as_ref().map(|(f, _)| *f);
    let mut v_old = [0.0; N];
    let mut w_old = [0.0; NC];
    for c in 0..NC {
        w_old[c] = contact_slip_rate(plan, c, &start.v, &start.epp);
    }
    let mut qp = if NC > 0 {
        Some(
            BoxQp::new(ops.w.as_slice(), NC)
                .map_err(|source| SimError::Friction { t: 0.0, source })?,
        )
    } else {
        None
    };
    let mut pq = PatternQp::<NC>::new(ops.w.as_slice(), &lo, &hi);

    let mut peaks = Peaks::for_plan(plan);
    debug_assert_eq!(peaks.drift.len(), plan.drifts.len());

    let mut ag0 = plan.ground_accel(0.0);
    let mut ground = plan.ground_steps();
    let mut p0 = plan.force(0.0);
    peaks.observe_floors(&u, &a, ag0);
    peaks.observe_base_shear(base_shear(&o.mr, msum, &a, ag0, p0));
    for c in 0..NC {
        let l = link[c];
        let x_other = if l.epp { epp[c].u } else { l.other.at(&u) };
        l.observe_start(&u, x_other, &mut peaks);
    }

    let mut wfree = [0.0; NC];
    let mut f_new = [0.0; NC];
    let mut slip_rate = [0.0; NC];
    let mut epp_pred = [EppPred::default(); NC];
    let mut qp_iter_total: u64 = 0;
    let mut qp_iter_max: u32 = 0;
    for step in 0..plan.steps {
        let ag1 = ground.next_accel();
        let p1 = if forced {
            plan.force((step + 1) as f64 * dt)
        } else {
            0.0
        };
        let mut ut = [0.0; N];
        let mut vt = [0.0; N];
        for i in 0..N {
            ut[i] = u[i] + dt * v[i] + c_u * a[i];
            vt[i] = v[i] + c_v * a[i];
        }
        let (zu, zv) = if alpha == 0.0 {
            (ut, vt)
        } else {
            let mut zu = [0.0; N];
            let mut zv = [0.0; N];
            for i in 0..N {
                zu[i] = (1.0 + alpha) * ut[i] - alpha * u[i];
                zv[i] = (1.0 + alpha) * vt[i] - alpha * v[i];
            }
            (zu, zv)
        };
        let load = -((1.0 + alpha) * ag1 - alpha * ag0);
        let cp = (1.0 + alpha) * p1 - alpha * p0;
        let ch = alpha / (1.0 + alpha);
        // The accelerations without friction: a_free = h·load + Q z (+ force, + HHT's
        // friction memory).
        let (qzu, qzv) = (mul(&o.qu, &zu), mul(&o.qv, &zv));
        let mut af = [0.0; N];
        for i in 0..N {
            af[i] = load * o.h[i] + (qzu[i] + qzv[i]);
        }
        if forced {
            for i in 0..N {
                af[i] += cp * o.hp[i];
            }
        }
        if hhht {
            for j in 0..NC {
                for i in 0..N {
                    af[i] += ch * f_old[j] * o.g[j][i];
                }
            }
        }
        if let Some(qp) = qp.as_mut() {
            for c in 0..NC {
                (wfree[c], epp_pred[c]) = link[c].free_slip_rate(&k, epp[c], (&u, &ut, &vt), &af);
            }
            let iterations = match pq.solve(&wfree, &mut f_new, &mut slip_rate) {
                Some(it) => it,
                None => {
                    let stats = qp.solve(&wfree, &lo, &hi, &mut f_new).map_err(|source| {
                        SimError::Friction {
                            t: (step + 1) as f64 * dt,
                            source,
                        }
                    })?;
                    pq.adopt(|c| qp.status(c), &wfree, &f_new, &mut slip_rate);
                    stats.iterations + 1
                }
            };
            qp_iter_total += u64::from(iterations);
            qp_iter_max = qp_iter_max.max(iterations);
            let gf = mul(&o.g, &f_new);
            for i in 0..N {
                af[i] -= gf[i];
            }
        }
        if energies.is_some() {
            v_old = v;
        }
        let mut finite = 0.0;
        for i in 0..N {
            let ai = af[i];
            a[i] = ai;
            u[i] = ut[i] + bdt2 * ai;
            v[i] = vt[i] + gdt * ai;
            finite += u[i];
        }
        if !finite.is_finite() {
            return Err(non_finite(step + 1, dt));
        }
        for c in 0..NC {
            slip_rate[c] = link[c].finish_step(
                &k,
                (epp_pred[c], slip_rate[c]),
                (&u, &v),
                pq.status(c) == Bound::Free,
                &mut epp[c],
                &mut stuck[c],
                &mut peaks,
            );
        }
        peaks.observe_floors(&u, &a, ag1);
        peaks.observe_base_shear(base_shear(&o.mr, msum, &a, ag1, p1));
        if let Some(e) = &energies {
            let data = StepEnergyData {
                second: None,
                dt,
                mr: &o.mr,
                ag: (ag0, ag1),
                p: (p0, p1),
                force_floor,
                v: (&v_old, &v),
                f: (&f_old, &f_new),
                w: (&w_old, &slip_rate),
                epp_mean_rate: true,
            };
            let q = e.forms(plan, (&v_old, &v), &u, &epp);
            acc.step(plan, &data, q, &epp);
            w_old = slip_rate;
        }
        f_old = f_new;
        ag0 = ag1;
        p0 = p1;
        if peaks.collapsed((step + 1) as f64 * dt) {
            break;
        }
    }
    let energy = energies.is_some().then(|| acc.finish(plan, &u, &v, &epp));
    Ok(outcome(
        plan,
        peaks,
        &acc,
        energy,
        (qp_iter_total, qp_iter_max),
        None,
    ))
}

/// Σⱼ cols[j]·x[j], summed as two interleaved halves (even and odd j) that meet at the
/// end, so that the chain of additions each output waits on is half as long (the
/// products of the displacement and the velocity predictors also run as two independent
/// sums).
#[inline(always)]
fn mul<const R: usize, const C: usize>(cols: &[[f64; R]; C], x: &[f64; C]) -> [f64; R] {
    let mut even = [0.0; R];
    let mut odd = [0.0; R];
    let mut j = 0;
    while j + 1 < C {
        let (x0, x1) = (x[j], x[j + 1]);
        for i in 0..R {
            even[i] += cols[j][i] * x0;
            odd[i] += cols[j + 1][i] * x1;
        }
        j += 2;
    }
    if j < C {
        let x0 = x[j];
        for i in 0..R {
            even[i] += cols[j][i] * x0;
        }
    }
    for i in 0..R {
        even[i] += odd[i];
    }
    even
}

/// Σᵢ a[i]·b[i], in order.
#[inline(always)]
fn dot<const R: usize>(a: &[f64; R], b: &[f64; R]) -> f64 {
    let mut s = 0.0;
    for i in 0..R {
        s += a[i] * b[i];
    }
    s
}
