//! [`optimize_in_plan`] (`slipload optimize` on a study in plan): the sweep, the `model`
//! refiner from its best design, then the final table (bare frame, the file's slip loads,
//! the optimum and its planar split) at the finer step, the files and the figures.
//!
//! Every design the sweep and the refinement evaluate is journalled in
//! `plan-journal.jsonl` (first line: the study's fingerprint); a run over the same folder
//! replays it, so an interrupted study loses nothing it computed and a finished one
//! writes the same bytes again without simulating. A journal of another study is
//! refused (or removed with `fresh`).

use super::figures::FigureWriter;
use crate::base::error::OptError;
use crate::eval::progress::{Phase, Progress, phase};
use crate::model::config::{RefineConfig, RefineMethod};
use crate::model::fingerprint::Fnv64;
use crate::phases::refine::{Evaluations, Point, refine};
use crate::plan::config::Placement;
use crate::plan::evaluate::{DesignEval, Step, evaluate_loads};
use crate::plan::protocol::PlanTestProtocol;
use crate::plan::report::{
    PlanReport, PlanRow, check_md, dampers_csv, dampers_md, devices_csv, devices_md, figure_data,
    planar_split, profiles_csv, summary,
};
use crate::plan::study::PlanStudy;
use crate::store::folder::{Discarded, FolderRequest, StudyFolder};
use std::io::Write as _;

/// The journal of a study in plan.
pub const PLAN_JOURNAL: &str = "plan-journal.jsonl";

/// Designs the sweep evaluates per batch (each a journal flush).
const SWEEP_BATCH: usize = 4;

/// What an `optimize` run on a study in plan did.
#[derive(Debug, Clone)]
pub struct PlanRun {
    /// Everything the run found.
    pub report: PlanReport,
    /// The summary, as `plan-summary.txt` holds it.
    pub summary: String,
    /// The figures drawn.
    pub drawn: Vec<String>,
    /// The files written besides the figures.
    pub files: Vec<&'static str>,
    /// What `fresh` removed and kept.
    pub discarded: Option<Discarded>,
}

/// The study's fingerprint: everything that sets a journalled design's numbers (the
/// buildings of every case, the records' samples as run, the space, objective, limits and
/// fidelity, the integrators' version) — not the sweep's or the refinement's settings,
/// which only choose the designs: a rerun with a larger budget replays what was run.
pub fn fingerprint(study: &PlanStudy) -> u64 {
    let mut h = Fnv64::default();
    h.u64(u64::from(slipload_sim::NUMERICS_VERSION));
    for case in &study.cases {
        let b = &case.building;
        h.str(&case.name);
        if study.config.property_bounds.is_some() {
            h.f64(case.slip_factor).f64(case.brace_factor);
            h.u64(u64::from(case.objective));
        }
        h.f64s(b.mass.as_slice())
            .f64s(b.stiffness.as_slice())
            .f64s(b.damping.as_slice());
        for line in &b.lines {
            h.str(&line.name).f64(line.angle).f64s(&line.point);
            h.f64s(&line.stiffness);
            for y in &line.storey_yield {
                match y {
                    Some(y) => h.str(&format!("{y:?}")),
                    None => h.str("-"),
                };
            }
            for d in &line.dissipators {
                match d {
                    Some(d) => h
                        .f64(d.brace_stiffness)
                        .f64(d.mass)
                        .f64(d.brace_damping)
                        .f64(d.lower)
                        .f64(d.upper),
                    None => h.str("-"),
                };
            }
        }
        if let Some(c) = &b.collapse_drift {
            h.f64s(c);
        }
        if let Some(hs) = &b.storey_heights {
            h.f64s(hs);
        }
    }
    for s in &study.suites {
        h.str(&s.name).f64s(&s.angles_deg);
        h.f64(s.duration_s.unwrap_or(-1.0));
        for p in &s.pairs {
            h.str(&p.name);
            for r in [&p.first, &p.second] {
                h.f64(r.dt()).f64s(r.samples());
            }
        }
    }
    let cfg = &study.config;
    let json = |v: &dyn erased::Ser| v.json();
    // (the sweep's and the refinement's settings choose which designs run, not what a
    // design gives: a journal serves a study that asks for more of them)
    h.str(&json(&cfg.space))
        .str(&json(&cfg.objective))
        .str(&json(&cfg.limits))
        .str(&json(&cfg.fidelity));
    h.str(study.method.as_str());
    h.finish()
}

/// JSON text of a config part (for the fingerprint).
mod erased {
    pub trait Ser {
        fn json(&self) -> String;
    }
    impl<T: serde::Serialize> Ser for T {
        fn json(&self) -> String {
            serde_json::to_string(self).unwrap_or_default()
        }
    }
}

/// Reads the journal's points when its fingerprint is `fp`; refuses another study's.
fn read_journal(folder: &StudyFolder, fp: u64) -> Result<Vec<Point>, OptError> {
    let path = folder.path(PLAN_JOURNAL);
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(source) => return Err(OptError::Io { path, source }),
    };
    let mut lines = text.lines();
    let head = lines.next().unwrap_or("");
    let want = format!("{{\"fingerprint\":\"{fp:016x}\"}}");
    if head != want {
        return Err(OptError::Argument(format!(
            "{}: its journal {PLAN_JOURNAL} is another study's (or another version's): run with --fresh to start afresh, or give another --out",
            folder.dir().display()
        )));
    }
    let mut out = Vec::new();
    for line in lines {
        // a line cut by an interruption ends the journal
        match serde_json::from_str::<Point>(line) {
            Ok(p) => out.push(p),
            Err(_) => break,
        }
    }
    Ok(out)
}

/// `slipload optimize` on a study in plan, into the folder of `request`.
pub fn optimize_in_plan(
    study: &PlanStudy,
    request: FolderRequest<'_>,
    progress: &dyn Progress,
    figures: &dyn FigureWriter,
) -> Result<PlanRun, OptError> {
    StudyFolder::check_path(request.option, request.path)?;
    figures.check()?;
    let (folder, discarded) = StudyFolder::open(request)?;
    if let Some(d) = &discarded {
        progress.discarded(folder.dir(), d);
    }
    let fp = fingerprint(study);
    let journal_path = folder.journal(PLAN_JOURNAL)?;
    let replay = read_journal(&folder, fp)?;
    // the journal is written again from its valid part: a cut last line goes
    {
        let mut text = format!("{{\"fingerprint\":\"{fp:016x}\"}}\n");
        for p in &replay {
            text.push_str(
                &serde_json::to_string(p)
                    .map_err(|e| OptError::Argument(format!("journal entry: {e}")))?,
            );
            text.push('\n');
        }
        crate::base::output::write_atomic(&journal_path, text.as_bytes())?;
    }
    let mut file = std::fs::OpenOptions::new()
        .append(true)
        .open(&journal_path)
        .map_err(|source| OptError::Io {
            path: journal_path.clone(),
            source,
        })?;
    let oracle = |zs: &[Vec<f64>]| -> Result<Vec<(f64, Option<crate::phases::refine::LimitValues>)>, OptError> {
        let loads: Vec<Vec<Option<f64>>> = zs.iter().map(|z| study.all_slip_loads(z)).collect();
        let evals = evaluate_loads(study, &loads, Step::SEARCH)?;
        // one tick per design run (the sweep's and the refinement's bars; a design the
        // journal gives is not run)
        for _ in &evals {
            progress.tick();
        }
        Ok(evals.iter().map(|e| e.point_value(study)).collect())
    };
    let jp = journal_path.clone();
    let hook = move |p: &Point| -> Result<(), OptError> {
        let line = serde_json::to_string(p)
            .map_err(|e| OptError::Argument(format!("journal entry: {e}")))?;
        writeln!(file, "{line}").map_err(|source| OptError::Io {
            path: jp.clone(),
            source,
        })
    };
    let mut ev =
        Evaluations::with_limits(Box::new(oracle), Vec::new()).with_journal(replay, Box::new(hook));
    // the sweep: the file's design where the space holds it, then a shifted Halton sample
    let space = &study.space;
    let mut sample: Vec<Vec<f64>> = Vec::new();
    let file_loads: Option<Vec<f64>> = space
        .dampers
        .iter()
        .map(|&k| study.dampers[k].file_slip_load)
        .collect();
    if let Some(z) = file_loads.and_then(|l| space.point_of(&l)) {
        sample.push(z);
    }
    sample.extend(crate::model::sampler::sample(
        space,
        &crate::model::config::SweepConfig {
            sampler: crate::model::config::SamplerKind::Halton,
            points: study.config.sweep.points,
            seed: study.config.sweep.seed,
            ..crate::model::config::SweepConfig::default()
        },
    ));
    phase(progress, Phase::Sweep, sample.len(), |_| {
        for chunk in sample.chunks(SWEEP_BATCH) {
            ev.eval(chunk)?;
        }
        Ok(())
    })?;
    let sweep_designs = ev.count();
    // the refinement from the best sweep design
    let start = best_point(&ev).ok_or_else(|| {
        OptError::Argument("the sweep evaluated no design: the space holds none".into())
    })?;
    let cfg = RefineConfig {
        method: RefineMethod::Model,
        starts: 1,
        max_evaluations: study.config.refine.max_evaluations,
        parallel_starts: false,
        tolerance: study.config.refine.tolerance,
        initial_radius: 0.15,
        finalists: 1,
        seed: 1,
    };
    let max = study.config.refine.max_evaluations;
    let stop = phase(progress, Phase::Refine, max, |_| {
        let budget = sweep_designs + max;
        if max == 0 {
            return Ok("no refinement asked (max_evaluations 0)".to_string());
        }
        let r = refine(RefineMethod::Model, space, &start, &mut ev, &cfg, budget)?;
        Ok(r.stop.as_str().to_string())
    })?;
    let refine_designs = ev.count() - sweep_designs;
    let best = best_point(&ev).unwrap_or(start);
    let replayed = ev.replayed;
    drop(ev);
    // the final table at the finer step
    let factor = study.config.fidelity.check_dt_factor.unwrap_or(0.25);
    let opt_loads = study.all_slip_loads(&best.z);
    let bare: Vec<Option<f64>> = study.dampers.iter().map(|_| Some(0.0)).collect();
    let file: Vec<Option<f64>> = study.dampers.iter().map(|d| d.file_slip_load).collect();
    let mut designs: Vec<(String, String, Vec<Option<f64>>)> = vec![
        (
            "bare".into(),
            "every damper free (no slip load)".into(),
            bare,
        ),
        ("file".into(), "the building file's slip loads".into(), file),
        (
            "optimum".into(),
            "the study's best design".into(),
            opt_loads.clone(),
        ),
    ];
    if study.config.space.placement != Placement::Directions {
        designs.push((
            "planar split".into(),
            "the optimum's slip load per storey and direction, split between the direction's lines in proportion to their stiffness (as a planar model places it)".into(),
            planar_split(study, &opt_loads),
        ));
    }
    let loads: Vec<Vec<Option<f64>>> = designs.iter().map(|d| d.2.clone()).collect();
    let evals: Vec<DesignEval> = phase(progress, Phase::DesignTable, 1, |tick| {
        let e = evaluate_loads(
            study,
            &loads,
            Step {
                factor,
                demands: true,
            },
        )?;
        tick();
        Ok(e)
    })?;
    let rows: Vec<PlanRow> = designs
        .into_iter()
        .zip(evals)
        .map(|((design, description, _), eval)| PlanRow {
            objective: eval.objective(study),
            passes: eval.passes(study),
            ratios: eval.ratios(study),
            design,
            description,
            eval,
        })
        .collect();
    let report = PlanReport {
        study: study.name.clone(),
        variables: space.names.clone(),
        limits: DesignEval::ratio_names(study),
        sweep_designs,
        refine_designs,
        replayed,
        stop,
        z: best.z.clone(),
        objective_sweep: best.f,
        runs_per_design: study.runs_per_design(),
        rows,
        check_dt_factor: factor,
    };
    let text = summary(study, &report);
    // the device tests of the optimum, when the study asks for them
    let protocol = study
        .config
        .devices
        .and_then(|d| d.test_protocol)
        .zip(report.row("optimum"))
        .map(|(c, row)| PlanTestProtocol::of(study, c, row));
    let mut value = serde_json::json!({
        "study": report.study,
        "variables": report.variables,
        "z": report.z,
        "objective_sweep_step": finite(report.objective_sweep),
        "sweep_designs": report.sweep_designs,
        "refine_designs": report.refine_designs,
        "stop": report.stop,
        "check_dt_factor": report.check_dt_factor,
        "limits": report.limits,
        "rows": report.rows.iter().map(|r| serde_json::json!({
            "design": r.design,
            "description": r.description,
            "objective": finite(r.objective),
            "passes": r.passes,
            "ratios": r.ratios,
            "collapsed_runs": r.eval.collapsed(),
            "slip_loads_n": study.dampers.iter().zip(&r.eval.loads).map(|(d, l)| serde_json::json!({
                "damper": d.name, "slip_load_n": l
            })).collect::<Vec<_>>(),
            "cells": r.eval.cells.iter().map(|c| serde_json::json!({
                "suite": study.suites[c.suite].name,
                "case": study.cases[c.case].name,
                "edge_drift_ratio": c.edge,
                "line_drift_ratio": c.line,
                "torsional_ratio": c.torsional,
                "rotation_rad": c.rotation,
                "collapsed_runs": c.peaks.collapsed,
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    });
    if let (Some(p), Some(o)) = (&protocol, value.as_object_mut()) {
        let v = serde_json::to_value(p)
            .map_err(|e| OptError::Argument(format!("plan-optimum.json: {e}")))?;
        o.insert("test_protocol".into(), v);
    }
    let json = serde_json::to_string_pretty(&value)
        .map_err(|e| OptError::Argument(format!("plan-optimum.json: {e}")))?;
    folder.write("plan-summary.txt", text.as_bytes())?;
    folder.write("plan-optimum.json", format!("{json}\n").as_bytes())?;
    folder.write("plan-designs.csv", designs_csv(study, &folder)?.as_bytes())?;
    folder.write("plan-dampers.csv", dampers_csv(study, &report).as_bytes())?;
    folder.write("plan-dampers.md", dampers_md(study, &report).as_bytes())?;
    folder.write("plan-check.md", check_md(study, &report).as_bytes())?;
    folder.write("plan-devices.csv", devices_csv(study, &report).as_bytes())?;
    let mut devices = devices_md(study, &report);
    if let Some(p) = &protocol {
        devices.push_str(&p.to_markdown());
    }
    folder.write("plan-devices.md", devices.as_bytes())?;
    folder.write("plan-profiles.csv", profiles_csv(study, &report).as_bytes())?;
    let names: Vec<String> = crate::store::folder::PLAN_FIGURE_STEMS
        .iter()
        .flat_map(|s| ["svg", "png", "csv"].map(|e| format!("{s}.{e}")))
        .collect();
    folder.claim(&names)?;
    let drawn = figures.plan(&figure_data(study, &report), folder.dir())?;
    Ok(PlanRun {
        report,
        summary: text,
        drawn,
        files: PlanReport::FILES.to_vec(),
        discarded,
    })
}

fn finite(v: f64) -> serde_json::Value {
    if v.is_finite() {
        serde_json::json!(v)
    } else {
        serde_json::json!("inf")
    }
}

/// The best point seen: the least objective among those that pass; where none passes,
/// the one whose largest limit ratio is least (the nearest to passing).
fn best_point(ev: &Evaluations<'_>) -> Option<Point> {
    if let Some(p) = ev.best().filter(|p| p.f.is_finite()) {
        return Some(p);
    }
    let worst = |p: &Point| {
        p.limits.as_ref().map_or(f64::INFINITY, |l| {
            l.ratios.iter().copied().fold(0.0, f64::max)
        })
    };
    let mut best: Option<&Point> = None;
    for p in ev.all() {
        if best.is_none_or(|b| worst(p) < worst(b)) {
            best = Some(p);
        }
    }
    best.cloned()
}

/// `plan-designs.csv`: every design the journal holds (sweep, then refinement), its
/// variables' slip loads and its objective and limit ratios.
fn designs_csv(study: &PlanStudy, folder: &StudyFolder) -> Result<String, OptError> {
    let points = read_journal(folder, fingerprint(study))?;
    let mut s = String::from("design");
    for n in &study.space.names {
        s.push_str(&format!(",\"{} (z)\"", n.replace('"', "\"\"")));
    }
    s.push_str(",objective,passes");
    for n in DesignEval::ratio_names(study) {
        s.push_str(&format!(",\"{}\"", n.replace('"', "\"\"")));
    }
    s.push('\n');
    for (i, p) in points.iter().enumerate() {
        s.push_str(&format!("{}", i + 1));
        for z in &p.z {
            s.push_str(&format!(",{z:.6}"));
        }
        let obj = p.limits.as_ref().map_or(p.f, |l| l.objective);
        s.push_str(&format!(",{},{}", obj, p.f.is_finite()));
        if let Some(l) = &p.limits {
            for r in &l.ratios {
                s.push_str(&format!(",{r:.6}"));
            }
        }
        s.push('\n');
    }
    Ok(s)
}
