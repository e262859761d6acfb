//! One run of a study's design as a scene: what `slipload simulate --study` and
//! `slipload opensees --study` run, so that a design goes from a study folder to a re-run
//! (and to OpenSees) with its suite's record and scale factor and its property case,
//! without anybody copying slip loads from a table or a factor from a manifest.

use crate::base::error::OptError;
use crate::eval::evaluate::{design_scene, design_scene_of};
use crate::model::fidelity::Fidelity;
use crate::model::study::Study;
use crate::phases::rank::{load_designs, to_newtons};
use crate::phases::sweep::Manifest;
use slipload_sim::Scene;
use std::path::Path;

/// Which run of which design.
#[derive(Debug, Clone, Copy)]
pub struct DesignRun<'a> {
    /// The study's output folder (its `candidates.json`, as `optimize` writes it), or a
    /// candidates file (`[{"name", "slip_loads_kn"}, …]`).
    pub designs: &'a Path,
    /// The design's name there (`optimum`, `uniform`, `storey-shear`, `file`, `bare`, or a
    /// name of the user's file).
    pub design: &'a str,
    /// The run, as the study's tables name it: the record's name, and at a property
    /// bound the case after it (`NAME [lower]`); a record file may be named by its file
    /// name or its stem (`RSN1084_NORTHR_SCS142 [upper]`).
    pub run: &'a str,
    /// The suite of the run, where its record is in several (each suite scales it its own
    /// way).
    pub suite: Option<&'a str>,
    /// Another method than the check's (`bilinear` for an OpenSees script of dampers
    /// with mass); the check's time step rule stays.
    pub method: Option<slipload_sim::MethodName>,
}

/// The run `asked` names in suite `suite` (any suite when `None`): the runs whose record
/// is named `asked` without its case (as written, or by its file name or file stem) at
/// that case (` [lower]`, ` [upper]`, none for the nominal case). `None` when no run is;
/// several (one record in several suites, each scaled its own way) are refused, naming
/// the suites to choose from.
fn find_run(
    study: &Study,
    names: &[String],
    asked: &str,
    suite: Option<&str>,
) -> Result<Option<usize>, OptError> {
    if let Some(s) = suite
        && !study.suites.iter().any(|x| x.name == s)
    {
        return Err(OptError::Argument(format!(
            "--suite {s:?}: study {} has no suite of that name; its suites are {}",
            study.name,
            suite_names(study)
        )));
    }
    let (base, case) = match asked.rsplit_once(" [") {
        Some((b, c)) if c.ends_with(']') => (b, Some(&c[..c.len() - 1])),
        _ => (asked, None),
    };
    let hits: Vec<usize> = (0..study.runs())
        .filter(|&i| {
            let (c, r) = study.run(i);
            let same_case = match case {
                None => c.is_nominal(),
                Some(name) => !c.is_nominal() && c.name.as_str() == name,
            };
            let name = study.records[r].name();
            let path = Path::new(name);
            let same_record = name == base
                || [path.file_name(), path.file_stem()]
                    .iter()
                    .flatten()
                    .any(|n| n.to_str() == Some(base));
            let in_suite = suite.is_none_or(|s| {
                study
                    .suites
                    .iter()
                    .any(|x| x.name == s && x.range.contains(&r))
            });
            same_case && same_record && in_suite
        })
        .collect();
    match hits.as_slice() {
        [] => Ok(None),
        [i] => Ok(Some(*i)),
        many => Err(OptError::Argument(format!(
            "--run {asked:?} names {} runs of study {} ({}): the record is in several suites, each scaled its own way; give --suite ({})",
            many.len(),
            study.name,
            many.iter()
                .map(|&i| names[i].as_str())
                .collect::<Vec<_>>()
                .join(", "),
            suite_names(study)
        ))),
    }
}

/// The run and the record of `asked` when it names one orientation of a pair run
/// `worst` (`PAIR@30deg`, or `PAIR@30deg [upper]` at a bound), in suite `suite` (any when
/// `None`).
fn find_orientation(
    study: &Study,
    asked: &str,
    suite: Option<&str>,
) -> Option<(usize, std::sync::Arc<slipload_motion::Record>)> {
    let (base, case) = match asked.rsplit_once(" [") {
        Some((b, c)) if c.ends_with(']') => (b, Some(&c[..c.len() - 1])),
        _ => (asked, None),
    };
    (0..study.runs()).find_map(|i| {
        let (c, r) = study.run(i);
        let same_case = match case {
            None => c.is_nominal(),
            Some(name) => !c.is_nominal() && c.name.as_str() == name,
        };
        let in_suite = suite.is_none_or(|s| {
            study
                .suites
                .iter()
                .any(|x| x.name == s && x.range.contains(&r))
        });
        if !(same_case && in_suite) {
            return None;
        }
        let o = study.orientations.get(r)?;
        o.iter().find(|x| x.name() == base).map(|x| (i, x.clone()))
    })
}

fn suite_names(study: &Study) -> String {
    study
        .suites
        .iter()
        .map(|s| s.name.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Most run names an error lists before it says how many there are.
const NAMES_SHOWN: usize = 8;

/// The scene of run `req.run` of design `req.design`, at the study's check fidelity (the
/// reference accuracy its code check ran at; `req.method` in place of its method): the
/// record scaled as its suite scales it,
/// the case's factors on the slip loads and brace stiffnesses. A folder must hold this
/// study's results: a folder of another study, or of this study changed since, is
/// refused, naming what changed.
pub fn design_run_scene(study: &Study, req: &DesignRun<'_>) -> Result<Scene, OptError> {
    let file = if req.designs.is_dir() {
        let manifest_path = req.designs.join("manifest.json");
        if manifest_path.exists() {
            let found = Manifest::read(&manifest_path)?;
            let ours = Manifest::of(study);
            if found.fingerprint != ours.fingerprint {
                return Err(OptError::Argument(format!(
                    "{} holds the results of {} (changed: {}), not of study {}: give the folder this study wrote",
                    req.designs.display(),
                    if found.study == study.name {
                        "another version of the study".to_string()
                    } else {
                        format!("study {:?}", found.study)
                    },
                    ours.fingerprint.describe_changes(&found.fingerprint),
                    study.name
                )));
            }
        }
        let file = req.designs.join("candidates.json");
        if !file.exists() {
            return Err(OptError::Argument(format!(
                "{} has no candidates.json: run `slipload optimize` on the study with --out {} first, or give a candidates file",
                req.designs.display(),
                req.designs.display()
            )));
        }
        file
    } else {
        req.designs.to_path_buf()
    };
    let designs = load_designs(study, &file)?;
    let loads = to_newtons(study, &designs)?;
    let Some(d) = designs.iter().position(|d| d.name == req.design) else {
        return Err(OptError::Argument(format!(
            "--design {:?}: {} has no design of that name; it has {}",
            req.design,
            file.display(),
            designs
                .iter()
                .map(|d| d.name.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )));
    };
    let names = study.run_names();
    // one orientation of a pair run `worst` (`PAIR@30deg`, with its case after it)
    if let Some((run, rec)) = find_orientation(study, req.run, req.suite) {
        let check = Fidelity::check(study);
        let fid = Fidelity {
            method: req.method.unwrap_or(check.method),
            ..check
        };
        let mut scene = design_scene_of(study, &loads[d], run, &rec, &fid, req.design);
        scene.name = format!(
            "{}, design {} under {} (one orientation of {})",
            study.name, req.design, req.run, names[run]
        );
        return Ok(scene);
    }
    let found = find_run(study, &names, req.run, req.suite)?;
    if let Some(run) = found
        && let (_, record) = study.run(run)
        && let Some(o) = study.orientations.get(record)
        && !o.is_empty()
    {
        return Err(OptError::Argument(format!(
            "--run {:?} is the envelope of {} runs (its pair at each orientation); name one orientation: {}",
            req.run,
            o.len(),
            o.iter().map(|r| r.name()).collect::<Vec<_>>().join(", ")
        )));
    }
    let Some(run) = found else {
        let shown: Vec<&str> = names.iter().take(NAMES_SHOWN).map(String::as_str).collect();
        return Err(OptError::Argument(format!(
            "--run {:?}: study {} has no run of that name; its runs are {}{} ({} in all: a record's name, with ` [lower]` or ` [upper]` after it at a property bound)",
            req.run,
            study.name,
            shown.join(", "),
            if names.len() > NAMES_SHOWN {
                ", …"
            } else {
                ""
            },
            names.len()
        )));
    };
    let check = Fidelity::check(study);
    let fid = Fidelity {
        method: req.method.unwrap_or(check.method),
        ..check
    };
    let mut scene = design_scene(study, &loads[d], run, &fid, req.design);
    let (_, record) = study.run(run);
    let suite = study
        .suites
        .iter()
        .find(|s| s.range.contains(&record))
        .map_or("", |s| s.name.as_str());
    scene.name = format!(
        "{}, design {} under {} (suite {suite})",
        study.name, req.design, names[run]
    );
    Ok(scene)
}
