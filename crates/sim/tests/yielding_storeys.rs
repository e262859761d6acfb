//! Yielding storeys (bilinear shear–drift law, kinematic hardening) and P-Δ.
//!
//! A storey's law k, Fy, α is an elastic spring αk in parallel with an elastic–perfectly
//! plastic spring (1−α)k yielding at (1−α)Fy: the plan carries the second as a contact
//! between floors i−1 and i, like a massless dissipator, so `exact` stays exact.
//!
//! Closed forms (single storey, mass m, ω² = k/m, u_y = Fy/k, no damping), from rest at
//! u = 0 with velocity v₀ > ω u_y:
//! - elastic until u_y, reached with v₁² = v₀² − ω²u_y²;
//! - α = 0: plastic flow against the constant force Fy, stopping at
//!   u_max = u_y + m v₁²/(2 Fy); plastic drift u_max − u_y; plastic work Fy (u_max − u_y);
//! - α > 0: the force on loading is αk u + (1−α)Fy, so ½ m v₁² = αk(u_max² − u_y²)/2 +
//!   (1−α)Fy (u_max − u_y), a quadratic in u_max;
//! - unloading is elastic with amplitude (1−α)… below yield: no further yielding without
//!   load, so the peaks are those of the first excursion.
//!
//! Tolerances: `exact` locates the yield instant by root finding to ~1e-14 s and is exact
//! between events, so its peaks and works agree with the closed forms to round-off (1e-10
//! relative leaves a wide margin over the ~1e-15 measured). `newmark` is second order:
//! its error falls by about 4 when the step halves, but the step in which the storey
//! yields adds a local error whose size depends on where in the step the yield falls,
//! which changes with the step, so single halvings scatter (measured 1.8–4.5×). The checks
//! ask for a fall at every halving and a least-squares order of at least 1.5 over four
//! halvings, which a first-order error (order 1) could not give.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_sim::{Outcome, Plan, SceneOverrides, simulate};

fn run(text: &str, method: &str) -> Outcome {
    let over = SceneOverrides {
        method: Some(method.parse().unwrap()),
        ..Default::default()
    };
    simulate(&scene_json(text, &over)).unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

/// One storey, m = 1e5 kg, k = 4e7 N/m (ω = 20 rad/s), Fy = 200 kN (u_y = 5 mm), thrown
/// from rest at u = 0 with velocity `v0`.
fn sdof(alpha: f64, v0: f64, extra: &str, dt: f64) -> String {
    format!(
        r#"{{ "building": {{ "floor_masses": [1.0e5], "storey_stiffness": [4.0e7] {extra},
              "storey_yield": [ {{ "storey": 1, "yield_shear": "200 kN", "post_yield_ratio": {alpha} }} ] }},
             "excitation": {{ "initial": {{ "floor_velocity": [{v0}] }} }},
             "duration": 1.0, "method": {{ "name": "exact", "dt": {dt} }},
             "outputs": {{ "energies": true }} }}"#
    )
}

/// u_max of the closed form above.
fn closed_form_peak(alpha: f64, v0: f64) -> f64 {
    let (m, k, fy) = (1.0e5, 4.0e7, 2.0e5);
    let uy = fy / k;
    let v1sq = v0 * v0 - k / m * uy * uy;
    let energy = 0.5 * m * v1sq;
    if alpha == 0.0 {
        return uy + energy / fy;
    }
    // αk/2 (u² − u_y²) + (1−α)Fy (u − u_y) = E, the positive root.
    let (a, b) = (alpha * k / 2.0, (1.0 - alpha) * fy);
    let c = -(energy + a * uy * uy + b * uy);
    (-b + (b * b - 4.0 * a * c).sqrt()) / (2.0 * a)
}

#[test]
fn elastic_perfectly_plastic_storey_matches_the_closed_form() {
    let (alpha, v0) = (0.0, 0.5);
    let umax = closed_form_peak(alpha, v0);
    let uy = 5e-3;
    let out = run(&sdof(alpha, v0, "", 1e-3), "exact");
    let r = &out.response;
    let e = r.energy.unwrap();
    assert!(
        rel(r.peak_drift[0], umax) < 1e-10,
        "{} vs {umax}",
        r.peak_drift[0]
    );
    let plastic = r.peak_plastic_drift.as_ref().unwrap()[0];
    assert!(rel(plastic, umax - uy) < 1e-10, "{plastic}");
    assert!(rel(e.plastic.unwrap(), 2e5 * (umax - uy)) < 1e-10, "{e:?}");
    let mu = r.peak_ductility.as_ref().unwrap()[0].unwrap();
    assert!(rel(mu, umax / uy) < 1e-10, "{mu}");
    // Nothing else dissipates; the balance closes to round-off.
    assert_eq!(e.friction, 0.0);
    assert!(e.balance_error.abs() < 1e-10 * 0.5 * 1e5 * v0 * v0, "{e:?}");
    assert_eq!(
        r.transitions,
        vec![0],
        "a storey's yielding is no damper transition"
    );
    assert_eq!(r.peak_slip, vec![0.0]);
}

#[test]
fn hardening_storey_matches_the_closed_form_and_newmark_converges_to_it() {
    let (alpha, v0) = (0.1, 0.5);
    let umax = closed_form_peak(alpha, v0);
    let exact = run(&sdof(alpha, v0, "", 1e-3), "exact");
    assert!(
        rel(exact.response.peak_drift[0], umax) < 1e-10,
        "{} vs {umax}",
        exact.response.peak_drift[0]
    );
    // Sampled peaks: a step of T/4000 keeps the sampling error (~(ωΔt)²/8) below the
    // integration error being measured.
    let dts = [4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5];
    let mut errs = Vec::new();
    for dt in dts {
        let nm = run(&sdof(alpha, v0, "", dt), "newmark");
        errs.push(rel(nm.response.peak_drift[0], umax));
    }
    assert!(errs[2] < 1e-3, "newmark at T/3000: {errs:?}");
    assert!(
        errs.windows(2).all(|w| w[0] > w[1]),
        "the error falls at every halving: {errs:?}"
    );
    // least-squares slope of log(error) against log(Δt)
    let xs: Vec<f64> = dts.iter().map(|d: &f64| d.ln()).collect();
    let ys: Vec<f64> = errs.iter().map(|e| e.ln()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / 5.0, ys.iter().sum::<f64>() / 5.0);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    let order = sxy / sxx;
    assert!(
        order >= 1.5,
        "second-order convergence: order {order}, errors {errs:?}"
    );
}

#[test]
fn a_storey_displaced_beyond_yield_settles_at_its_plastic_offset() {
    // At rest at u₀ = 3 u_y: it starts yielded (plastic drift 2 u_y), then oscillates
    // elastically about 2 u_y with amplitude u_y, decaying with 5 % damping: the residual
    // drift is 2 u_y within u_y·e^{−ζωt}/√(1−ζ²).
    let (uy, zeta, omega, t): (f64, f64, f64, f64) = (5e-3, 0.05, 20.0, 12.0);
    let c = 2.0 * zeta * omega * 1.0e5;
    let text = format!(
        r#"{{ "building": {{ "floor_masses": [1.0e5], "storey_stiffness": [4.0e7],
              "damping": {{ "storey": [{c}] }},
              "storey_yield": [ {{ "storey": 1, "yield_drift": "{uy} m" }} ] }},
             "excitation": {{ "initial": {{ "floor_displacement": [{}] }} }},
             "duration": {t}, "method": {{ "name": "exact", "dt": 0.002 }} }}"#,
        3.0 * uy
    );
    let plan = Plan::compile(&scene_json(&text, &SceneOverrides::default())).unwrap();
    assert!(
        plan.explain().contains("starts yielded"),
        "{}",
        plan.explain()
    );
    let bound = uy * (-zeta * omega * t).exp() / (1.0 - zeta * zeta).sqrt();
    for method in ["exact", "newmark"] {
        let r = run(&text, method).response;
        let residual = r.residual_drift[0];
        assert!(
            (residual - 2.0 * uy).abs() <= bound * 1.01,
            "{method}: residual {residual}, expected {} ± {bound}",
            2.0 * uy
        );
        assert!(rel(r.peak_drift[0], 3.0 * uy) < 1e-12, "{method}: {:?}", r);
        assert!(rel(r.peak_plastic_drift.as_ref().unwrap()[0], 2.0 * uy) < 1e-12);
    }
}

#[test]
fn yielding_at_the_first_step_is_located_inside_it() {
    // v₀ = 1 m/s reaches u_y = 5 mm after ~5 ms, inside the first 10 ms step; it stops
    // at u_max ≈ 0.25 m after ~0.5 s.
    let (alpha, v0) = (0.0, 1.0);
    let umax = closed_form_peak(alpha, v0);
    let out = run(&sdof(alpha, v0, "", 1e-2), "exact");
    assert!(rel(out.response.peak_drift[0], umax) < 1e-10);
    let nm = run(&sdof(alpha, v0, "", 2e-4), "newmark");
    assert!(
        rel(nm.response.peak_drift[0], umax) < 1e-3,
        "{:?}",
        nm.response
    );
}

#[test]
fn a_storey_yielding_as_its_damper_slips_in_the_same_instant() {
    // Storey (k, Fy) and a massless damper (k′, F_d) with F_d/k′ = Fy/k = u*: both reach
    // their bounds at the same drift. Elastic with ω² = (k + k′)/m up to u*, then both
    // slide against Fy + F_d: u_max = u* + ½ m v₁² / (Fy + F_d); the plastic and friction
    // works are Fy and F_d times (u_max − u*).
    let (m, k, kd, fy) = (1.0e5, 4.0e7, 2.0e7, 2.0e5);
    let us = fy / k;
    let fd = kd * us;
    let v0: f64 = 0.5;
    let v1sq = v0 * v0 - (k + kd) / m * us * us;
    let umax = us + 0.5 * m * v1sq / (fy + fd);
    let text = format!(
        r#"{{ "building": {{ "floor_masses": [{m}], "storey_stiffness": [{k}],
              "dissipators": [ {{ "floor": 1, "brace_stiffness": {kd}, "mass": 0, "slip_load": {fd} }} ],
              "storey_yield": [ {{ "storey": 1, "yield_shear": {fy} }} ] }},
             "excitation": {{ "initial": {{ "floor_velocity": [{v0}] }} }},
             "duration": 1.0, "method": {{ "name": "exact", "dt": 0.001 }},
             "outputs": {{ "energies": true }} }}"#
    );
    let out = run(&text, "exact");
    let r = &out.response;
    let e = r.energy.unwrap();
    assert!(
        rel(r.peak_drift[0], umax) < 1e-10,
        "{} vs {umax}",
        r.peak_drift[0]
    );
    assert!(rel(e.plastic.unwrap(), fy * (umax - us)) < 1e-10, "{e:?}");
    assert!(rel(e.friction, fd * (umax - us)) < 1e-10, "{e:?}");
    assert!(rel(e.friction_share().unwrap(), fd / (fd + fy)) < 1e-10);
    assert_eq!(
        r.transitions,
        vec![2],
        "the damper slips once and sticks again"
    );
    let nm = run(&text.replace("0.001", "0.0001"), "newmark");
    assert!(
        rel(nm.response.peak_drift[0], umax) < 1e-3,
        "{:?}",
        nm.response
    );
}

/// The benchmark-like three-storey shear frame with massless dampers, under 6 s of the
/// synthetic record; `extra` adds fields to the building.
fn frame(extra: &str, dt: f64) -> String {
    format!(
        r#"{{ "building": {{ "floor_masses": [2.0e5, 2.0e5, 1.5e5],
              "storey_stiffness": ["300 MN/m", "250 MN/m", "180 MN/m"],
              "storey_heights": [4.0, 3.5, 3.5],
              "damping": {{ "modal": {{ "ratio": 0.02 }} }},
              "dissipators": [
                {{ "floor": 1, "brace_stiffness": "200 MN/m", "mass": 0, "slip_load": "300 kN" }},
                {{ "floor": 2, "brace_stiffness": "200 MN/m", "mass": 0, "slip_load": "250 kN" }} ]
              {extra} }},
             "excitation": {{ "synthetic": {{ "seed": 11, "duration": 6, "dt": 0.01, "pga_g": 0.6 }} }},
             "method": {{ "name": "exact", "dt": {dt} }}, "outputs": {{ "energies": true }} }}"#
    )
}

const YIELDING: &str = r#", "storey_yield": [
    { "storey": 1, "yield_shear": "900 kN", "post_yield_ratio": 0.05 },
    { "storey": 2, "yield_drift": "3 mm", "post_yield_ratio": 0.02 },
    { "storey": 3, "yield_shear": "400 kN" } ],
  "p_delta": {}"#;

#[test]
fn an_unreachable_yield_shear_is_the_elastic_frame() {
    // Fy = 1e15 N is never reached: the storey is αk + (1−α)k, the same spring split in
    // two; peaks agree to round-off accumulated over the run (1e-9 relative), and no
    // plastic work is done.
    let huge = r#", "storey_yield": [
        { "storey": 1, "yield_shear": 1e15, "post_yield_ratio": 0.3 },
        { "storey": 3, "yield_shear": 1e15 } ]"#;
    for method in ["exact", "newmark"] {
        let elastic = run(&frame("", 0.005), method).response;
        let split = run(&frame(huge, 0.005), method).response;
        for (a, b) in split.peak_drift.iter().zip(&elastic.peak_drift) {
            assert!(rel(*a, *b) < 1e-9, "{method}: {a} vs {b}");
        }
        assert_eq!(split.transitions, elastic.transitions, "{method}");
        let e = split.energy.unwrap();
        assert!(
            e.plastic.unwrap().abs() <= 1e-9 * e.input.abs(),
            "{method}: {e:?}"
        );
        assert!(elastic.energy.unwrap().plastic.is_none());
        assert!(elastic.peak_ductility.is_none() && elastic.collapse.is_none());
    }
}

#[test]
fn a_frame_without_yield_laws_compiles_to_the_same_plan() {
    let over = SceneOverrides::default();
    let bare = Plan::compile(&scene_json(&frame("", 0.005), &over)).unwrap();
    let empty =
        Plan::compile(&scene_json(&frame(r#", "storey_yield": []"#, 0.005), &over)).unwrap();
    assert_eq!(bare.contacts, empty.contacts);
    assert_eq!(bare.stiffness, empty.stiffness);
    assert_eq!(bare.notes, empty.notes);
    assert!(!bare.explain().contains("yield") && !bare.explain().contains("P-Delta"));
    // One yielding storey: the dampers' contacts are unchanged and first; the storey adds
    // one contact and takes (1−α)k out of K.
    let one = r#", "storey_yield": [ { "storey": 2, "yield_shear": "600 kN", "post_yield_ratio": 0.1 } ]"#;
    let y = Plan::compile(&scene_json(&frame(one, 0.005), &over)).unwrap();
    assert_eq!(y.contacts[..bare.contacts.len()], bare.contacts[..]);
    assert_eq!(y.contacts.len(), bare.contacts.len() + 1);
    let dk = &bare.stiffness - &y.stiffness;
    let kp = 0.9 * 250e6;
    // Round-off of the difference of sums of ~1e9 N/m entries.
    // (Storey 2 joins floors 1 and 2, indices 0 and 1.)
    assert!(
        rel(dk[(0, 0)], kp) < 1e-12 && rel(dk[(1, 1)], kp) < 1e-12,
        "{dk}"
    );
    assert!(rel(-dk[(0, 1)], kp) < 1e-12 && dk[(2, 2)] == 0.0, "{dk}");
    assert!(y.explain().contains("storey 2: yields"), "{}", y.explain());
}

#[test]
fn newmark_converges_to_exact_on_a_yielding_p_delta_frame_and_both_balance() {
    let exact = run(&frame(YIELDING, 0.005), "exact");
    let er = &exact.response;
    let ee = er.energy.unwrap();
    let plastic = ee.plastic.unwrap();
    assert!(plastic > 0.05 * ee.input, "the scene must yield: {ee:?}");
    assert!(ee.friction > 0.05 * ee.input, "and slip: {ee:?}");
    // The balance closes to round-off for exact (1e-10 as in energy_balance.rs) and for
    // Newmark's average acceleration, whose step-averaged energies are an identity of the
    // method.
    assert!(exact.diagnostics.balance_error_max_relative < 1e-10);
    let mu = er.peak_ductility.as_ref().unwrap();
    assert!(mu.iter().all(|m| m.is_some()), "{mu:?}");
    assert!(mu.iter().flatten().any(|m| *m > 1.0), "{mu:?}");
    let mut errs = Vec::new();
    for dt in [0.002, 0.001, 0.0005] {
        let nm = run(&frame(YIELDING, dt), "newmark");
        assert!(nm.diagnostics.balance_error_max_relative < 1e-10);
        let ne = nm.response.energy.unwrap();
        let drift = nm
            .response
            .peak_drift
            .iter()
            .zip(&er.peak_drift)
            .map(|(a, b)| rel(*a, *b))
            .fold(0.0, f64::max);
        errs.push((drift, rel(ne.plastic.unwrap(), plastic)));
    }
    assert!(errs[2].0 < 5e-3 && errs[2].1 < 5e-3, "{errs:?}");
    assert!(
        errs[0].1 > 2.0 * errs[2].1,
        "plastic work converges as the step shrinks: {errs:?}"
    );
}

#[test]
fn p_delta_with_a_perfectly_plastic_storey_collapses_as_a_typed_outcome() {
    // Post-yield tangent −P/h = −0.05 k: pushed past 20 u_y = 0.1 m the storey runs away.
    // The run stops when the drift passes the default limit (10 % of h = 0.3 m), with the
    // storey and the instant, and no NaN. Without P-Δ the same push stops at
    // u_max = u_y + m v₁²/(2 Fy) ≈ 0.2 m, inside the limit.
    let text = r#"{ "building": { "floor_masses": [1.0e5], "storey_stiffness": [4.0e7],
          "storey_heights": [3.0],
          "storey_yield": [ { "storey": 1, "yield_shear": "200 kN" } ],
          "p_delta": { "gravity_loads": ["6 MN"] } },
         "excitation": { "initial": { "floor_velocity": [0.9] } },
         "duration": 5.0, "method": { "name": "exact", "dt": 0.001 },
         "outputs": { "energies": true } }"#;
    for method in ["exact", "newmark"] {
        let r = run(text, method).response;
        let c = r
            .collapse
            .unwrap_or_else(|| panic!("{method}: no collapse: {r:?}"));
        assert_eq!(c.storey, 1);
        assert!((c.limit - 0.3).abs() < 1e-12, "{c:?}");
        assert!(c.drift > c.limit && c.drift < 1.01 * c.limit, "{c:?}");
        assert!(c.time > 0.0 && c.time < 1.0, "{c:?}");
        // the steps run, to the one past the limit (dt = 1 ms)
        assert_eq!(r.steps, (c.time / 1e-3).round() as usize, "{r:?}");
        assert!(r.first_non_finite().is_none(), "{method}: {r:?}");
    }
    // Without P-Δ the same push stays bounded: no collapse.
    let bounded = text.replace(
        r#""p_delta": { "gravity_loads": ["6 MN"] }"#,
        r#""p_delta": null"#,
    );
    assert_ne!(bounded, text);
    let r = run(&bounded, "exact").response;
    assert!(r.collapse.is_none(), "{r:?}");
    assert!(rel(r.peak_drift[0], closed_form_peak(0.0, 0.9)) < 1e-10);
}

#[test]
fn delacruz_says_it_does_not_model_yielding_storeys() {
    let over = SceneOverrides {
        method: Some("delacruz".parse().unwrap()),
        ..Default::default()
    };
    let err = simulate(&scene_json(&sdof(0.0, 0.5, "", 1e-3), &over)).unwrap_err();
    assert!(
        err.to_string().contains("does not model yielding storeys"),
        "{err}"
    );
}

#[test]
fn bad_yield_laws_are_refused_by_field() {
    let over = SceneOverrides::default();
    for (extra, field, what) in [
        (
            r#", "storey_yield": [ { "storey": 4, "yield_shear": 1e5 } ]"#,
            "storey_yield[0].storey",
            "from 1 to 3",
        ),
        (
            r#", "storey_yield": [ { "storey": 1, "yield_shear": 1e5, "yield_drift": 0.01 } ]"#,
            "storey_yield[0].yield_drift",
            "not both",
        ),
        (
            r#", "storey_yield": [ { "storey": 1, "yield_shear": 1e5, "post_yield_ratio": 1.0 } ]"#,
            "storey_yield[0].post_yield_ratio",
            "[0, 1)",
        ),
        (
            r#", "storey_yield": [ { "storey": 1 } ]"#,
            "storey_yield[0].yield_shear",
            "missing",
        ),
        (
            r#", "collapse_drift_ratio": -1"#,
            "collapse_drift_ratio",
            "positive",
        ),
    ] {
        let text = frame(extra, 0.005);
        let err = slipload_sim::Scene::from_json(&text, &configs().join("inline.json"), &over)
            .unwrap_err()
            .to_string();
        assert!(err.contains(field) && err.contains(what), "{extra}: {err}");
    }
    // P-Δ needs storey heights; a matrix frame must say which spring yields.
    let no_heights =
        frame(r#", "p_delta": {}"#, 0.005).replace(r#""storey_heights": [4.0, 3.5, 3.5],"#, "");
    let err = slipload_sim::Scene::from_json(&no_heights, &configs().join("inline.json"), &over)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("p_delta") && err.contains("storey_heights"),
        "{err}"
    );
    let matrix = r#"{ "building": { "floor_masses": [1e5, 1e5],
          "stiffness_matrix": [["8e7", "-4e7"], ["-4e7", "4e7"]],
          "storey_yield": [ { "storey": 2, "yield_shear": 1e5 } ] },
         "duration": 1 }"#;
    let err = slipload_sim::Scene::from_json(matrix, &configs().join("inline.json"), &over)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("storey_yield[0].stiffness") && err.contains("stiffness_matrix"),
        "{err}"
    );
}

#[test]
fn a_slow_push_past_yield_and_back_follows_the_static_law() {
    // F(t) = F_max sin(ω_f t) over half a cycle, ω_f = ω/100, 5 % damping: quasi-static
    // to (ω_f/ω)² (inertia) and 2ζω_f/ω (damping force) ≈ 1e-3 of the response. The
    // static law with hardening: u_max = u_y + (F_max − Fy)/(αk); unloading is elastic
    // (the elastic range 2(1−α)Fy exceeds F_max here), so at F = 0 the residual drift is
    // u_max − F_max/k, and the plastic element has slipped u_max − u_y.
    let (m, k, fy, alpha): (f64, f64, f64, f64) = (1.0e5, 4.0e7, 2.0e5, 0.1);
    let omega = (k / m).sqrt();
    let wf = omega / 100.0;
    let fmax = 1.5 * fy;
    let c = 2.0 * 0.05 * omega * m;
    let uy = fy / k;
    let umax = uy + (fmax - fy) / (alpha * k);
    let ures = umax - fmax / k;
    let text = format!(
        r#"{{ "building": {{ "floor_masses": [{m}], "storey_stiffness": [{k}],
              "damping": {{ "storey": [{c}] }},
              "storey_yield": [ {{ "storey": 1, "yield_shear": {fy}, "post_yield_ratio": {alpha} }} ] }},
             "excitation": {{ "harmonic": {{ "floor": 1, "amplitude": {fmax}, "omega": {wf} }} }},
             "duration": {}, "method": {{ "name": "exact", "dt": 0.005 }} }}"#,
        std::f64::consts::PI / wf
    );
    for method in ["exact", "newmark"] {
        let r = run(&text, method).response;
        assert!(
            rel(r.peak_drift[0], umax) < 5e-3,
            "{method}: {} vs {umax}",
            r.peak_drift[0]
        );
        assert!(
            (r.residual_drift[0] - ures).abs() < 5e-3 * umax,
            "{method}: residual {} vs {ures}",
            r.residual_drift[0]
        );
        // the plastic element's slip: everything past u_y
        let plastic = r.peak_plastic_drift.as_ref().unwrap()[0];
        assert!(
            rel(plastic, umax - uy) < 5e-3 * umax / (umax - uy),
            "{method}: {r:?}"
        );
    }
}

#[test]
fn a_storey_of_a_matrix_frame_yields_when_its_spring_is_named() {
    // The benchmark's condensed matrix: the first storey's spring (k = 1e8 N/m of the
    // coupling the matrix holds) yields; exact and newmark agree to newmark's accuracy at
    // its default step (1e-2), and the balance closes.
    let b = std::fs::read_to_string(configs().join("benchmark-3story-massless.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&b).unwrap();
    v["storey_yield"] = serde_json::json!([{ "storey": 1, "yield_shear": "900 kN", "stiffness": "100 MN/m", "post_yield_ratio": 0.05 }]);
    let text = format!(
        r#"{{ "building": {v},
             "excitation": {{ "synthetic": {{ "seed": 3, "duration": 8, "dt": 0.01, "pga_g": 0.6 }} }},
             "outputs": {{ "energies": true }} }}"#
    );
    let exact = run(&text, "exact");
    let nm = run(&text, "newmark");
    let pe = exact.response.energy.unwrap().plastic.unwrap();
    assert!(pe > 0.0, "the storey must yield");
    assert!(exact.diagnostics.balance_error_max_relative < 1e-10);
    for (a, b) in nm
        .response
        .peak_drift
        .iter()
        .zip(&exact.response.peak_drift)
    {
        assert!(rel(*a, *b) < 1e-2, "{a} vs {b}");
    }
}
