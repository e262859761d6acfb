//! Contract: design spaces map scaled variables to slip loads as documented — profiles
//! have the shapes their definitions give on a shear building, constraints on slip loads
//! become the same constraints on z, and samples stay feasible.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::model::sampler;
use slipload_opt::{Bound, Shape, Study};
use std::path::{Path, PathBuf};

fn configs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs")
}

fn benchmark(edit: impl FnOnce(&mut serde_json::Value)) -> Study {
    let path = configs().join("study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["suites"][0]["synthetic"]["count"] = 1.into();
    edit(&mut v);
    Study::from_json(&v.to_string(), &path).unwrap()
}

#[test]
fn profiles_on_the_ten_storey_shear_building() {
    let b = slipload_sim::Building::load(&configs().join("ten-story.json")).unwrap();
    // storey i joins floors i−1 and i: kᵢ = −K[i][i−1], k₀ = K[0][0] + K[1][0]
    let k: Vec<f64> = (0..10)
        .map(|i| {
            if i == 0 {
                b.stiffness[(0, 0)] + b.stiffness[(1, 0)]
            } else {
                -b.stiffness[(i, i - 1)]
            }
        })
        .collect();
    assert!(
        (k[1] / k[0] - 466.6 / 494.0).abs() < 1e-12,
        "the file's storey stiffnesses"
    );
    // for a shear building Vᵢ/δᵢ is the storey stiffness whatever the load pattern:
    // round-off of one linear solve, relative 1e-9
    let st = Shape::Stiffness.on_floors(&b);
    for i in 0..10 {
        assert!(
            (st[i] - k[i] / k[0]).abs() < 1e-9,
            "storey {i}: {} vs {}",
            st[i],
            k[i] / k[0]
        );
    }
    // Vᵢ = Σ_{j≥i} m_j h_j with 3.5 m storeys: masses 350 t ×9 and 280 t at the roof
    let m: Vec<f64> = (0..10).map(|i| if i < 9 { 350e3 } else { 280e3 }).collect();
    let v: Vec<f64> = (0..10)
        .map(|i| (i..10).map(|j| m[j] * 3.5 * (j + 1) as f64).sum())
        .collect();
    let sh = Shape::StoreyShear.on_floors(&b);
    for i in 0..10 {
        assert!((sh[i] - v[i] / v[0]).abs() < 1e-12);
    }
    // the ten-storey file's slip loads follow this shape (8 % of the weight at the base),
    // to the 1 kN the file rounds to
    let file = [
        2691.0, 2640.0, 2539.0, 2386.0, 2183.0, 1929.0, 1625.0, 1269.0, 863.0, 406.0,
    ];
    for i in 0..10 {
        assert!((file[i] - 2691.0 * sh[i]).abs() < 1.5, "floor {}", i + 1);
    }
    assert_eq!(Shape::Uniform.on_floors(&b), vec![1.0; 10]);
}

#[test]
fn constraints_carry_over_to_the_scaled_variables() {
    let s = benchmark(|v| {
        v["space"]["free"]["lower_kn"] = serde_json::json!([100, 0, 0]);
        v["constraints"] = serde_json::json!({ "budget_kn": 3000, "non_increasing": true });
    });
    let sp = &s.space;
    // z ↦ slip loads: lower + z (upper − lower), N
    assert_eq!(sp.slip_loads(&[0.0, 0.5, 1.0]), vec![100e3, 1000e3, 2000e3]);
    // non-increasing broken (floor 3 above floor 2)
    assert!(!sp.is_feasible(&[1.0, 0.5, 1.0]));
    // budget: 2000 + 500 + 500 = 3000 kN just fits; one kN more does not
    let z1 = (2000e3 - 100e3) / 1900e3;
    assert!(sp.is_feasible(&[z1, 0.25, 0.25]));
    assert!(!sp.is_feasible(&[z1, 0.25, 0.2505]));
    // every sample point honours the constraints
    for z in sampler::sample(sp, &s.config.sweep) {
        let l = sp.slip_loads(&z);
        assert!(l[0] >= l[1] - 1e-6 && l[1] >= l[2] - 1e-6, "{l:?}");
        assert!(l.iter().sum::<f64>() <= 3000e3 * (1.0 + 1e-9), "{l:?}");
    }
}

#[test]
fn profile_space_scales_one_shape() {
    let s = benchmark(|v| {
        v["space"] =
            serde_json::json!({ "profile": { "shape": "storey_shear", "scale_kn": [0, 1000] } });
    });
    assert_eq!(s.space.dim(), 1);
    let l = s.space.slip_loads(&[0.5]);
    let sh = Shape::StoreyShear.on_floors(&s.building);
    for i in 0..3 {
        assert!((l[i] - 500e3 * sh[i]).abs() < 1e-6);
    }
}

#[test]
fn family_scaling_scales_periods_and_records() {
    let s = benchmark(|_| {});
    let t = slipload_opt::phases::family::scaled_study(&s, 1.25, 2.0).unwrap();
    // K/p² with M fixed: every period × p (eigen-solver round-off, 1e-9 relative)
    let (p0, p1) = (s.building.modes.periods(), t.building.modes.periods());
    for (a, b) in p0.iter().zip(&p1) {
        assert!((b / a - 1.25).abs() < 1e-9, "{a} → {b}");
    }
    // C/p keeps cᵢⱼ/(kᵢⱼ ωᵢ)-type ratios: C·p = C₀ exactly up to one rounding
    let c = &t.building.damping * 1.25;
    assert!((c - &s.building.damping).abs().max() <= 1e-12 * s.building.damping.abs().max());
    assert_eq!(t.records[0].pga(), 2.0 * s.records[0].pga());
    assert!(slipload_opt::phases::family::scaled_study(&s, 0.0, 1.0).is_err());
}

#[test]
fn variables_on_a_bound_are_named_with_their_floors() {
    let free = benchmark(|_| {});
    let on = free.space.on_bounds(&[1.0, 0.4, 0.0]);
    let named: Vec<(&str, &[usize], Bound)> = on
        .iter()
        .map(|b| (b.variable.as_str(), b.floors.as_slice(), b.bound))
        .collect();
    assert_eq!(
        named,
        [
            ("floor1", &[1][..], Bound::Upper),
            ("floor3", &[3][..], Bound::Lower)
        ]
    );
    // Within a millionth of the range is on the bound; a thousandth inside is not.
    assert_eq!(free.space.on_bounds(&[1.0 - 1e-7, 0.5, 0.5]).len(), 1);
    assert!(free.space.on_bounds(&[0.999, 0.5, 0.001]).is_empty());
    // A profile has one variable, the scale, which sets every floor with a damper.
    let profile = benchmark(|v| {
        v["space"] =
            serde_json::json!({ "profile": { "shape": "uniform", "scale_kn": [0, 1500] } });
    });
    let on = profile.space.on_bounds(&[1.0]);
    assert_eq!(on.len(), 1);
    assert_eq!(
        (
            on[0].variable.as_str(),
            on[0].floors.as_slice(),
            on[0].bound
        ),
        ("scale", &[1, 2, 3][..], Bound::Upper)
    );
}
