//! Contract: a study naming `objectives` gets, after the one-objective phases, a front
//! searched from its sweep (`pareto.jsonl`), checked at the check fidelity and written
//! as `pareto.csv`, `pareto.json` and `pareto-table.*`; a second run over the folder
//! runs nothing and writes the same bytes; one and two threads write the same bytes; a
//! study without the key keeps its fingerprint components and files; bad `objectives`
//! are refused naming the field; [`evaluate_objectives`] gives the search's vectors;
//! every design the study evaluated (sweep, search, file, refinement) is a candidate for
//! the front, and the optimum is no worse than any design the search evaluated.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::Study;
use slipload_opt::eval::progress::NoProgress;
use slipload_opt::phases::pareto::search::Source;
use slipload_opt::phases::pareto::{ParetoReport, dominates, evaluate_objectives};
use slipload_opt::phases::sweep::Manifest;
use slipload_opt::pipeline::{NoFigures, OptimizeOptions, StudyReport, optimize_study};
use std::path::{Path, PathBuf};

mod common;
use common::folder;

fn config() -> (serde_json::Value, PathBuf) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/study-pareto.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["suites"][0]["synthetic"]["count"] = 2.into();
    v["suites"][0]["synthetic"]["duration_s"] = 4.0.into();
    v["sweep"]["points"] = 6.into();
    v["refine"]["starts"] = 1.into();
    v["refine"]["max_evaluations"] = 4.into();
    v["refine"]["finalists"] = 1.into();
    v["pareto"]["designs"] = 6.into();
    v["pareto"]["batch"] = 3.into();
    (v, path)
}

/// The Pareto study on 2 synthetic records of 4 s, 6 sweep and 6 search designs.
fn study() -> Study {
    let (v, path) = config();
    Study::from_json(&v.to_string(), &path).unwrap()
}

/// `study` optimised into `out` with the default options, no progress and no figures.
fn optimized(study: &Study, out: &Path) -> Result<StudyReport, slipload_opt::OptError> {
    optimize_study(
        study,
        &OptimizeOptions::default(),
        folder(out),
        &NoProgress,
        &NoFigures,
    )
    .map(|r| r.report)
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slipload-pareto-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

const JOURNALS: [&str; 4] = [
    "journal.jsonl",
    "refine-trust-region.jsonl",
    "check.jsonl",
    "pareto.jsonl",
];

fn bytes(out: &Path, names: &[&str]) -> Vec<Vec<u8>> {
    names
        .iter()
        .map(|f| std::fs::read(out.join(f)).unwrap())
        .collect()
}

#[test]
fn the_front_is_searched_checked_written_and_resumed_to_the_same_bytes() {
    let st = study();
    let nr = st.records.len();
    let out = scratch("run");
    let r = optimized(&st, &out).unwrap();
    let p = r.pareto.as_ref().unwrap();
    let ev = &p.search.evaluated;
    assert_eq!(p.search.sweep_designs, 6);
    assert_eq!(p.search.search_designs, 6);
    assert_eq!(p.search.simulations(nr), 14 * nr, "bare, file, 12 designs");
    // one study, one best design: every design it evaluated at the sweep fidelity is a
    // candidate for the front — the 6 sweep and 6 search designs, the file's (where the
    // space holds it) and each distinct refinement evaluation
    let of = |source: Source| ev.iter().filter(|e| e.source == source).count();
    assert_eq!((of(Source::Sweep), of(Source::Search)), (6, 6));
    let file_z = st.space.point_of(&st.file_slip_loads());
    assert_eq!(of(Source::File), usize::from(file_z.is_some()));
    for q in &r.refine.log {
        assert!(ev.iter().any(|e| e.z == q.z), "refinement point {:?}", q.z);
    }
    let refined = of(Source::Refine);
    assert!(refined > 0, "the refinement's designs join the front");
    assert_eq!(ev.len(), 12 + of(Source::File) + of(Source::Refine));
    // ...and for the optimum: no design the search evaluated has a lower objective
    // (the study has no limits, so the refiners read the objective itself)
    for e in &ev[6..12] {
        let (f, check) = e.scalar.as_ref().unwrap();
        assert!(check.is_none());
        assert!(*f >= r.refine.optimum.f, "{} below the optimum", e.label);
    }
    assert!(
        ev.iter().any(|e| e.z == r.refine.optimum.z),
        "the optimum is a candidate"
    );
    // the fresh run computed the refinement's runs: the front runs nothing more
    let w = r.work.pareto.unwrap();
    assert_eq!((w[0].run, w[0].reused), (6 * nr, 0));
    // the front: non-dominated, and every other design dominated by a front design
    let front = &p.certified.front;
    assert!(!front.is_empty());
    for (i, e) in ev.iter().enumerate() {
        let dominated = ev.iter().any(|o| dominates(&o.objectives, &e.objectives));
        assert_eq!(front.contains(&i), !dominated, "design {}", e.label);
        assert_eq!(p.ranks[i] == 1, !dominated);
    }
    // sorted by the first objective, so the second falls along it
    for w in front.windows(2) {
        let (a, b) = (&ev[w[0]].objectives, &ev[w[1]].objectives);
        assert!(a[0] <= b[0] && a[1] >= b[1]);
    }
    assert!(p.knee < front.len());
    assert_eq!(p.certified.check.len(), front.len());
    // the extremes minimise their objective over the whole front
    for (m, &pos) in p.extremes.iter().enumerate() {
        let best = front
            .iter()
            .map(|&i| ev[i].objectives[m])
            .fold(f64::INFINITY, f64::min);
        assert_eq!(ev[front[pos]].objectives[m], best);
    }
    // the design table names the extremes and the knee (a design twice is listed once)
    let names: Vec<&str> = p.table.rows.iter().map(|r| r.design.as_str()).collect();
    assert_eq!(names.first(), Some(&"min-peak_drift_ratio"));
    assert!(names.contains(&"file") && names.contains(&"bare"));
    assert_eq!(p.table_runs.len(), 1 + 3 * p.table_designs.len());

    // the files say what the report holds
    let csv = std::fs::read_to_string(out.join("pareto.csv")).unwrap();
    assert_eq!(csv, p.csv());
    assert_eq!(csv.lines().count(), 1 + ev.len());
    let head = csv.lines().next().unwrap();
    assert!(head.contains("mean_peak_drift_ratio,mean_peak_floor_acceleration,rank,crowding"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("pareto.json")).unwrap()).unwrap();
    assert_eq!(json["front"].as_array().unwrap().len(), front.len());
    assert_eq!(json["knee"], p.front_labels()[p.knee]);
    assert_eq!(json["held"], p.certified.held());
    let hv = slipload_opt::phases::pareto::hypervolume(
        &front
            .iter()
            .map(|&i| ev[i].objectives.clone())
            .collect::<Vec<_>>(),
        &p.reference,
    );
    assert_eq!(json["hypervolume"].as_f64().unwrap(), hv);
    for f in ParetoReport::FILES.iter().chain(&JOURNALS) {
        assert!(out.join(f).is_file(), "{f} written");
    }

    // the second run: nothing runs, no journal grows, the same bytes
    let files: Vec<&str> = StudyReport::FILES
        .iter()
        .chain(&ParetoReport::FILES)
        .copied()
        .collect();
    let before = bytes(&out, &files);
    let journals = bytes(&out, &JOURNALS);
    let r2 = optimized(&st, &out).unwrap();
    assert_eq!(r2.work.run(), 0, "nothing simulated again");
    let w2 = r2.work.pareto.unwrap();
    // (the refinement's designs, replayed, take their runs from pareto.jsonl)
    assert_eq!((w2[0].run, w2[0].reused), (0, (6 + refined) * nr));
    assert!(bytes(&out, &files) == before, "the same files");
    assert!(bytes(&out, &JOURNALS) == journals, "no journal grew");

    // a search cut short (its journal's last lines gone) resumes to the same bytes
    let pj = out.join("pareto.jsonl");
    let text = std::fs::read_to_string(&pj).unwrap();
    let keep: Vec<&str> = text.lines().take(1 + 3 * nr).collect();
    std::fs::write(&pj, keep.join("\n") + "\n").unwrap();
    // (the refinement, replayed from its own journal, has no runs in memory: its
    // designs, whose runs were cut from pareto.jsonl too, run again for the front)
    let r3 = optimized(&st, &out).unwrap();
    let w3 = r3.work.pareto.unwrap();
    assert_eq!((w3[0].run, w3[0].reused), ((3 + refined) * nr, 3 * nr));
    assert!(
        bytes(&out, &files) == before,
        "the same files after the resume"
    );

    // the Python-facing evaluation gives the search's vectors
    let designs: Vec<Vec<f64>> = ev[6..8].iter().map(|e| e.slip_loads_n.clone()).collect();
    let v = evaluate_objectives(&st, &designs, &NoProgress).unwrap();
    assert_eq!(v, vec![ev[6].objectives.clone(), ev[7].objectives.clone()]);
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn one_and_two_threads_write_the_same_bytes() {
    let st = study();
    let files: Vec<&str> = StudyReport::FILES
        .iter()
        .chain(&ParetoReport::FILES)
        .chain(&JOURNALS[3..])
        .copied()
        .collect();
    let mut all = Vec::new();
    for threads in [1, 2] {
        let out = scratch(&format!("threads-{threads}"));
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| optimized(&st, &out)).unwrap();
        // pareto.jsonl holds tasks in finishing order: compare its sorted lines
        let mut b = bytes(&out, &files);
        let last = b.pop().unwrap();
        let mut lines: Vec<&[u8]> = last.split(|&c| c == b'\n').collect();
        lines.sort();
        b.push(lines.concat());
        all.push(b);
        std::fs::remove_dir_all(&out).unwrap();
    }
    assert!(all[0] == all[1], "1 and 2 threads: the same files");
}

#[test]
fn a_study_without_objectives_keeps_its_fingerprint_components() {
    let (mut v, path) = config();
    let with = Study::from_json(&v.to_string(), &path).unwrap();
    v.as_object_mut().unwrap().remove("objectives");
    v.as_object_mut().unwrap().remove("pareto");
    let without = Study::from_json(&v.to_string(), &path).unwrap();
    let keys = |s: &Study| -> Vec<String> {
        Manifest::of(s)
            .fingerprint
            .components
            .iter()
            .map(|c| c.key.clone())
            .collect()
    };
    assert!(!keys(&without).contains(&"objectives".to_string()));
    assert!(keys(&with).contains(&"objectives".to_string()));
    // every other component is the same: the objectives change nothing else
    let a = Manifest::of(&with).fingerprint;
    let b = Manifest::of(&without).fingerprint;
    let changed = a.changes_from(&b);
    assert_eq!(changed.len(), 1, "{changed:?}");
    assert!(without.objectives.is_empty());
    let e = evaluate_objectives(&without, &[vec![0.0; 3]], &NoProgress)
        .unwrap_err()
        .to_string();
    assert!(e.contains("objectives"), "{e}");
    let e = evaluate_objectives(&with, &[vec![0.0; 2]], &NoProgress)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("2 slip loads") && e.contains("3 dissipators"),
        "{e}"
    );
}

#[test]
fn bad_objectives_are_refused_naming_the_field() {
    let cases: Vec<(serde_json::Value, Option<serde_json::Value>, &str)> = vec![
        (
            serde_json::json!([{ "metric": "peak_drift_ratio" }]),
            None,
            "`objectives`: a front takes 2 to 4 objectives, got 1",
        ),
        (
            serde_json::json!([{ "metric": "peak_drift_ratio" }, { "metric": "damper_size", "statistic": "max" }]),
            None,
            "`objectives[1].statistic`",
        ),
        (
            serde_json::json!([{ "metric": "peak_drift_ratio" }, { "metric": "peak_ductility" }]),
            None,
            "`objectives[1].metric`: peak_ductility needs a frame whose storeys yield",
        ),
        (
            serde_json::json!([{ "metric": "peak_drift_ratio" }, { "metric": "peak_drift_ratio", "statistic": "mean" }]),
            None,
            "`objectives[1]`: repeats objectives[0]",
        ),
        (
            serde_json::json!([{ "metric": "peak_drift_ratio" }, { "metric": "base_shear" }]),
            Some(serde_json::json!({ "batch": 0 })),
            "`pareto.batch`: must be at least 1",
        ),
        (
            serde_json::json!([{ "metric": "peak_drift_ratio" }, { "metric": "base_shear" }]),
            Some(serde_json::json!({ "initial_radius": 0 })),
            "`pareto.initial_radius`",
        ),
        (
            serde_json::json!([{ "metric": "peak_drift_ratio" }, { "metric": "drift" }]),
            None,
            "unknown variant `drift`",
        ),
    ];
    for (objectives, pareto, says) in cases {
        let (mut v, path) = config();
        v["objectives"] = objectives;
        if let Some(p) = pareto {
            v["pareto"] = p;
        }
        let e = Study::from_json(&v.to_string(), &path)
            .unwrap_err()
            .to_string();
        assert!(e.contains(says), "expected {says:?} in: {e}");
        assert!(e.contains("study-pareto.json"), "names the file: {e}");
    }
    // `pareto` without `objectives`
    let (mut v, path) = config();
    v.as_object_mut().unwrap().remove("objectives");
    let e = Study::from_json(&v.to_string(), &path)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`pareto`") && e.contains("no `objectives`"),
        "{e}"
    );
}
