//! Contract: a suite's `pairs` says how a planar model runs a pair of horizontal
//! components: `components` (each component a run, as without the key), `angles` (the pair
//! rotated to θ = 0, s, …, < 180°, a_θ = a₁ cos θ + a₂ sin θ, each orientation a run) or
//! `worst` (every orientation run, each response its largest over them: one run per
//! pair). The grid's step divides 90°, so 0° and 90° are the recorded components to the
//! bit; half a turn suffices because the response to −a mirrors the response to a. The
//! report says which; a pair counts as one ground motion in the allowance of
//! unacceptable responses; bad keys are refused naming their field.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::eval::evaluate::{DesignLoads, design_scene_of, run_one};
use slipload_opt::model::fidelity::Fidelity;
use std::path::Path;
use std::sync::Arc;

/// Two short events with both components (records/README.md): Sylmar 090/360 and
/// Landers Yermo 270/360, 40 s and 44 s at 0.02 s.
const PAIRS: &str = r#"["records/SYL090.AT2", "records/SYL360.AT2"],
    ["records/RSN900_LANDERS_YER270.AT2", "records/pairs/RSN900_LANDERS_YER360.AT2"]"#;

fn study(pairs: &str, scale: &str, limits: &str) -> Result<Study, slipload_opt::OptError> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = format!(
        r#"{{ "building": "configs/benchmark-3story.json",
  "suites": [ {{ "name": "pairs", "records": [{PAIRS}], "units": "g"{scale}{pairs}{limits} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    Study::from_json(&text, &root.join("study.json"))
}

fn message(e: slipload_opt::OptError) -> String {
    e.to_string()
}

#[test]
fn components_explicit_or_at_a_quarter_turn_are_the_recorded_components_to_the_bit() {
    let plain = study("", "", "").unwrap();
    let named = study(r#", "pairs": { "run": "components" }"#, "", "").unwrap();
    let quarter = study(r#", "pairs": { "run": "angles", "step_deg": 90 }"#, "", "").unwrap();
    assert_eq!(plain.records.len(), 4);
    for st in [&named, &quarter] {
        assert_eq!(st.records.len(), 4);
        for (a, b) in plain.records.iter().zip(&st.records) {
            assert_eq!(a.samples(), b.samples());
            assert_eq!(a.dt(), b.dt());
        }
    }
    assert!(plain.suites[0].pair_run.is_none());
    // the report says which
    assert!(
        quarter.suites[0]
            .pair_run
            .as_deref()
            .unwrap()
            .contains("2 orientations (0°, 90°)")
    );
    assert_eq!(quarter.suites[0].motions(), 2);
}

#[test]
fn the_response_to_the_opposite_orientation_is_the_mirror() {
    // what lets the grid stop at half a turn: every peak of −a is the peak of a
    let st = study("", "", "").unwrap();
    let design = DesignLoads::from(vec![300e3, 250e3, 150e3]);
    let fid = Fidelity::sweep(&st);
    let a = &st.records[0];
    let neg = Arc::new(a.try_scaled(-1.0).unwrap());
    let run = |r: &Arc<slipload_motion::Record>| {
        let scene = design_scene_of(&st, &design, 0, r, &fid, "mirror");
        slipload_sim::run_plan(&slipload_sim::Plan::compile(&scene).unwrap()).unwrap()
    };
    let (p, q) = (run(a), run(&neg));
    let (rp, rq) = (&p.response, &q.response);
    // the integrators are odd in the load: equal to round-off of the peaks
    for (x, y) in rp.peak_drift.iter().zip(&rq.peak_drift) {
        assert!((x - y).abs() <= 1e-12 * x.abs().max(1e-30), "{x} vs {y}");
    }
    for (x, y) in rp.peak_slip.iter().zip(&rq.peak_slip) {
        assert!((x - y).abs() <= 1e-12 * x.abs().max(1e-30), "{x} vs {y}");
    }
    assert!((rp.peak_base_shear - rq.peak_base_shear).abs() <= 1e-12 * rp.peak_base_shear);
}

#[test]
fn worst_is_each_responses_largest_over_the_angles_runs() {
    let angles = study(r#", "pairs": { "run": "angles", "step_deg": 45 }"#, "", "").unwrap();
    let worst = study(r#", "pairs": { "run": "worst", "step_deg": 45 }"#, "", "").unwrap();
    // four orientations a pair: four runs each, or one run each
    assert_eq!(angles.records.len(), 8);
    assert_eq!(worst.records.len(), 2);
    assert_eq!(worst.orientations[0].len(), 4);
    assert!(
        worst.records[0]
            .name()
            .ends_with("(worst of 4 orientations)")
    );
    assert_eq!(angles.suites[0].motions(), 2);
    assert_eq!(worst.suites[0].motions(), 2);
    // the 45° orientation is the two components' sum over √2
    let r45 = &angles.records[1];
    let (a, b) = (angles.records[0].samples(), angles.records[2].samples());
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for (j, v) in r45.samples().iter().enumerate() {
        assert!((v - (a[j] + b[j]) * h).abs() <= 1e-15 * (a[j].abs() + b[j].abs() + 1e-30));
    }
    let design = vec![300e3, 250e3, 150e3];
    let fid = Fidelity::sweep(&worst);
    for p in 0..2 {
        let runs: Vec<_> = (0..4)
            .map(|k| run_one(&angles, &design, 4 * p + k, &fid, "angles").unwrap())
            .collect();
        let env = run_one(&worst, &design, p, &fid, "worst").unwrap();
        for s in 0..3 {
            let most = runs.iter().map(|m| m.drift_ratio[s]).fold(0.0, f64::max);
            assert_eq!(env.drift_ratio[s], most);
            let most = runs
                .iter()
                .map(|m| m.residual_drift_ratio[s])
                .fold(0.0, f64::max);
            assert_eq!(env.residual_drift_ratio[s], most);
            let most = runs.iter().map(|m| m.stroke[s]).fold(0.0, f64::max);
            assert_eq!(env.stroke[s], most);
        }
        let most = runs.iter().map(|m| m.peak_base_shear).fold(0.0, f64::max);
        assert_eq!(env.peak_base_shear, most);
        let most = runs
            .iter()
            .map(|m| m.peak_floor_acceleration)
            .fold(0.0, f64::max);
        assert_eq!(env.peak_floor_acceleration, most);
        // and the orientations differ: the envelope is not one of them throughout
        assert!(runs.iter().any(|m| m.drift_ratio != runs[0].drift_ratio));
    }
}

#[test]
fn bad_pair_keys_are_refused_naming_their_field() {
    let e =
        message(study(r#", "pairs": { "run": "angles", "step_deg": 25 }"#, "", "").unwrap_err());
    assert!(
        e.contains("suites[0].pairs.step_deg") && e.contains("divides 90"),
        "{e}"
    );
    let e = message(study(r#", "pairs": { "run": "diagonal" }"#, "", "").unwrap_err());
    assert!(
        e.contains("suites[0].pairs.run") && e.contains("worst"),
        "{e}"
    );
    let e = message(
        study(
            r#", "pairs": { "run": "components", "step_deg": 30 }"#,
            "",
            "",
        )
        .unwrap_err(),
    );
    assert!(e.contains("suites[0].pairs.step_deg"), "{e}");
    let e = message(
        study(
            r#", "pairs": { "run": "worst" }"#,
            r#", "scale": { "pga_g": 0.4 }"#,
            "",
        )
        .unwrap_err(),
    );
    assert!(
        e.contains("suites[0].scale") && e.contains("one factor"),
        "{e}"
    );
    // a factor scales both components alike: accepted, and the runs carry it
    let st = study(
        r#", "pairs": { "run": "angles", "step_deg": 90 }"#,
        r#", "scale": { "factor": 1.5 }"#,
        "",
    )
    .unwrap();
    assert!(
        st.records
            .iter()
            .all(|r| (r.scale_factor() - 1.5).abs() < 1e-15)
    );
}

#[test]
fn a_suite_that_says_how_pairs_run_must_name_a_pair() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = r#"{ "building": "configs/benchmark-3story.json",
  "suites": [ { "name": "single", "records": ["records/SYL090.AT2"], "units": "g",
                "pairs": { "run": "worst" } } ],
  "space": { "free": { "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] } },
  "objective": { "terms": [ { "metric": "peak_drift_ratio", "statistic": "mean" } ] },
  "fidelity": { "method": "newmark" },
  "sweep": { "sampler": "halton", "points": 2, "seed": 5 } }"#;
    let e = message(Study::from_json(text, &root.join("study.json")).unwrap_err());
    assert!(
        e.contains("suites[0].pairs") && e.contains("names no pair"),
        "{e}"
    );
}

#[test]
fn a_worst_pair_reruns_one_orientation_by_name_and_refuses_its_envelope() {
    use slipload_opt::pipeline::{DesignRun, design_run_scene};
    let st = study(r#", "pairs": { "run": "worst", "step_deg": 45 }"#, "", "").unwrap();
    let dir = std::env::temp_dir().join(format!("slipload-orient-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("candidates.json");
    std::fs::write(
        &file,
        r#"[{"name": "d", "slip_loads_kn": [300, 250, 150]}]"#,
    )
    .unwrap();
    let pair = st.orientations[0][1].name().to_string();
    assert!(pair.ends_with("@45deg"), "{pair}");
    fn req<'a>(file: &'a Path, run: &'a str) -> DesignRun<'a> {
        DesignRun {
            designs: file,
            design: "d",
            run,
            suite: None,
            method: None,
        }
    }
    let scene = design_run_scene(&st, &req(&file, &pair)).unwrap();
    let rec = scene.record.as_ref().unwrap();
    assert_eq!(rec.name(), pair);
    assert_eq!(rec.samples(), st.orientations[0][1].samples());
    // the pair's own run is the envelope of four: refused, naming them
    let e = design_run_scene(&st, &req(&file, st.records[0].name()))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("envelope of 4 runs") && e.contains("@135deg"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
