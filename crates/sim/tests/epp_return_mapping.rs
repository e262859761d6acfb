//! `newmark` on massless dissipators without a brace dashpot is Newmark's average
//! acceleration with the elastic–perfectly plastic element's return mapping (docs/MODEL.md
//! § Integrators): the friction law is imposed on the slip of each step, not on the slip
//! rate at its end. Checked against an independent implementation of that scheme written
//! here the way a general-purpose finite-element code does it — Newton iterations on the
//! displacements, the element force from an elastic predictor clipped to its slip load
//! (the scheme of OpenSees's Newmark + EPP material, scripts/compare-opensees-precision.py)
//! — on the plan's own matrices and ground steps.
//!
//! Both solve the same piecewise-linear equations of each step, one exactly (a box QP),
//! the other by Newton to a displacement increment of 1e-14 of the response: the peaks
//! agree to round-off accumulated over the steps (tolerance 1e-9 relative, as the
//! reduced-plan equivalences).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use nalgebra::DVector;
use slipload_sim::plan::ContactKind;
use slipload_sim::{Plan, SceneOverrides, run_plan};

/// Peak |drift| per storey of Newmark (β = ¼, γ = ½) + EPP return mapping, by Newton.
fn newton_return_mapping(plan: &Plan) -> (Vec<f64>, usize) {
    let n = plan.dofs();
    assert_eq!(n, plan.floors, "a plan whose dissipators are all condensed");
    let dt = plan.method.dt;
    let (beta, gamma) = (0.25, 0.5);
    let (m, c, k) = (&plan.mass, &plan.damping, &plan.stiffness);
    let mr = plan.mass_influence();
    let contacts = &plan.contacts;
    for ct in contacts {
        assert_eq!(ct.kind, ContactKind::Epp);
        assert_eq!(ct.brace_damping, 0.0);
    }
    let drift_of =
        |u: &DVector<f64>, f: usize, below: Option<usize>| u[f] - below.map_or(0.0, |j| u[j]);
    let mut u = DVector::zeros(n);
    let mut v = DVector::zeros(n);
    let ag0 = plan.ground_accel(0.0);
    // at rest: M a0 = −M r ag0
    let mut a = -&mr * ag0;
    a = m.clone().cholesky().unwrap().solve(&a);
    let mut plastic = vec![0.0; contacts.len()];
    let mut peaks = vec![0.0f64; n];
    let mut ground = plan.ground_steps();
    let mut newton_max = 0;
    let k_dyn = m / (beta * dt * dt) + c * (gamma / (beta * dt)) + k;
    for _ in 0..plan.steps {
        let ag1 = ground.next_accel();
        let ut = &u + &v * dt + &a * ((0.5 - beta) * dt * dt);
        let vt = &v + &a * ((1.0 - gamma) * dt);
        let mut x = ut.clone();
        let scale = u.amax().max(1e-6);
        let mut done = false;
        for it in 0..100 {
            let acc = (&x - &ut) / (beta * dt * dt);
            let vel = &vt + &acc * (gamma * dt);
            let mut r = m * &acc + c * &vel + k * &x + &mr * ag1;
            let mut tangent = k_dyn.clone();
            for (e, ct) in contacts.iter().enumerate() {
                let trial = ct.brace_stiffness * (drift_of(&x, ct.floor, ct.below()) - plastic[e]);
                let (force, kt) = if trial > ct.upper {
                    (ct.upper, 0.0)
                } else if trial < ct.lower {
                    (ct.lower, 0.0)
                } else {
                    (trial, ct.brace_stiffness)
                };
                r[ct.floor] += force;
                tangent[(ct.floor, ct.floor)] += kt;
                if let Some(j) = ct.below() {
                    r[j] -= force;
                    tangent[(j, j)] += kt;
                    tangent[(ct.floor, j)] -= kt;
                    tangent[(j, ct.floor)] -= kt;
                }
            }
            let dx = tangent.lu().solve(&(-r)).unwrap();
            x += &dx;
            if dx.amax() <= 1e-14 * scale {
                newton_max = newton_max.max(it + 1);
                done = true;
                break;
            }
        }
        assert!(done, "Newton did not converge");
        let acc = (&x - &ut) / (beta * dt * dt);
        v = &vt + &acc * (gamma * dt);
        a = acc;
        u = x;
        for (e, ct) in contacts.iter().enumerate() {
            let d = drift_of(&u, ct.floor, ct.below());
            let trial = ct.brace_stiffness * (d - plastic[e]);
            let force = trial.clamp(ct.lower, ct.upper);
            plastic[e] = d - force / ct.brace_stiffness;
        }
        let mut below = 0.0;
        for i in 0..n {
            peaks[i] = peaks[i].max((u[i] - below).abs());
            below = u[i];
        }
    }
    (peaks, newton_max)
}

fn check(building: &str, record: &str, pga_g: f64, duration: f64) {
    let json = format!(
        r#"{{ "building": "{building}", "excitation": {{ "record": {{ "file": "../records/{record}", "scale_pga_g": {pga_g} }} }},
             "duration": {duration}, "outputs": {{ "energies": false }} }}"#
    );
    let scene = scene_json(&json, &SceneOverrides::default());
    let plan = Plan::compile(&scene).unwrap();
    let out = run_plan(&plan).unwrap().response;
    assert!(
        out.transitions.iter().sum::<u64>() > 20,
        "the dampers must stick and slip for the check to bite"
    );
    let (reference, newton) = newton_return_mapping(&plan);
    assert!(newton >= 2, "Newton must have iterated on the slips");
    for (s, (a, b)) in out.peak_drift.iter().zip(&reference).enumerate() {
        assert!(
            (a - b).abs() <= 1e-9 * b,
            "{building} under {record}: storey {}: newmark {a} vs Newton + return mapping {b}",
            s + 1
        );
    }
}

#[test]
fn massless_benchmark_equals_newton_with_the_return_mapping() {
    check("benchmark-3story-massless.json", "SYL090.AT2", 0.6, 10.0);
}

#[test]
fn ten_storey_equals_newton_with_the_return_mapping() {
    // ten-story.json: massless dissipators, condensed (reduce, the default)
    check("ten-story.json", "I-ELC180.AT2", 0.5, 8.0);
}
