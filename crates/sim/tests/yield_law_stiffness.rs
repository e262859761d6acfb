//! A storey's yield law (`storey_yield`) is a spring inside the storey: it may not be
//! stiffer than the storey's own stiffness in the frame, 1/(eᵀK⁻¹e) with
//! e = e(floor i) − e(floor i−1) (`slipload_sim::building::storey_stiffness`) — for a shear
//! building the storey's own spring, for a full condensed matrix what the frame offers
//! between the two floors. A stiffer one is refused, naming the storey, both stiffnesses
//! and their units; one up to that stiffness is accepted.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::*;
use nalgebra::DMatrix;
use slipload_sim::building::storey_stiffness;
use slipload_sim::{Scene, SceneOverrides};

fn load(building: &str) -> Result<Scene, String> {
    Scene::from_json(
        &format!(r#"{{ "building": {building}, "duration": 1 }}"#),
        &configs().join("yield.json"),
        &SceneOverrides::default(),
    )
    .map_err(|e| e.to_string())
}

/// Two storeys k₁ = 200 MN/m, k₂ = 150 MN/m, with `yield_law` in `storey_yield`.
fn shear(yield_law: &str) -> String {
    format!(
        r#"{{ "floor_masses": [1e5, 1e5], "storey_stiffness": ["200 MN/m", "150 MN/m"],
             "storey_yield": [ {yield_law} ] }}"#
    )
}

/// The benchmark's condensed frame matrix (MN/m, docs/MODEL.md), not a shear building.
fn benchmark_k() -> DMatrix<f64> {
    DMatrix::from_row_slice(
        3,
        3,
        &[
            436.575, -237.344, 41.445, -237.344, 313.526, -128.931, 41.445, -128.931, 93.585,
        ],
    ) * 1e6
}

fn benchmark(yield_law: &str) -> String {
    format!(
        r#"{{ "floor_masses": [4.78e5, 4.78e5, 5.18e5],
             "stiffness_matrix": [["436.575 MN/m", "-237.344 MN/m", "41.445 MN/m"],
                                  ["-237.344 MN/m", "313.526 MN/m", "-128.931 MN/m"],
                                  ["41.445 MN/m", "-128.931 MN/m", "93.585 MN/m"]],
             "storey_yield": [ {yield_law} ] }}"#
    )
}

#[test]
fn storey_stiffness_of_a_shear_building_is_its_spring() {
    let (k1, k2, k3) = (2.0e8, 1.5e8, 0.7e8);
    let k = DMatrix::from_row_slice(3, 3, &[k1 + k2, -k2, 0.0, -k2, k2 + k3, -k3, 0.0, -k3, k3]);
    // a Cholesky solve of a 3×3 with condition ~10: round-off at 1e-14 relative
    for (i, want) in [k1, k2, k3].into_iter().enumerate() {
        let got = storey_stiffness(&k, i).unwrap();
        assert!(
            (got - want).abs() <= 1e-12 * want,
            "storey {}: {got} vs {want}",
            i + 1
        );
    }
    // not the diagonal entry: the first storey's K₁₁ = k₁ + k₂
    assert!(storey_stiffness(&k, 0).unwrap() < 0.6 * k[(0, 0)]);
    assert!(storey_stiffness(&k, 3).is_none());
}

#[test]
fn storey_stiffness_of_a_full_matrix_is_what_can_be_taken_out_of_it() {
    // K − k e eᵀ is positive semi-definite exactly up to k = storey stiffness: singular
    // there, indefinite just past it.
    let k = benchmark_k();
    for i in 0..3 {
        let ks = storey_stiffness(&k, i).unwrap();
        let mut e = nalgebra::DVector::zeros(3);
        e[i] = 1.0;
        if i > 0 {
            e[i - 1] = -1.0;
        }
        let at = |kk: f64| {
            (&k - &e * e.transpose() * kk)
                .symmetric_eigenvalues()
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min)
        };
        let lmax = k.symmetric_eigenvalues().max();
        // smallest eigenvalue zero to round-off of the eigen solver on entries of 1e8
        assert!(at(ks).abs() < 1e-9 * lmax, "storey {}: {}", i + 1, at(ks));
        assert!(at(ks * (1.0 + 1e-6)) < 0.0, "storey {}", i + 1);
        assert!(at(ks * (1.0 - 1e-6)) > 0.0, "storey {}", i + 1);
    }
}

#[test]
fn a_spring_stiffer_than_its_storey_is_refused_with_both_stiffnesses() {
    // storey 2 (150 MN/m)
    let err = load(&shear(
        r#"{ "storey": 2, "yield_shear": "100 kN", "stiffness": "160 MN/m" }"#,
    ))
    .unwrap_err();
    for want in [
        "yield.json",
        "storey_yield[0].stiffness",
        "storey 2",
        "1.600000e8 N/m",
        "1.500000e8 N/m",
        "stiffer than the storey it sits in",
        "floors 1 and 2",
    ] {
        assert!(err.contains(want), "{want:?} not in {err}");
    }
    // storey 1: stiffer than k₁ = 200 MN/m but below the diagonal K₁₁ = 350 MN/m, which
    // the old check compared it with
    let err = load(&shear(
        r#"{ "storey": 1, "yield_shear": "100 kN", "stiffness": "300 MN/m" }"#,
    ))
    .unwrap_err();
    for want in [
        "storey 1",
        "3.000000e8 N/m",
        "2.000000e8 N/m",
        "floor 1, the ground fixed",
    ] {
        assert!(err.contains(want), "{want:?} not in {err}");
    }
    // the storey's own spring, and less, are accepted
    for law in [
        r#"{ "storey": 2, "yield_shear": "100 kN" }"#,
        r#"{ "storey": 2, "yield_shear": "100 kN", "stiffness": "150 MN/m" }"#,
        r#"{ "storey": 1, "yield_shear": "100 kN", "stiffness": "120 MN/m" }"#,
    ] {
        load(&shear(law)).unwrap_or_else(|e| panic!("{law}: {e}"));
    }
}

#[test]
fn a_full_matrix_frame_is_checked_against_its_storey_stiffness() {
    let k = benchmark_k();
    for i in 0..3 {
        let ks = storey_stiffness(&k, i).unwrap();
        let law = |kk: f64| {
            format!(
                r#"{{ "storey": {}, "yield_shear": "100 kN", "stiffness": {kk} }}"#,
                i + 1
            )
        };
        let err = load(&benchmark(&law(ks * 1.001))).unwrap_err();
        for want in [
            format!("storey {}", i + 1),
            format!("{:.6e} N/m", ks * 1.001),
            format!("{ks:.6e} N/m"),
        ] {
            assert!(err.contains(&want), "{want:?} not in {err}");
        }
        load(&benchmark(&law(ks * 0.999))).unwrap();
    }
    // storey 1: below the diagonal K₁₁ (what the first storey was once compared with) yet
    // stiffer than the storey
    let ks1 = storey_stiffness(&k, 0).unwrap();
    let between = 0.5 * (ks1 + k[(0, 0)]);
    assert!(between > ks1 * 1.01);
    let err = load(&benchmark(&format!(
        r#"{{ "storey": 1, "yield_shear": "100 kN", "stiffness": {between} }}"#
    )))
    .unwrap_err();
    assert!(err.contains("stiffer than the storey"), "{err}");
}
