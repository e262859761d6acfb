//! Contract: on the benchmark study (reduced to 3 records of 10 s so the test stays
//! fast) the trust-region refiner's optimum is within 1 % of the best objective of an
//! exhaustive 11³ grid over the same space, found with at most 10 % of the grid's
//! simulations (sweep included). Nelder–Mead and random search are run the same way and
//! their evaluations-to-within-1 % are printed for comparison.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::eval::evaluate::run_designs;
use slipload_opt::model::config::RefineMethod;
use slipload_opt::model::fidelity::Fidelity;
use slipload_opt::phases::refinement::optimize;
use slipload_opt::phases::sweep::Manifest;
use std::path::Path;

fn study(sweep: serde_json::Value) -> Study {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["suites"][0]["synthetic"]["count"] = 3.into();
    v["suites"][0]["synthetic"]["duration_s"] = 10.0.into();
    v["sweep"] = sweep;
    Study::from_json(&v.to_string(), &path).unwrap()
}

fn rows_of(study: &Study, m: &Manifest) -> Vec<slipload_opt::RecordMetrics> {
    let designs: Vec<Vec<f64>> = m.designs.iter().map(|d| d.slip_loads_n.clone()).collect();
    run_designs(study, &designs, &Fidelity::sweep(study), &|| {})
        .unwrap()
        .into_iter()
        .flatten()
        .collect()
}

#[test]
fn trust_region_matches_a_fine_grid_with_a_tenth_of_its_simulations() {
    let grid_study = study(serde_json::json!({ "sampler": "grid", "levels": 11 }));
    let gm = Manifest::of(&grid_study);
    let grid_designs = gm.designs.len() - 2;
    assert_eq!(grid_designs, 1331);
    let gobj = gm.objectives(&rows_of(&grid_study, &gm)).unwrap();
    let grid_best = gobj[2..].iter().map(|o| o.0).fold(f64::INFINITY, f64::min);

    let st = study(serde_json::json!({ "sampler": "halton", "points": 48, "seed": 2007 }));
    let m = Manifest::of(&st);
    let rows = rows_of(&st, &m);
    let mut lines = Vec::new();
    for method in [
        RefineMethod::TrustRegion,
        RefineMethod::NelderMead,
        RefineMethod::Random,
    ] {
        let r = optimize(&st, &m, &rows, method, None, None, &|| {}).unwrap();
        assert!(st.space.is_feasible(&r.optimum.z));
        // evaluations (sweep designs + refinement designs) until within 1 % of the grid's best
        let target = 1.01 * grid_best;
        let within = if r.best_sweep.f <= target {
            Some(r.sweep_designs)
        } else {
            r.log
                .iter()
                .position(|p| p.f <= target)
                .map(|i| r.sweep_designs + i + 1)
        };
        lines.push(format!(
            "{:>13}: optimum {:.6} ({:+.3} % vs grid {:.6}), designs to within 1 %: {}, refine designs {}",
            method.as_str(),
            r.optimum.f,
            100.0 * (r.optimum.f / grid_best - 1.0),
            grid_best,
            within.map_or("never".to_string(), |n| n.to_string()),
            r.log.len()
        ));
        if method == RefineMethod::TrustRegion {
            assert!(
                r.optimum.f <= target,
                "trust region {} not within 1 % of the grid's {grid_best}",
                r.optimum.f
            );
            let used = r.sweep_designs + r.log.len();
            assert!(
                used * 10 <= grid_designs,
                "{used} designs is more than 10 % of the grid's {grid_designs}"
            );
        }
    }
    eprintln!("{}", lines.join("\n"));
}
