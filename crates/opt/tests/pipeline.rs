//! Contract: `pipeline::optimize_study` runs sweep, refine, check and design table (and
//! the objective map when asked, journalled with the check's runs) in that order, each announced to the progress callback
//! with a tick per simulation; its report holds what the files it writes say; a second
//! run over the same folder takes every journalled phase from its journal — nothing is
//! simulated, no journal grows — and writes the same bytes; bad options and a folder of
//! another study are refused before anything is written. A sweep in shards, merged,
//! gives the figure data of one whole sweep.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

use slipload_opt::eval::progress::{NoProgress, Phase, Progress};
use slipload_opt::phases::figures::MapRequest;
use slipload_opt::phases::table::DesignTable;
use slipload_opt::pipeline::{
    NoFigures, OptimizeOptions, StudyReport, merge_shards, optimize_study, sweep_study,
};
use slipload_opt::{Shard, Study};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

mod common;
use common::folder;

/// The benchmark study on 2 synthetic records of 4 s, `points` Halton designs, a short
/// trust-region refinement and 2 finalists.
fn study(points: usize) -> Study {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["suites"][0]["synthetic"]["count"] = 2.into();
    v["suites"][0]["synthetic"]["duration_s"] = 4.0.into();
    v["sweep"]["points"] = points.into();
    v["refine"]["starts"] = 1.into();
    v["refine"]["max_evaluations"] = 6.into();
    v["refine"]["finalists"] = 2.into();
    Study::from_json(&v.to_string(), &path).unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slipload-pipeline-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Every phase started, with the work announced and the ticks counted until it finished.
#[derive(Default)]
struct Recorder {
    phases: Mutex<Vec<(Phase, usize, usize)>>,
    ticks: AtomicUsize,
}

impl Progress for Recorder {
    fn start(&self, phase: Phase, work: usize) {
        self.ticks.store(0, Ordering::SeqCst);
        self.phases.lock().unwrap().push((phase, work, usize::MAX));
    }
    fn tick(&self) {
        self.ticks.fetch_add(1, Ordering::SeqCst);
    }
    fn finish(&self, phase: Phase) {
        let mut phases = self.phases.lock().unwrap();
        let last = phases.last_mut().unwrap();
        assert_eq!(last.0, phase, "a phase finishes before the next starts");
        last.2 = self.ticks.load(Ordering::SeqCst);
    }
}

impl Recorder {
    fn order(&self) -> Vec<Phase> {
        self.phases.lock().unwrap().iter().map(|p| p.0).collect()
    }
    /// (work announced, ticks) of `phase`.
    fn of(&self, phase: Phase) -> (usize, usize) {
        let phases = self.phases.lock().unwrap();
        let p = phases.iter().find(|p| p.0 == phase).unwrap();
        (p.1, p.2)
    }
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

const JOURNALS: [&str; 3] = ["journal.jsonl", "refine-trust-region.jsonl", "check.jsonl"];

#[test]
fn optimize_study_runs_the_phases_and_resumes_them_from_their_journals() {
    let st = study(6);
    let nr = st.records.len();
    let out = scratch("resume");
    let options = OptimizeOptions {
        refine: None,
        map: Some(MapRequest {
            floors: [1, 3],
            grid: 2,
        }),
    };
    let progress = Recorder::default();
    let r = optimize_study(&st, &options, folder(&out), &progress, &NoFigures)
        .map(|r| r.report)
        .unwrap();

    // the phases, in order, each ticked once per simulation it ran
    assert_eq!(
        progress.order(),
        [
            Phase::Sweep,
            Phase::Refine,
            Phase::Check,
            Phase::DesignTable,
            Phase::ObjectiveMap
        ]
    );
    let tasks = r.sweep.manifest.tasks();
    assert_eq!(tasks, (6 + 2) * nr);
    assert_eq!(progress.of(Phase::Sweep), (tasks, tasks));
    assert_eq!((r.work.sweep.run, r.work.sweep.reused), (tasks, 0));
    let evaluations = r.refine.log.len();
    assert!(evaluations > 0 && r.refine.replayed == 0);
    assert_eq!(progress.of(Phase::Refine).1, evaluations * nr);
    assert_eq!(
        (r.work.refine.run, r.work.refine.reused),
        (evaluations * nr, 0)
    );
    let checked = (r.refine.finalists.len() + 1) * nr;
    assert_eq!(r.refine.finalists.len(), 2);
    assert_eq!(progress.of(Phase::Check), (checked, checked));
    assert_eq!((r.work.check.run, r.work.check.reused), (checked, 0));
    let tabled = (r.designs.len() * 3 + 1) * nr;
    assert_eq!(progress.of(Phase::DesignTable), (tabled, tabled));
    assert_eq!((r.work.table.run, r.work.table.reused), (tabled, 0));
    assert_eq!(progress.of(Phase::ObjectiveMap), (4 * nr, 4 * nr));
    assert_eq!(r.work.map.map(|m| m.run), Some(4 * nr));
    assert_eq!(
        r.work.run(),
        tasks + evaluations * nr + checked + tabled + 4 * nr
    );

    // the files say what the report holds
    let optimum = json(&out.join("optimum.json"));
    assert_eq!(optimum["study"], "benchmark-3story");
    assert_eq!(
        optimum["objective_value"].as_f64(),
        Some(r.refine.optimum.f)
    );
    let loads: Vec<f64> = optimum["slip_loads_kN"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let expected: Vec<f64> = r.refine.optimum_loads.iter().map(|v| v / 1e3).collect();
    assert_eq!(loads, expected);
    assert_eq!(
        optimum["refine_evaluations"].as_u64(),
        Some(evaluations as u64)
    );
    assert_eq!(optimum["finalists"].as_array().unwrap().len(), 2);
    let keys: Vec<&String> = optimum.as_object().unwrap().keys().collect();
    assert!(
        keys.windows(2).all(|k| k[0] < k[1]),
        "sorted keys: {keys:?}"
    );
    let refine_csv = std::fs::read_to_string(out.join("refine.csv")).unwrap();
    assert_eq!(refine_csv, r.refine_csv());
    assert_eq!(refine_csv.lines().count(), evaluations + 1);
    let candidates: Vec<slipload_opt::phases::rank::NamedDesign> =
        serde_json::from_str(&std::fs::read_to_string(out.join("candidates.json")).unwrap())
            .unwrap();
    assert_eq!(candidates, r.candidates);
    assert_eq!(candidates[0].name, "optimum");
    assert_eq!(candidates.len(), r.designs.len());
    let table: DesignTable = serde_json::from_value(json(&out.join("design-table.json"))).unwrap();
    assert_eq!(table, r.table);
    for f in StudyReport::FILES.iter().chain(&JOURNALS) {
        assert!(out.join(f).is_file(), "{f} written");
    }

    // the figure data
    let fig = &r.figures;
    assert_eq!(fig.suites.len(), 1, "one suite: the plain figures");
    assert_eq!(fig.suites[0].profiles.len(), r.designs.len());
    assert_eq!(fig.suites[0].scatter.as_ref().unwrap().bare.len(), nr);
    assert_eq!(fig.convergence.len(), 1);
    assert_eq!(fig.convergence[0].points.len(), evaluations + 1);
    assert_eq!(fig.map.as_ref().unwrap().objective.len(), 4);

    // the second run: every phase comes from its journal, nothing is simulated again
    let bytes = |names: &[&str]| -> Vec<Vec<u8>> {
        names
            .iter()
            .map(|f| std::fs::read(out.join(f)).unwrap())
            .collect()
    };
    let files = bytes(&StudyReport::FILES);
    let journals = bytes(&JOURNALS);
    let again = Recorder::default();
    let r2 = optimize_study(
        &st,
        &OptimizeOptions::default(),
        folder(&out),
        &again,
        &NoFigures,
    )
    .map(|r| r.report)
    .unwrap();
    assert_eq!(
        again.order(),
        [
            Phase::Sweep,
            Phase::Refine,
            Phase::Check,
            Phase::DesignTable
        ]
    );
    assert_eq!(again.of(Phase::Sweep).1, 0, "no sweep task ran");
    assert_eq!(again.of(Phase::Refine).1, 0, "no refinement point ran");
    assert_eq!((r2.work.sweep.run, r2.work.sweep.reused), (0, tasks));
    assert_eq!(r2.refine.replayed, evaluations);
    assert_eq!(
        (r2.work.refine.run, r2.work.refine.reused),
        (0, evaluations * nr)
    );
    assert_eq!((r2.work.check.run, r2.work.check.reused), (0, checked));
    assert_eq!((r2.work.table.run, r2.work.table.reused), (0, tabled));
    assert_eq!(r2.work.map, None);
    assert_eq!(r2.work.run(), 0);
    assert_eq!(r2.refine.optimum, r.refine.optimum);
    assert!(bytes(&StudyReport::FILES) == files, "the same files");
    assert!(bytes(&JOURNALS) == journals, "no journal grew");
    // asked again, the objective map comes from check.jsonl too
    let r3 = optimize_study(&st, &options, folder(&out), &NoProgress, &NoFigures)
        .map(|r| r.report)
        .unwrap();
    let m = r3.work.map.unwrap();
    assert_eq!((m.run, m.reused), (0, 4 * nr));
    assert_eq!(r3.work.run(), 0);
    assert!(bytes(&JOURNALS) == journals, "no journal grew");
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn bad_options_and_another_studys_folder_are_refused_before_anything_runs() {
    let st = study(3);
    for (floors, grid, says) in [
        ([1, 4], 3, "floor 4 has no dissipator"),
        ([2, 2], 3, "two different floors"),
        ([1, 2], 1, "at least 2"),
    ] {
        let out = scratch("bad-map");
        let options = OptimizeOptions {
            refine: None,
            map: Some(MapRequest { floors, grid }),
        };
        let progress = Recorder::default();
        let e = optimize_study(&st, &options, folder(&out), &progress, &NoFigures)
            .map(|r| r.report)
            .unwrap_err()
            .to_string();
        assert!(e.contains(says), "{e}");
        assert!(progress.order().is_empty(), "no phase started");
        assert!(!out.exists(), "nothing written");
    }
    // a folder holding another study's journals
    let out = scratch("other");
    sweep_study(
        &study(2),
        Shard::ALL,
        false,
        folder(&out),
        &NoProgress,
        &NoFigures,
    )
    .unwrap();
    let progress = Recorder::default();
    let e = optimize_study(
        &st,
        &OptimizeOptions::default(),
        folder(&out),
        &progress,
        &NoFigures,
    )
    .map(|r| r.report)
    .unwrap_err();
    let chain = std::iter::successors(Some(&e as &dyn std::error::Error), |e| e.source())
        .map(ToString::to_string)
        .collect::<Vec<_>>();
    assert!(
        chain[0].starts_with("optimizing benchmark-3story into"),
        "{chain:?}"
    );
    assert!(chain[1].contains("another study"), "{chain:?}");
    assert!(progress.order().is_empty(), "no phase started");
    assert!(!out.join("check.jsonl").exists());
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn merged_shards_give_the_figure_data_of_one_whole_sweep() {
    let st = study(4);
    let whole = scratch("whole");
    let progress = Recorder::default();
    let one = sweep_study(
        &st,
        Shard::ALL,
        false,
        folder(&whole),
        &progress,
        &NoFigures,
    )
    .unwrap();
    let tasks = one.report.manifest.tasks();
    assert_eq!(progress.order(), [Phase::Sweep]);
    assert_eq!(progress.of(Phase::Sweep), (tasks, tasks));
    let whole_figures = one.figures.unwrap();
    assert_eq!(
        whole_figures.suites[0].profiles.len(),
        5,
        "3 best, file, bare"
    );

    let dirs: Vec<PathBuf> = (0..2).map(|i| scratch(&format!("shard{i}"))).collect();
    for (i, d) in dirs.iter().enumerate() {
        let shard = Shard { index: i, count: 2 };
        let progress = Recorder::default();
        let part = sweep_study(&st, shard, false, folder(d), &progress, &NoFigures).unwrap();
        let mine = (0..tasks).filter(|&k| shard.owns(k)).count();
        assert_eq!(progress.of(Phase::Sweep), (mine, mine));
        assert!(part.figures.is_none(), "a shard draws nothing");
    }
    let merged = scratch("merged");
    let shards: Vec<&Path> = dirs.iter().map(PathBuf::as_path).collect();
    let m = merge_shards(&shards, folder(&merged), &NoFigures).unwrap();
    assert_eq!(m.figures.unwrap(), whole_figures);
    for f in ["manifest.json", "designs.csv", "responses.csv"] {
        assert!(
            std::fs::read(merged.join(f)).unwrap() == std::fs::read(whole.join(f)).unwrap(),
            "{f}: merge writes the bytes of one run"
        );
    }
    for d in dirs.iter().chain([&whole, &merged]) {
        std::fs::remove_dir_all(d).unwrap();
    }
}

/// On its first tick, from inside the running sweep, a second call into the same folder
/// (with `fresh`) is made on another thread of the process — as two Python threads do —
/// and its outcome kept.
struct Intruder<'a> {
    study: &'a Study,
    out: &'a Path,
    second: Mutex<Option<Result<(), String>>>,
}

impl Progress for Intruder<'_> {
    fn tick(&self) {
        let mut second = self.second.lock().unwrap();
        if second.is_some() {
            return;
        }
        let (study, out) = (self.study, self.out);
        let outcome = std::thread::scope(|s| {
            s.spawn(|| {
                let request = slipload_opt::store::folder::FolderRequest {
                    path: out,
                    option: "out",
                    fresh: true,
                };
                sweep_study(study, Shard::ALL, false, request, &NoProgress, &NoFigures)
                    .map(|_| ())
                    .map_err(|e| match e {
                        slipload_opt::base::error::OptError::FolderBusy { .. } => {
                            format!("busy: {e}")
                        }
                        other => other.to_string(),
                    })
            })
            .join()
            .unwrap()
        });
        *second = Some(outcome);
    }
}

/// One folder, one writer, within one process too: a second call into a folder that a
/// running call holds — from another thread, `fresh` asked — is refused at once as a
/// second process is; it removes nothing, and the first call finishes with the bytes of a
/// sweep that ran alone.
#[test]
fn a_second_thread_into_a_folder_in_use_is_refused_and_erases_nothing() {
    let st = study(3);
    let out = scratch("threads");
    let intruder = Intruder {
        study: &st,
        out: &out,
        second: Mutex::new(None),
    };
    sweep_study(&st, Shard::ALL, false, folder(&out), &intruder, &NoFigures).unwrap();
    let second = intruder.second.lock().unwrap().clone().unwrap();
    let err = second.expect_err("the second call ran while the first held the folder");
    assert!(err.starts_with("busy: "), "{err}");
    assert!(err.contains("in use by another slipload command"), "{err}");
    let alone = scratch("threads-alone");
    sweep_study(
        &st,
        Shard::ALL,
        false,
        folder(&alone),
        &NoProgress,
        &NoFigures,
    )
    .unwrap();
    for name in ["responses.csv", "designs.csv"] {
        assert_eq!(
            std::fs::read(out.join(name)).unwrap(),
            std::fs::read(alone.join(name)).unwrap(),
            "{name}"
        );
    }
    let _ = std::fs::remove_dir_all(&out);
    let _ = std::fs::remove_dir_all(&alone);
}
