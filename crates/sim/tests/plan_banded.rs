//! The banded step of `newmark` on buildings in plan (docs/MODEL.md § Integrators, banded
//! frames): a contact's vector b is top − bottom (up to six weighted DOFs of two
//! consecutive floors), the operators have half-bandwidth 5 with Rayleigh damping, and the
//! step solves the same equations and the same friction QP as the dense step. So their
//! answers differ by round-off only: on asymmetric plans (the ten-storey plan of
//! `configs/plan-ten-story.json` with Rayleigh damping, under one component and under the
//! Newhall pair of `configs/plan-ten-story-pair.json`; a small hand-built plan with a
//! yielding line and massless dampers, with and without brace dashpots, that slip and
//! stick) every drift, displacement, acceleration, base shear, slip, per-damper demand
//! and energy agrees with the dense step's; the fallback to the dense box QP gives the
//! same answer; plans with modal damping or dampers with mass stay dense.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_motion::Record;
use slipload_sim::floorplan::{FloorPlan, FloorPlanConfig, FloorPlanScene, GroundComponent};
use slipload_sim::integrator::newmark::{BandedStats, StepPath, run_on_path};
use slipload_sim::scene::OutputsConfig;
use slipload_sim::{MethodName, Outcome, Plan};
use std::path::Path;
use std::sync::Arc;

/// Peaks to `PEAK_REL` of each array's largest value (lengths: or of the largest peak
/// displacement, so that a slip that never grows is compared with the motion), energies
/// and per-damper demands to `ENERGY_REL` of the input energy or of the largest demand of
/// their kind: the tolerance kind of `banded_step.rs`, for the same reason. The two steps
/// solve the same linear systems (one by a dense Cholesky factor of A and explicit
/// products with A⁻¹K, A⁻¹C, A⁻¹B, the other by a banded LDLᵀ of A plus the stuck
/// contacts' springs) and the same strictly convex QP, whose minimiser is unique, so a
/// step differs by the round-off of those solves, ~κ(A)·ε with A = M + γΔtC + βΔt²K well
/// conditioned at Δt ≈ T₁/400 (the rotation's DOF is scaled by the plan's size, which
/// κ(A) carries: ≲ 1e3 here); the dissipative map does not amplify it over the run, and a
/// contact decided at the round-off threshold moves a force by at most that threshold.
/// The measured differences are below 1e-12 (peaks) and 1e-13 (energies); a wrong force
/// in one step (a wrong stick/slip decision, a missed second-component term, a wrong
/// weight of b) moves peaks by 1e-4 or more.
const PEAK_REL: f64 = 1e-10;
const ENERGY_REL: f64 = 1e-10;

/// Runs `plan` on the banded step (at most `passes` active-set passes a step, `None`: the
/// default) and on the dense step.
fn both(plan: &Plan, passes: Option<u32>) -> (Outcome, BandedStats, Outcome) {
    let path = passes.map_or(StepPath::Banded, StepPath::BandedPasses);
    let (b, stats) = run_on_path(plan, path).unwrap();
    let (d, none) = run_on_path(plan, StepPath::Dense).unwrap();
    assert!(
        none.is_none(),
        "the dense path reports no banded statistics"
    );
    (b, stats.unwrap(), d)
}

/// Largest difference of two arrays over the larger of their largest value and `floor`.
fn rel_diff(a: &[f64], b: &[f64], floor: f64) -> f64 {
    let scale = a
        .iter()
        .chain(b)
        .fold(floor, |m, v| m.max(v.abs()))
        .max(1e-300);
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / scale)
        .fold(0.0, f64::max)
}

/// Every output of the two runs agrees ([`PEAK_REL`], [`ENERGY_REL`]); returns the largest
/// relative difference of the peaks seen (for the messages).
fn assert_agree(name: &str, b: &Outcome, d: &Outcome) -> f64 {
    let (rb, rd) = (&b.response, &d.response);
    assert_eq!(rb.steps, rd.steps, "{name}: steps");
    let (ib, id) = (rb.in_plan.as_ref().unwrap(), rd.in_plan.as_ref().unwrap());
    assert_eq!(
        (&ib.drifts, &ib.points, &ib.dampers, &ib.plastic),
        (&id.drifts, &id.points, &id.dampers, &id.plastic),
        "{name}: the measures' names"
    );
    // the torsional irregularity ratios: ratios of peaks, to the peaks' tolerance
    let flat = |i: &slipload_sim::response::InPlan| -> Vec<f64> {
        i.torsional_irregularity
            .iter()
            .flatten()
            .flat_map(|r| r.iter().copied())
            .collect()
    };
    let e = rel_diff(&flat(ib), &flat(id), 0.0);
    assert!(
        e <= 4.0 * PEAK_REL,
        "{name}: torsional ratios differ by {e:e}"
    );
    // the base's shears along x and y and its torque: the inertia forces' resultant
    let base = |i: &slipload_sim::response::InPlan| {
        i.peak_base
            .map(|b| vec![b.shear_x_n, b.shear_y_n, b.torque_nm])
            .unwrap_or_default()
    };
    let (bb, bd) = (base(ib), base(id));
    assert_eq!(bb.len(), 3, "{name}: base forces");
    for k in 0..3 {
        let e = (bb[k] - bd[k]).abs() / bd[k].abs().max(f64::MIN_POSITIVE);
        assert!(
            e <= PEAK_REL,
            "{name}: base force {k} differs by {e:e} ({} banded, {} dense)",
            bb[k],
            bd[k]
        );
    }
    let motion = rd.peak_displacement.iter().fold(0.0f64, |m, v| m.max(*v));
    let mut worst = 0.0f64;
    let plastic = (
        rb.peak_plastic_drift.clone().unwrap_or_default(),
        rd.peak_plastic_drift.clone().unwrap_or_default(),
    );
    for (what, x, y) in [
        ("peak_drift", &rb.peak_drift, &rd.peak_drift),
        (
            "peak_displacement",
            &rb.peak_displacement,
            &rd.peak_displacement,
        ),
        (
            "peak_abs_acceleration",
            &rb.peak_abs_acceleration,
            &rd.peak_abs_acceleration,
        ),
        ("peak_slip", &rb.peak_slip, &rd.peak_slip),
        ("residual_drift", &rb.residual_drift, &rd.residual_drift),
        ("peak_plastic_drift", &plastic.0, &plastic.1),
    ] {
        assert_eq!(x.len(), y.len(), "{name}: {what} lengths");
        let floor = if what == "peak_abs_acceleration" {
            0.0
        } else {
            motion
        };
        let e = rel_diff(x, y, floor);
        worst = worst.max(e);
        assert!(
            e <= PEAK_REL,
            "{name}: {what} differs by {e:e}: {x:?} vs {y:?}"
        );
    }
    let e = rel_diff(&[rb.peak_base_shear], &[rd.peak_base_shear], 0.0);
    assert!(e <= PEAK_REL, "{name}: base shear differs by {e:e}");
    // stick↔slip counts: a grazing contact may stick for one step on one path only
    let near = |p: u64, q: u64| p.abs_diff(q) <= 2u64.max(q / 100);
    for (i, (p, q)) in rb.transitions.iter().zip(&rd.transitions).enumerate() {
        assert!(near(*p, *q), "{name}: transitions[{i}] {p} vs {q}");
    }
    let (eb, ed) = (rb.energy.as_ref().unwrap(), rd.energy.as_ref().unwrap());
    let scale = ed.input.abs().max(1e-300);
    for (what, x, y) in [
        ("input", eb.input, ed.input),
        ("kinetic", eb.kinetic, ed.kinetic),
        ("strain", eb.strain, ed.strain),
        ("viscous", eb.viscous, ed.viscous),
        ("friction", eb.friction, ed.friction),
        (
            "plastic",
            eb.plastic.unwrap_or(0.0),
            ed.plastic.unwrap_or(0.0),
        ),
        ("balance", eb.balance_error, ed.balance_error),
    ] {
        assert!(
            (x - y).abs() <= ENERGY_REL * scale,
            "{name}: energy {what} {x} vs {y} (input {scale})"
        );
    }
    // per-damper demands, each kind against its largest over the dampers
    let (db, dd) = (rb.dampers.as_ref().unwrap(), rd.dampers.as_ref().unwrap());
    assert_eq!(db.len(), dd.len(), "{name}: dampers");
    for k in 0..8 {
        let xs: Vec<f64> = db.iter().map(|x| x.values()[k].1).collect();
        let ys: Vec<f64> = dd.iter().map(|x| x.values()[k].1).collect();
        let what = dd[0].values()[k].0;
        if what.contains("excursion") || what.contains("cycle") {
            // counts of slips: a grazing contact may add one on one path only
            for (x, y) in xs.iter().zip(&ys) {
                assert!(
                    (x - y).abs() <= 2f64.max(y.abs() / 100.0),
                    "{name}: damper {what} {x} vs {y}"
                );
            }
            continue;
        }
        let e = rel_diff(&xs, &ys, 0.0);
        assert!(e <= ENERGY_REL, "{name}: damper {what} differs by {e:e}");
    }
    worst
}

/// The outputs the comparisons read: energies and per-damper demands.
fn outputs() -> OutputsConfig {
    OutputsConfig {
        energies: true,
        dampers: true,
        ..OutputsConfig::default()
    }
}

/// A building in plan from its JSON text with its damping replaced by `damping`.
fn with_damping(text: &str, damping: serde_json::Value, anchor: &Path) -> FloorPlan {
    let mut v: serde_json::Value = serde_json::from_str(text).unwrap();
    v["damping"] = damping;
    let cfg: FloorPlanConfig = serde_json::from_value(v).unwrap();
    FloorPlan::from_config(&cfg, anchor).unwrap()
}

/// 2 % Rayleigh damping at the first and the sixth mode (the second set of x, y and
/// torsion modes), as a plan's `damping`.
fn rayleigh() -> serde_json::Value {
    serde_json::json!({"rayleigh": {"ratio": 0.02, "modes": [1, 6]}})
}

/// The ten-storey plan of `configs/plan-ten-story.json` with `damping`.
fn ten_storey(damping: serde_json::Value) -> FloorPlan {
    let path = configs().join("plan-ten-story.json");
    with_damping(&std::fs::read_to_string(&path).unwrap(), damping, &path)
}

/// The Newhall pair of `configs/plan-ten-story-pair.json` on the building `b` for
/// `duration` s (both components, or the first one alone at `angle` degrees).
fn newhall(b: FloorPlan, pair: bool, angle: f64, duration: f64) -> FloorPlanScene {
    let mut scene = FloorPlanScene::load(&configs().join("plan-ten-story-pair.json")).unwrap();
    assert_eq!(scene.ground.len(), 2);
    let dt = scene.method.dt;
    if !pair {
        scene.ground.truncate(1);
        scene.ground[0].angle = angle.to_radians();
    }
    scene.building = Arc::new(b);
    scene.duration = duration;
    scene.outputs = outputs();
    let mut s = FloorPlanScene::new(
        scene.building.clone(),
        scene.ground.clone(),
        duration,
        MethodName::Newmark,
        outputs(),
    );
    s.method.dt = dt;
    s
}

fn compile(scene: &FloorPlanScene) -> Plan {
    slipload_sim::floorplan::compile(scene).unwrap()
}

/// The ten-storey plan with Rayleigh damping has the half-bandwidth of rigid floors on
/// lines, 5; its dampers are massless elements between a line's points on two floors.
#[test]
fn the_ten_storey_plan_is_banded_with_rayleigh_damping() {
    let plan = compile(&newhall(ten_storey(rayleigh()), true, 0.0, 1.0));
    assert!(!plan.is_chain());
    assert_eq!(plan.dofs(), 30);
    assert_eq!(plan.half_bandwidth(), 5);
    assert!(plan.second.is_some());
    // with modal damping (as shipped) the operators are full: the dense step
    let modal = compile(&newhall(
        ten_storey(serde_json::json!({"modal": {"ratio": 0.02}})),
        true,
        0.0,
        1.0,
    ));
    assert_eq!(modal.half_bandwidth(), 29);
    assert!(run_on_path(&modal, StepPath::Auto).unwrap().1.is_none());
    let err = run_on_path(&modal, StepPath::Banded)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("half-bandwidth of at most 5 (this plan's is 29)"),
        "{err}"
    );
}

/// One component, oblique (it twists the plan and loads both directions' lines): the
/// banded step is the dense step; it ran banded, without the fallback, and refactorised
/// as the stuck set changed.
#[test]
fn ten_storey_plan_under_one_component() {
    let plan = compile(&newhall(ten_storey(rayleigh()), false, 30.0, 12.0));
    assert!(plan.second.is_none());
    let (b, stats, d) = both(&plan, None);
    let worst = assert_agree("ten storeys, one component at 30°", &b, &d);
    eprintln!("one component: largest peak difference {worst:e}, {stats:?}");
    assert_eq!(stats.fallbacks, 0, "{stats:?}");
    assert!(!stats.aligned);
    assert!(
        stats.factorizations > 10,
        "the stuck set changed: {stats:?}"
    );
    assert!(stats.passes >= b.response.steps as u64, "{stats:?}");
    let r = &b.response;
    assert!(r.peak_slip.iter().any(|s| *s > 1e-3), "the dampers slip");
    assert!(r.transitions.iter().any(|t| *t > 2), "and stick again");
    // the automatic choice takes the banded step (30 DOFs against a bandwidth of 5) and
    // gives its bits
    let (auto, s) = run_on_path(&plan, StepPath::Auto).unwrap();
    assert!(s.is_some(), "newmark chooses the banded step");
    assert_eq!(auto.response.peak_drift, b.response.peak_drift);
    let run = slipload_sim::run_plan(&plan).unwrap();
    assert_eq!(run.response.peak_drift, b.response.peak_drift);
}

/// Both components of the Newhall pair at once (the second component's load, its share of
/// the absolute accelerations and of the base shear along x, its input energy), with
/// Newmark and with HHT-α: the banded step is the dense step.
#[test]
fn ten_storey_plan_under_the_pair() {
    let scene = newhall(ten_storey(rayleigh()), true, 0.0, 20.0);
    let plan = compile(&scene);
    assert!(plan.second.is_some());
    let (b, stats, d) = both(&plan, None);
    let worst = assert_agree("ten storeys, the pair", &b, &d);
    eprintln!("pair: largest peak difference {worst:e}, {stats:?}");
    assert_eq!(stats.fallbacks, 0, "{stats:?}");
    assert!(stats.factorizations > 10, "{stats:?}");
    // the balance closes on the banded step (Newmark, α = 0)
    let e = b.response.energy.as_ref().unwrap();
    assert!(
        e.balance_error.abs() <= 1e-9 * e.input.abs(),
        "balance {} of input {}",
        e.balance_error,
        e.input
    );
    // HHT-α over the first 8 s
    let mut hht = scene.clone();
    hht.method.name = MethodName::Hht;
    hht.method.alpha = -0.05;
    hht.duration = 8.0;
    let plan = compile(&hht);
    let (b, stats, d) = both(&plan, None);
    assert_agree("ten storeys, the pair, HHT", &b, &d);
    assert_eq!(stats.fallbacks, 0, "{stats:?}");
}

/// A short, broadband ground motion (m/s², dt 0.01 s): decaying sines.
fn sines(pga: f64, (w1, w2, phase): (f64, f64, f64)) -> Arc<Record> {
    let dt = 0.01;
    let a: Vec<f64> = (0..400)
        .map(|i| {
            let t = i as f64 * dt;
            let env = (t / 0.5).min(1.0) * (-(t - 0.5).max(0.0) / 1.5).exp();
            env * ((w1 * t).sin() + 0.6 * (w2 * t + phase).sin() + 0.35 * (3.1 * t).sin())
        })
        .collect();
    let peak = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    Arc::new(Record::new("sines", dt, a.iter().map(|x| x * pga / peak).collect()).unwrap())
}

/// Three storeys, 20 m × 12 m: a stiff line A and a flexible line D along y (stiffness
/// eccentricity 27 % of the width), D's first storey yielding and a massless damper on
/// each of D's storeys (the second with a brace dashpot), two lines along x, the second
/// with a massless damper on its third storey; Rayleigh damping by its coefficients and
/// storey dashpots on line A; a named point at a corner.
const SMALL: &str = r#"{
  "name": "small asymmetric", "plan_size": [20, 12],
  "floors": [{"mass": "400 t"}, {"mass": "380 t"}, {"mass": "300 t"}],
  "storey_heights": [4.0, 3.5, 3.5],
  "damping": {"rayleigh": {"alpha": 0.3, "beta": 0.002}},
  "points": [{"name": "NE", "at": [20, 12]}],
  "lines": [
    {"name": "A", "direction": "y", "at": 0, "storey_stiffness": ["500 MN/m", "450 MN/m", "350 MN/m"],
     "storey_damping": ["1 MN*s/m", "0.8 MN*s/m", "0.6 MN*s/m"]},
    {"name": "D", "direction": "y", "at": 20, "storey_stiffness": ["150 MN/m", "130 MN/m", "100 MN/m"],
     "storey_yield": [{"storey": 1, "yield_drift": 0.006, "post_yield_ratio": 0.05}],
     "dissipators": [
       {"floor": 1, "brace_stiffness": "300 MN/m", "slip_load": "350 kN"},
       {"floor": 2, "brace_stiffness": "260 MN/m", "slip_load": "250 kN", "brace_damping": 2.0e5},
       {"floor": 3, "brace_stiffness": "200 MN/m", "slip_load": "150 kN"}
     ]},
    {"name": "1", "direction": "x", "at": 0, "storey_stiffness": ["300 MN/m", "280 MN/m", "220 MN/m"]},
    {"name": "2", "direction": "30", "through": [10, 12], "storey_stiffness": ["300 MN/m", "280 MN/m", "220 MN/m"],
     "dissipators": [{"floor": 3, "brace_stiffness": "250 MN/m", "slip_load": "120 kN"}]}
  ]
}"#;

/// The small plan under `components` (record, angle in degrees) at Δt = 2 ms.
fn small(components: &[(Arc<Record>, f64)], alpha: f64) -> Plan {
    let cfg: FloorPlanConfig = serde_json::from_str(SMALL).unwrap();
    let b = FloorPlan::from_config(&cfg, Path::new("small.json")).unwrap();
    let ground = components
        .iter()
        .map(|(record, a)| GroundComponent {
            record: record.clone(),
            angle: a.to_radians(),
        })
        .collect();
    let method = if alpha == 0.0 {
        MethodName::Newmark
    } else {
        MethodName::Hht
    };
    let mut scene = FloorPlanScene::new(
        Arc::new(b),
        ground,
        components[0].0.duration(),
        method,
        outputs(),
    );
    scene.method.dt = 0.002;
    scene.method.alpha = alpha;
    compile(&scene)
}

/// The small plan with a yielding line and slipping and sticking dampers, under one
/// component, under two, and with HHT-α: the banded step is the dense step; the line
/// yields and every damper slips and sticks again.
#[test]
fn a_small_plan_with_a_yielding_line_and_dampers() {
    let a = sines(3.5, (7.3, 17.1, 0.4));
    let b = sines(2.5, (5.1, 11.7, 1.0));
    for (name, comps, alpha) in [
        ("one component at 90°", vec![(a.clone(), 90.0)], 0.0),
        (
            "two components",
            vec![(a.clone(), 0.0), (b.clone(), 90.0)],
            0.0,
        ),
        (
            "two components, HHT",
            vec![(a.clone(), 20.0), (b, 110.0)],
            -0.1,
        ),
    ] {
        let plan = small(&comps, alpha);
        assert_eq!(plan.dofs(), 9);
        assert_eq!(plan.half_bandwidth(), 5);
        assert_eq!(plan.second.is_some(), comps.len() == 2);
        let (bo, stats, d) = both(&plan, None);
        let worst = assert_agree(name, &bo, &d);
        eprintln!("small plan, {name}: largest peak difference {worst:e}, {stats:?}");
        assert_eq!(stats.fallbacks, 0, "{name}: {stats:?}");
        let r = &bo.response;
        let plastic = r.peak_plastic_drift.as_ref().unwrap();
        assert!(plastic[0] > 1e-4, "{name}: line D yields: {plastic:?}");
        let dampers = r.dampers.as_ref().unwrap();
        assert_eq!(dampers.len(), 4);
        for (k, x) in dampers.iter().enumerate() {
            assert!(x.cumulative_travel_m > 1e-4, "{name}: damper {k} slips");
        }
        assert!(
            r.transitions.iter().filter(|t| **t >= 2).count() >= 3,
            "{name}: dampers stick again: {:?}",
            r.transitions
        );
    }
}

/// With one active-set pass a step, every step whose stick/slip pattern changes is
/// answered by the dense box QP on W: the same answer, to round-off.
#[test]
fn the_fallback_to_the_dense_box_qp_gives_the_same_answer() {
    let a = sines(3.5, (7.3, 17.1, 0.4));
    let b = sines(2.5, (5.1, 11.7, 1.0));
    let plan = small(&[(a, 0.0), (b, 90.0)], 0.0);
    let (bo, stats, d) = both(&plan, Some(1));
    assert!(stats.fallbacks > 10, "the fallback ran: {stats:?}");
    assert_agree("small plan, one pass a step", &bo, &d);
    let plan = compile(&newhall(ten_storey(rayleigh()), true, 0.0, 6.0));
    let (bo, stats, d) = both(&plan, Some(1));
    assert!(stats.fallbacks > 10, "the fallback ran: {stats:?}");
    assert_agree("ten storeys, one pass a step", &bo, &d);
}

/// Dampers with mass add DOFs after the floors' (not banded): such a plan, and one asking
/// for histories, takes the dense step, and forcing the banded step is refused; a plan of
/// fewer than twelve DOFs takes the dense step by itself.
#[test]
fn plans_the_banded_step_cannot_run_stay_dense() {
    let text = SMALL.replace(
        r#""slip_load": "150 kN"}"#,
        r#""slip_load": "150 kN", "mass": 800}"#,
    );
    let cfg: FloorPlanConfig = serde_json::from_str(&text).unwrap();
    let b = FloorPlan::from_config(&cfg, Path::new("small.json")).unwrap();
    let a = sines(3.5, (7.3, 17.1, 0.4));
    let ground = vec![GroundComponent {
        record: a.clone(),
        angle: 0.0,
    }];
    let scene = FloorPlanScene::new(Arc::new(b), ground, 1.0, MethodName::Newmark, outputs());
    let plan = compile(&scene);
    assert_eq!(plan.dofs(), 10);
    assert!(run_on_path(&plan, StepPath::Auto).unwrap().1.is_none());
    assert!(run_on_path(&plan, StepPath::Banded).is_err());
    // below twelve DOFs (2 (p + 1)) a plan keeps the dense step by itself
    let three = small(&[(a.clone(), 0.0)], 0.0);
    assert_eq!(three.dofs(), 9);
    assert!(run_on_path(&three, StepPath::Auto).unwrap().1.is_none());
    let mut hist = small(&[(a, 0.0)], 0.0);
    hist.outputs.histories = true;
    assert!(run_on_path(&hist, StepPath::Banded).is_err());
}
