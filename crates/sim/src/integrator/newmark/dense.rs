//! The run on the dense operators: the fixed-size loop (`fixed.rs`) for the DOF and
//! contact counts it is compiled for when no histories are asked, else the general step
//! loop here, compiled once per small DOF count (1–8, 10, 12, 20) with the count a
//! constant and once for any other count.

use super::fixed;
use super::link::{EppPred, links};
use super::operators::{Operators, StepConstants};
use super::outcome::{non_finite, outcome};
use super::tangent::Tangent;
use crate::error::SimError;
use crate::friction::BoxQp;
use crate::friction::box_qp::Bound;
use crate::integrator::state::{
    self, EnergyAccumulator, StepEnergyData, StepForms, history_columns, initial_state, record_row,
    slip, slip_rate,
};
use crate::plan::Plan;
use crate::response::{Outcome, Peaks};

/// Dispatches a run without histories to the fixed-size loop of its DOF and contact counts, for
/// the counts listed (up to eight DOFs with up to four dampers; up to twelve storeys with
/// a massless damper on every floor; ten storeys with dissipator DOFs); `None` for any
/// other, which the general loop runs.
macro_rules! fixed_dispatch {
    ($plan:expr, $ops:expr, $links:expr; $(($n:literal, $nc:literal)),* $(,)?) => {
        match ($ops.n, $plan.contacts.len()) {
            $(($n, $nc) => Some(if $plan.outputs.energies {
                fixed::run::<$n, $nc, true>($plan, $ops, $links)
            } else {
                fixed::run::<$n, $nc, false>($plan, $ops, $links)
            }),)*
            _ => None,
        }
    };
}

/// The run on the dense operators: the fixed-size loop of its sizes, or the general loop.
pub(super) fn run_dense(plan: &Plan) -> Result<Outcome, SimError> {
    let ops = Operators::build(plan)?;
    // (the fixed-size loop carries no tangent: `applies` is false with sensitivities)
    if fixed::applies(plan) {
        let links = links(plan, &ops);
        let run = fixed_dispatch!(plan, &ops, &links;
            (1, 0), (1, 1),
            (2, 0), (2, 1), (2, 2),
            (3, 0), (3, 1), (3, 2), (3, 3),
            (4, 0), (4, 1), (4, 2), (4, 3), (4, 4),
            (5, 0), (5, 1), (5, 2), (5, 3), (5, 4),
            (6, 0), (6, 1), (6, 2), (6, 3), (6, 4),
            (7, 0), (7, 1), (7, 2), (7, 3), (7, 4),
            (8, 0), (8, 1), (8, 2), (8, 3), (8, 4),
            (5, 5), (6, 6), (7, 7), (8, 8), (10, 10), (12, 12), (20, 10),
        );
        if let Some(outcome) = run {
            return outcome;
        }
    }
    match ops.n {
        1 => run_loop::<1>(plan, &ops),
        2 => run_loop::<2>(plan, &ops),
        3 => run_loop::<3>(plan, &ops),
        4 => run_loop::<4>(plan, &ops),
        5 => run_loop::<5>(plan, &ops),
        6 => run_loop::<6>(plan, &ops),
        7 => run_loop::<7>(plan, &ops),
        8 => run_loop::<8>(plan, &ops),
        10 => run_loop::<10>(plan, &ops),
        12 => run_loop::<12>(plan, &ops),
        20 => run_loop::<20>(plan, &ops),
        _ => run_loop::<0>(plan, &ops),
    }
}

/// The step loop for `N` DOFs (`N = 0`: any count, read from the operators).
fn run_loop<const N: usize>(plan: &Plan, ops: &Operators) -> Result<Outcome, SimError> {
    let n = if N > 0 { N } else { ops.n };
    debug_assert_eq!(n, ops.n);
    let dt = plan.method.dt;
    let nc = plan.contacts.len();
    let (alpha, beta, gamma) = (ops.alpha, ops.beta, ops.gamma);
    let k = StepConstants::new(dt, beta, gamma);
    let (c_u, c_v, gdt, bdt2) = (k.c_u, k.c_v, k.gdt, k.bdt2);
    let msum: f64 = plan.influence_mass();
    let lo: Vec<f64> = plan.contacts.iter().map(|c| c.lower).collect();
    let hi: Vec<f64> = plan.contacts.iter().map(|c| c.upper).collect();
    let links = links(plan, ops);
    // Flat operators: Q column-major n×2n, G column-major n×nc, W symmetric nc×nc.
    let qm = &ops.q.as_slice()[..2 * n * n];
    let h = &ops.h.as_slice()[..n];
    let g = &ops.g.as_slice()[..n * nc];
    let w = ops.w.as_slice();
    let mr = &ops.mr.as_slice()[..n];
    // a second ground component: M r₂, A⁻¹ M r₂ and r₁ᵀ M r₂ (the base shear along the
    // first component's direction per unit of the second)
    let second = ops
        .second
        .as_ref()
        .map(|(m2, h2)| (m2.as_slice(), h2.as_slice()));
    let cross = plan.cross_mass();
    let hhht = alpha != 0.0 && nc > 0;

    let start = initial_state(plan)?;
    // State (u, v, a), 3n.
    let mut s = vec![0.0; 3 * n];
    s[..n].copy_from_slice(&start.u);
    s[n..2 * n].copy_from_slice(&start.v);
    s[2 * n..].copy_from_slice(&start.a);
    let mut f_old = start.f.clone();
    let mut f_new = vec![0.0; nc];
    let mut epp = start.epp;
    let mut stuck = start.stuck;
    let mut qp = if nc > 0 {
        Some(BoxQp::new(w, nc).map_err(|source| SimError::Friction { t: 0.0, source })?)
    } else {
        None
    };
    let mut af = vec![0.0; n];
    let mut ut = vec![0.0; n];
    let mut vt = vec![0.0; n];
    let mut z = vec![0.0; 2 * n];
    let mut wfree = vec![0.0; nc];
    let mut w_old: Vec<f64> = (0..nc)
        .map(|c| slip_rate(plan, c, &start.v, &epp))
        .collect();
    let mut w_new = vec![0.0; nc];
    let mut v_old = vec![0.0; n];
    let mut epp_pred = vec![EppPred::default(); nc];

    let energies = plan.outputs.energies;
    let mut acc = EnergyAccumulator::start(plan, &start.u, &start.v, &epp);

    let mut peaks = Peaks::for_plan(plan);
    debug_assert_eq!(peaks.drift.len(), plan.drifts.len());
    let mut ag0 = plan.ground_accel(0.0);
    let mut ground = plan.ground_steps();
    let mut ag2_0 = plan.ground2_accel(0.0);
    let mut ground2 = plan.ground2_steps();
    let mut p0 = plan.force(0.0);
    peaks.observe_floors2(&start.u, &start.a, ag0, ag2_0);
    let hf = ops.hp.as_ref().map(|(f, _)| *f);
    let base_shear = |a: &[f64], ag: f64, p: f64, ag2: f64| {
        if second.is_some() {
            // signed along the first component, then its size
            let v = state::signed_base_shear(mr, msum, a, ag, p) + cross * ag2;
            v.abs()
        } else {
            state::base_shear(mr, msum, a, ag, p)
        }
    };
    peaks.observe_base_shear(base_shear(&start.a, ag0, p0, ag2_0));
    for c in 0..nc {
        peaks.observe_slip(plan.contacts[c].slot, slip(plan, c, &start.u, &epp));
    }
    state::observe_dampers(plan, &mut peaks, 0.0, &start.u, &f_old, &w_old, &epp);

    let mut history = plan
        .outputs
        .histories
        .then(|| history_columns(plan, energies));
    if let Some(hist) = history.as_mut() {
        let e = energies.then(|| acc.initial_row());
        record_row(plan, hist, 0.0, ag0, &start.u, &f_old, &w_old, &epp, e);
    }

    let mut tangent = plan
        .outputs
        .sensitivities
        .then(|| Tangent::new(plan, ops, &links));

    let mut qp_iter_total: u64 = 0;
    let mut qp_iter_max: u32 = 0;
    for step in 0..plan.steps {
        let t1 = (step + 1) as f64 * dt;
        let ag1 = ground.next_accel();
        let ag2_1 = ground2.next_accel();
        let p1 = if hf.is_some() { plan.force(t1) } else { 0.0 };
        // Predictors ũ, ṽ; then the linear part a_free = Q z + loads (+ HHT friction memory)
        // with z = (1+α)(ũ, ṽ) − α(u, v).
        for i in 0..n {
            let (u, v, a) = (s[i], s[n + i], s[2 * n + i]);
            ut[i] = u + dt * v + c_u * a;
            vt[i] = v + c_v * a;
        }
        let zs: &[f64] = if alpha == 0.0 {
            z[..n].copy_from_slice(&ut);
            z[n..].copy_from_slice(&vt);
            &z
        } else {
            for i in 0..n {
                z[i] = (1.0 + alpha) * ut[i] - alpha * s[i];
                z[n + i] = (1.0 + alpha) * vt[i] - alpha * s[n + i];
            }
            &z
        };
        let load = -((1.0 + alpha) * ag1 - alpha * ag0);
        for i in 0..n {
            af[i] = load * h[i];
        }
        if let Some((_, h2)) = second {
            let load2 = -((1.0 + alpha) * ag2_1 - alpha * ag2_0);
            for i in 0..n {
                af[i] += load2 * h2[i];
            }
        }
        for (j, &zj) in zs.iter().enumerate() {
            let col = &qm[j * n..(j + 1) * n];
            for i in 0..n {
                af[i] += col[i] * zj;
            }
        }
        if let Some((_, hp)) = &ops.hp {
            let c = (1.0 + alpha) * p1 - alpha * p0;
            for i in 0..n {
                af[i] += c * hp[i];
            }
        }
        if hhht {
            let c = alpha / (1.0 + alpha);
            for (j, &fj) in f_old.iter().enumerate() {
                let col = &g[j * n..(j + 1) * n];
                for i in 0..n {
                    af[i] += c * fj * col[i];
                }
            }
        }
        if let Some(qp) = qp.as_mut() {
            for (c, l) in links.iter().enumerate() {
                (wfree[c], epp_pred[c]) = l.free_slip_rate(&k, epp[c], (&s[..n], &ut, &vt), &af);
            }
            let stats = qp
                .solve(&wfree, &lo, &hi, &mut f_new)
                .map_err(|source| SimError::Friction { t: t1, source })?;
            qp_iter_total += u64::from(stats.iterations);
            qp_iter_max = qp_iter_max.max(stats.iterations);
            for (j, &fj) in f_new.iter().enumerate() {
                if fj != 0.0 {
                    let col = &g[j * n..(j + 1) * n];
                    for i in 0..n {
                        af[i] -= fj * col[i];
                    }
                }
            }
        }
        if energies {
            v_old.copy_from_slice(&s[n..2 * n]);
        }
        let mut finite = 0.0;
        for i in 0..n {
            let a = af[i];
            s[2 * n + i] = a;
            s[i] = ut[i] + bdt2 * a;
            s[n + i] = vt[i] + gdt * a;
            finite += s[i];
        }
        if !finite.is_finite() {
            return Err(non_finite(step + 1, dt));
        }
        let (u_now, rest) = s.split_at(n);
        let (v_now, a_now) = rest.split_at(n);
        if let Some(qp) = qp.as_ref() {
            for (c, l) in links.iter().enumerate() {
                let wc = &w[c * nc..(c + 1) * nc];
                let mut wf = 0.0;
                for (wcj, fj) in wc.iter().zip(&f_new) {
                    wf += wcj * fj;
                }
                w_new[c] = l.finish_step(
                    &k,
                    (epp_pred[c], wfree[c] - wf),
                    (u_now, v_now),
                    qp.status(c) == Bound::Free,
                    &mut epp[c],
                    &mut stuck[c],
                    &mut peaks,
                );
            }
        }
        if let Some(tg) = tangent.as_mut() {
            if let Some(qp) = qp.as_ref() {
                tg.step(ops, &links, &k, |c| qp.status(c), &w_new);
            }
            let mut shear = msum * ag1 - p1;
            for (m, a) in mr.iter().zip(a_now) {
                shear += m * a;
            }
            tg.observe(&peaks, (u_now, a_now, ag1), shear, mr);
        }
        state::observe_dampers(plan, &mut peaks, t1, u_now, &f_new, &w_new, &epp);
        peaks.observe_floors2(u_now, a_now, ag1, ag2_1);
        peaks.observe_base_shear(base_shear(a_now, ag1, p1, ag2_1));
        let mut e_row = None;
        if energies {
            let data = StepEnergyData {
                dt,
                mr,
                ag: (ag0, ag1),
                second: second.map(|(m2, _)| (m2, (ag2_0, ag2_1))),
                p: (p0, p1),
                force_floor: hf,
                v: (&v_old, v_now),
                f: (&f_old, &f_new),
                w: (&w_old, &w_new),
                epp_mean_rate: true,
            };
            let q = StepForms::of_plan(plan, (&v_old, v_now), u_now, &epp);
            e_row = Some(acc.step(plan, &data, q, &epp));
        }
        if let Some(hist) = history.as_mut() {
            record_row(plan, hist, t1, ag1, u_now, &f_new, &w_new, &epp, e_row);
        }
        std::mem::swap(&mut f_old, &mut f_new);
        std::mem::swap(&mut w_old, &mut w_new);
        ag0 = ag1;
        ag2_0 = ag2_1;
        p0 = p1;
        if peaks.collapsed(t1) {
            break;
        }
    }
    let (u_end, rest) = s.split_at(n);
    let v_end = &rest[..n];
    let energy = energies.then(|| acc.finish(plan, u_end, v_end, &epp));
    let mut out = outcome(
        plan,
        peaks,
        &acc,
        energy,
        (qp_iter_total, qp_iter_max),
        history,
    );
    out.response.sensitivity = tangent.map(|tg| tg.finish(u_end));
    Ok(out)
}
