//! A yielding, P-Δ frame from the command line: `explain` says which storeys yield, where
//! P-Δ acts and what it leaves of a yielded storey's stiffness, and the collapse limit;
//! `simulate` prints each storey's ductility and plastic drift, the plastic energy in the
//! balance, and a collapse as a typed outcome (exit 0: an answer, not an error); `--plot`
//! draws the storey shear–drift loops beside the dampers'.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{scratch, slipload};

fn stdout(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn explain_names_the_yielding_storeys_p_delta_and_the_collapse_limit() {
    let o = slipload(&[
        "explain",
        "configs/ten-story-yielding.json",
        "--duration",
        "1",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = stdout(&o);
    for want in [
        "storey 1: yields (k = 4.940000e8 N/m, Fy = 1.296750e7 N",
        "storey 10: yields",
        "P-Delta: geometric stiffness -P/h per storey",
        "P-Delta: post-yield tangent alpha*k - P/h per storey",
        "collapse limit: a storey drift past [0.3500",
        "10 yielding storeys as elastic-perfectly plastic elements",
    ] {
        assert!(out.contains(want), "missing {want:?} in\n{out}");
    }
    // The elastic frame's plan says none of it.
    let o = slipload(&["explain", "configs/ten-story.json", "--duration", "1"]);
    let out = stdout(&o);
    assert!(!out.contains("yield") && !out.contains("P-Delta") && !out.contains("collapse"));
}

#[test]
fn a_collapse_is_reported_as_an_outcome() {
    let dir = scratch("yielding-cli", "collapse");
    let scene = dir.join("pdelta.json");
    std::fs::write(
        &scene,
        r#"{ "name": "p-delta sdof", "building": { "floor_masses": [1.0e5], "storey_stiffness": [4.0e7],
              "storey_heights": [3.0],
              "storey_yield": [ { "storey": 1, "yield_shear": "200 kN" } ],
              "p_delta": { "gravity_loads": ["6 MN"] } },
             "excitation": { "initial": { "floor_velocity": [0.9] } },
             "duration": 5.0, "method": { "name": "exact", "dt": 0.001 } }"#,
    )
    .unwrap();
    let o = slipload(&["simulate", scene.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = stdout(&o);
    assert!(out.contains("COLLAPSE: storey 1 drifted"), "{out}");
    assert!(
        out.contains("ductility") && out.contains("plastic drift (m)"),
        "{out}"
    );
    assert!(
        out.contains("plastic (hysteretic) energy of the frame"),
        "{out}"
    );
    let o = slipload(&["simulate", scene.to_str().unwrap(), "--format", "json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["collapse"]["storey"], 1);
    assert!(v["energy"]["plastic"].as_f64().unwrap() > 0.0);
}

#[test]
fn plot_draws_the_storey_loops_beside_the_dampers() {
    let dir = scratch("yielding-cli", "plot");
    let o = slipload(&[
        "simulate",
        "configs/ten-story-yielding.json",
        "--record",
        "records/RSN1106_KOBE_KJM000.AT2",
        "--scale-pga-g",
        "0.6",
        "--window",
        "5,10",
        "--plot",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in [
        "storey-hysteresis.svg",
        "storey-hysteresis.png",
        "energy.svg",
    ] {
        assert!(dir.join(f).is_file(), "{f}");
    }
    let history = std::fs::read_to_string(dir.join("history.csv")).unwrap();
    let header = history.lines().next().unwrap();
    assert!(
        header.contains("Fp1_N") && header.contains("E_plastic_J"),
        "{header}"
    );
}
