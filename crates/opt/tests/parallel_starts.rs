//! Starts side by side (`refine.parallel_starts`): each start refines from its sweep point
//! with its own budget, independent of the other starts and of the threads, and an
//! interrupted refinement resumes to the same bytes.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;

use slipload_opt::Study;
use slipload_opt::phases::refine::StopReason;
use slipload_opt::store::folder::FolderRequest;
use std::path::{Path, PathBuf};

const BUDGET: usize = 8;

/// The three-storey benchmark, two short synthetic records, the model refiner with
/// `starts` starts of [`BUDGET`] evaluations and a tolerance it does not reach first.
fn study(starts: usize, parallel: bool) -> Study {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs/study-benchmark.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["suites"][0]["synthetic"]["count"] = 2.into();
    v["suites"][0]["synthetic"]["duration_s"] = 3.0.into();
    v["sweep"]["points"] = 6.into();
    v["fidelity"] = serde_json::json!({ "method": "newmark", "check_method": "newmark" });
    v["refine"] = serde_json::json!({
        "method": "model", "starts": starts, "max_evaluations": BUDGET,
        "tolerance": 1e-6, "parallel_starts": parallel, "finalists": 2
    });
    Study::from_json(&v.to_string(), &path).unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "slipload-parallel-starts-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn outputs(dir: &Path) -> (Vec<u8>, Vec<u8>) {
    (
        std::fs::read(dir.join("optimum.json")).unwrap(),
        std::fs::read(dir.join("refine.csv")).unwrap(),
    )
}

/// Both starts spend their own budget; the first start's path is the one it takes
/// alone (the second one does not feed it), and one or two threads give the same bytes.
#[test]
fn starts_side_by_side_keep_their_own_budget_and_path_on_any_thread_count() {
    let alone = scratch("alone");
    let one = common::optimize_fresh(&study(1, false), &alone);
    std::fs::remove_dir_all(&alone).unwrap();
    let mut outs = Vec::new();
    for threads in [1, 2] {
        let dir = scratch(&format!("threads-{threads}"));
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let run = pool.install(|| common::optimize_fresh(&study(2, true), &dir));
        let r = &run.report.refine;
        // (the premise: each start stops on its budget, so each spends exactly BUDGET)
        assert_eq!(r.stops, vec![StopReason::Budget; 2], "{:?}", r.stops);
        assert_eq!(one.report.refine.stops, vec![StopReason::Budget]);
        // the first start's evaluations are those of the start alone, in its order
        assert_eq!(r.log[..BUDGET], one.report.refine.log[..BUDGET]);
        // the second start's evaluations follow, its own BUDGET of them: after them only
        // the post-check's polls (each of 2d + 2 = 8 moves at most)
        let polls = r.stationarity.as_ref().unwrap().polls;
        assert!(
            r.log.len() <= 2 * BUDGET + polls * 8,
            "{} evaluations",
            r.log.len()
        );
        assert!(r.log[BUDGET..2 * BUDGET] != one.report.refine.log[..BUDGET]);
        outs.push(outputs(&dir));
        std::fs::remove_dir_all(&dir).unwrap();
    }
    assert!(outs[0] == outs[1], "one and two threads differ");
}

/// A refinement interrupted with part of its journal written resumes from it (the
/// journalled designs replayed, not simulated again) to the bytes of an uninterrupted
/// run.
#[test]
fn an_interrupted_side_by_side_refinement_resumes_to_the_same_bytes() {
    let dir = scratch("resume");
    let s = study(2, true);
    let first = common::optimize_fresh(&s, &dir);
    let whole = outputs(&dir);
    let journal = dir.join("refine-model.jsonl");
    let text = std::fs::read_to_string(&journal).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines.len() > 4, "{} journal lines", lines.len());
    // keep the header and the first half of the evaluations, as a killed run leaves them
    let kept = lines[..lines.len() / 2].join("\n") + "\n";
    std::fs::write(&journal, kept).unwrap();
    for f in ["optimum.json", "refine.csv"] {
        std::fs::remove_file(dir.join(f)).unwrap();
    }
    let again = slipload_opt::pipeline::optimize_study(
        &s,
        &slipload_opt::pipeline::OptimizeOptions::default(),
        FolderRequest {
            path: &dir,
            option: "--out",
            fresh: false,
        },
        &slipload_opt::eval::progress::NoProgress,
        &slipload_opt::pipeline::NoFigures,
    )
    .unwrap();
    assert_eq!(first.report.refine.replayed, 0);
    assert!(again.report.refine.replayed > 0, "nothing replayed");
    assert_eq!(outputs(&dir), whole);
    std::fs::remove_dir_all(&dir).unwrap();
}
