//! Contract: a study evaluates the building file's design as written. A `locked` damper
//! stays locked (not 0 kN) and asymmetric bounds stay asymmetric wherever "the file's
//! design" runs: the sweep's design 1, the design table's `file` row, the candidates
//! (`candidates.json`) and `rank`. The right answer is a run of the building exactly as
//! the file gives it, compared bit for bit (same scene, same integrator).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::eval::evaluate::{DesignLoads, run_designs};
use slipload_opt::model::fidelity::{Fidelity, hht_alpha};
use slipload_opt::model::sampler::FrictionLaw;
use slipload_opt::phases::rank::{NamedDesign, rank, to_newtons};
use slipload_opt::phases::sweep::{self, Manifest};
use slipload_opt::phases::table::{DesignTable, standard_designs};
use slipload_opt::{RecordMetrics, Shard, Study};
use slipload_sim::scene::{InitialState, MethodSettings, OutputsConfig, Scene, default_dt};
use slipload_sim::{Plan, run_plan};
use std::path::{Path, PathBuf};

mod common;
use common::open_folder;

/// The benchmark study on two 2-s synthetic records and two sample points, its building
/// inlined with the dissipators edited by `edit`.
fn study(edit: impl Fn(&mut serde_json::Value)) -> Study {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs");
    let mut b: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root.join("benchmark-3story.json")).unwrap())
            .unwrap();
    edit(&mut b["dissipators"]);
    let path = root.join("study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["building"] = b;
    v["suites"][0]["synthetic"]["count"] = 2.into();
    v["suites"][0]["synthetic"]["duration_s"] = 2.0.into();
    v["sweep"]["points"] = 2.into();
    v["fidelity"]["method"] = "newmark".into();
    Study::from_json(&v.to_string(), &path).unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slipload-written-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Record `r` of the study on its building exactly as the file gives it, at `fid`.
fn as_written(study: &Study, r: usize, fid: &Fidelity) -> RecordMetrics {
    let rec = &study.records[r];
    let dt = fid.dt_s.unwrap_or_else(|| {
        default_dt(
            fid.method,
            study.building.t1(),
            Some(rec.dt()),
            rec.duration(),
        )
    }) * fid.dt_factor;
    let scene = Scene {
        name: "as written".into(),
        building: study.building.clone(),
        record: Some(rec.clone()),
        harmonic: None,
        initial: InitialState::rest(study.building.floors()),
        duration: rec.duration(),
        method: MethodSettings {
            name: fid.method,
            dt,
            alpha: hht_alpha(fid.method),
            eps_a: None,
            eps_f: None,
            max_iterations: None,
        },
        outputs: OutputsConfig {
            energies: fid.energies,
            histories: false,
            dampers: false,
            sensitivities: false,
        },
        reduce: true,
        notes: Vec::new(),
    };
    let out = run_plan(&Plan::compile(&scene).unwrap()).unwrap();
    RecordMetrics::from_outcome(&out, study.building.storey_heights.as_deref().unwrap())
}

/// The sweep's rows of design 1 (the file's), record by record.
fn file_rows(st: &Study, dir: &Path) -> Vec<RecordMetrics> {
    let rows = sweep::run(st, &open_folder(dir), Shard::ALL, false, &|| {})
        .unwrap()
        .rows
        .unwrap();
    let nr = st.records.len();
    rows[nr..2 * nr].to_vec()
}

#[test]
fn a_locked_damper_stays_locked_in_the_sweep() {
    let st = study(|d| d[1]["slip_load"] = "locked".into());
    let m = Manifest::of(&st);
    let laws = m.designs[1].friction_n.clone().unwrap();
    assert_eq!(laws[1], FrictionLaw::Locked);
    assert_eq!(laws[0], FrictionLaw::Bounds([-834.095e3, 834.095e3]));
    let dir = scratch("locked");
    let rows = file_rows(&st, &dir);
    let fid = Fidelity::sweep(&st);
    for (r, row) in rows.iter().enumerate() {
        assert_eq!(*row, as_written(&st, r, &fid), "record {r}");
    }
    // what a 0 kN damper on floor 2 gives (the file read as 0): another answer
    let zero = run_designs(&st, &[m.designs[1].slip_loads_n.clone()], &fid, &|| {}).unwrap();
    assert_eq!(m.designs[1].slip_loads_n[1], 0.0);
    assert_ne!(zero[0], rows, "the locked damper must not run as 0 kN");
    // the tables say so
    let designs_csv = std::fs::read_to_string(dir.join("designs.csv")).unwrap();
    let file_line = designs_csv.lines().nth(2).unwrap();
    assert!(
        file_line.starts_with("1,file,-834.095..834.095,locked,"),
        "{file_line}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn asymmetric_bounds_stay_asymmetric_in_the_sweep() {
    let st = study(|d| {
        d[0].as_object_mut().unwrap().remove("slip_load");
        d[0]["bounds"] = serde_json::json!(["-200 kN", "900 kN"]);
    });
    let m = Manifest::of(&st);
    assert_eq!(
        m.designs[1].friction_n.as_ref().unwrap()[0],
        FrictionLaw::Bounds([-200e3, 900e3])
    );
    let dir = scratch("asym");
    let rows = file_rows(&st, &dir);
    let fid = Fidelity::sweep(&st);
    for (r, row) in rows.iter().enumerate() {
        assert_eq!(*row, as_written(&st, r, &fid), "record {r}");
    }
    // the symmetric reading (±900 kN) is another answer
    let symmetric = run_designs(&st, &[m.designs[1].slip_loads_n.clone()], &fid, &|| {}).unwrap();
    assert_eq!(m.designs[1].slip_loads_n[0], 900e3);
    assert_ne!(symmetric[0], rows, "the bounds must not run symmetric");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_symmetric_file_design_has_no_friction_law() {
    // the manifest (and so every byte a symmetric study writes) is as before
    let st = study(|_| {});
    assert_eq!(st.file_friction(), None);
    let json = Manifest::of(&st).to_json();
    assert!(!json.contains("friction_n"), "{json}");
}

#[test]
fn the_design_table_candidates_and_rank_carry_the_law() {
    let st = study(|d| d[2]["slip_load"] = "locked".into());
    let optimum = vec![500e3, 400e3, 300e3];
    let designs = standard_designs(&st, &optimum);
    let (name, file) = designs.iter().find(|(n, _)| n == "file").unwrap();
    assert_eq!(file, &DesignLoads::file(&st), "{name}");
    let (table, runs) = DesignTable::build_with_runs(&st, &designs, &|| {}).unwrap();
    let k = designs.iter().position(|(n, _)| n == "file").unwrap();
    let fid = Fidelity::check(&st);
    for (r, row) in runs[1 + 3 * k].iter().enumerate() {
        assert_eq!(*row, as_written(&st, r, &fid), "design table, record {r}");
    }
    let row = &table.rows[k];
    assert_eq!(
        row.friction_kn.as_ref().unwrap()[2],
        FrictionLaw::Locked,
        "the table's file row names the law"
    );
    let md = table.to_markdown();
    assert!(md.contains("| 3 | locked | locked | locked |"), "{md}");
    let csv = table.to_csv();
    let line = csv.lines().find(|l| l.starts_with("file,")).unwrap();
    assert!(line.contains(",locked,"), "{line}");
    // the candidates (candidates.json) keep the law, and rank runs it
    let named = NamedDesign {
        name: "file".into(),
        slip_loads_kn: file.slip_loads_n.iter().map(|v| v / 1e3).collect(),
        friction_kn: file
            .friction_n
            .as_ref()
            .map(|l| l.iter().map(|x| x.scaled(1e-3)).collect()),
    };
    let text = serde_json::to_string(std::slice::from_ref(&named)).unwrap();
    assert!(text.contains(r#""locked""#), "{text}");
    let back: Vec<NamedDesign> = serde_json::from_str(&text).unwrap();
    let loads = to_newtons(&st, &back).unwrap();
    assert_eq!(
        loads[0].friction_n.as_ref().unwrap()[2],
        FrictionLaw::Locked
    );
    let zero = NamedDesign {
        name: "file read as 0 kN".into(),
        friction_kn: None,
        ..named
    };
    let ranking = rank(&st, &[back[0].clone(), zero], 4, 1, &|| {}).unwrap();
    let obj = &ranking.suites[0].objective;
    assert_ne!(obj[0], obj[1], "rank runs the locked damper locked");
}
