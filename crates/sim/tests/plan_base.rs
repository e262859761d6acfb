//! A building in plan's base forces (shear along x and y, torque about the centre of
//! mass), its lines' storey dashpots, its named points and its scaling periods.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_motion::Record;
use slipload_sim::floorplan::{FloorPlan, FloorPlanConfig, FloorPlanScene, GroundComponent};
use slipload_sim::scene::OutputsConfig;
use slipload_sim::{MethodName, run_plan};
use std::path::Path;
use std::sync::Arc;

mod common;
use common::{floor_plan, rel};

fn motion(pga: f64, phase: f64) -> Arc<Record> {
    common::decaying_sines(pga, phase)
}

fn run(
    b: &FloorPlan,
    components: &[(Arc<Record>, f64)],
    method: MethodName,
    outputs: OutputsConfig,
) -> (
    slipload_sim::scene::MethodSettings,
    slipload_sim::response::Outcome,
) {
    let mut scene = FloorPlanScene::new(
        Arc::new(b.clone()),
        components
            .iter()
            .map(|(record, deg)| GroundComponent {
                record: record.clone(),
                angle: deg.to_radians(),
            })
            .collect(),
        components[0].0.duration(),
        method,
        outputs,
    );
    scene.method.dt = 0.002;
    let plan = slipload_sim::floorplan::compile(&scene).unwrap();
    (plan.method, run_plan(&plan).unwrap())
}

/// A run of `b` under `components` that keeps its history.
fn with_history(
    b: &FloorPlan,
    components: &[(Arc<Record>, f64)],
    method: MethodName,
) -> slipload_sim::response::Outcome {
    let outputs = OutputsConfig {
        histories: true,
        ..OutputsConfig::default()
    };
    run(b, components, method, outputs).1
}

/// Eccentric masses, a line at 30°, massless dampers slipping on two lines, a yielding
/// storey; no frame damping, so the base's reaction is the first storey's elements'
/// forces alone.
const ECCENTRIC: &str = r#"{
  "name": "eccentric", "plan_size": [20, 12],
  "floors": [
    {"mass": "400 t", "centre_of_mass": [12.0, 7.0]},
    {"mass": "380 t", "centre_of_mass": [11.0, 6.5]},
    {"mass": "300 t", "centre_of_mass": [13.0, 5.0]}
  ],
  "storey_heights": [4.0, 3.5, 3.5],
  "lines": [
    {"name": "A", "direction": "y", "at": 0, "storey_stiffness": ["500 MN/m", "450 MN/m", "350 MN/m"]},
    {"name": "D", "direction": "y", "at": 20, "storey_stiffness": ["150 MN/m", "130 MN/m", "100 MN/m"],
     "storey_yield": [{"storey": 1, "yield_drift": 0.004, "post_yield_ratio": 0.05}],
     "dissipators": [
       {"floor": 1, "brace_stiffness": "300 MN/m", "slip_load": "300 kN"},
       {"floor": 2, "brace_stiffness": "260 MN/m", "slip_load": "250 kN"}
     ]},
    {"name": "1", "direction": "x", "at": 0, "storey_stiffness": ["300 MN/m", "280 MN/m", "220 MN/m"]},
    {"name": "2", "direction": "x", "at": 12, "storey_stiffness": ["200 MN/m", "180 MN/m", "150 MN/m"]},
    {"name": "R", "direction": 30, "through": [10, 6], "storey_stiffness": ["100 MN/m", "90 MN/m", "80 MN/m"],
     "dissipators": [{"floor": 1, "brace_stiffness": "200 MN/m", "slip_load": "200 kN"}]}
  ]
}"#;

#[test]
fn the_base_forces_are_the_first_storeys_element_forces_resolved_on_x_y_and_the_centre_of_mass() {
    // Without frame damping, M(a + r a_g) = −(K u + B F): a rigid motion e of the base
    // sees only the first storey's elements (every higher storey's two ends move with
    // it), so the base's shear along x and y and torque about the building's centre of
    // mass P at each step are Σ over the lines of (c, s, lever about P) × (elastic force
    // + damper force + plastic force) of storey 1, from the history's drifts and forces:
    // an independent sum of
    // the same numbers; round-off (1e-9 of the peak) is all that separates them.
    let b = floor_plan(ECCENTRIC);
    let components = [(motion(4.0, 0.0), 20.0), (motion(3.0, 1.1), 110.0)];
    for method in [MethodName::Newmark, MethodName::Exact] {
        let out = with_history(&b, &components, method);
        let h = out.history.as_ref().unwrap();
        let r = &out.response;
        let base = r.in_plan.as_ref().unwrap().peak_base.unwrap();
        let mut peaks = [0.0f64; 3];
        let rows = h.rows.len() / h.columns.len();
        let col = |name: &str| h.column(name);
        let mut sums = vec![[0.0; 3]; rows];
        // the lever of a line about the building's centre of mass P
        let total: f64 = b.floors.iter().map(|f| f.mass).sum();
        let p = [0, 1].map(|k| b.floors.iter().map(|f| f.mass * f.centre[k]).sum::<f64>() / total);
        assert_eq!(base.torque_about_m, p);
        for line in &b.lines {
            let [c, s, lever] = line.weights();
            let w = [c, s, lever - (p[0] * s - p[1] * c)];
            let drift = col(&format!("drift_{}/1_m", line.name)).unwrap();
            let mut k = line.stiffness[0];
            let mut forces: Vec<Vec<f64>> = Vec::new();
            if let Some(y) = line.storey_yield[0] {
                k -= (1.0 - y.post_yield_ratio) * y.stiffness;
                forces.push(col(&format!("Fp_{}/1_N", line.name)).unwrap());
            }
            if line.dissipators[0].is_some() {
                forces.push(col(&format!("F_{}/1_N", line.name)).unwrap());
            }
            for (i, s) in sums.iter_mut().enumerate() {
                let f = k * drift[i] + forces.iter().map(|c| c[i]).sum::<f64>();
                for j in 0..3 {
                    s[j] += w[j] * f;
                }
            }
        }
        for s in &sums {
            for j in 0..3 {
                peaks[j] = peaks[j].max(s[j].abs());
            }
        }
        let got = [base.shear_x_n, base.shear_y_n, base.torque_nm];
        for j in 0..3 {
            assert!(
                rel(got[j], peaks[j]) < 1e-9,
                "{method:?} base force {j}: {} from the inertia forces, {} from the first storey",
                got[j],
                peaks[j]
            );
        }
        // an eccentric plan under both components: real shears both ways and a torque
        // that is not round-off (a lever of metres on meganewtons)
        assert!(base.shear_x_n > 1e5 && base.shear_y_n > 1e5, "{base:?}");
        assert!(
            base.torque_nm > 1.0 * base.shear_x_n.min(base.shear_y_n),
            "{base:?}"
        );
        // the dampers and the yielding storey took part
        assert!(r.peak_slip.iter().any(|s| *s > 1e-4), "{:?}", r.peak_slip);
        assert!(r.peak_plastic_drift.as_ref().unwrap()[0] > 0.0);
    }
}

/// The chain: three storeys, massless dampers, storey dashpots.
const CHAIN: &str = r#"{
  "name": "chain", "floor_masses": [400000, 380000, 300000],
  "storey_stiffness": [3.0e8, 2.6e8, 2.0e8], "storey_heights": [4.0, 3.5, 3.5],
  "damping": {"storey": ["1.2 MN*s/m", "0.9 MN*s/m", "600 kN*s/m"]},
  "dissipators": [
    {"floor": 1, "brace_stiffness": 4.0e8, "slip_load": 4.0e5},
    {"floor": 3, "brace_stiffness": 3.0e8, "slip_load": 2.0e5}
  ]
}"#;

/// The chain as line X of a plan through the centre of mass, its storey dashpots the
/// line's.
const PLANAR: &str = r#"{
  "name": "planar in plan",
  "floors": [
    {"mass": 400000, "inertia_kg_m2": 2.0e7, "centre_of_mass": [0, 0]},
    {"mass": 380000, "inertia_kg_m2": 1.9e7, "centre_of_mass": [0, 0]},
    {"mass": 300000, "inertia_kg_m2": 1.5e7, "centre_of_mass": [0, 0]}
  ],
  "storey_heights": [4.0, 3.5, 3.5],
  "lines": [
    {"name": "X", "direction": "x", "at": 0,
     "storey_stiffness": [3.0e8, 2.6e8, 2.0e8],
     "storey_damping": ["1.2 MN*s/m", "0.9 MN*s/m", "600 kN*s/m"],
     "dissipators": [
       {"floor": 1, "brace_stiffness": 4.0e8, "slip_load": 4.0e5},
       {"floor": 3, "brace_stiffness": 3.0e8, "slip_load": 2.0e5}
     ]},
    {"name": "Y1", "direction": "y", "at": -8, "storey_stiffness": [2.0e8, 2.0e8, 2.0e8]},
    {"name": "Y2", "direction": "y", "at": 8, "storey_stiffness": [2.0e8, 2.0e8, 2.0e8]}
  ]
}"#;

#[test]
fn a_lines_storey_dashpots_are_the_chains_storey_damping() {
    // The chain's storey dashpots written on the line: the plan's x block holds the
    // chain's C as it holds its K, so the runs agree to round-off carried through the
    // stick–slip decisions (1e-9, the chain-as-plan tolerance), energies included.
    let record = motion(3.0, 0.0);
    let plan_b = floor_plan(PLANAR);
    let cfg: slipload_sim::BuildingConfig = serde_json::from_str(CHAIN).unwrap();
    let chain_b = slipload_sim::Building::from_config(&cfg, Path::new("chain.json")).unwrap();
    let outputs = OutputsConfig {
        energies: true,
        ..OutputsConfig::default()
    };
    for method in [MethodName::Exact, MethodName::Newmark] {
        let (settings, out) = run(&plan_b, &[(record.clone(), 0.0)], method, outputs);
        let p = out.response;
        let mut settings = settings;
        settings.dt = 0.002;
        let c = common::chain_response(&chain_b, &record, settings, outputs);
        let names = &p.in_plan.as_ref().unwrap().drifts;
        for s in 0..3 {
            let k = names
                .iter()
                .position(|d| *d == format!("X/{}", s + 1))
                .unwrap();
            assert!(
                rel(p.peak_drift[k], c.peak_drift[s]) < 1e-9,
                "{method:?} storey {}: {} in plan, {} as a chain",
                s + 1,
                p.peak_drift[k],
                c.peak_drift[s]
            );
        }
        let (pe, ce) = (p.energy.unwrap(), c.energy.unwrap());
        assert!(
            rel(pe.viscous, ce.viscous) < 1e-9 && ce.viscous > 0.05 * ce.input,
            "{method:?} viscous {} in plan, {} as a chain (input {})",
            pe.viscous,
            ce.viscous,
            ce.input
        );
        assert!(rel(pe.friction, ce.friction) < 1e-9);
        let base = p.in_plan.as_ref().unwrap().peak_base.unwrap();
        assert!(rel(base.shear_x_n, c.peak_base_shear) < 1e-9, "{method:?}");
        assert!(
            rel(p.peak_base_shear, c.peak_base_shear) < 1e-9,
            "{method:?}"
        );
        // the chain lies on the x axis through the centre of mass: no shear across, no
        // torque
        assert!(base.shear_y_n <= 1e-12 * base.shear_x_n, "{base:?}");
        assert!(base.torque_nm <= 1e-12 * base.shear_x_n, "{base:?}");
    }
}

#[test]
fn a_lines_storey_damping_is_checked_by_field() {
    let err = |replace: (&str, &str)| {
        let json = PLANAR.replacen(replace.0, replace.1, 1);
        let cfg: FloorPlanConfig = serde_json::from_str(&json).unwrap();
        FloorPlan::from_config(&cfg, Path::new("plan.json"))
            .unwrap_err()
            .to_string()
    };
    let e = err((r#""600 kN*s/m""#, r#"-5"#));
    assert!(
        e.contains("plan.json") && e.contains("lines[0].storey_damping[2]") && e.contains("≥ 0"),
        "{e}"
    );
    let e = err((r#", "600 kN*s/m""#, ""));
    assert!(
        e.contains("lines[0].storey_damping") && e.contains("expected 3"),
        "{e}"
    );
}

#[test]
fn a_named_point_moves_with_its_floor_as_a_rigid_body() {
    // A point (x, y) of a rigid floor moves by (u_x − (y − y_c)θ, u_y + (x − x_c)θ) from
    // its centre of mass's motion: from the history's centre-of-mass columns, the peaks
    // of a corner agree to round-off (1e-9 of the peak); a point placed on floor 1's
    // centre of mass is that centre's measure, the same arithmetic (1e-12), under both
    // components at once (each component's influence on the point by its direction).
    let json = ECCENTRIC.replacen(
        r#""storey_heights""#,
        r#""points": [{"name": "NE", "at": [20, 12]}, {"name": "c1", "at": ["12 m", "7 m"]}],
  "storey_heights""#,
        1,
    );
    let b = floor_plan(&json);
    let components = [(motion(4.0, 0.0), 20.0), (motion(3.0, 1.1), 110.0)];
    for method in [MethodName::Newmark, MethodName::Exact] {
        let out = with_history(&b, &components, method);
        let (r, h) = (&out.response, out.history.as_ref().unwrap());
        let names = &r.in_plan.as_ref().unwrap().points;
        assert_eq!(names.len(), 3 * 3 + 2 * 2 * 3, "{names:?}");
        let at = |name: &str| names.iter().position(|p| p == name).unwrap();
        for (axis, k) in [("x", 0), ("y", 1)] {
            let (c, p) = (at(&format!("1 {axis}")), at(&format!("1 c1 {axis}")));
            assert!(rel(r.peak_displacement[p], r.peak_displacement[c]) < 1e-12);
            assert!(
                rel(r.peak_abs_acceleration[p], r.peak_abs_acceleration[c]) < 1e-12,
                "{method:?} {axis}"
            );
            for (f, fl) in b.floors.iter().enumerate() {
                let col = |q: &str| h.column(&format!("x_{}_{q}", f + 1)).unwrap();
                let (u, rot) = (col(&format!("{axis}_m")), col("rot_rad"));
                let lever = if k == 0 {
                    -(12.0 - fl.centre[1])
                } else {
                    20.0 - fl.centre[0]
                };
                let want = u
                    .iter()
                    .zip(&rot)
                    .map(|(u, t)| (u + lever * t).abs())
                    .fold(0.0, f64::max);
                let got = r.peak_displacement[at(&format!("{} NE {axis}", f + 1))];
                assert!(
                    rel(got, want) < 1e-9,
                    "{method:?} floor {} NE {axis}: {got} vs {want}",
                    f + 1
                );
                // the corner of a twisting floor is not its centre
                let centre = r.peak_displacement[at(&format!("{} {axis}", f + 1))];
                assert!(rel(got, centre) > 1e-3, "{got} vs {centre}");
            }
        }
    }
    // names are checked by field
    let dup = json.replacen(r#""name": "c1""#, r#""name": "NE""#, 1);
    let cfg: FloorPlanConfig = serde_json::from_str(&dup).unwrap();
    let e = FloorPlan::from_config(&cfg, Path::new("plan.json"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("points[1].name") && e.contains("already"), "{e}");
}

#[test]
fn a_planar_building_in_plan_has_the_chains_scaling_periods_along_its_line() {
    // The chain as line X of a plan whose y lines are far stiffer: x holds the longer
    // first-mode period bare and the braced plan's shorter one is y's unless x's is; the
    // x block is the chain's, so T₁ bare equals the chain's (eigensolver round-off,
    // 1e-9), and the 90 %-mass period, the shorter over both directions, is at most the
    // chain's.
    let cfg: slipload_sim::BuildingConfig = serde_json::from_str(CHAIN).unwrap();
    let chain = slipload_sim::Building::from_config(&cfg, Path::new("chain.json"))
        .unwrap()
        .scaling_periods()
        .unwrap();
    let plan = floor_plan(&PLANAR.replace("2.0e8, 2.0e8, 2.0e8", "2.0e10, 2.0e10, 2.0e10"))
        .scaling_periods()
        .unwrap();
    assert!(
        rel(plan.bare_t1_s, chain.bare_t1_s) < 1e-9,
        "{plan:?} {chain:?}"
    );
    assert!(plan.stuck_t1_s <= chain.stuck_t1_s * (1.0 + 1e-9));
    assert!(plan.mass_90_period_s <= chain.mass_90_period_s * (1.0 + 1e-9));
    assert!(plan.stuck_t1_s < plan.bare_t1_s);
}

#[test]
fn the_secant_periods_of_a_one_storey_plan_have_their_closed_forms() {
    // Symmetric about its centre of mass, so x, y and the twist are uncoupled: along x two
    // lines each with a damper (1 MN on a 1000 MN/m brace) that slips at 50 mm (its brace
    // would carry 50 MN), adding F/δ each; along y two lines yielding at 10 mm (2 MN,
    // 10 % after), at 50 mm each at its secant 2.8 MN / 50 mm. Eigensolver round-off:
    // 1e-12.
    let b = floor_plan(
        r#"{
      "floors": [{"mass": 500000, "inertia_kg_m2": 3.0e7, "centre_of_mass": [0, 0]}],
      "storey_heights": [4.0],
      "lines": [
        {"name": "X1", "direction": "x", "at": -5, "storey_stiffness": [1.5e8],
         "dissipators": [{"floor": 1, "brace_stiffness": 1.0e9, "slip_load": 1.0e6}]},
        {"name": "X2", "direction": "x", "at": 5, "storey_stiffness": [1.5e8],
         "dissipators": [{"floor": 1, "brace_stiffness": 1.0e9, "slip_load": 1.0e6}]},
        {"name": "Y1", "direction": "y", "at": -9, "storey_stiffness": [2.0e8],
         "storey_yield": [{"storey": 1, "yield_drift": "10 mm", "post_yield_ratio": 0.1}]},
        {"name": "Y2", "direction": "y", "at": 9, "storey_stiffness": [2.0e8],
         "storey_yield": [{"storey": 1, "yield_drift": "10 mm", "post_yield_ratio": 0.1}]}
      ]
    }"#,
    );
    let period = |k: f64| 2.0 * std::f64::consts::PI * (5e5 / k).sqrt();
    let drift = vec![vec![Some(0.05)]; 4];
    let force = vec![vec![1e6]; 4];
    let [tx, ty] = b.secant_periods(&drift, &force).unwrap();
    assert!(rel(tx, period(3.0e8 + 2.0 * 1e6 / 0.05)) < 1e-12, "{tx}");
    assert!(rel(ty, period(2.0 * 2.8e6 / 0.05)) < 1e-12, "{ty}");
    // a slip load the brace does not reach: stuck, the brace in parallel
    let stuck = vec![vec![1e8]; 4];
    let [tx, _] = b.secant_periods(&drift, &stuck).unwrap();
    assert!(rel(tx, period(3.0e8 + 2.0e9)) < 1e-12, "{tx}");
    // no drift: the initial stiffnesses
    let [tx, ty] = b.secant_periods(&vec![vec![None]; 4], &force).unwrap();
    assert!(rel(tx, period(3.0e8)) < 1e-12 && rel(ty, period(4.0e8)) < 1e-12);
}

#[test]
fn a_plans_history_csv_keeps_a_name_with_a_comma_in_one_column() {
    // names come from the file: a comma or a quote in one is quoted, not a new column
    let b = floor_plan(&ECCENTRIC.replacen(r#""name": "A""#, r#""name": "A, \"west\"""#, 1));
    let out = with_history(&b, &[(motion(1.0, 0.0), 0.0)], MethodName::Newmark);
    let h = out.history.unwrap();
    let csv = h.to_csv();
    let header = csv.lines().next().unwrap();
    assert!(header.contains(r#""drift_A,_""west""/1_m""#), "{header}");
    let data_fields = csv.lines().nth(1).unwrap().split(',').count();
    assert_eq!(data_fields, h.columns.len());
    // outside the quotes the header has one comma fewer than columns
    let mut quoted = false;
    let commas = header
        .chars()
        .filter(|c| {
            if *c == '"' {
                quoted = !quoted;
            }
            *c == ',' && !quoted
        })
        .count();
    assert_eq!(commas + 1, h.columns.len(), "{header}");
}
