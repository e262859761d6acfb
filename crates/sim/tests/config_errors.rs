//! Bad buildings and scenes give clear errors that name the field and what was expected.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_sim::{Scene, SceneOverrides};

fn error_of(json: &str) -> String {
    match Scene::from_json(
        json,
        &configs().join("bad.json"),
        &SceneOverrides {
            duration: Some(1.0),
            ..Default::default()
        },
    ) {
        Ok(_) => panic!("accepted a bad config: {json}"),
        Err(e) => e.to_string(),
    }
}

const OK_FLOOR: &str = r#""floor_masses": [1000], "storey_stiffness": [1e5]"#;

#[test]
fn each_validation_names_its_field() {
    let cases: &[(String, &[&str])] = &[
        (
            r#"{ "floor_masses": [1000], "storey_stifness": [1e5] }"#.into(),
            &["bad.json", "unknown field `storey_stifness`", "line"],
        ),
        (
            r#"{ "floor_masses": [-1], "storey_stiffness": [1e5] }"#.into(),
            &["floor_masses[0]", "positive"],
        ),
        (
            r#"{ "floor_masses": [1000, 1000], "storey_stiffness": [1e5] }"#.into(),
            &["storey_stiffness", "expected 2"],
        ),
        (
            r#"{ "floor_masses": [1000], "storey_stiffness": ["1e5 kN"] }"#.into(),
            &["stiffness", "kN"],
        ),
        (
            r#"{ "mass_matrix": [[1, 0], [0.5, 1]], "storey_stiffness": [1, 1] }"#.into(),
            &["mass_matrix[1][0]", "symmetric"],
        ),
        (
            r#"{ "mass_matrix": [[1, 2], [2, 1]], "storey_stiffness": [1, 1] }"#.into(),
            &["mass_matrix", "positive definite"],
        ),
        (
            r#"{ "floor_masses": [1, 1], "stiffness_matrix": [[1, 2], [2, 1]] }"#.into(),
            &["stiffness_matrix", "positive definite"],
        ),
        (
            format!(
                r#"{{ {OK_FLOOR}, "damping": {{ "rayleigh": {{ "alpha": -1, "beta": 0 }} }} }}"#
            ),
            &["damping.rayleigh.alpha"],
        ),
        (
            format!(r#"{{ {OK_FLOOR}, "damping": {{ "modal": {{ "ratio": 1.5 }} }} }}"#),
            &["damping.modal", "[0, 1)"],
        ),
        (
            format!(r#"{{ {OK_FLOOR}, "storey_heights": [0] }}"#),
            &["storey_heights[0]"],
        ),
        (
            format!(
                r#"{{ {OK_FLOOR}, "dissipators": [{{ "floor": 2, "brace_stiffness": 1e6, "slip_load": 1 }}] }}"#
            ),
            &["dissipators[0].floor", "from 1 to 1"],
        ),
        (
            format!(
                r#"{{ {OK_FLOOR}, "dissipators": [{{ "floor": 1, "brace_stiffness": 0, "slip_load": 1 }}] }}"#
            ),
            &["dissipators[0].brace_stiffness", "positive"],
        ),
        (
            format!(
                r#"{{ {OK_FLOOR}, "dissipators": [{{ "floor": 1, "brace_stiffness": 1e6, "mass": -1, "slip_load": 1 }}] }}"#
            ),
            &["dissipators[0].mass"],
        ),
        (
            format!(
                r#"{{ {OK_FLOOR}, "dissipators": [{{ "floor": 1, "brace_stiffness": 1e6, "brace_damping": -3, "slip_load": 1 }}] }}"#
            ),
            &["dissipators[0].brace_damping"],
        ),
        (
            format!(
                r#"{{ {OK_FLOOR}, "dissipators": [{{ "floor": 1, "brace_stiffness": 1e6, "slip_load": -5 }}] }}"#
            ),
            &["dissipators[0].slip_load"],
        ),
        (
            format!(
                r#"{{ {OK_FLOOR}, "dissipators": [{{ "floor": 1, "brace_stiffness": 1e6, "bounds": [10, 20] }}] }}"#
            ),
            &["dissipators[0].bounds[0]", "F-"],
        ),
        (
            format!(
                r#"{{ {OK_FLOOR}, "dissipators": [{{ "floor": 1, "brace_stiffness": 1e6, "bounds": [-10, -2] }}] }}"#
            ),
            &["dissipators[0].bounds[1]", "F+"],
        ),
        (
            format!(
                r#"{{ {OK_FLOOR}, "dissipators": [{{ "floor": 1, "brace_stiffness": 1e6 }}] }}"#
            ),
            &["dissipators[0].slip_load", "missing"],
        ),
        (
            format!(
                r#"{{ {OK_FLOOR}, "dissipators": [{{ "floor": 1, "brace_stiffness": 1e6, "slip_load": 1 }}, {{ "floor": 1, "brace_stiffness": 1e6, "slip_load": 1 }}] }}"#
            ),
            &["dissipators[1].floor", "already"],
        ),
        (
            format!(
                r#"{{ "building": {{ {OK_FLOOR} }}, "excitation": {{ "harmonic": {{ "floor": 3, "amplitude": 1, "omega": 1 }} }} }}"#
            ),
            &["excitation.harmonic.floor"],
        ),
        (
            format!(
                r#"{{ "building": {{ {OK_FLOOR} }}, "method": {{ "name": "hht", "alpha": -0.5 }} }}"#
            ),
            &["method.alpha", "[-1/3, 0]"],
        ),
        (
            format!(r#"{{ "building": {{ {OK_FLOOR} }}, "method": {{ "name": "rk4" }} }}"#),
            &["unknown variant `rk4`"],
        ),
        (
            format!(
                r#"{{ "building": {{ {OK_FLOOR} }}, "excitation": {{ "initial": {{ "floor_displacement": [1, 2] }} }} }}"#
            ),
            &["excitation.initial.floor_displacement", "expected 1"],
        ),
    ];
    for (json, needles) in cases {
        let e = error_of(json);
        for n in *needles {
            assert!(
                e.contains(n),
                "error for {json}\n  was: {e}\n  expected to contain: {n}"
            );
        }
    }
}

#[test]
fn a_scene_without_record_or_duration_is_refused() {
    let e = Scene::from_json(
        &format!(r#"{{ {OK_FLOOR} }}"#),
        &configs().join("b.json"),
        &SceneOverrides::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("no record and no duration"), "{e}");
}

#[test]
fn inconsistent_initial_state_of_a_massless_dissipator_is_refused() {
    // Brace force k′·x′₀ = 1e6 · 0.1 = 1e5 N > slip load 10 N.
    let json = format!(
        r#"{{ "building": {{ {OK_FLOOR}, "dissipators": [{{ "floor": 1, "brace_stiffness": 1e6, "slip_load": 10 }}] }},
             "excitation": {{ "initial": {{ "dissipator_displacement": [0.1] }} }}, "duration": 1 }}"#
    );
    let scene =
        Scene::from_json(&json, &configs().join("b.json"), &SceneOverrides::default()).unwrap();
    let e = slipload_sim::simulate(&scene).unwrap_err().to_string();
    assert!(
        e.contains("massless dissipator of floor 1")
            && e.contains("consistent initial dissipator displacement"),
        "{e}"
    );
}

#[test]
fn synthetic_excitations_by_index_or_seed() {
    let load = |syn: &str| {
        Scene::from_json(
            &format!(
                r#"{{ "building": {{ {OK_FLOOR} }}, "excitation": {{ "synthetic": {syn} }} }}"#
            ),
            &configs().join("s.json"),
            &SceneOverrides::default(),
        )
    };
    let suite = slipload_motion::default_suite();
    let by_index = load(r#"{ "index": 3 }"#).unwrap();
    assert_eq!(
        by_index.record.as_ref().unwrap().samples(),
        suite[3].samples()
    );
    let seeded = load(r#"{ "seed": 11, "pga_g": 0.3, "duration": 5, "dt": 0.005 }"#).unwrap();
    let r = seeded.record.as_ref().unwrap();
    assert_eq!(r.dt(), 0.005);
    assert!((r.duration() - 5.0).abs() < 1e-12);
    assert_eq!(
        r.pga(),
        0.3 * slipload_motion::G,
        "scaled exactly to the PGA"
    );
    let again = load(r#"{ "seed": 11, "pga_g": 0.3, "duration": 5, "dt": 0.005 }"#).unwrap();
    assert_eq!(
        again.record.as_ref().unwrap().samples(),
        r.samples(),
        "same seed, same record"
    );
    for (bad, needle) in [
        (r#"{ "index": 99 }"#, "excitation.synthetic.index"),
        (r#"{ "index": 1, "seed": 2 }"#, "not both"),
        (r#"{ "dt": 0.01 }"#, "give seed too"),
        (
            r#"{ "seed": 1, "pga_g": -1 }"#,
            "excitation.synthetic.pga_g",
        ),
    ] {
        let e = load(bad).unwrap_err().to_string();
        assert!(e.contains(needle), "{bad}: {e}");
    }
}
