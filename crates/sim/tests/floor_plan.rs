//! Buildings in plan (docs/MODEL.md § Buildings in plan): the planar building written as a
//! plan gives the chain's answers; a symmetric plan does not twist; the plan's matrices
//! are the textbook ones of rigid floors on lines; `exact` on an asymmetric plan with
//! yielding lines and dampers agrees with an independent event-driven reference; `newmark`
//! converges to it; the energy balance closes; bad files name their field.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use nalgebra::{DMatrix, DVector};
use slipload_motion::Record;
use slipload_sim::floorplan::{FloorPlan, FloorPlanScene, GroundComponent};
use slipload_sim::plan::{ContactKind, Plan};
use slipload_sim::scene::OutputsConfig;
use slipload_sim::{MethodName, Response, run_plan};
use std::path::Path;
use std::sync::Arc;

/// A short, broadband ground motion (m/s², dt 0.01 s): a few decaying sines, enough to
/// slip the dampers and yield the weak line.
fn motion(pga: f64) -> Arc<Record> {
    common::decaying_sines(pga, 0.0)
}

use common::{floor_plan, rel};

fn outputs(energies: bool) -> OutputsConfig {
    OutputsConfig {
        energies,
        ..OutputsConfig::default()
    }
}

fn run_in_plan(
    b: &FloorPlan,
    record: &Arc<Record>,
    angle_deg: f64,
    method: MethodName,
    dt: Option<f64>,
    energies: bool,
) -> (Plan, Response) {
    run_pair(b, &[(record.clone(), angle_deg)], method, dt, energies)
}

/// A run under the components given (record, angle from x in degrees), all at once.
fn run_pair(
    b: &FloorPlan,
    components: &[(Arc<Record>, f64)],
    method: MethodName,
    dt: Option<f64>,
    energies: bool,
) -> (Plan, Response) {
    let mut scene = FloorPlanScene::new(
        Arc::new(b.clone()),
        components
            .iter()
            .map(|(record, angle_deg)| GroundComponent {
                record: record.clone(),
                angle: angle_deg.to_radians(),
            })
            .collect(),
        components[0].0.duration(),
        method,
        outputs(energies),
    );
    if let Some(dt) = dt {
        scene.method.dt = dt;
    }
    let plan = slipload_sim::floorplan::compile(&scene).unwrap();
    let out = run_plan(&plan).unwrap();
    (plan, out.response)
}

/// The chain: three storeys, a massless damper on storeys 1 and 3, a damper with mass on
/// storey 2, storey 1 yielding; Rayleigh damping by its coefficients.
const CHAIN: &str = r#"{
  "name": "chain", "floor_masses": [400000, 380000, 300000],
  "storey_stiffness": [3.0e8, 2.6e8, 2.0e8], "storey_heights": [4.0, 3.5, 3.5],
  "damping": {"rayleigh": {"alpha": 0.4, "beta": 0.002}},
  "storey_yield": [{"storey": 1, "yield_shear": 1.2e6, "post_yield_ratio": 0.05}],
  "dissipators": [
    {"floor": 1, "brace_stiffness": 4.0e8, "slip_load": 4.0e5},
    {"floor": 2, "brace_stiffness": 3.5e8, "slip_load": 3.0e5, "mass": 800},
    {"floor": 3, "brace_stiffness": 3.0e8, "slip_load": 2.0e5}
  ]
}"#;

/// The same frame as a plan: the chain as line X through the centre of mass (the origin),
/// two lines along y at x = ±8 m holding y and the rotation; Rayleigh coefficients as the
/// chain's.
const PLANAR: &str = r#"{
  "name": "planar in plan",
  "floors": [
    {"mass": 400000, "inertia_kg_m2": 2.0e7, "centre_of_mass": [0, 0]},
    {"mass": 380000, "inertia_kg_m2": 1.9e7, "centre_of_mass": [0, 0]},
    {"mass": 300000, "inertia_kg_m2": 1.5e7, "centre_of_mass": [0, 0]}
  ],
  "storey_heights": [4.0, 3.5, 3.5],
  "damping": {"rayleigh": {"alpha": 0.4, "beta": 0.002}},
  "lines": [
    {"name": "X", "direction": "x", "at": 0,
     "storey_stiffness": [3.0e8, 2.6e8, 2.0e8],
     "storey_yield": [{"storey": 1, "yield_shear": 1.2e6, "post_yield_ratio": 0.05}],
     "dissipators": [
       {"floor": 1, "brace_stiffness": 4.0e8, "slip_load": 4.0e5},
       {"floor": 2, "brace_stiffness": 3.5e8, "slip_load": 3.0e5, "mass": 800},
       {"floor": 3, "brace_stiffness": 3.0e8, "slip_load": 2.0e5}
     ]},
    {"name": "Y1", "direction": "y", "at": -8, "storey_stiffness": [2.0e8, 2.0e8, 2.0e8]},
    {"name": "Y2", "direction": "y", "at": 8, "storey_stiffness": [2.0e8, 2.0e8, 2.0e8]}
  ]
}"#;

#[test]
fn a_planar_building_written_in_plan_gives_the_chains_answers() {
    let record = motion(3.0);
    let plan_b = floor_plan(PLANAR);
    let cfg: slipload_sim::BuildingConfig = serde_json::from_str(CHAIN).unwrap();
    let chain_b = slipload_sim::Building::from_config(&cfg, Path::new("chain.json")).unwrap();
    for method in [MethodName::Exact, MethodName::Newmark] {
        let (plan, p) = run_in_plan(&plan_b, &record, 0.0, method, Some(0.002), true);
        assert!(!plan.is_chain());
        let mut settings = plan.method;
        settings.dt = 0.002;
        let c = common::chain_response(&chain_b, &record, settings, outputs(true));
        let labels = p.in_plan.as_ref().unwrap();
        // Round-off: the plan's operators hold the chain's in their x block (the y and
        // rotation DOFs are uncoupled from it exactly), summed in another order; 1e-9
        // leaves room for round-off carried through the run's stick-slip decisions.
        let tol = 1e-9;
        for s in 0..3 {
            let k = labels
                .drifts
                .iter()
                .position(|d| *d == format!("X/{}", s + 1))
                .unwrap();
            assert!(
                rel(p.peak_drift[k], c.peak_drift[s]) < tol,
                "{method:?} storey {}: drift {} in plan, {} as a chain",
                s + 1,
                p.peak_drift[k],
                c.peak_drift[s]
            );
            assert!(
                rel(p.residual_drift[k], c.residual_drift[s]) < 1e-6
                    || (p.residual_drift[k] - c.residual_drift[s]).abs() < 1e-9 * c.peak_drift[s]
            );
            assert!(
                rel(p.peak_slip[s], c.peak_slip[s]) < tol,
                "{method:?} slip {s}"
            );
            assert_eq!(
                p.transitions[s], c.transitions[s],
                "{method:?} transitions {s}"
            );
            let x = labels
                .points
                .iter()
                .position(|q| *q == format!("{} x", s + 1))
                .unwrap();
            assert!(rel(p.peak_abs_acceleration[x], c.peak_abs_acceleration[s]) < tol);
            assert!(rel(p.peak_displacement[x], c.peak_displacement[s]) < tol);
            // no twist, no motion across
            let rot = labels
                .points
                .iter()
                .position(|q| *q == format!("{} rot", s + 1))
                .unwrap();
            assert!(
                p.peak_displacement[rot] <= 1e-14 * c.peak_displacement[s],
                "{method:?} rotation {}",
                p.peak_displacement[rot]
            );
        }
        assert!(
            rel(p.peak_base_shear, c.peak_base_shear) < tol,
            "{method:?} base shear"
        );
        let (pe, ce) = (p.energy.unwrap(), c.energy.unwrap());
        assert!(rel(pe.input, ce.input) < tol && rel(pe.friction, ce.friction) < tol);
        assert!(
            rel(
                p.peak_plastic_drift.as_ref().unwrap()[0],
                c.peak_plastic_drift.as_ref().unwrap()[0]
            ) < tol
        );
    }
}

/// An asymmetric plan, 20 m × 12 m, three storeys: a stiff line along y at x = 0 and a
/// flexible one at x = 20 m (stiffness eccentricity 0.27 of the width), two equal lines
/// along x; massless dampers on the flexible edge, the flexible edge's first storey
/// yielding; modal damping 3 %.
const ASYMMETRIC: &str = r#"{
  "name": "asymmetric", "plan_size": [20, 12],
  "floors": [{"mass": "400 t"}, {"mass": "380 t"}, {"mass": "300 t"}],
  "storey_heights": [4.0, 3.5, 3.5],
  "damping": {"modal": {"ratio": 0.03}},
  "lines": [
    {"name": "A", "direction": "y", "at": 0, "storey_stiffness": ["500 MN/m", "450 MN/m", "350 MN/m"]},
    {"name": "D", "direction": "y", "at": 20, "storey_stiffness": ["150 MN/m", "130 MN/m", "100 MN/m"],
     "storey_yield": [{"storey": 1, "yield_drift": 0.006, "post_yield_ratio": 0.05}],
     "dissipators": [
       {"floor": 1, "brace_stiffness": "300 MN/m", "slip_load": "350 kN"},
       {"floor": 2, "brace_stiffness": "260 MN/m", "slip_load": "250 kN"},
       {"floor": 3, "brace_stiffness": "200 MN/m", "slip_load": "150 kN"}
     ]},
    {"name": "1", "direction": "x", "at": 0, "storey_stiffness": ["300 MN/m", "280 MN/m", "220 MN/m"]},
    {"name": "2", "direction": "x", "at": 12, "storey_stiffness": ["300 MN/m", "280 MN/m", "220 MN/m"]}
  ]
}"#;

#[test]
fn a_symmetric_plan_does_not_twist_and_a_shifted_centre_of_mass_twists_it_both_ways() {
    // the flexible line D as stiff as A and A with D's yield law and dampers: mirror
    // symmetric about x = 10 m, the centre of mass
    let d_line = ASYMMETRIC
        .split(r#"{"name": "D""#)
        .nth(1)
        .and_then(|t| t.split(r#"{"name": "1""#).next())
        .unwrap()
        .replace("150 MN/m", "500 MN/m")
        .replace("130 MN/m", "450 MN/m")
        .replace("100 MN/m", "350 MN/m");
    let a_line = d_line.replace(r#""at": 20"#, r#""at": 0"#);
    let head = ASYMMETRIC.split(r#"{"name": "A""#).next().unwrap();
    let tail = ASYMMETRIC.split(r#"{"name": "1""#).nth(1).unwrap();
    let sym = floor_plan(&format!(
        r#"{head}{{"name": "A"{a_line}{{"name": "D"{d_line}{{"name": "1"{tail}"#
    ));
    assert_eq!(sym.lines[0].dissipators, sym.lines[1].dissipators);
    let record = motion(2.5);
    for angle in [90.0, 30.0] {
        let (_, r) = run_in_plan(&sym, &record, angle, MethodName::Newmark, None, false);
        let ip = r.in_plan.as_ref().unwrap();
        let trans = r.peak_displacement.iter().fold(0.0f64, |m, x| m.max(*x));
        for (k, name) in ip
            .points
            .iter()
            .enumerate()
            .filter(|(_, n)| n.ends_with("rot"))
        {
            // θ·(plan size) against the translations: zero but for round-off
            assert!(
                r.peak_displacement[k] * 20.0 <= 1e-12 * trans,
                "{angle} deg {name}: {}",
                r.peak_displacement[k]
            );
        }
        for t in ip.torsional_irregularity.as_ref().unwrap() {
            for v in t {
                assert!((v - 1.0).abs() < 1e-9, "{angle} deg: ratio {v}");
            }
        }
    }
    // Accidental torsion: the centre of mass 5 % of the width either side of the centre
    // twists the floors by the same amount in opposite senses (mirror images).
    let plus = sym.with_centre_shift([1.0, 0.0]);
    let minus = sym.with_centre_shift([-1.0, 0.0]);
    let (_, rp) = run_in_plan(&plus, &record, 90.0, MethodName::Exact, None, false);
    let (_, rm) = run_in_plan(&minus, &record, 90.0, MethodName::Exact, None, false);
    let ip = rp.in_plan.as_ref().unwrap();
    let rot = ip.points.iter().position(|n| n == "3 rot").unwrap();
    assert!(
        rp.peak_displacement[rot] > 1e-6,
        "a shifted centre twists: {}",
        rp.peak_displacement[rot]
    );
    // the mirror exchanges the edges x=0 and x=Lx, and the lines A and D are equal
    assert!(rel(rp.peak_displacement[rot], rm.peak_displacement[rot]) < 1e-9);
    let d =
        |r: &Response, name: &str| r.peak_drift[ip.drifts.iter().position(|n| n == name).unwrap()];
    for s in 1..=3 {
        let (a, b) = (format!("edge x=0 (y)/{s}"), format!("edge x=Lx (y)/{s}"));
        assert!(rel(d(&rp, &a), d(&rm, &b)) < 1e-9, "storey {s}");
        assert!(rel(d(&rp, &b), d(&rm, &a)) < 1e-9, "storey {s}");
        assert!(
            rp.in_plan
                .as_ref()
                .unwrap()
                .torsional_irregularity
                .as_ref()
                .unwrap()[s - 1][1]
                > 1.0
        );
    }
}

#[test]
fn the_plans_matrices_are_those_of_rigid_floors_on_lines() {
    let b = floor_plan(ASYMMETRIC);
    // By hand, one floor: m = 400 t at the centre (10, 6) of a 20 × 12 plan, J = m(20² +
    // 12²)/12 about it; the lines' storey-1 springs in the textbook form (Chopra,
    // Dynamics of Structures, §9.5): K = [[Σkx, 0, −Σkx·y], [0, Σky, Σky·x],
    // [−Σkx·y, Σky·x, Σkx·y² + Σky·x²]] for lines along x at y and along y at x.
    let (m, xc, yc) = (400e3, 10.0, 6.0);
    let j = m * (400.0 + 144.0) / 12.0;
    let mh = DMatrix::from_row_slice(
        3,
        3,
        &[
            m,
            0.0,
            -m * yc,
            0.0,
            m,
            m * xc,
            -m * yc,
            m * xc,
            j + m * (xc * xc + yc * yc),
        ],
    );
    let kx = [(300e6, 0.0), (300e6, 12.0)];
    let ky = [(500e6, 0.0), (150e6, 20.0)];
    let sum = |v: &[(f64, f64)], f: &dyn Fn(f64, f64) -> f64| {
        v.iter().map(|(k, p)| f(*k, *p)).sum::<f64>()
    };
    let kxx = sum(&kx, &|k, _| k);
    let kyy = sum(&ky, &|k, _| k);
    let kxt = -sum(&kx, &|k, y| k * y);
    let kyt = sum(&ky, &|k, x| k * x);
    let ktt = sum(&kx, &|k, y| k * y * y) + sum(&ky, &|k, x| k * x * x);
    let k1 = DMatrix::from_row_slice(3, 3, &[kxx, 0.0, kxt, 0.0, kyy, kyt, kxt, kyt, ktt]);
    let m_block = b.mass.view((0, 0), (3, 3)).into_owned();
    assert!((m_block - &mh).norm() <= 1e-12 * mh.norm());
    // storey 1's springs act on floor 1 alone: K[0..3, 0..3] is storeys 1 and 2 together,
    // K[0..3, 3..6] is −storey 2; so storey 1 = K[0..3,0..3] + K[0..3,3..6]
    let s1 = b.stiffness.view((0, 0), (3, 3)).into_owned()
        + b.stiffness.view((0, 3), (3, 3)).into_owned();
    assert!((s1 - &k1).norm() <= 1e-12 * k1.norm(), "storey 1 stiffness");
    // the centre of rigidity of storey 1 sits 0.27 of the width from the centre of mass
    let xr = kyt / kyy;
    assert!(((xc - xr) / 20.0 - 0.2692).abs() < 1e-3);
    // modes: M-orthonormal, and the bare periods solve det(K − ω²M) = 0
    let modes = &b.modes;
    let orth = modes.shapes.transpose() * &b.mass * &modes.shapes;
    assert!((orth - DMatrix::identity(9, 9)).norm() < 1e-9);
    for w in modes.omega.iter() {
        let d = (&b.stiffness - &b.mass * (w * w)).determinant();
        let scale = b.stiffness.determinant();
        assert!((d / scale).abs() < 1e-6, "ω = {w}: det ratio {}", d / scale);
    }
}

#[derive(Clone, Copy, PartialEq, Debug)]
enum Mode {
    Stuck,
    Upper,
    Lower,
}

/// An independent reference for plans whose contacts are elastic–perfectly plastic
/// elements (massless dampers and yielding lines): classical RK4 at a step far below the
/// plan's, each element's brace elongation a state that follows its points' relative
/// motion while stuck and rests at its bound while sliding; every stick↔slip change
/// located by bisection inside its RK4 step. It shares the plan's matrices (checked by
/// hand above) and nothing of `exact`'s integration (no exponentials, no Taylor rows, no
/// QP). Returns the peaks of every drift sampled at the plan's output steps, the drifts at
/// the end, and the friction work of the dampers.
fn reference(plan: &Plan, h_per_step: usize) -> (Vec<f64>, Vec<f64>, f64) {
    let n = plan.dofs();
    let nc = plan.contacts.len();
    assert!(plan.contacts.iter().all(|c| c.kind == ContactKind::Epp));
    let minv = plan.mass.clone().try_inverse().unwrap();
    let bvec: Vec<DVector<f64>> = plan
        .contacts
        .iter()
        .map(|c| {
            let mut v = DVector::zeros(n);
            for (i, w) in c.top.entries() {
                v[i] += w;
            }
            for (i, w) in c.bottom.entries() {
                v[i] -= w;
            }
            v
        })
        .collect();
    let mr = &plan.mass * &plan.influence;
    let record = plan.record.clone().unwrap();
    let second = plan
        .second
        .as_ref()
        .map(|g| (&plan.mass * &g.influence, g.record.clone()));
    let deriv = |t: f64, z: &DVector<f64>, modes: &[Mode]| -> DVector<f64> {
        let u = z.rows(0, n);
        let v = z.rows(n, n);
        let mut force = -(&plan.stiffness * u) - &plan.damping * v - &mr * record.accel_at(t);
        if let Some((mr2, r2)) = &second {
            force -= mr2 * r2.accel_at(t);
        }
        let mut dz = DVector::zeros(2 * n + nc);
        for (c, ct) in plan.contacts.iter().enumerate() {
            let f = ct.brace_stiffness * z[2 * n + c];
            force -= &bvec[c] * f;
            dz[2 * n + c] = if modes[c] == Mode::Stuck {
                bvec[c].dot(&v)
            } else {
                0.0
            };
        }
        dz.rows_mut(0, n).copy_from(&v);
        dz.rows_mut(n, n).copy_from(&(&minv * force));
        dz
    };
    let rk4 = |t: f64, z: &DVector<f64>, h: f64, modes: &[Mode]| -> DVector<f64> {
        let k1 = deriv(t, z, modes);
        let k2 = deriv(t + h / 2.0, &(z + &k1 * (h / 2.0)), modes);
        let k3 = deriv(t + h / 2.0, &(z + &k2 * (h / 2.0)), modes);
        let k4 = deriv(t + h, &(z + &k3 * h), modes);
        z + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
    };
    // the event function of contact c in its mode: crosses zero from below at a change
    let event = |c: usize, z: &DVector<f64>, modes: &[Mode]| -> f64 {
        let ct = &plan.contacts[c];
        let w = bvec[c].dot(&z.rows(n, n));
        match modes[c] {
            Mode::Stuck => {
                let f = ct.brace_stiffness * z[2 * n + c];
                (f - ct.upper).max(ct.lower - f)
            }
            Mode::Upper => -w,
            Mode::Lower => w,
        }
    };
    let mut z = DVector::zeros(2 * n + nc);
    let mut modes = vec![Mode::Stuck; nc];
    let dt = plan.method.dt;
    let h = dt / h_per_step as f64;
    let drift = |z: &DVector<f64>| -> Vec<f64> {
        plan.drifts
            .iter()
            .map(|(a, b)| a.at(z.as_slice()) - b.at(z.as_slice()))
            .collect()
    };
    let mut peaks = vec![0.0f64; plan.drifts.len()];
    let mut friction = 0.0;
    for step in 0..plan.steps {
        for sub in 0..h_per_step {
            let mut t = (step * h_per_step + sub) as f64 * h;
            let t_end = t + h;
            let mut guard = 0;
            while t < t_end - 1e-15 * dt {
                guard += 1;
                assert!(guard < 100, "too many events in one substep");
                let hh = t_end - t;
                let next = rk4(t, &z, hh, &modes);
                // the first contact to change inside (t, t + hh]
                let fired = (0..nc)
                    .filter(|&c| event(c, &next, &modes) > 0.0 && event(c, &z, &modes) <= 0.0)
                    .map(|c| {
                        let (mut lo, mut hi) = (0.0, 1.0);
                        for _ in 0..80 {
                            let mid = 0.5 * (lo + hi);
                            if event(c, &rk4(t, &z, mid * hh, &modes), &modes) > 0.0 {
                                hi = mid;
                            } else {
                                lo = mid;
                            }
                        }
                        (hi, c)
                    })
                    .min_by(|a, b| a.0.total_cmp(&b.0));
                let (frac, fired) = match fired {
                    Some((f, c)) => (f, Some(c)),
                    None => (1.0, None),
                };
                let znew = rk4(t, &z, frac * hh, &modes);
                // friction work over the piece: F·w of the sliding dampers (trapezoid on a
                // piece far below the plan's step; F is constant while sliding)
                for (c, ct) in plan.contacts.iter().enumerate() {
                    if modes[c] != Mode::Stuck && ct.role == slipload_sim::plan::ContactRole::Damper
                    {
                        let f = ct.brace_stiffness * z[2 * n + c];
                        let w0 = bvec[c].dot(&z.rows(n, n));
                        let w1 = bvec[c].dot(&znew.rows(n, n));
                        friction += f * 0.5 * (w0 + w1) * frac * hh;
                    }
                }
                z = znew;
                t += frac * hh;
                // the contact that fired, and any other whose change falls at the same
                // instant (two elements on one storey of one line slide and stick together:
                // their slip rates are the same relative velocity)
                let changed: Vec<usize> = match fired {
                    Some(c) => (0..nc)
                        .filter(|&k| k == c || event(k, &z, &modes) > 0.0)
                        .collect(),
                    None => Vec::new(),
                };
                for c in changed {
                    let ct = &plan.contacts[c];
                    modes[c] = match modes[c] {
                        Mode::Stuck => {
                            let f = ct.brace_stiffness * z[2 * n + c];
                            if f >= ct.upper {
                                z[2 * n + c] = ct.upper / ct.brace_stiffness;
                                Mode::Upper
                            } else {
                                z[2 * n + c] = ct.lower / ct.brace_stiffness;
                                Mode::Lower
                            }
                        }
                        Mode::Upper | Mode::Lower => Mode::Stuck,
                    };
                }
            }
        }
        for (p, d) in peaks.iter_mut().zip(drift(&z)) {
            *p = p.max(d.abs());
        }
    }
    let last = drift(&z).iter().map(|d| d.abs()).collect();
    (peaks, last, friction)
}

#[test]
fn exact_on_an_asymmetric_plan_agrees_with_an_independent_reference() {
    let b = floor_plan(ASYMMETRIC);
    let record = motion(3.5);
    let (plan, r) = run_in_plan(&b, &record, 90.0, MethodName::Exact, Some(0.005), true);
    let ip = r.in_plan.as_ref().unwrap();
    // the run reaches every regime: the dampers slip, the weak line yields, floors twist
    assert!(
        r.peak_slip.iter().all(|s| *s > 1e-4),
        "slips {:?}",
        r.peak_slip
    );
    assert!(r.peak_plastic_drift.as_ref().unwrap()[0] > 1e-4);
    let rot = ip.points.iter().position(|n| n == "3 rot").unwrap();
    assert!(r.peak_displacement[rot] > 1e-5);
    let (peaks, last, friction) = reference(&plan, 32);
    let scale = peaks.iter().fold(0.0f64, |m, p| m.max(*p));
    let sampled = r.peak_drift.clone();
    // `exact`'s continuous peaks are at least the sampled ones, and its sampled ones
    // (diagnostics) are the reference's: RK4 at Δt/32 is accurate to ~1e-10 here
    // ((ωh)⁵/120 per step at ωh < 0.01 over 2.6e4 steps), the events located to 1e-18
    // of a step; 1e-9 of the largest drift leaves room for both (measured 4e-11).
    let out = run_plan(&plan).unwrap();
    let sampled_exact = out.diagnostics.sampled_peak_drift.unwrap();
    for (k, name) in ip.drifts.iter().enumerate() {
        assert!(
            (sampled_exact[k] - peaks[k]).abs() <= 1e-9 * scale,
            "{name}: exact (sampled) {} reference {}",
            sampled_exact[k],
            peaks[k]
        );
        assert!(sampled[k] >= sampled_exact[k] * (1.0 - 1e-12));
        assert!(
            (r.residual_drift[k] - last[k]).abs() <= 1e-9 * scale,
            "{name} residual"
        );
    }
    let worst = ip
        .drifts
        .iter()
        .enumerate()
        .map(|(k, _)| {
            (sampled_exact[k] - peaks[k])
                .abs()
                .max((r.residual_drift[k] - last[k]).abs())
        })
        .fold(0.0, f64::max);
    eprintln!(
        "exact vs reference: largest difference {:e} of the largest drift",
        worst / scale
    );
    let e = r.energy.unwrap();
    assert!(
        rel(e.friction, friction) < 1e-6,
        "friction work {} vs {friction}",
        e.friction
    );
    assert!(
        e.balance_error.abs() < 1e-8,
        "exact's energy balance {}",
        e.balance_error
    );
}

#[test]
fn newmark_converges_to_exact_on_an_asymmetric_plan() {
    let b = floor_plan(ASYMMETRIC);
    let record = motion(3.5);
    let (_, ex) = run_in_plan(&b, &record, 60.0, MethodName::Exact, Some(0.00125), false);
    let scale = ex.peak_drift.iter().fold(0.0f64, |m, p| m.max(*p));
    let err = |dt: f64| {
        let (_, r) = run_in_plan(&b, &record, 60.0, MethodName::Newmark, Some(dt), true);
        assert!(r.energy.unwrap().balance_error.abs() < 1e-6);
        r.peak_drift
            .iter()
            .zip(&ex.peak_drift)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / scale
    };
    let (e1, e2, e3) = (err(0.005), err(0.0025), err(0.00125));
    eprintln!("newmark errors {e1:e} {e2:e} {e3:e}");
    assert!(
        e3 < 1e-3,
        "newmark at 1.25 ms is within 0.1 % of exact: {e3:e}"
    );
    // second order (the trapezoidal rule; 4 per halving) but for the stick-slip
    // changes, which the step places to within its length: measured 3.3 and 4.0
    assert!(
        e1 / e2 > 2.5 && e2 / e3 > 2.5,
        "errors fall at second order: {e1:e} {e2:e} {e3:e}"
    );
}

/// A second motion for pairs: other frequencies, the same length and step.
fn motion2(pga: f64) -> Arc<Record> {
    let dt = 0.01;
    let a: Vec<f64> = (0..400)
        .map(|i| {
            let t = i as f64 * dt;
            let env = (t / 0.8).min(1.0) * (-(t - 0.8).max(0.0) / 1.2).exp();
            env * ((5.1 * t + 1.0).sin() + 0.5 * (11.7 * t).sin())
        })
        .collect();
    let peak = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    Arc::new(Record::new("second", dt, a.iter().map(|x| x * pga / peak).collect()).unwrap())
}

#[test]
fn a_pair_of_equal_components_along_x_and_y_is_one_component_root_two_larger_at_45_degrees() {
    // −M(r(0°) + r(90°))a = −M r(45°) √2 a on every DOF, dampers' included: the same
    // loads, so the same nonlinear run (dampers slipping, a line yielding) to round-off.
    let b = floor_plan(ASYMMETRIC);
    let a = motion(2.0);
    let scaled = Arc::new(a.try_scaled(std::f64::consts::SQRT_2).unwrap());
    for method in [MethodName::Exact, MethodName::Newmark] {
        let (plan, pair) = run_pair(
            &b,
            &[(a.clone(), 0.0), (a.clone(), 90.0)],
            method,
            Some(0.005),
            true,
        );
        assert!(plan.second.is_some());
        let (_, one) = run_pair(&b, &[(scaled.clone(), 45.0)], method, Some(0.005), true);
        assert!(
            pair.peak_slip.iter().any(|s| *s > 1e-4),
            "{method:?}: the dampers slip"
        );
        // round-off of the two loads' sum against one product, carried through the run
        for (k, (p, o)) in pair.peak_drift.iter().zip(&one.peak_drift).enumerate() {
            assert!(rel(*p, *o) < 1e-9, "{method:?} drift {k}: {p} {o}");
        }
        for (p, o) in pair
            .peak_abs_acceleration
            .iter()
            .zip(&one.peak_abs_acceleration)
        {
            assert!(
                (p - o).abs() <= 1e-9 * o.abs().max(1e-3),
                "{method:?} acceleration {p} {o}"
            );
        }
        let (ep, eo) = (pair.energy.unwrap(), one.energy.unwrap());
        assert!(rel(ep.input, eo.input) < 1e-9 && rel(ep.friction, eo.friction) < 1e-9);
    }
}

#[test]
fn exact_under_both_components_agrees_with_the_reference_and_balances_its_energy() {
    let b = floor_plan(ASYMMETRIC);
    let (a1, a2) = (motion(3.0), motion2(2.0));
    let (plan, r) = run_pair(
        &b,
        &[(a1, 20.0), (a2, 110.0)],
        MethodName::Exact,
        Some(0.005),
        true,
    );
    let out = run_plan(&plan).unwrap();
    let sampled = out.diagnostics.sampled_peak_drift.unwrap();
    let (peaks, last, friction) = reference(&plan, 32);
    let scale = peaks.iter().fold(0.0f64, |m, p| m.max(*p));
    assert!(r.peak_slip.iter().all(|s| *s > 1e-4));
    for k in 0..peaks.len() {
        assert!(
            (sampled[k] - peaks[k]).abs() <= 1e-9 * scale,
            "drift {k}: {} {}",
            sampled[k],
            peaks[k]
        );
        assert!((r.residual_drift[k] - last[k]).abs() <= 1e-9 * scale);
    }
    let e = r.energy.unwrap();
    assert!(rel(e.friction, friction) < 1e-6);
    assert!(e.balance_error.abs() < 1e-8, "balance {}", e.balance_error);
    // newmark under the same pair balances its energy to its step's accuracy
    let (_, nm) = run_pair(
        &b,
        &[(motion(3.0), 20.0), (motion2(2.0), 110.0)],
        MethodName::Newmark,
        Some(0.002),
        true,
    );
    assert!(nm.energy.unwrap().balance_error.abs() < 1e-3);
}

#[test]
fn per_damper_demands_of_a_plan_are_by_damper_and_add_up_to_the_friction_work() {
    let b = floor_plan(ASYMMETRIC);
    let record = motion(3.5);
    for method in [MethodName::Exact, MethodName::Newmark] {
        let mut scene = FloorPlanScene::new(
            Arc::new(b.clone()),
            vec![GroundComponent {
                record: record.clone(),
                angle: 90f64.to_radians(),
            }],
            record.duration(),
            method,
            OutputsConfig {
                dampers: true,
                ..outputs(true)
            },
        );
        scene.method.dt = 0.002;
        let r = slipload_sim::floorplan::simulate(&scene).unwrap().response;
        let d = r.dampers.as_ref().unwrap();
        let ip = r.in_plan.as_ref().unwrap();
        assert_eq!(d.len(), ip.dampers.len());
        assert_eq!(ip.dampers, ["D/1", "D/2", "D/3"]);
        let mut energy = 0.0;
        for (k, x) in d.iter().enumerate() {
            // the largest slip either way is the peak slip (both from the start of the run)
            assert!(
                rel(x.slip_max_pos_m.max(x.slip_max_neg_m), r.peak_slip[k]) < 1e-12,
                "{method:?} {k}"
            );
            // its force never passes the slip load
            let bound = [350e3, 250e3, 150e3][k];
            assert!(
                x.peak_force_n <= bound * (1.0 + 1e-12),
                "{method:?} {k}: {}",
                x.peak_force_n
            );
            energy += x.energy_j;
        }
        // the dampers' energies are the run's friction work (sampled at the output steps:
        // the step's accuracy for newmark, 1e-3 for both here)
        let friction = r.energy.unwrap().friction;
        assert!(
            rel(energy, friction) < 1e-3,
            "{method:?}: {energy} vs {friction}"
        );
    }
}

/// P-Δ of the chain written as a plan: the storeys' gravity loads, spread as the mass
/// above (centroid on line X), give the chain's P-Δ along x to round-off; the twist and y
/// are held apart exactly.
#[test]
fn p_delta_of_a_planar_building_in_plan_is_the_chains() {
    let record = motion(3.0);
    let with = |json: &str, key: &str| json.replacen(key, &format!("\"p_delta\": {{}}, {key}"), 1);
    let plan_b = floor_plan(&with(PLANAR, "\"storey_heights\""));
    let cfg: slipload_sim::BuildingConfig =
        serde_json::from_str(&with(CHAIN, "\"storey_heights\"")).unwrap();
    let chain_b = slipload_sim::Building::from_config(&cfg, Path::new("chain.json")).unwrap();
    assert!(chain_b.gravity_loads.is_some() && plan_b.p_delta.is_some());
    for s in 0..3 {
        let (a, b) = (
            plan_b.p_delta.as_ref().unwrap().loads[s],
            chain_b.gravity_loads.as_ref().unwrap()[s],
        );
        assert!(rel(a, b) < 1e-14, "storey {s}: {a} vs {b}");
    }
    for method in [MethodName::Exact, MethodName::Newmark] {
        let (plan, p) = run_in_plan(&plan_b, &record, 0.0, method, Some(0.002), false);
        let mut settings = plan.method;
        settings.dt = 0.002;
        let c = common::chain_response(&chain_b, &record, settings, outputs(false));
        let without = run_in_plan(
            &floor_plan(PLANAR),
            &record,
            0.0,
            method,
            Some(0.002),
            false,
        )
        .1;
        let labels = p.in_plan.as_ref().unwrap();
        for s in 0..3 {
            let k = labels
                .drifts
                .iter()
                .position(|d| *d == format!("X/{}", s + 1))
                .unwrap();
            // round-off carried through the stick-slip decisions, as without P-Δ
            assert!(
                rel(p.peak_drift[k], c.peak_drift[s]) < 1e-9,
                "{method:?} storey {}: {} in plan, {} as a chain",
                s + 1,
                p.peak_drift[k],
                c.peak_drift[s]
            );
            assert_ne!(
                p.peak_drift[k], without.peak_drift[k],
                "P-Δ changes the run"
            );
        }
    }
}

/// One storey, symmetric: with P-Δ the plan's periods are the closed forms
/// ω² = (k − P/h)/m along x and y and ω² = (k_θ − P ρ²/h)/J in twist (ρ² = J/m: the load
/// spread as the mass).
#[test]
fn p_delta_of_a_one_storey_plan_lowers_each_frequency_as_the_closed_form_says() {
    let json = r#"{
      "floors": [{"mass": 500000, "inertia_kg_m2": 3.0e7, "centre_of_mass": [0, 0]}],
      "storey_heights": [4.0],
      "p_delta": {"gravity_loads": ["60 MN"]},
      "lines": [
        {"name": "X1", "direction": "x", "at": -5, "storey_stiffness": [1.5e8]},
        {"name": "X2", "direction": "x", "at": 5, "storey_stiffness": [1.5e8]},
        {"name": "Y1", "direction": "y", "at": -9, "storey_stiffness": [2.0e8]},
        {"name": "Y2", "direction": "y", "at": 9, "storey_stiffness": [2.0e8]}
      ]
    }"#;
    let b = floor_plan(json);
    let (plan, _) = run_in_plan(
        &b,
        &motion(0.1),
        0.0,
        MethodName::Newmark,
        Some(0.002),
        false,
    );
    let k = &plan.stiffness;
    let m = &plan.mass;
    let (p, h, mass, j) = (60e6, 4.0, 5e5, 3.0e7);
    let rho2 = j / mass;
    let kx = 3.0e8 - p / h;
    let ky = 4.0e8 - p / h;
    let kt = 2.0 * 1.5e8 * 25.0 + 2.0 * 2.0e8 * 81.0 - p * rho2 / h;
    let want = [kx / mass, ky / mass, kt / j];
    for (i, w) in want.iter().enumerate() {
        let got = k[(i, i)] / m[(i, i)];
        assert!(rel(got, *w) < 1e-12, "DOF {i}: {got} vs {w}");
    }
    // the OpenSees export writes the storey's P-Δ as springs at the load's centroid:
    // −P/h along x and y, −Pρ²/h about the vertical (the py tests run it against newmark)
    let scene = FloorPlanScene::new(
        Arc::new(b.clone()),
        vec![GroundComponent {
            record: motion(0.1),
            angle: 0.0,
        }],
        1.0,
        MethodName::Newmark,
        outputs(false),
    );
    let script = slipload_sim::floorplan::opensees_script(&scene).unwrap();
    let row: Vec<f64> = script
        .split("P_DELTA = [\n")
        .nth(1)
        .and_then(|t| t.lines().next())
        .unwrap()
        .trim()
        .trim_start_matches('(')
        .trim_end_matches("),")
        .split(", ")
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(row.len(), 4, "{row:?}");
    assert!(
        row[0].abs() < 1e-12 && row[1].abs() < 1e-12,
        "centroid {row:?}"
    );
    assert!(rel(row[2], -p / h) < 1e-12, "{row:?}");
    assert!(rel(row[3], -p * rho2 / h) < 1e-12, "{row:?}");
    // uncoupled: a symmetric plan's off-diagonal terms are zero
    assert_eq!(k[(0, 1)], 0.0);
    assert_eq!(k[(0, 2)], 0.0);
    assert_eq!(k[(1, 2)], 0.0);
}
