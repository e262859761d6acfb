//! Studies in plan (issue 46 §4): the design space by line and by direction, the planar
//! split, accidental torsion as property cases, the journal's replay, thread
//! independence, limits, refusals by field — and the placement question: on a
//! plan-asymmetric building the optimum puts more of a direction's slip load on the
//! flexible edge than the planar placement (in proportion to stiffness) does, and drifts
//! less at the edges for the same total.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use serde_json::{Value, json};
use slipload_opt::pipeline::{NoFigures, optimize_in_plan};
use slipload_opt::plan::report::{line_shares, planar_split};
use slipload_opt::plan::{PlanStudy, Step, evaluate_loads};
use slipload_opt::store::folder::FolderRequest;
use std::path::{Path, PathBuf};

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slipload-plan-study-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A two-column record (time, m/s²): a decaying sum of sines, its own per `seed`.
fn write_record(dir: &Path, name: &str, seed: f64) -> String {
    let dt = 0.01;
    let mut s = String::new();
    for i in 0..=600 {
        let t = i as f64 * dt;
        let env = (t / 0.8).min(1.0) * (-(t - 2.0).max(0.0) / 1.5).exp();
        let a = env
            * (3.0 * (2.0 * std::f64::consts::PI * (1.6 + 0.2 * seed) * t).sin()
                + 2.0 * (2.0 * std::f64::consts::PI * (0.9 + 0.1 * seed) * t + seed).sin()
                + 1.5 * (2.0 * std::f64::consts::PI * 3.1 * t + 2.0 * seed).cos());
        s.push_str(&format!("{t:.2},{a:.6}\n"));
    }
    let file = format!("{name}.csv");
    std::fs::write(dir.join(&file), s).unwrap();
    file
}

/// A three-storey 20 x 12 m plan: along y the stiff line A (x = 0, 70 %) and the
/// flexible line D (x = 20 m, 30 %); along x two equal lines 1 (y = 0) and 2 (y = 12 m);
/// a massless damper per line and storey on a brace as stiff as the line's storey.
fn building(a_share: f64) -> Value {
    let total = [160.0, 140.0, 110.0]; // MN/m per storey and direction
    let line = |name: &str, dir: &str, at: f64, share: f64, slip: f64| {
        let k: Vec<String> = total
            .iter()
            .map(|t| format!("{} MN/m", t * share))
            .collect();
        let dampers: Vec<Value> = (0..3)
            .map(|f| {
                json!({"floor": f + 1, "brace_stiffness": k[f], "slip_load": format!("{} kN", slip * (1.0 - 0.25 * f as f64))})
            })
            .collect();
        json!({"name": name, "direction": dir, "at": at, "storey_stiffness": k, "dissipators": dampers})
    };
    json!({
        "name": "three-storey plan",
        "plan_size": ["20 m", "12 m"],
        "floors": [{"mass": "200 t"}, {"mass": "200 t"}, {"mass": "180 t"}],
        "storey_heights": ["3.5 m", "3.5 m", "3.5 m"],
        "damping": {"modal": {"ratio": 0.03}},
        "lines": [
            line("A", "y", 0.0, a_share, 250.0 * a_share / 0.5),
            line("D", "y", 20.0, 1.0 - a_share, 250.0 * (1.0 - a_share) / 0.5),
            line("1", "x", 0.0, 0.5, 250.0),
            line("2", "x", 12.0, 0.5, 250.0),
        ]
    })
}

fn study(dir: &Path, a_share: f64, edit: impl FnOnce(&mut Value)) -> PathBuf {
    let r: Vec<String> = (0..4)
        .map(|k| write_record(dir, &format!("rec{k}"), k as f64))
        .collect();
    let mut v = json!({
        "name": "small plan",
        "building": building(a_share),
        "suites": [{"name": "pairs", "pairs": [[r[0], r[1]], [r[2], r[3]]], "angles_deg": [0, 90]}],
        "space": {"placement": "lines", "slip_load_kn": [0, 1500]},
        "sweep": {"points": 12},
        "refine": {"max_evaluations": 30}
    });
    edit(&mut v);
    let p = dir.join("study.json");
    std::fs::write(&p, serde_json::to_string_pretty(&v).unwrap()).unwrap();
    p
}

fn run(path: &Path, out: &Path) -> slipload_opt::pipeline::PlanRun {
    let s = PlanStudy::load(path).unwrap();
    optimize_in_plan(
        &s,
        FolderRequest {
            path: out,
            option: "--out",
            fresh: false,
        },
        &slipload_opt::eval::progress::NoProgress,
        &NoFigures,
    )
    .unwrap()
}

fn read_all(dir: &Path) -> Vec<(String, String)> {
    let mut v: Vec<(String, String)> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            (name, std::fs::read_to_string(e.path()).unwrap())
        })
        .filter(|(n, _)| n.starts_with("plan-"))
        .collect();
    v.sort();
    v
}

#[test]
fn the_directions_placement_splits_each_storey_by_stiffness_and_follows_the_storey_shear() {
    let dir = tmp("directions");
    let p = study(&dir, 0.7, |v| v["space"]["placement"] = json!("directions"));
    let s = PlanStudy::load(&p).unwrap();
    assert_eq!(s.space.dim(), 2);
    let loads = s.all_slip_loads(&[0.4, 0.7]);
    let at = |name: &str| {
        let k = s.dampers.iter().position(|d| d.name == name).unwrap();
        loads[k].unwrap()
    };
    for f in 1..=3 {
        // A : D = 70 : 30 at every storey, the stiffness shares (round-off of the map)
        let ratio = at(&format!("A/{f}")) / at(&format!("D/{f}"));
        assert!(
            (ratio - 0.7 / 0.3).abs() < 1e-12 * ratio,
            "storey {f}: {ratio}"
        );
        let r12 = at(&format!("1/{f}")) / at(&format!("2/{f}"));
        assert!((r12 - 1.0).abs() < 1e-12);
    }
    // the direction's first-storey total is the variable: 0.4 of [0, 1500] kN
    let total1 = at("A/1") + at("D/1");
    assert!((total1 - 600e3).abs() < 1e-9 * 600e3, "{total1}");
    // up the height as the storey shear of a triangular pattern: Σ m h above
    let (m, h) = ([200.0, 200.0, 180.0], [3.5, 7.0, 10.5]);
    let shear = |i: usize| (i..3).map(|j| m[j] * h[j]).sum::<f64>();
    for f in 2..=3 {
        let total = at(&format!("A/{f}")) + at(&format!("D/{f}"));
        let want = 600e3 * shear(f - 1) / shear(0);
        assert!(
            (total - want).abs() < 1e-9 * want,
            "storey {f}: {total} vs {want}"
        );
    }
}

#[test]
fn the_planar_split_keeps_every_storey_total_and_splits_it_by_stiffness() {
    let dir = tmp("split");
    let p = study(&dir, 0.7, |_| {});
    let s = PlanStudy::load(&p).unwrap();
    assert_eq!(s.space.dim(), 4);
    let loads = s.all_slip_loads(&[0.2, 0.9, 0.5, 0.1]);
    let split = planar_split(&s, &loads);
    let get = |v: &[Option<f64>], name: &str| {
        v[s.dampers.iter().position(|d| d.name == name).unwrap()].unwrap()
    };
    for f in 1..=3 {
        for (a, b, share) in [("A", "D", 0.7), ("1", "2", 0.5)] {
            let (na, nb) = (format!("{a}/{f}"), format!("{b}/{f}"));
            let before = get(&loads, &na) + get(&loads, &nb);
            let after = get(&split, &na) + get(&split, &nb);
            assert!((before - after).abs() < 1e-12 * before);
            assert!((get(&split, &na) / after - share).abs() < 1e-12);
        }
    }
    let shares = line_shares(&s, &split);
    let d = shares.iter().find(|(n, _)| n == "D").unwrap().1;
    assert!((d - 0.3).abs() < 1e-12, "{d}");
}

#[test]
fn the_optimum_puts_more_slip_load_on_the_flexible_edge_than_the_planar_split_and_drifts_less() {
    let dir = tmp("placement");
    let p = study(&dir, 0.7, |_| {});
    let out = dir.join("out");
    let r = run(&p, &out);
    let s = PlanStudy::load(&p).unwrap();
    let opt = r.report.row("optimum").unwrap();
    let planar = r.report.row("planar split").unwrap();
    let shares = line_shares(&s, &opt.eval.loads);
    let d = shares.iter().find(|(n, _)| n == "D").unwrap().1;
    println!("flexible line D's share at the optimum: {d:.3} (planar 0.300)");
    println!(
        "edge drift: optimum {:.5}, planar split {:.5}, file {:.5}, bare {:.5}",
        opt.objective,
        planar.objective,
        r.report.row("file").unwrap().objective,
        r.report.row("bare").unwrap().objective
    );
    assert!(d > 0.3 + 0.05, "the flexible line carries {d}");
    // the same total slip load, placed by stiffness, drifts more at the edges
    let total = |row: &slipload_opt::plan::PlanRow| -> f64 {
        row.eval.loads.iter().map(|l| l.unwrap()).sum()
    };
    assert!((total(opt) - total(planar)).abs() < 1e-9 * total(opt));
    assert!(
        opt.objective < planar.objective,
        "{} vs {}",
        opt.objective,
        planar.objective
    );
    // and the dampers do their work: the bare frame drifts more than the optimum
    assert!(opt.objective < r.report.row("bare").unwrap().objective);
    // the device table's demands: the stroke is the peak slip (the slip starts at 0), the
    // force never passes the slip load, the dampers that slip dissipate
    for c in &opt.eval.cells {
        let dv = &c.peaks.devices;
        assert_eq!(dv.stroke.len(), s.dampers.len());
        for k in 0..s.dampers.len() {
            let load = opt.eval.loads[k].unwrap();
            assert!((dv.stroke[k] - c.peaks.slip[k]).abs() <= 1e-12 * c.peaks.slip[k].max(1e-12));
            assert!(
                dv.force[k] <= load * (1.0 + 1e-9),
                "{} > {load}",
                dv.force[k]
            );
            if c.peaks.slip[k] > 1e-6 {
                assert!(dv.energy[k] > 0.0 && dv.velocity[k] > 0.0 && dv.travel[k] >= dv.stroke[k]);
            }
        }
    }
    let table = std::fs::read_to_string(out.join("plan-devices.csv")).unwrap();
    assert_eq!(table.lines().count(), 1 + s.dampers.len());
    // every file the run names is there
    for f in r.files {
        assert!(out.join(f).is_file(), "{f}");
    }
    assert!(out.join("plan-journal.jsonl").is_file());
}

#[test]
fn a_rerun_replays_the_journal_and_a_cut_journal_resumes_to_the_same_bytes() {
    let dir = tmp("replay");
    let p = study(&dir, 0.7, |v| v["refine"]["max_evaluations"] = json!(12));
    let out = dir.join("out");
    let first = run(&p, &out);
    let bytes = read_all(&out);
    let n = first.report.sweep_designs + first.report.refine_designs;
    let again = run(&p, &out);
    assert_eq!(again.report.replayed, n, "every design from the journal");
    assert_eq!(read_all(&out), bytes);
    // an interruption: the journal cut in the middle of a line, half its designs gone
    let j = out.join("plan-journal.jsonl");
    let text = std::fs::read_to_string(&j).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let keep = 1 + n / 2;
    let mut cut = lines[..keep].join("\n");
    cut.push('\n');
    cut.push_str(&lines[keep][..lines[keep].len() / 2]);
    std::fs::write(&j, cut).unwrap();
    let resumed = run(&p, &out);
    assert_eq!(resumed.report.replayed, keep - 1);
    assert_eq!(read_all(&out), bytes);
    // a larger budget continues from the journal: every design run before is replayed
    let more = study(&dir, 0.7, |v| v["refine"]["max_evaluations"] = json!(20));
    let r = run(&more, &out);
    assert!(r.report.replayed >= n, "{} of {n}", r.report.replayed);
    assert!(r.report.refine_designs > first.report.refine_designs);
}

#[test]
fn another_studys_journal_is_refused() {
    let dir = tmp("foreign");
    let p = study(&dir, 0.7, |v| v["refine"]["max_evaluations"] = json!(0));
    let out = dir.join("out");
    run(&p, &out);
    let p2 = study(&dir, 0.6, |v| v["refine"]["max_evaluations"] = json!(0));
    let s = PlanStudy::load(&p2).unwrap();
    let e = optimize_in_plan(
        &s,
        FolderRequest {
            path: &out,
            option: "--out",
            fresh: false,
        },
        &slipload_opt::eval::progress::NoProgress,
        &NoFigures,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("another study") && e.contains("--fresh"), "{e}");
}

#[test]
fn the_results_do_not_depend_on_the_threads() {
    let dir = tmp("threads");
    let p = study(&dir, 0.7, |v| v["refine"]["max_evaluations"] = json!(10));
    let mut outs = Vec::new();
    for threads in [1, 2] {
        let out = dir.join(format!("out{threads}"));
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| run(&p, &out));
        outs.push(read_all(&out));
    }
    assert_eq!(outs[0], outs[1]);
}

#[test]
fn accidental_torsion_on_a_symmetric_plan_gives_mirrored_cases_and_no_twist_in_the_nominal() {
    let dir = tmp("torsion");
    let p = study(&dir, 0.5, |v| v["accidental_torsion"] = json!(0.05));
    let s = PlanStudy::load(&p).unwrap();
    assert_eq!(s.cases.len(), 5);
    assert_eq!(s.cases[1].name, "centre of mass +5 % x");
    // moved by 5 % of 20 m along x: 1 m
    let c0 = s.cases[0].building.floors[0].centre;
    let c1 = s.cases[1].building.floors[0].centre;
    assert!((c1[0] - c0[0] - 1.0).abs() < 1e-12 && c1[1] == c0[1]);
    // the case is the building written with its centres moved: its mass, modes and
    // damping (modal, on its own modes) are that file's (round-off of the eigensolver)
    let mut moved = building(0.5);
    for f in moved["floors"].as_array_mut().unwrap() {
        f["centre_of_mass"] = json!(["11 m", "6 m"]);
    }
    let cfg: slipload_sim::floorplan::FloorPlanConfig = serde_json::from_value(moved).unwrap();
    let direct = slipload_sim::floorplan::FloorPlan::from_config(&cfg, Path::new("moved")).unwrap();
    let case = &s.cases[1].building;
    let close =
        |a: &nalgebra::DMatrix<f64>, b: &nalgebra::DMatrix<f64>| (a - b).amax() <= 1e-9 * b.amax();
    assert!(close(&case.mass, &direct.mass));
    assert!(
        close(&case.damping, &direct.damping),
        "the damping of the moved plan is its own"
    );
    assert!(!close(&case.damping, &s.cases[0].building.damping));
    let loads: Vec<Option<f64>> = s.dampers.iter().map(|d| d.file_slip_load).collect();
    let e = &evaluate_loads(&s, &[loads], Step::SEARCH).unwrap()[0];
    let cell = |case: usize| e.cells.iter().find(|c| c.case == case).unwrap();
    // the nominal symmetric plan does not twist (ratio 1 to round-off)
    assert!(
        (cell(0).torsional - 1.0).abs() < 1e-9,
        "{}",
        cell(0).torsional
    );
    // the centre moved +x or -x by the same amount: the mirror image (edges exchanged)
    for (a, b) in [(1, 2), (3, 4)] {
        let (x, y) = (cell(a).edge, cell(b).edge);
        assert!((x - y).abs() < 1e-9 * x, "cases {a} and {b}: {x} vs {y}");
        assert!(
            cell(a).torsional > 1.0 + 1e-6,
            "a shifted centre twists the plan"
        );
    }
    // the objective reads the worst case
    let worst = (0..5).map(|c| cell(c).edge).fold(0.0, f64::max);
    assert_eq!(e.objective(&s), worst);
}

#[test]
fn property_bounds_run_every_case_at_the_lower_and_upper_slip_loads_and_the_limits_read_them() {
    let dir = tmp("bounds");
    let plain = PlanStudy::load(&study(&dir, 0.7, |v| {
        v["accidental_torsion"] = json!(0.05);
        v["limits"] = json!({"edge_drift_ratio": 0.05});
    }))
    .unwrap();
    let s = PlanStudy::load(&study(&dir, 0.7, |v| {
        v["accidental_torsion"] = json!(0.05);
        v["limits"] = json!({"edge_drift_ratio": 0.05});
        v["property_bounds"] = json!({"slip_load": {"lower": 0.8, "upper": 1.25},
                                      "brace_stiffness": {"lower": 0.9, "upper": 1.1}});
    }))
    .unwrap();
    // the five torsion cases at nominal properties, then at the lower and the upper bound
    assert_eq!(s.cases.len(), 15);
    assert_eq!(s.cases[5].name, "lower bound");
    assert_eq!(s.cases[11].name, "upper bound, centre of mass +5 % x");
    assert_eq!(s.runs_per_design(), 3 * plain.runs_per_design());
    // the case's building carries the factors on every damper
    let loads: Vec<Option<f64>> = s.dampers.iter().map(|d| d.file_slip_load).collect();
    let b = s.with_slip_loads(11, &loads);
    let nominal = s.with_slip_loads(1, &loads);
    for site in &s.dampers {
        let (d, n) = (
            b.lines[site.line].dissipators[site.storey].unwrap(),
            nominal.lines[site.line].dissipators[site.storey].unwrap(),
        );
        assert!((d.upper - 1.25 * n.upper).abs() <= 1e-12 * n.upper);
        assert!((d.lower - 1.25 * n.lower).abs() <= 1e-12 * n.upper);
        assert!((d.brace_stiffness - 1.1 * n.brace_stiffness).abs() <= 1e-12 * n.brace_stiffness);
    }
    assert_eq!(s.cases[11].building.floors, s.cases[1].building.floors);
    let e = &evaluate_loads(&s, std::slice::from_ref(&loads), Step::SEARCH).unwrap()[0];
    let p = &evaluate_loads(&plain, std::slice::from_ref(&loads), Step::SEARCH).unwrap()[0];
    // the nominal-property cells are the plain study's, bit for bit: the same runs
    for c in &p.cells {
        let same = e
            .cells
            .iter()
            .find(|x| x.suite == c.suite && x.case == c.case)
            .unwrap();
        assert_eq!(same.peaks, c.peaks);
    }
    // objective_reads defaults to nominal: the objective is the plain study's
    assert_eq!(e.objective(&s), p.objective(&plain));
    // the limit reads the worst case, bounds included: the lower bound slips more and
    // drifts more here, so the ratio is the bounds' and above the plain study's
    let worst_edge = e.cells.iter().map(|c| c.edge).fold(0.0, f64::max);
    assert!((e.ratios(&s)[0] - worst_edge / 0.05).abs() <= 1e-15 * worst_edge / 0.05);
    assert!(
        e.ratios(&s)[0] > p.ratios(&plain)[0],
        "{:?} vs {:?}",
        e.ratios(&s),
        p.ratios(&plain)
    );
    // objective_reads worst: the objective is the worst case of all fifteen
    let w = PlanStudy::load(&study(&dir, 0.7, |v| {
        v["accidental_torsion"] = json!(0.05);
        v["property_bounds"] =
            json!({"slip_load": {"lower": 0.8, "upper": 1.25}, "objective_reads": "worst"});
    }))
    .unwrap();
    let ew = &evaluate_loads(&w, std::slice::from_ref(&loads), Step::SEARCH).unwrap()[0];
    let all = ew.cells.iter().map(|c| c.edge).fold(0.0, f64::max);
    assert_eq!(ew.objective(&w), all);
    assert!(
        all > ew
            .cells
            .iter()
            .filter(|c| c.case < 5)
            .map(|c| c.edge)
            .fold(0.0, f64::max)
    );
    // the device table's peak force is the worst case's: the upper bound's slip load
    let demand = Step {
        factor: 1.0,
        demands: true,
    };
    let ed = &evaluate_loads(&s, std::slice::from_ref(&loads), demand).unwrap()[0];
    let force = |case: usize, k: usize| {
        ed.cells
            .iter()
            .filter(|c| c.case == case)
            .map(|c| c.peaks.devices.force[k])
            .fold(0.0, f64::max)
    };
    let k = (0..s.dampers.len())
        .max_by(|a, b| force(0, *a).total_cmp(&force(0, *b)))
        .unwrap();
    let nominal_load = loads[k].unwrap();
    assert!(force(0, k) <= nominal_load * (1.0 + 1e-9));
    assert!(
        force(10, k) > nominal_load * 1.01 && force(10, k) <= 1.25 * nominal_load * (1.0 + 1e-9),
        "damper {}: {} N at the upper bound, slip load {} N",
        s.dampers[k].name,
        force(10, k),
        nominal_load
    );
    // bad factors are refused by name
    let bad = study(&dir, 0.7, |v| {
        v["property_bounds"] = json!({"slip_load": {"lower": 1.2, "upper": 1.25}});
    });
    let err = PlanStudy::load(&bad).unwrap_err().to_string();
    assert!(err.contains("property_bounds.slip_load"), "{err}");
}

#[test]
fn a_suite_of_pairs_scaled_to_a_code_spectrum_meets_it_by_their_maximum_direction_spectra() {
    let dir = tmp("code");
    let spectrum = json!({"sds_g": 0.9, "sd1_g": 0.5, "tl_s": 8.0, "min_records": 2});
    let p = study(&dir, 0.7, |v| {
        v["suites"][0]["code_spectrum"] = spectrum.clone()
    });
    let s = PlanStudy::load(&p).unwrap();
    let su = &s.suites[0];
    let c = su.code.as_ref().unwrap();
    assert_eq!(su.factor, c.factor);
    assert_eq!(c.pairs, Some(2));
    // the range from the plan's own periods: 2 × the larger first-mode period of x and
    // y (bare), down to the lesser of 0.2 × the braced plan's smaller one and the
    // 90 %-mass period
    let periods = s.building.scaling_periods().unwrap();
    assert!((c.range_s[1] - 2.0 * periods.bare_t1_s).abs() <= 1e-12 * c.range_s[1]);
    assert!(
        (c.range_s[0] - (0.2 * periods.stuck_t1_s).min(periods.mass_90_period_s)).abs()
            <= 1e-12 * c.range_s[0]
    );
    assert!(periods.stuck_t1_s < periods.bare_t1_s);
    // the factor is the one that meets 90 % of the target: nowhere below, touching it at
    // the controlling period (the grid's resolution, 1e-9)
    let ratio = c
        .mean_sa_g
        .iter()
        .zip(&c.target_sa_g)
        .map(|(m, t)| m / (0.9 * t))
        .fold(f64::INFINITY, f64::min);
    assert!(
        (ratio - 1.0).abs() < 1e-6,
        "least mean / (0.9 target) {ratio}"
    );
    // both components of every pair carry that factor (the unscaled study's pairs × it)
    let plain = PlanStudy::load(&study(&dir, 0.7, |_| {})).unwrap();
    for (a, b) in su.pairs.iter().zip(&plain.suites[0].pairs) {
        for (x, y) in [(&a.first, &b.first), (&a.second, &b.second)] {
            let k = x.samples().len() / 2;
            assert!((x.samples()[k] - c.factor * y.samples()[k]).abs() <= 1e-12 * x.pga());
        }
    }
    // the summary says so
    let out = dir.join("out");
    let std = run(
        &study(&dir, 0.7, |v| {
            v["suites"][0]["code_spectrum"] = spectrum.clone();
            v["sweep"] = json!({"points": 2});
            v["refine"] = json!({"max_evaluations": 0});
        }),
        &out,
    );
    assert!(
        std.summary
            .contains("scaled to a code spectrum, S_DS = 0.9 g"),
        "{}",
        std.summary
    );
    // refused with the pairs' field: too few pairs for the standard, and a factor too
    let few = study(&dir, 0.7, |v| {
        v["suites"][0]["code_spectrum"] = json!({"sds_g": 0.9, "sd1_g": 0.5, "tl_s": 8.0});
    });
    let e = PlanStudy::load(&few).unwrap_err().to_string();
    assert!(
        e.contains("suites[0].pairs") && e.contains("7 pairs"),
        "{e}"
    );
    let both = study(&dir, 0.7, |v| {
        v["suites"][0]["code_spectrum"] = spectrum.clone();
        v["suites"][0]["factor"] = json!(2.0);
    });
    let e = PlanStudy::load(&both).unwrap_err().to_string();
    assert!(e.contains("suites[0].factor"), "{e}");
}

#[test]
fn the_device_test_protocol_reads_the_strokes_the_secant_periods_and_the_bounds() {
    let dir = tmp("protocol");
    let p = study(&dir, 0.7, |v| {
        v["property_bounds"] = json!({"slip_load": {"lower": 0.85, "upper": 1.2}});
        v["devices"] =
            json!({"test_protocol": {"cycles": 5, "band_percent": 15, "production_cycles": 2}});
        v["sweep"] = json!({"points": 2});
        v["refine"] = json!({"max_evaluations": 0});
    });
    let out = dir.join("out");
    let r = run(&p, &out);
    let s = PlanStudy::load(&p).unwrap();
    let opt = r.report.row("optimum").unwrap();
    let demands = slipload_opt::plan::report::device_demands(opt);
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan-optimum.json")).unwrap())
            .unwrap();
    let t = &json["test_protocol"];
    let t1m: Vec<f64> = t["t1m_s"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let t1: Vec<f64> = t["t1_s"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    // slipping dampers add F/δ: the secant plan is stiffer than the bare one (no line yields)
    assert!(t1m[0] < t1[0] && t1m[1] < t1[1], "{t1m:?} {t1:?}");
    let rows = t["dampers"].as_array().unwrap();
    assert_eq!(rows.len(), s.dampers.len());
    for (k, d) in rows.iter().enumerate() {
        let a = d["amplitude_mm"].as_f64().unwrap();
        // one suite: the stroke is the device table's (its worst case), in mm
        assert!(
            (a - 1e3 * demands[k][0]).abs() <= 1e-12 * a.max(1e-9),
            "{d}"
        );
        let dir = d["direction"].as_u64().unwrap() as usize;
        let line = &s.building.lines[s.dampers[k].line];
        assert_eq!(
            dir,
            usize::from(line.direction().1.abs() > line.direction().0.abs())
        );
        let v = d["velocity_mm_s"].as_f64().unwrap();
        assert!((v - 2.0 * std::f64::consts::PI * a / t1m[dir]).abs() <= 1e-12 * v.max(1e-9));
        let f: Vec<f64> = d["force_kn"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let load = opt.eval.loads[k].unwrap() / 1e3;
        assert!((f[0] - load).abs() <= 1e-12 * load && (f[1] - 0.85 * load).abs() <= 1e-12 * load);
        assert!((f[2] - 1.2 * load).abs() <= 1e-12 * load);
        let e = d["loop_energy_kj"][0].as_f64().unwrap();
        assert!((e - 4.0 * load * a / 1e3).abs() <= 1e-12 * e.max(1e-12));
    }
    let md = std::fs::read_to_string(out.join("plan-devices.md")).unwrap();
    assert!(
        md.contains("## Test protocol") && md.contains("**Production test**"),
        "{md}"
    );
    assert_eq!(md.matches("| D\\/").count(), 2 * 3, "{md}"); // device table and protocol rows
    // a band out of range is refused by its field
    let bad = study(&dir, 0.7, |v| {
        v["devices"] = json!({"test_protocol": {"cycles": 5, "band_percent": 150}});
    });
    let e = PlanStudy::load(&bad).unwrap_err().to_string();
    assert!(e.contains("devices.test_protocol.band_percent"), "{e}");
}

#[test]
fn the_least_slip_load_that_passes_an_edge_drift_limit_passes_it() {
    let dir = tmp("least");
    // the limit between the bare frame's edge drift and the file design's
    let p0 = study(&dir, 0.7, |_| {});
    let s0 = PlanStudy::load(&p0).unwrap();
    let bare: Vec<Option<f64>> = s0.dampers.iter().map(|_| Some(0.0)).collect();
    let file: Vec<Option<f64>> = s0.dampers.iter().map(|d| d.file_slip_load).collect();
    let e = evaluate_loads(&s0, &[bare, file], Step::SEARCH).unwrap();
    let limit = 0.5 * (e[0].objective(&s0) + e[1].objective(&s0));
    let p = study(&dir, 0.7, |v| {
        v["objective"] = json!({"metric": "total_slip_load"});
        v["limits"] = json!({"edge_drift_ratio": limit});
    });
    let out = dir.join("out");
    let r = run(&p, &out);
    let opt = r.report.row("optimum").unwrap();
    assert!(!r.report.row("bare").unwrap().passes);
    // passes at the search's step; the finer check may move it by its error only
    assert!(opt.ratios[0] <= 1.0 + 1e-3, "{:?}", opt.ratios);
    // the check page states the verdict and each storey against the limit
    let check = std::fs::read_to_string(out.join("plan-check.md")).unwrap();
    let verdict = if opt.passes {
        "## optimum — PASS"
    } else {
        "## optimum — FAIL"
    };
    assert!(check.contains(verdict), "{check}");
    assert!(
        check.contains(&format!("| {:.3} |", limit * 100.0)),
        "{check}"
    );
    let total: f64 = opt.eval.loads.iter().map(|l| l.unwrap()).sum();
    let file_total: f64 = s0.dampers.iter().map(|d| d.file_slip_load.unwrap()).sum();
    println!(
        "least total slip load {:.1} kN (file {:.1} kN)",
        total / 1e3,
        file_total / 1e3
    );
    assert!(
        total < file_total,
        "the least slip load that passes is below a design that passes easily"
    );
}

#[test]
fn bad_studies_are_refused_naming_the_field() {
    let dir = tmp("refusals");
    type Edit = Box<dyn Fn(&mut Value)>;
    let cases: Vec<(&str, Edit)> = vec![
        (
            "space.lines[0]",
            Box::new(|v| v["space"]["lines"] = json!(["Z"])),
        ),
        (
            "space.shape",
            Box::new(|v| {
                v["space"]["placement"] = json!("free");
                v["space"]["shape"] = json!("uniform");
            }),
        ),
        (
            "space.slip_load_kn",
            Box::new(|v| v["space"]["slip_load_kn"] = json!([5, 1])),
        ),
        (
            "objective.metric",
            Box::new(|v| v["objective"] = json!({"metric": "total_slip_load"})),
        ),
        (
            "objective.metric",
            Box::new(|v| {
                v["building"]
                    .as_object_mut()
                    .unwrap()
                    .remove("storey_heights");
            }),
        ),
        (
            "accidental_torsion",
            Box::new(|v| v["accidental_torsion"] = json!(0.5)),
        ),
        ("limits", Box::new(|v| v["limits"] = json!({}))),
        (
            "limits.torsional_ratio",
            Box::new(|v| v["limits"] = json!({"torsional_ratio": 0.9})),
        ),
        (
            "suites[0].angles_deg",
            Box::new(|v| v["suites"][0]["angles_deg"] = json!([])),
        ),
        (
            "suites[0].pairs[1][0]",
            Box::new(|v| v["suites"][0]["pairs"][1][0] = json!("missing.csv")),
        ),
        (
            "fidelity.method",
            Box::new(|v| v["fidelity"] = json!({"method": "delacruz"})),
        ),
        (
            "space.budget_kn",
            Box::new(|v| {
                v["space"]["slip_load_kn"] = json!([100, 1500]);
                v["space"]["budget_kn"] = json!(10);
            }),
        ),
    ];
    for (field, edit) in cases {
        let p = study(&dir, 0.7, |v| edit(v));
        let e = PlanStudy::load(&p).unwrap_err().to_string();
        assert!(e.contains(&format!("`{field}`")), "{field}: {e}");
        assert!(e.contains("study.json"), "{e}");
    }
    // an unknown key is refused by name
    let p = study(&dir, 0.7, |v| v["space"]["placment"] = json!("lines"));
    let e = PlanStudy::load(&p).unwrap_err().to_string();
    assert!(e.contains("placment"), "{e}");
}

#[test]
fn a_plan_without_its_size_is_studied_for_its_rotation_and_its_check_page_shows_no_edges() {
    let dir = tmp("nosize");
    let p = study(&dir, 0.7, |v| {
        v["building"].as_object_mut().unwrap().remove("plan_size");
        for f in v["building"]["floors"].as_array_mut().unwrap() {
            f["centre_of_mass"] = json!(["10 m", "6 m"]);
            f["inertia_kg_m2"] = json!(9.0e6);
        }
        v["objective"] = json!({"metric": "rotation"});
        v["sweep"] = json!({"points": 3});
        v["refine"] = json!({"max_evaluations": 0});
    });
    let out = dir.join("out");
    let r = run(&p, &out);
    let opt = r.report.row("optimum").unwrap();
    assert!(opt.objective > 0.0 && opt.objective.is_finite());
    let check = std::fs::read_to_string(out.join("plan-check.md")).unwrap();
    assert!(!check.contains("NaN") && !check.contains("inf"), "{check}");
    assert!(check.contains("| 1 | — |"), "{check}");
}
