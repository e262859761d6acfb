//! `configs/benchmark-3story.json` is the benchmark building of De la Cruz, López-Almansa &
//! Oller (2007), Comput. Struct. 85:30–42, as the paper prints it: the bare-frame periods,
//! the damping matrix Cˢˢ its Rayleigh coefficients give, and the modal damping ratios those
//! imply. Every figure the paper prints is rounded, so each check's tolerance is half a
//! unit in the last printed digit (the damping matrix: the paper's 0.03 % agreement, held
//! to 0.05 %).

mod common;

use common::configs;
use slipload_sim::building::Building;

/// The bare-frame stiffness the paper prints, MN/m, without the 45.664 MN/m misprint of
/// its first two diagonal terms (docs/MODEL.md, Known misprints).
const PRINTED_K_MN: [[f64; 3]; 3] = [
    [436.575, -237.344, 41.445],
    [-237.344, 313.526, -128.931],
    [41.445, -128.931, 93.585],
];

/// The frame damping matrix Cˢˢ the paper prints, kN·s/m.
const PRINTED_C_KNS: [[f64; 3]; 3] = [
    [509.253, -221.488, 38.679],
    [-221.488, 394.428, -120.313],
    [38.679, -120.313, 197.705],
];

fn benchmark() -> Building {
    Building::load(&configs().join("benchmark-3story.json")).expect("the benchmark building loads")
}

#[test]
fn frame_is_the_printed_condensed_matrix() {
    let b = benchmark();
    for (i, row) in PRINTED_K_MN.iter().enumerate() {
        for (j, &printed) in row.iter().enumerate() {
            let k = b.stiffness[(i, j)];
            // The file gives the entries with units ("436.575 MN/m"): exact to the digit.
            assert!(
                (k - printed * 1e6).abs() <= 1e-9 * printed.abs() * 1e6,
                "K[{i}][{j}] = {k} N/m, printed {printed} MN/m"
            );
        }
    }
    let m: Vec<f64> = (0..3).map(|i| b.mass[(i, i)]).collect();
    assert_eq!(m, vec![4.78e5, 4.78e5, 5.18e5]);
    assert_eq!(b.storey_heights.as_deref(), Some(&[3.96, 3.96, 3.96][..]));
}

#[test]
fn bare_periods_are_the_printed_ones() {
    let periods = benchmark().modes.periods();
    // The condensed matrix's periods to three decimals, and the paper's two-decimal print.
    for (t, (three, two)) in periods
        .iter()
        .zip([(1.008, 1.01), (0.327, 0.33), (0.172, 0.17)])
    {
        assert!(
            (t - three).abs() <= 5e-4,
            "period {t} s, expected {three} s"
        );
        assert!(
            (t - two).abs() <= 5e-3,
            "period {t} s, the paper prints {two} s"
        );
    }
}

#[test]
fn rayleigh_damping_reproduces_the_printed_matrix() {
    let b = benchmark();
    for (i, row) in PRINTED_C_KNS.iter().enumerate() {
        for (j, &printed) in row.iter().enumerate() {
            let c = b.damping[(i, j)] / 1e3;
            let rel = (c - printed).abs() / printed.abs();
            assert!(
                rel <= 5e-4,
                "C[{i}][{j}] = {c:.3} kN·s/m, printed {printed} ({:.3} % off)",
                rel * 100.0
            );
        }
    }
}

#[test]
fn modal_damping_is_two_percent_in_modes_one_and_three() {
    let b = benchmark();
    let phi = &b.modes.shapes;
    // Mass-normalised shapes: φₖᵀ C φₖ = 2 ζₖ ωₖ (Rayleigh damping is classical).
    let zeta: Vec<f64> = (0..3)
        .map(|k| {
            let p = phi.column(k);
            (p.transpose() * &b.damping * p)[(0, 0)] / (2.0 * b.modes.omega[k])
        })
        .collect();
    for (z, printed) in zeta.iter().zip([2.00, 1.45, 2.00]) {
        assert!(
            (z * 100.0 - printed).abs() <= 5e-3,
            "modal damping {:.4} %, expected {printed} %",
            z * 100.0
        );
    }
    // And it is classical: the off-diagonal modal terms vanish to round-off.
    let modal = phi.transpose() * &b.damping * phi;
    for i in 0..3 {
        for j in 0..3 {
            if i != j {
                assert!(
                    modal[(i, j)].abs() <= 1e-12 * modal[(i, i)].abs().max(modal[(j, j)].abs())
                );
            }
        }
    }
}

#[test]
fn matrices_accept_units_entrywise() {
    // The same frame given in N/m numbers, in kN/m strings and with a damping matrix in
    // kN·s/m builds the same matrices.
    let numbers = r#"{ "floor_masses": [4.78e5, 4.78e5, 5.18e5],
        "stiffness_matrix": [[436.575e6, -237.344e6, 41.445e6], [-237.344e6, 313.526e6, -128.931e6], [41.445e6, -128.931e6, 93.585e6]],
        "damping": { "matrix": [[509253, -221488, 38679], [-221488, 394428, -120313], [38679, -120313, 197705]] } }"#;
    let units = r#"{ "mass_matrix": [["478 t", 0, 0], [0, "4.78e5 kg", 0], [0, 0, "518000 kg"]],
        "stiffness_matrix": [["436575 kN/m", "-237.344 MN/m", "41445 kN/m"], ["-237344 kN/m", "313.526 MN/m", "-128.931 MN/m"], ["41.445 MN/m", "-128931 kN/m", "93.585 MN/m"]],
        "damping": { "matrix": [["509.253 kN·s/m", "-221.488 kN·s/m", "38.679 kN·s/m"], ["-221.488 kN·s/m", "394.428 kN·s/m", "-120.313 kN·s/m"], ["38.679 kN·s/m", "-120.313 kN·s/m", "197.705 kN·s/m"]] } }"#;
    let load = |text: &str| {
        let cfg: slipload_sim::building::BuildingConfig =
            serde_json::from_str(text).expect("parses");
        Building::from_config(&cfg, std::path::Path::new("inline.json")).expect("valid")
    };
    let (a, b) = (load(numbers), load(units));
    for (x, y) in [
        (&a.mass, &b.mass),
        (&a.stiffness, &b.stiffness),
        (&a.damping, &b.damping),
    ] {
        assert!((x - y).norm() <= 1e-12 * x.norm(), "{x} vs {y}");
    }
    // A unit of the wrong dimension names the entry.
    let wrong = r#"{ "floor_masses": [1000], "stiffness_matrix": [["5 kN"]] }"#;
    let e = serde_json::from_str::<slipload_sim::building::BuildingConfig>(wrong)
        .expect_err("a force is not a stiffness")
        .to_string();
    assert!(e.contains("stiffness") && e.contains("kN"), "{e}");
}

#[test]
fn sylmar_energies_are_the_papers() {
    use slipload_sim::scene::{MethodName, SceneOverrides};
    // The paper's Figs. 12-13: the benchmark under Sylmar 1994 90°, first 10 s. Its energy
    // plot ends at about 1350 kJ dissipated by friction, 219 kJ by viscous damping, of
    // 1640 kJ put in. Read off a figure, they hold to a few percent: 5 % here.
    let scene = common::scene_file(
        "paper-benchmark-sylmar.json",
        &SceneOverrides {
            method: Some(MethodName::Exact),
            energies: Some(true),
            ..Default::default()
        },
    );
    let e = slipload_sim::simulate(&scene)
        .expect("exact runs the paper's case")
        .response
        .energy
        .expect("energies asked for");
    for (what, ours, paper) in [
        ("friction", e.friction, 1350e3),
        ("viscous", e.viscous, 219e3),
        ("input", e.input, 1640e3),
    ] {
        let rel = (ours - paper).abs() / paper;
        assert!(
            rel <= 0.05,
            "{what} energy {:.0} kJ, the paper's {:.0} kJ ({:.1} % off)",
            ours / 1e3,
            paper / 1e3,
            rel * 100.0
        );
    }
}
