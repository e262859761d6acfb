//! The rules a scene is held to (module docs of `slipload_sim::scene`), each with an input
//! per failure mode:
//! - one window rule: the override (`--window`) replaces the scene's window; a window past
//!   the record's end is padded with the ground at rest — the rule a duration longer than
//!   the record has — and the scene carries a note saying so; a window that starts at or
//!   past the end is refused;
//! - times are accepted with units wherever a time is (window, duration, record dt, dt);
//! - a `method` option the chosen method does not read is refused, naming the option, the
//!   method and the options it takes;
//! - mutually exclusive excitation fields (`record` and `synthetic`, `scale` and
//!   `scale_pga_g`) are refused;
//! - a building alone can be planned for `explain` (nominal duration, said in a note) but
//!   not run;
//! - `simulate::check` (what `explain` runs) refuses exactly what `simulate` refuses before
//!   its first step, with the same message.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use slipload_motion::{G, Record, read_record};
use slipload_sim::{MethodName, Plan, Scene, SceneOverrides, simulate};

/// SYL090 lasts 39.98 s (2000 samples at 0.02 s).
const SYL_END: f64 = 39.98;

fn syl() -> Record {
    read_record(&records().join("SYL090.AT2"), None, None).unwrap()
}

/// The benchmark building under SYL090 with `record_extra` in the record object and
/// `extra` at the scene's top level.
fn syl_scene_json(record_extra: &str, extra: &str) -> String {
    format!(
        r#"{{ "building": "benchmark-3story.json",
             "excitation": {{ "record": {{ "file": "../records/SYL090.AT2"{record_extra} }} }}{extra} }}"#
    )
}

fn load(json: &str, over: &SceneOverrides) -> Result<Scene, String> {
    Scene::from_json(json, &configs().join("rules.json"), over).map_err(|e| e.to_string())
}

fn refused(json: &str, over: &SceneOverrides, needles: &[&str]) -> String {
    let err = match load(json, over) {
        Ok(_) => panic!("accepted: {json} with {over:?}"),
        Err(e) => e,
    };
    for n in needles {
        assert!(err.contains(n), "{n:?} not in: {err}");
    }
    err
}

fn window(s: f64, d: f64) -> SceneOverrides {
    SceneOverrides {
        window: Some((s, d)),
        ..Default::default()
    }
}

#[test]
fn the_window_flag_replaces_the_scene_window() {
    // Applied on top, the flag's (1, 2) inside the scene's [5, 10] would be [6, 8] of the
    // record; replacing, it is [1, 3].
    let json = syl_scene_json(r#", "window": [5, 10]"#, "");
    let s = load(&json, &window(1.0, 2.0)).unwrap();
    let r = s.record.as_ref().unwrap();
    let want = syl().window(1.0, 2.0).unwrap();
    assert_eq!(r.samples(), want.samples());
    assert_eq!(s.duration, 2.0);
    assert!(s.notes.is_empty(), "{:?}", s.notes);
    // without the flag the scene's own window holds
    let s = load(&json, &SceneOverrides::default()).unwrap();
    assert_eq!(
        s.record.as_ref().unwrap().samples(),
        syl().window(5.0, 10.0).unwrap().samples()
    );
    assert_eq!(s.duration, 10.0);
}

#[test]
fn a_window_past_the_record_end_is_padded_as_a_long_duration_is_and_says_so() {
    let json = syl_scene_json(r#", "window": [38, 5]"#, "");
    let s = load(&json, &SceneOverrides::default()).unwrap();
    // the run is the window's 5 s; the ground motion is what the record has from 38 s
    assert_eq!(s.duration, 5.0);
    let r = s.record.as_ref().unwrap();
    assert!(
        (r.duration() - (SYL_END - 38.0)).abs() < 1e-9,
        "{}",
        r.duration()
    );
    assert_eq!(s.notes.len(), 1, "{:?}", s.notes);
    let note = &s.notes[0];
    for want in [
        "excitation.record.window",
        "[38 s, 5 s] runs past the end of",
        "SYL090.AT2",
        "1.98 s of ground motion from 38 s",
        "at rest for the last 3.02 s of the 5 s run",
    ] {
        assert!(note.contains(want), "{want:?} not in {note}");
    }
    // The same answer as the in-range window made as long with `duration`: one rule.
    let same = load(
        &syl_scene_json(r#", "window": [38, 1.98]"#, r#", "duration": 5"#),
        &SceneOverrides::default(),
    )
    .unwrap();
    assert_eq!(same.duration, s.duration);
    assert_eq!(same.record.as_ref().unwrap().samples(), r.samples());
    assert_eq!(same.notes.len(), 1, "{:?}", same.notes);
    assert!(
        same.notes[0].contains("at rest for the last 3.02 s"),
        "{}",
        same.notes[0]
    );
    let (a, b) = (simulate(&s).unwrap(), simulate(&same).unwrap());
    assert_eq!(a.response.peak_drift, b.response.peak_drift);
    // the flag says it is the flag
    let s = load(&syl_scene_json("", ""), &window(38.0, 5.0)).unwrap();
    assert_eq!(s.duration, 5.0);
    assert!(
        s.notes[0].starts_with("--window [38 s, 5 s]"),
        "{:?}",
        s.notes
    );
}

#[test]
fn a_duration_past_the_record_end_says_so() {
    let s = load(
        &syl_scene_json("", r#", "duration": "45 s""#),
        &Default::default(),
    )
    .unwrap();
    assert_eq!(s.duration, 45.0);
    assert_eq!(s.notes.len(), 1, "{:?}", s.notes);
    assert!(
        s.notes[0].contains("lasts 39.98 s") && s.notes[0].contains("last 5.02 s"),
        "{}",
        s.notes[0]
    );
    // within the record: no note
    let s = load(
        &syl_scene_json("", r#", "duration": 10"#),
        &Default::default(),
    )
    .unwrap();
    assert!(s.notes.is_empty(), "{:?}", s.notes);
}

#[test]
fn a_window_that_starts_at_or_past_the_end_is_refused() {
    for start in ["39.98", "60"] {
        refused(
            &syl_scene_json(&format!(r#", "window": [{start}, 5]"#), ""),
            &SceneOverrides::default(),
            &[
                "rules.json",
                "excitation.record.window",
                &format!("the window starts at {start} s"),
                "39.98 s long",
                "give a start below 39.98 s",
            ],
        );
    }
    refused(
        &syl_scene_json("", ""),
        &window(60.0, 5.0),
        &["--window", "the window starts at 60 s"],
    );
    for bad in ["[-1, 5]", "[0, 0]", "[0, -2]"] {
        refused(
            &syl_scene_json(&format!(r#", "window": {bad}"#), ""),
            &SceneOverrides::default(),
            &[
                "excitation.record.window",
                "start >= 0 s and a duration > 0 s",
            ],
        );
    }
}

#[test]
fn the_window_flag_applies_to_a_synthetic_ground_motion_and_needs_one() {
    let json =
        r#"{ "building": "benchmark-3story.json", "excitation": { "synthetic": { "index": 2 } } }"#;
    let whole = load(json, &SceneOverrides::default()).unwrap();
    let s = load(json, &window(3.0, 4.0)).unwrap();
    assert_eq!(s.duration, 4.0);
    let r = s.record.as_ref().unwrap();
    assert!((r.duration() - 4.0).abs() < 1e-9, "{}", r.duration());
    // windowed, then scaled to the suite's PGA, as a record's window is
    assert!((r.pga() - 0.4 * G).abs() < 1e-9 * G, "{}", r.pga());
    assert!(whole.duration > 10.0);
    // no ground motion at all: the window has nothing to cut
    refused(
        r#"{ "building": "benchmark-3story.json", "duration": 2 }"#,
        &window(0.0, 1.0),
        &["--window", "no ground motion to window"],
    );
}

#[test]
fn times_take_units_wherever_a_time_is() {
    let plain = load(
        &syl_scene_json(
            r#", "window": [2, 10]"#,
            r#", "duration": 8, "method": { "dt": 0.005 }"#,
        ),
        &SceneOverrides::default(),
    )
    .unwrap();
    let units = load(
        &syl_scene_json(
            r#", "window": ["2 s", "10 s"]"#,
            r#", "duration": "8 s", "method": { "dt": "5 ms" }"#,
        ),
        &SceneOverrides::default(),
    )
    .unwrap();
    assert_eq!(plain.duration, units.duration);
    assert_eq!(plain.method.dt, units.method.dt);
    assert_eq!(
        plain.record.as_ref().unwrap().samples(),
        units.record.as_ref().unwrap().samples()
    );
    // a record's sample interval, for a one-column text file
    let dir = std::env::temp_dir().join(format!("slipload-scene-rules-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("ten.txt");
    std::fs::write(&file, "0\n0.1\n-0.2\n0.05\n0\n").unwrap();
    let text_scene = |dt: &str| {
        format!(
            r#"{{ "building": {{ "floor_masses": [1000], "storey_stiffness": [1e5] }},
                 "excitation": {{ "record": {{ "file": {:?}, "dt": {dt} }} }} }}"#,
            file.display().to_string()
        )
    };
    let a = load(&text_scene("0.01"), &SceneOverrides::default()).unwrap();
    let b = load(&text_scene(r#""10 ms""#), &SceneOverrides::default()).unwrap();
    assert_eq!(a.record.as_ref().unwrap().dt(), 0.01);
    assert_eq!(b.record.as_ref().unwrap().dt(), 0.01);
    // the wrong dimension names what was expected
    for bad in [
        syl_scene_json(r#", "window": ["2 kg", "10 s"]"#, ""),
        syl_scene_json("", r#", "duration": "8 kN""#),
        syl_scene_json("", r#", "method": { "dt": "5 m" }"#),
    ] {
        refused(
            &bad,
            &SceneOverrides::default(),
            &["rules.json", "a time in s"],
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A value of each `method` option that is valid for the methods that take it.
fn option_value(option: &str) -> &'static str {
    match option {
        "dt" => "0.001",
        "alpha" => "-0.05",
        "eps_a" => "1.0",
        "eps_f" => "100.0",
        "max_iterations" => "50",
        other => panic!("no value for {other}"),
    }
}

const OPTIONS: [&str; 5] = ["dt", "alpha", "eps_a", "eps_f", "max_iterations"];

#[test]
fn every_method_refuses_the_options_it_does_not_use() {
    let takes = |m: MethodName| -> &[&str] {
        match m {
            MethodName::Newmark | MethodName::Bilinear | MethodName::Exact => &["dt"],
            MethodName::Hht => &["dt", "alpha"],
            MethodName::Delacruz => &["dt", "eps_a", "eps_f", "max_iterations"],
        }
    };
    for m in MethodName::ALL {
        assert_eq!(m.options(), takes(m), "{}", m.as_str());
        for option in OPTIONS {
            let json = syl_scene_json(
                r#", "window": [0, 2]"#,
                &format!(
                    r#", "method": {{ "name": "{}", "{option}": {} }}"#,
                    m.as_str(),
                    option_value(option)
                ),
            );
            if takes(m).contains(&option) {
                load(&json, &SceneOverrides::default())
                    .unwrap_or_else(|e| panic!("{} {option}: {e}", m.as_str()));
            } else {
                let err = refused(
                    &json,
                    &SceneOverrides::default(),
                    &[
                        "rules.json",
                        &format!("field `method.{option}`"),
                        &format!("method {} does not use {option}", m.as_str()),
                        &format!("(it takes {})", takes(m).join(", ")),
                    ],
                );
                // and it says which method reads it
                let users: Vec<&str> = MethodName::ALL
                    .iter()
                    .filter(|u| takes(**u).contains(&option))
                    .map(|u| u.as_str())
                    .collect();
                assert!(
                    err.contains(&format!("{option} is an option of {}", users.join(", "))),
                    "{err}"
                );
            }
        }
    }
    // chosen with the flag, the method's options are those of the flag's method
    let hht = syl_scene_json("", r#", "method": { "name": "hht", "alpha": -0.1 }"#);
    refused(
        &hht,
        &SceneOverrides {
            method: Some(MethodName::Newmark),
            ..Default::default()
        },
        &[
            "method.alpha",
            "method newmark (from --method) does not use alpha",
        ],
    );
}

#[test]
fn exclusive_excitation_fields_are_refused() {
    refused(
        r#"{ "building": "benchmark-3story.json",
             "excitation": { "record": { "file": "../records/SYL090.AT2" }, "synthetic": { "index": 1 } } }"#,
        &SceneOverrides::default(),
        &[
            "rules.json",
            "excitation.synthetic",
            "either record",
            "or synthetic",
            "not both",
        ],
    );
    // refused before the record is read: the file need not exist
    refused(
        r#"{ "building": "benchmark-3story.json",
             "excitation": { "record": { "file": "missing.AT2", "scale": 2, "scale_pga_g": 0.3 } } }"#,
        &SceneOverrides::default(),
        &[
            "excitation.record.scale",
            "either scale or scale_pga_g, not both",
        ],
    );
    refused(
        r#"{ "building": "benchmark-3story.json",
             "excitation": { "synthetic": { "index": 1, "seed": 4 } } }"#,
        &SceneOverrides::default(),
        &["excitation.synthetic", "either index", "or seed, not both"],
    );
}

#[test]
fn a_building_alone_is_planned_for_explain_but_not_run() {
    let building = std::fs::read_to_string(configs().join("benchmark-3story.json")).unwrap();
    refused(
        &building,
        &SceneOverrides::default(),
        &["no record and no duration"],
    );
    let s = load(
        &building,
        &SceneOverrides {
            plan_only: true,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(s.duration, s.building.t1());
    assert!(
        s.notes
            .iter()
            .any(|n| n.contains("no ground motion and no duration")),
        "{:?}",
        s.notes
    );
    let plan = Plan::compile(&s).unwrap();
    assert!(
        plan.explain()
            .contains("planned over one bare-frame period")
    );
    slipload_sim::simulate::check(&plan).unwrap();
}

/// Scenes `simulate` refuses before its first step; `check` must refuse each with the
/// same message.
#[test]
fn check_refuses_what_simulate_refuses_with_the_same_words() {
    let yielding = r#"{ "building": { "floor_masses": [1e5], "storey_stiffness": [4e7],
          "storey_yield": [ { "storey": 1, "yield_shear": "200 kN" } ] },
        "excitation": { "initial": { "floor_velocity": [0.5] } },
        "duration": 1, "method": { "name": "delacruz", "dt": 0.001 } }"#;
    let massless = |method: &str| {
        format!(
            r#"{{ "building": {{ "floor_masses": [1000], "storey_stiffness": [1e5],
                  "dissipators": [ {{ "floor": 1, "brace_stiffness": 1e6, "mass": 0, "slip_load": 500 }} ] }},
                "excitation": {{ "initial": {{ "floor_velocity": [0.5] }} }},
                "duration": 1, "reduce": false, "method": {{ "name": "{method}", "dt": 0.001 }} }}"#
        )
    };
    let outside = r#"{ "building": { "floor_masses": [1000], "storey_stiffness": [1e5],
          "dissipators": [ { "floor": 1, "brace_stiffness": 1e6, "mass": 0, "slip_load": 500 } ] },
        "excitation": { "initial": { "dissipator_displacement": [0.01] } },
        "duration": 1, "method": { "dt": 0.001 } }"#;
    for (json, needle) in [
        (
            yielding.to_string(),
            "delacruz does not model yielding storeys",
        ),
        (massless("delacruz"), "zero-mass DOF of an unreduced plan"),
        (massless("exact"), "has zero mass but keeps a DOF"),
        (outside.to_string(), "outside its friction bounds"),
    ] {
        let scene = load(&json, &SceneOverrides::default()).unwrap();
        let plan = Plan::compile(&scene).unwrap();
        let by_check = slipload_sim::simulate::check(&plan)
            .unwrap_err()
            .to_string();
        let by_run = simulate(&scene).unwrap_err().to_string();
        assert!(by_check.contains(needle), "{needle:?} not in {by_check}");
        assert_eq!(by_check, by_run);
    }
    // and a scene simulate runs passes the check
    let ok = load(
        &yielding.replace("delacruz", "newmark"),
        &SceneOverrides::default(),
    )
    .unwrap();
    slipload_sim::simulate::check(&Plan::compile(&ok).unwrap()).unwrap();
}

#[test]
fn frequencies_angles_and_velocities_take_units() {
    let scene = |omega: &str, phase: &str, v: &str| {
        format!(
            r#"{{ "building": {{ "floor_masses": [1000, 1000], "storey_stiffness": [1e5, 1e5] }},
                 "excitation": {{ "harmonic": {{ "floor": 2, "amplitude": "1 kN", "omega": {omega}, "phase": {phase} }},
                                  "initial": {{ "floor_velocity": [{v}, 0] }} }},
                 "duration": 1 }}"#
        )
    };
    let tau = std::f64::consts::TAU;
    let plain = load(
        &scene(&format!("{}", 2.0 * tau), &format!("{}", tau / 4.0), "0.5"),
        &SceneOverrides::default(),
    )
    .unwrap();
    let units = load(
        &scene(r#""2 Hz""#, r#""90 deg""#, r#""50 cm/s""#),
        &SceneOverrides::default(),
    )
    .unwrap();
    let (a, b) = (plain.harmonic.unwrap(), units.harmonic.unwrap());
    // "2 Hz" is 2·2π rad/s and "90 deg" π/2 rad, to the round-off of one product
    assert!(
        (a.omega - b.omega).abs() <= 1e-15 * a.omega,
        "{} {}",
        a.omega,
        b.omega
    );
    assert!(
        (a.phase - b.phase).abs() <= 1e-15,
        "{} {}",
        a.phase,
        b.phase
    );
    assert_eq!(plain.initial.floor_velocity, units.initial.floor_velocity);
    for bad in [
        scene(r#""2 kg""#, "0", "0"),
        scene("1", r#""2 s""#, "0"),
        scene("1", "0", r#""5 m""#),
    ] {
        refused(
            &bad,
            &SceneOverrides::default(),
            &["rules.json", "expected"],
        );
    }
    // the messages say what was expected
    refused(
        &scene(r#""2 kg""#, "0", "0"),
        &SceneOverrides::default(),
        &["a circular frequency in rad/s"],
    );
    refused(
        &scene("1", "0", r#""5 m""#),
        &SceneOverrides::default(),
        &["a velocity in m/s"],
    );
}

#[test]
fn a_window_inside_the_record_lasts_what_it_keeps_without_a_note() {
    // [0.7, 2.55] on a 0.02 s record keeps 127 intervals (2.54 s): no padding, no note
    let s = load(
        &syl_scene_json(r#", "window": [0.7, 2.55]"#, ""),
        &SceneOverrides::default(),
    )
    .unwrap();
    let r = s.record.as_ref().unwrap();
    assert!((r.duration() - 2.54).abs() < 1e-9, "{}", r.duration());
    assert_eq!(s.duration, r.duration());
    assert!(s.notes.is_empty(), "{:?}", s.notes);
}
