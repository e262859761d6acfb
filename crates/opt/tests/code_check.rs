//! Contract: a study with `property_bounds` runs every design at its nominal, lower- and
//! upper-bound properties; a bound case is the design with every slip load × λ (and
//! every brace stiffness × its λ) run at nominal properties. With `suites[i].limits` the
//! optimum is a design that meets every limit at every case, and its code check says so
//! with demands equal to those of the re-simulated design; a study whose limits no design
//! can meet reports the closest design, failing, naming the governing limit. The
//! objective's `worst` reading is the largest of the cases' objectives. Bad bounds and
//! limits are refused naming the field.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::base::metrics::RecordMetrics;
use slipload_opt::eval::evaluate::run_one;
use slipload_opt::eval::progress::NoProgress;
use slipload_opt::model::check::CaseName;
use slipload_opt::model::fidelity::Fidelity;
use slipload_opt::model::objective::Statistic;
use slipload_opt::pipeline::{NoFigures, OptimizeOptions, optimize_study};
use std::path::{Path, PathBuf};

mod common;
use common::folder;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The benchmark study on 3 synthetic records of 6 s, a short sweep and refinement,
/// with `patch` applied to its JSON.
fn study(patch: impl Fn(&mut serde_json::Value)) -> Result<Study, slipload_opt::OptError> {
    let path = root().join("configs/study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["suites"][0]["synthetic"]["count"] = 3.into();
    v["suites"][0]["synthetic"]["duration_s"] = 6.0.into();
    v["sweep"]["points"] = 10.into();
    v["refine"]["starts"] = 1.into();
    v["refine"]["max_evaluations"] = 6.into();
    v["refine"]["finalists"] = 2.into();
    v["fidelity"] = serde_json::json!({ "method": "newmark", "check_method": "newmark", "check_dt_factor": 0.5 });
    patch(&mut v);
    Study::from_json(&v.to_string(), &path)
}

/// An edit of the study's JSON.
type Patch = dyn Fn(&mut serde_json::Value);

fn bounds(v: &mut serde_json::Value) {
    v["property_bounds"] = serde_json::json!({
        "slip_load": { "lower": 0.8, "upper": 1.25 },
        "brace_stiffness": { "lower": 0.9, "upper": 1.1 },
        "objective_reads": "worst"
    });
}

fn limits(drift: f64) -> impl Fn(&mut serde_json::Value) {
    move |v: &mut serde_json::Value| {
        bounds(v);
        v["suites"][0]["limits"] = serde_json::json!({
            "criteria": [
                { "metric": "peak_drift_ratio", "statistic": "mean", "max": drift },
                { "metric": "residual_drift_ratio", "statistic": "max", "max": 0.005 }
            ],
            "unacceptable": { "max_count": 0, "record_limits": [ { "metric": "peak_drift_ratio", "max": 1.5 * drift } ] }
        });
        v["devices"] = serde_json::json!({ "brace_angle_deg": 35 });
    }
}

/// The same study with every brace stiffness of its building × `k` and no bounds.
fn braces_times(k: f64) -> Study {
    let b: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root().join("configs/benchmark-3story.json")).unwrap(),
    )
    .unwrap();
    let mut b = b;
    for d in b["dissipators"].as_array_mut().unwrap() {
        d["brace_stiffness"] = format!("{} N/m", 448.12e6 * k).into();
    }
    study(|v| v["building"] = b.clone()).unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slipload-check-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn a_bound_case_is_the_scaled_design_at_nominal_properties() {
    let st = study(bounds).unwrap();
    let n = st.records.len();
    assert_eq!(st.runs(), 3 * n);
    assert_eq!(st.run_name(n), format!("{} [lower]", st.records[0].name()));
    let fid = Fidelity::sweep(&st);
    let design = [900e3, 700e3, 400e3];
    for (case, lambda, k) in [(1, 0.8, 0.9), (2, 1.25, 1.1)] {
        let other = braces_times(k);
        let scaled: Vec<f64> = design.iter().map(|v| lambda * v).collect();
        for r in 0..n {
            let at_case = run_one(&st, &design, case * n + r, &fid, "case").unwrap();
            let by_hand = run_one(&other, &scaled, r, &fid, "by hand").unwrap();
            // one simulation, set up two ways: every bit agrees
            assert_eq!(at_case, by_hand, "case {case}, record {r}");
        }
    }
}

#[test]
fn the_worst_reading_is_the_largest_case_objective() {
    let worst = study(bounds).unwrap();
    let fid = Fidelity::sweep(&worst);
    let runs = |s: &Study, d: &[f64]| -> Vec<RecordMetrics> {
        (0..s.runs())
            .map(|r| run_one(s, d, r, &fid, "d").unwrap())
            .collect()
    };
    let bare = runs(&worst, &[0.0; 3]);
    let rows = runs(&worst, &[900e3, 700e3, 400e3]);
    let f = worst
        .objective_value(&rows, &bare, &[900e3, 700e3, 400e3])
        .unwrap();
    let n = worst.records.len();
    let per_case: Vec<f64> = (0..3)
        .map(|c| {
            let v: Vec<f64> = rows[c * n..(c + 1) * n]
                .iter()
                .map(RecordMetrics::peak_drift_ratio)
                .collect();
            Statistic::Mean.of(&v)
        })
        .collect();
    assert_eq!(
        f,
        per_case.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    );
    let nominal = study(|v| {
        bounds(v);
        v["property_bounds"]["objective_reads"] = "nominal".into();
    })
    .unwrap();
    assert_eq!(
        nominal
            .objective_value(&rows, &bare, &[900e3, 700e3, 400e3])
            .unwrap(),
        per_case[0]
    );
}

#[test]
fn the_optimum_meets_every_limit_and_its_check_is_the_resimulated_design() {
    let st = study(limits(0.012)).unwrap();
    let out = scratch("pass");
    let run = optimize_study(
        &st,
        &OptimizeOptions::default(),
        folder(&out),
        &NoProgress,
        &NoFigures,
    )
    .unwrap();
    let c = run.report.code_check.as_ref().unwrap();
    assert!(c.passes, "{}", c.verdict);
    assert!(c.verdict.starts_with("PASS"));
    for f in ["code-check.csv", "code-check.md", "code-check.json"] {
        assert!(out.join(f).is_file(), "{f}");
    }
    // re-simulate the optimum at each case, independently of the study's cases: the
    // scaled design on the building with scaled braces, at the check fidelity
    let optimum = &run.report.refine.optimum_loads;
    let check = Fidelity::check(&st);
    assert!(
        check.dampers,
        "a study with limits records the dampers at the check"
    );
    let n = st.records.len();
    let devices = run.report.devices.as_ref().unwrap();
    let mut all_runs: Vec<RecordMetrics> = Vec::new();
    for (case, lambda, k) in [
        (CaseName::Nominal, 1.0, 1.0),
        (CaseName::Lower, 0.8, 0.9),
        (CaseName::Upper, 1.25, 1.1),
    ] {
        let other = braces_times(k);
        let scaled: Vec<f64> = optimum.iter().map(|v| lambda * v).collect();
        let rows: Vec<RecordMetrics> = (0..n)
            .map(|r| run_one(&other, &scaled, r, &check, "again").unwrap())
            .collect();
        let drift: Vec<f64> = rows.iter().map(RecordMetrics::peak_drift_ratio).collect();
        let mean = Statistic::Mean.of(&drift);
        let residual = rows.iter().map(RecordMetrics::residual).fold(0.0, f64::max);
        let lines: Vec<_> = c.case_lines(case).collect();
        assert_eq!(lines.len(), 3);
        // the same numbers summed in the same order: equal to the last bit
        assert_eq!(lines[0].demand, mean, "{case:?}");
        assert_eq!(lines[1].demand, residual, "{case:?}");
        assert!(
            mean <= 0.012 && residual <= 0.005,
            "{case:?}: the claim holds"
        );
        let unacceptable = drift.iter().filter(|&&d| d > 1.5 * 0.012).count();
        assert_eq!(lines[2].demand, unacceptable as f64);
        assert_eq!(unacceptable, 0);
        all_runs.extend(rows);
    }
    // the device table: each damper's figures are the maxima over those simulations
    for (k, row) in devices.dampers.iter().enumerate() {
        let floor = st.space.dampers[k];
        let d: Vec<_> = all_runs
            .iter()
            .map(|m| m.dampers.as_ref().unwrap()[floor])
            .collect();
        let max = |f: &dyn Fn(&slipload_sim::response::DamperDemand) -> f64| {
            d.iter().map(f).fold(0.0, f64::max)
        };
        assert_eq!(row.floor, floor + 1);
        assert_eq!(row.peak_force_kn, max(&|x| x.peak_force_n) / 1e3);
        assert_eq!(row.stroke_mm[0], 1e3 * max(&|x| x.slip_max_pos_m));
        assert_eq!(row.stroke_mm[1], 1e3 * max(&|x| x.slip_max_neg_m));
        assert_eq!(
            row.slip_excursions,
            d.iter().map(|x| x.slip_excursions).max().unwrap()
        );
        assert_eq!(row.cycles, max(&|x| x.cycles));
        assert_eq!(row.energy_kj, max(&|x| x.energy_j) / 1e3);
        // a slip load is never passed: the friction force stays within the upper bound's
        // slip load (1.25 × nominal), to the round-off of the contact solve
        assert!(row.peak_force_kn <= 1.25 * row.slip_load_kn * (1.0 + 1e-9));
        // (the products in another order: round-off)
        for (got, want) in row
            .slip_load_range_kn
            .iter()
            .zip([0.8 * row.slip_load_kn, 1.25 * row.slip_load_kn])
        {
            assert!((got - want).abs() <= 1e-12 * want, "{got} vs {want}");
        }
        assert!(!row.never_slips, "these dampers slip under 0.4 g");
        // brace at the study's angle: F / cos θ and k′ / cos²θ
        let c = 35f64.to_radians().cos();
        assert_eq!(
            row.brace_axial_force_kn,
            Some(row.peak_force_kn * 1e3 / c / 1e3)
        );
        let k = 448.12e6;
        assert!((row.brace_axial_stiffness_mn_m.unwrap() - k / (c * c) / 1e6).abs() < 1e-9);
    }
    // a chevron: two braces at the angle share each damper's force and stiffness, so
    // each carries half the axial force and has half the axial stiffness (the products
    // in another order: round-off)
    let chevron = study(|v| {
        limits(0.012)(v);
        v["devices"]["braces_per_damper"] = 2.into();
    })
    .unwrap();
    let two = slipload_opt::phases::devices::DeviceTable::of(
        &chevron,
        optimum,
        &all_runs,
        "the check".into(),
    )
    .unwrap();
    assert_eq!(two.braces_per_damper, Some(2));
    for (one, two) in devices.dampers.iter().zip(&two.dampers) {
        for (a, b) in [
            (one.brace_axial_force_kn, two.brace_axial_force_kn),
            (
                one.brace_axial_stiffness_mn_m,
                two.brace_axial_stiffness_mn_m,
            ),
        ] {
            let (a, b) = (a.unwrap(), b.unwrap());
            assert!((b - a / 2.0).abs() <= 1e-12 * a, "{b} vs {a} / 2");
        }
    }
    assert!(
        two.to_markdown()
            .contains("2 brace(s) per damper (a chevron)")
    );
    for f in ["device-table.csv", "device-table.md", "device-table.json"] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let optimum_json = std::fs::read_to_string(out.join("optimum.json")).unwrap();
    assert!(optimum_json.contains("\"passes\": true"), "{optimum_json}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn limits_no_design_meets_end_with_the_closest_design_and_the_governing_limit() {
    // a mean peak drift of 0.1 % is beyond any slip load of the space
    let st = study(limits(0.001)).unwrap();
    let out = scratch("fail");
    let run = optimize_study(
        &st,
        &OptimizeOptions::default(),
        folder(&out),
        &NoProgress,
        &NoFigures,
    )
    .unwrap();
    let c = run.report.code_check.as_ref().unwrap();
    assert!(!c.passes);
    assert!(c.margin < 0.0);
    // the governing limit is a failing one, the largest ratio of all (here every record
    // exceeds the per-record limit: the count governs)
    let g = c.check.governing().unwrap();
    assert!(!g.pass);
    assert!(c.check.lines.iter().all(|l| l.ratio <= g.ratio));
    assert_eq!(g.source, "suites[0].limits.unacceptable");
    assert_eq!(g.demand, st.records.len() as f64);
    assert!(c.verdict.starts_with("FAIL"), "{}", c.verdict);
    assert!(
        c.chosen_as
            .contains("no evaluated design meets every limit")
    );
    // the files are written all the same
    assert!(out.join("code-check.md").is_file());
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_study_without_bounds_or_limits_has_one_case_and_no_check() {
    let st = study(|_| {}).unwrap();
    assert_eq!(st.runs(), st.records.len());
    assert!(st.checks.is_empty());
    let m = slipload_opt::phases::sweep::Manifest::of(&st);
    assert!(!m.to_json().contains("checks"));
}

#[test]
fn bad_bounds_and_limits_are_refused_by_field() {
    let cases: Vec<(Box<Patch>, &str)> = vec![
        (
            Box::new(|v| {
                v["property_bounds"] =
                    serde_json::json!({ "slip_load": { "lower": 1.2, "upper": 1.3 } })
            }),
            "property_bounds.slip_load.lower",
        ),
        (
            Box::new(|v| {
                v["property_bounds"] =
                    serde_json::json!({ "slip_load": { "lower": 0.8, "upper": 0.9 } })
            }),
            "property_bounds.slip_load.upper",
        ),
        (
            Box::new(
                |v| v["suites"][0]["limits"] = serde_json::json!({ "criteria": [ { "metric": "rpi", "statistic": "mean", "max": 1 } ] }),
            ),
            // the parser names the variant and the metrics a limit may read
            "unknown variant `rpi`, expected one of `peak_drift_ratio`",
        ),
        (
            Box::new(
                |v| v["suites"][0]["limits"] = serde_json::json!({ "criteria": [ { "metric": "peak_drift_ratio", "statistic": "mean", "max": -1 } ] }),
            ),
            "suites[0].limits.criteria[0].max",
        ),
        (
            Box::new(|v| v["suites"][0]["limits"] = serde_json::json!({})),
            "suites[0].limits.criteria",
        ),
        (
            Box::new(|v| v["devices"] = serde_json::json!({ "brace_angle_deg": 90 })),
            "devices.brace_angle_deg",
        ),
        (
            Box::new(|v| {
                limits(0.012)(v);
                v["devices"] = serde_json::json!({ "brace_angle_deg": 40, "braces_per_damper": 0 });
            }),
            "devices.braces_per_damper`: must be 1 (a single diagonal) to 8 (2: a chevron), got 0",
        ),
        (
            Box::new(|v| {
                limits(0.012)(v);
                v["devices"] = serde_json::json!({ "braces_per_damper": 2 });
            }),
            "devices.braces_per_damper`: the braces' forces and stiffnesses need their angle",
        ),
        // a brace angle without limits (no code check, so no device table) is refused,
        // not dropped
        (
            Box::new(|v| {
                bounds(v);
                v["devices"] = serde_json::json!({ "brace_angle_deg": 35 });
            }),
            "`devices`: the device table is written beside the code check, which needs acceptance limits",
        ),
        // a limit the elastic benchmark frame cannot evaluate is refused as it loads
        (
            Box::new(
                |v| v["suites"][0]["limits"] = serde_json::json!({ "criteria": [ { "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.02 }, { "metric": "peak_ductility", "statistic": "mean", "max": 4 } ] }),
            ),
            "suites[0].limits.criteria[1].metric`: peak_ductility needs a frame whose storeys yield",
        ),
        (
            Box::new(
                |v| v["suites"][0]["limits"] = serde_json::json!({ "unacceptable": { "record_limits": [ { "metric": "peak_ductility", "max": 6 } ] } }),
            ),
            "suites[0].limits.unacceptable.record_limits[0].metric`: peak_ductility needs",
        ),
        (
            Box::new(
                |v| v["objective"] = serde_json::json!({ "terms": [ { "metric": "peak_ductility", "statistic": "mean" } ] }),
            ),
            "objective.terms[0].metric`: peak_ductility needs",
        ),
    ];
    for (patch, field) in cases {
        let e = study(patch).unwrap_err().to_string();
        assert!(e.contains(field), "{field}: {e}");
    }
}

#[test]
fn a_damper_that_never_slips_is_flagged_as_a_rigid_brace() {
    // slip loads far above any storey force: the friction contact never breaks
    let st = study(limits(0.05)).unwrap();
    let fid = Fidelity::check(&st);
    let design = [3.0e9, 3.0e9, 3.0e9];
    let runs: Vec<RecordMetrics> = (0..st.runs())
        .map(|r| run_one(&st, &design, r, &fid, "locked").unwrap())
        .collect();
    let t = slipload_opt::phases::devices::DeviceTable::of(&st, &design, &runs, "check".into())
        .unwrap();
    assert_eq!(t.rigid_floors(), vec![1, 2, 3]);
    // a stuck contact's slip is the round-off of the floor's and the damper's
    // displacements (far below a nanometre), its dissipation as small
    for r in &t.dampers {
        assert!(
            r.stroke_mm[0] < 1e-6 && r.stroke_mm[1] < 1e-6,
            "{:?}",
            r.stroke_mm
        );
        assert_eq!(r.slip_excursions, 0);
        assert!(r.energy_kj.abs() < 1e-6, "{}", r.energy_kj);
    }
    assert!(
        t.to_markdown()
            .contains("acts as a rigid brace at this slip load")
    );
}

/// A base-shear limit is a number of newtons: one far below the building's weight (a
/// bare number meant as kN) is warned about as a slip load is ("did you mean kN?"),
/// naming the field; a plausible one is not.
#[test]
fn a_base_shear_limit_that_looks_like_kn_is_warned_about() {
    let with = |max: f64| {
        study(move |v| {
            v["suites"][0]["limits"] = serde_json::json!({ "criteria": [
                { "metric": "peak_drift_ratio", "statistic": "mean", "max": 0.02 },
                { "metric": "base_shear", "statistic": "mean", "max": max } ] });
        })
        .unwrap()
    };
    let w = with(5000.0).warnings();
    let shear: Vec<&String> = w.iter().filter(|w| w.contains("base-shear")).collect();
    assert_eq!(shear.len(), 1, "{w:?}");
    assert!(
        shear[0].starts_with("suites[0].limits.criteria[1].max: the base-shear limit 5000 N")
            && shear[0].contains("did you mean kN (5000000 N)?"),
        "{}",
        shear[0]
    );
    let w = with(5.0e6).warnings();
    assert!(!w.iter().any(|w| w.contains("base-shear")), "{w:?}");
}

/// The drift limit of the derived-bounds study.
const DRIFT: f64 = 0.0058;

/// Bounds built from their parts (`property_bounds.slip_load.derivation`) run exactly as
/// the same bounds given as numbers, and the code check prints how they were built and
/// the widest specification band at which the design passes (a drift limit close enough
/// that a band short of the widest searched fails).
#[test]
fn bounds_built_from_their_parts_run_as_their_numbers_and_the_check_prints_them() {
    let derived = |v: &mut serde_json::Value| {
        limits(DRIFT)(v);
        v["property_bounds"]["slip_load"] = serde_json::json!({ "derivation": {
            "testing": { "min": 0.9, "max": 1.1, "source": "prototype tests, report PT-1" },
            "aging_environment": { "min": 0.9, "max": 1.2 },
            "specification": { "min": 0.93, "max": 1.06 }
        } });
    };
    // ASCE 7-16 Eq. 17.2-1 and 17.2-2 by hand, in the order the study builds them
    let (lower, upper) = (
        (1.0 - 0.75 * (1.0 - 0.9)) * 0.9 * 0.93,
        (1.0 + 0.75 * (1.2 - 1.0)) * 1.1 * 1.06,
    );
    let numbers = move |v: &mut serde_json::Value| {
        limits(DRIFT)(v);
        v["property_bounds"]["slip_load"] = serde_json::json!({ "lower": lower, "upper": upper });
    };
    let (a, b) = (study(derived).unwrap(), study(numbers).unwrap());
    assert_eq!(a.checks.cases(), b.checks.cases());
    assert!(b.checks.derivations().is_empty());
    let out = scratch("derived-bounds");
    let run = optimize_study(
        &a,
        &OptimizeOptions::default(),
        folder(&out),
        &NoProgress,
        &NoFigures,
    )
    .unwrap();
    assert!(run.report.code_check.is_some());
    let md = std::fs::read_to_string(out.join("code-check.md")).unwrap();
    for line in [
        "- slip load: λ_max = (1 + 0.75 × (1.2 − 1)) × 1.1 × 1.06 = 1.3409",
        "- slip load: λ_min = (1 − 0.75 × (1 − 0.9)) × 0.9 × 0.93 = 0.7742",
        "- slip load, testing (0.9 to 1.1): prototype tests, report PT-1",
    ] {
        assert!(md.contains(line), "{line} in\n{md}");
    }
    let json = std::fs::read_to_string(out.join("code-check.json")).unwrap();
    assert!(json.contains("\"derivations\""), "{json}");
    // the widest specification band: the design passes there and fails one precision
    // step wider, each re-checked here on a study given the bounds as numbers
    let tol = run
        .report
        .code_check
        .as_ref()
        .unwrap()
        .tolerance
        .clone()
        .unwrap();
    assert!(
        md.contains("**Specification tolerance:** the widest"),
        "{md}"
    );
    let optimum = run.report.refine.finalists[0].slip_loads_n.clone();
    let passes_at = |t: f64| {
        let (lo, hi) = (
            (1.0 - 0.75 * (1.0 - 0.9)) * 0.9 * (1.0 - t),
            (1.0 + 0.75 * (1.2 - 1.0)) * 1.1 * (1.0 + t),
        );
        let s = study(move |v: &mut serde_json::Value| {
            limits(DRIFT)(v);
            v["property_bounds"]["slip_load"] = serde_json::json!({ "lower": lo, "upper": hi });
        })
        .unwrap();
        let fid = Fidelity::check(&s);
        let rows: Vec<RecordMetrics> = (0..s.runs())
            .map(|i| {
                slipload_opt::eval::evaluate::run_design(
                    &s,
                    &optimum.clone().into(),
                    i,
                    &fid,
                    "again",
                )
                .unwrap()
            })
            .collect();
        s.check_design(&rows).unwrap().passes()
    };
    let widest = tol
        .widest_band
        .expect("the optimum passes at the study's own band");
    assert!(widest >= 0.07, "{tol:?}: at least the study's ±7 %");
    assert!(passes_at(widest), "{tol:?}");
    // (measured: passes at ±19.47 %, fails at ±19.69 % after 9 checks)
    let (t, verdict) = tol.fails_at.clone().expect("a band short of ±50 % fails");
    assert!(
        t - widest <= slipload_opt::phases::tolerance::PRECISION,
        "{tol:?}"
    );
    assert!(verdict.starts_with("FAIL"), "{verdict}");
    assert!(!passes_at(t), "{tol:?}");
    let _ = std::fs::remove_dir_all(&out);
}
