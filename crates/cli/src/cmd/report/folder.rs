//! The files of a folder `slipload report` reads, and what kind of output folder they
//! make (a study, an accuracy study, a simulation, figures), with the page's title.

use anyhow::Context;
use std::path::{Path, PathBuf};

/// What kind of output folder this is, recognised from the files it holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FolderKind {
    /// `slipload optimize --out`: a finished sweep plus `optimum.json`.
    Optimize,
    /// `slipload sweep --out` (or `merge --out`): `manifest.json` of a study.
    Sweep,
    /// `slipload optimize --out` of a study in plan: `plan-summary.txt`.
    PlanStudy,
    /// `slipload accuracy --out`: `NAME.json` with the median and per-record studies.
    Accuracy,
    /// `slipload simulate --plot`: a time-history CSV (first column `t_s`).
    Simulation,
    /// Only figures (`NAME.svg`).
    Figures,
}

impl FolderKind {
    /// What the folder holds, in a sentence ("the design study").
    pub fn noun(self) -> &'static str {
        match self {
            Self::Optimize => "design study",
            Self::Sweep => "design sweep",
            Self::PlanStudy => "study in plan",
            Self::Accuracy => "accuracy study",
            Self::Simulation => "simulation",
            Self::Figures => "figures",
        }
    }

    /// A description for the page.
    pub fn describe(self) -> &'static str {
        match self {
            Self::Optimize => "design study (slipload optimize: sweep, refinement, design table)",
            Self::Sweep => "design sweep (slipload sweep)",
            Self::PlanStudy => {
                "study in plan (slipload optimize on a building in plan: where the dampers go, the optimum beside its planar split)"
            }
            Self::Accuracy => {
                "accuracy study (slipload accuracy: error vs cost per method and time step)"
            }
            Self::Simulation => "simulation (slipload simulate --plot)",
            Self::Figures => "figures",
        }
    }
}

/// One file of the folder.
#[derive(Debug, Clone)]
pub(super) struct Entry {
    pub(super) name: String,
    pub(super) stem: String,
    pub(super) ext: String,
    pub(super) path: PathBuf,
}

/// The files of the folder, by name, hidden and temporary files left out.
pub(super) fn list(dir: &Path) -> anyhow::Result<Vec<Entry>> {
    let mut files = Vec::new();
    for e in std::fs::read_dir(dir).with_context(|| format!("reading folder {}", dir.display()))? {
        let e = e.with_context(|| format!("reading folder {}", dir.display()))?;
        let path = e.path();
        let name = e.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') || !path.is_file() {
            continue;
        }
        let (stem, ext) = match name.rsplit_once('.') {
            Some((s, x)) => (s.to_string(), x.to_ascii_lowercase()),
            None => (name.clone(), String::new()),
        };
        files.push(Entry {
            name,
            stem,
            ext,
            path,
        });
    }
    files.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(files)
}

/// The text of `e`.
pub(super) fn read(e: &Entry) -> anyhow::Result<String> {
    std::fs::read_to_string(&e.path).with_context(|| format!("reading {}", e.path.display()))
}

/// The JSON of `e`, `None` when it is not JSON.
pub(super) fn read_json(e: &Entry) -> Option<serde_json::Value> {
    serde_json::from_str(&read(e).ok()?).ok()
}

/// The folder's kind and a title for the page, or `None` when nothing is recognised.
pub(super) fn recognise(dir: &Path, files: &[Entry]) -> Option<(FolderKind, String)> {
    let find = |name: &str| files.iter().find(|e| e.name == name);
    let dir_name = dir
        .canonicalize()
        .ok()
        .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .unwrap_or_else(|| dir.display().to_string());
    if let Some(m) = find("manifest.json").and_then(read_json)
        && m.get("designs").is_some()
        && let Some(study) = m.get("study").and_then(|s| s.as_str())
    {
        let kind = if find("optimum.json").is_some() {
            FolderKind::Optimize
        } else {
            FolderKind::Sweep
        };
        return Some((kind, study.to_string()));
    }
    if let Some(summary) = find("plan-summary.txt") {
        // the study's name, as the optimum's file or the summary's first line gives it
        let name = find("plan-optimum.json")
            .and_then(read_json)
            .and_then(|v| v.get("study").and_then(|s| s.as_str()).map(String::from))
            .or_else(|| {
                read(summary).ok().and_then(|t| {
                    t.lines()
                        .next()
                        .and_then(|l| l.strip_prefix("study in plan "))
                        .and_then(|l| l.split(':').next())
                        .map(String::from)
                })
            });
        return Some((FolderKind::PlanStudy, name.unwrap_or(dir_name)));
    }
    let accuracy: Vec<&Entry> = files
        .iter()
        .filter(|e| e.ext == "json")
        .filter(|e| {
            read_json(e).is_some_and(|v| v.get("median").is_some() && v.get("records").is_some())
        })
        .collect();
    if !accuracy.is_empty() {
        let title = match accuracy.as_slice() {
            [one] => one.stem.clone(),
            many => format!("{} accuracy studies", many.len()),
        };
        return Some((FolderKind::Accuracy, title));
    }
    let history = files.iter().find(|e| {
        e.ext == "csv"
            && read(e)
                .ok()
                .is_some_and(|t| t.starts_with("t_s,") || t.starts_with("\"t_s\","))
    });
    if history.is_some() {
        // the scene `simulate --plot` keeps beside its figures names the page
        let scene_name = find("scene.json")
            .into_iter()
            .chain(files.iter().filter(|e| e.ext == "json"))
            .filter_map(read_json)
            .find_map(|v| v.get("name").and_then(|n| n.as_str()).map(String::from));
        return Some((FolderKind::Simulation, scene_name.unwrap_or(dir_name)));
    }
    if files.iter().any(|e| e.ext == "svg") {
        return Some((FolderKind::Figures, dir_name));
    }
    None
}
