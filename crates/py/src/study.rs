//! Studies: `optimize`, `sweep`, `merge`, `rank` and `table` through the study pipeline
//! (`slipload_opt::pipeline`), writing exactly the files the command line writes (the
//! pipeline's, then the figures), with the same journals, resume and fingerprints.
//!
//! Each returns a dict: `out` (the folder), `files` (name → text of every JSON, CSV and
//! Markdown file the call wrote, for the Python layer to parse), and the call's counts.

use crate::errors::{PyResultExt, guarded, input};
use crate::records::PyRecord;
use crate::run::watched;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use slipload_figures::StudyFigures;
use slipload_opt::Study;
use slipload_opt::model::config::RefineMethod;
use slipload_opt::phases::family::FamilyReport;
use slipload_opt::phases::figures::MapRequest;
use slipload_opt::phases::rank::Ranking;
use slipload_opt::pipeline::{
    OptimizeOptions, SweepRun, family_study, merge_shards, optimize_study, rank_study, sweep_study,
};
use slipload_opt::store::folder::{Discarded, FolderRequest};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A validated study: its building, records, design space and objective.
#[pyclass(name = "Study", module = "slipload", frozen)]
#[derive(Debug, Clone)]
pub struct PyStudy {
    pub(crate) inner: Arc<Study>,
}

#[pymethods]
impl PyStudy {
    /// Loads a study file (its building and records are loaded and checked).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<PyStudy> {
        guarded(|| {
            Ok(PyStudy {
                inner: Arc::new(Study::load(&path).py()?),
            })
        })
    }

    /// A study from JSON text; `name` names it in errors and anchors relative paths
    /// (records, the building file) from the current folder.
    #[staticmethod]
    #[pyo3(signature = (text, name="study"))]
    fn from_json(text: &str, name: &str) -> PyResult<PyStudy> {
        guarded(|| {
            Ok(PyStudy {
                inner: Arc::new(
                    Study::from_json(text, Path::new(name))
                        .py()
                        .map_err(|e| crate::json_path::located(e, text, name))?,
                ),
            })
        })
    }

    /// The embedded benchmark study (the command line's default).
    #[staticmethod]
    fn benchmark() -> PyResult<PyStudy> {
        guarded(|| {
            Ok(PyStudy {
                inner: Arc::new(Study::benchmark().py()?),
            })
        })
    }

    /// What the study's inputs make doubtful without making them wrong (a slip load of
    /// the building file that looks like kN written as N, a base-shear limit that looks
    /// like kN written as N): the command line's warnings, in its words;
    /// `slipload.load_study` (and every study call) warns them as `UserWarning`s.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.inner.warnings()
    }

    /// The study's name.
    #[getter]
    fn name(&self) -> String {
        self.inner.name.clone()
    }

    /// The objective, as a label (`mean peak_drift_ratio`).
    #[getter]
    fn objective(&self) -> String {
        self.inner.objective.label()
    }

    /// Floors (from 1) of the design's dissipators.
    #[getter]
    fn damper_floors(&self) -> Vec<usize> {
        self.inner.space.dampers.iter().map(|f| f + 1).collect()
    }

    /// The building file's slip loads, N per dissipator.
    #[getter]
    fn file_slip_loads(&self) -> Vec<f64> {
        self.inner.file_slip_loads()
    }

    /// The records of every suite, in order.
    #[getter]
    fn records(&self) -> Vec<PyRecord> {
        self.inner
            .records
            .iter()
            .map(|r| PyRecord { inner: r.clone() })
            .collect()
    }

    /// The suites: name and number of records each.
    #[getter]
    fn suites(&self) -> Vec<(String, usize)> {
        self.inner
            .suites
            .iter()
            .map(|s| (s.name.clone(), s.range.len()))
            .collect()
    }

    /// The study's fingerprint (what its journals are keyed by).
    #[getter]
    fn fingerprint(&self) -> String {
        slipload_opt::phases::sweep::Manifest::of(&self.inner)
            .fingerprint
            .hash
    }

    fn __repr__(&self) -> String {
        format!(
            "Study({:?}, {}, {} records, dampers on floors {:?})",
            self.inner.name,
            self.inner.objective.label(),
            self.inner.records.len(),
            self.damper_floors()
        )
    }
}

/// The dict a study call returns: `out` and `files`, the text of every JSON, CSV and
/// Markdown file of `names` the call wrote in `out`, for the Python layer to parse.
fn report_dict<'py>(py: Python<'py>, out: &Path, names: &[&str]) -> PyResult<Bound<'py, PyDict>> {
    let files = PyDict::new(py);
    for n in names {
        if (n.ends_with(".json") || n.ends_with(".csv") || n.ends_with(".md"))
            && let Ok(text) = std::fs::read_to_string(out.join(n))
        {
            files.set_item(n, text)?;
        }
    }
    let d = PyDict::new(py);
    d.set_item("out", out.to_path_buf())?;
    d.set_item("files", files)?;
    Ok(d)
}

fn refine_method(name: Option<&str>) -> PyResult<Option<RefineMethod>> {
    name.map(|n| {
        n.parse::<RefineMethod>()
            .map_err(|e| input(format!("refine: {e}")))
    })
    .transpose()
}

/// The output folder of a call: `out`, named `out` in errors.
fn folder(out: &Path, fresh: bool) -> FolderRequest<'_> {
    FolderRequest {
        path: out,
        option: "out",
        fresh,
    }
}

/// `fresh`: what was removed and kept, into the returned dict.
fn fresh_items(d: &Bound<'_, PyDict>, discarded: Option<&Discarded>) -> PyResult<()> {
    if let Some(gone) = discarded {
        d.set_item("removed", gone.removed.clone())?;
        d.set_item("kept", gone.kept.clone())?;
    }
    Ok(())
}

/// Optimises a study into `out`, as `slipload optimize` does.
#[pyfunction]
#[pyo3(signature = (study=None, out="out/optimize".into(), *, refine=None, map_floors=None, map_grid=None, fresh=false, progress=None, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn optimize<'py>(
    py: Python<'py>,
    study: Option<&PyStudy>,
    out: PathBuf,
    refine: Option<&str>,
    map_floors: Option<&Bound<'py, PyAny>>,
    map_grid: Option<&Bound<'py, PyAny>>,
    fresh: bool,
    progress: Option<&Bound<'py, PyAny>>,
    threads: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let study = match study {
        Some(s) => s.inner.clone(),
        None => Arc::new(guarded(|| Study::benchmark().py())?),
    };
    let grid = crate::args::count(
        map_grid,
        "map_grid",
        "a whole number of grid points per axis",
    )?
    .map_or(11, |(n, _)| n);
    let floors = match map_floors.filter(|f| !f.is_none()) {
        None => None,
        Some(f) => {
            let pair: Vec<Bound<'py, PyAny>> = f
                .try_iter()
                .and_then(|i| i.collect::<PyResult<Vec<_>>>())
                .ok()
                .filter(|v| v.len() == 2)
                .ok_or_else(|| input("map_floors: expected two floors (from 1), as (a, b)"))?;
            let floor = |o: &Bound<'py, PyAny>| {
                crate::args::Whole::of(o, "map_floors", "two floors (from 1)")?
                    .count("map_floors", "two floors (from 1)")
            };
            Some([floor(&pair[0])?, floor(&pair[1])?])
        }
    };
    let options = OptimizeOptions {
        refine: refine_method(refine)?,
        map: floors.map(|floors| MapRequest { floors, grid }),
    };
    let run = watched(py, threads, progress, |ctl| {
        optimize_study(&study, &options, folder(&out, fresh), ctl, &StudyFigures).py()
    })?;
    let mut names: Vec<&str> = run.files.clone();
    names.extend(SweepRun::FILES);
    let d = report_dict(py, &out, &names)?;
    fresh_items(&d, run.discarded.as_ref())?;
    d.set_item("figures", run.drawn)?;
    let w = &run.report.work;
    let work = PyDict::new(py);
    for (name, p) in [
        ("sweep", Some(&w.sweep)),
        ("refine", Some(&w.refine)),
        ("check", Some(&w.check)),
        ("table", Some(&w.table)),
        ("map", w.map.as_ref()),
    ] {
        if let Some(p) = p {
            work.set_item(name, (p.run, p.reused))?;
        }
    }
    d.set_item("work", work)?;
    d.set_item("sweep_method", run.report.sweep.manifest.method.as_str())?;
    d.set_item(
        "sweep_method_reason",
        run.report.sweep.manifest.method_reason.clone(),
    )?;
    Ok(d)
}

/// Sweeps a study (or one shard of it) into `out`, as `slipload sweep` does.
#[pyfunction]
#[pyo3(signature = (study, out="out/sweep".into(), *, shard=None, resume=false, fresh=false, progress=None, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn sweep<'py>(
    py: Python<'py>,
    study: &PyStudy,
    out: PathBuf,
    shard: Option<&str>,
    resume: bool,
    fresh: bool,
    progress: Option<&Bound<'py, PyAny>>,
    threads: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    if resume && fresh {
        return Err(input(
            "resume and fresh exclude each other: resume continues the journal, fresh removes it",
        ));
    }
    let shard = match shard {
        None => slipload_opt::Shard::ALL,
        Some(spec) => slipload_opt::Shard::parse(spec, None, &|k| std::env::var(k).ok()).py()?,
    };
    let study = study.inner.clone();
    let run = watched(py, threads, progress, |ctl| {
        sweep_study(
            &study,
            shard,
            resume,
            folder(&out, fresh),
            ctl,
            &StudyFigures,
        )
        .py()
    })?;
    let r = &run.report;
    let d = report_dict(py, &out, &SweepRun::FILES)?;
    fresh_items(&d, run.discarded.as_ref())?;
    d.set_item("figures", run.drawn.clone())?;
    d.set_item("complete", run.figures.is_some())?;
    d.set_item("tasks", r.shard_tasks)?;
    d.set_item("ran", r.ran)?;
    d.set_item("resumed", r.resumed)?;
    d.set_item("distrusted", r.distrusted)?;
    d.set_item("shard", (shard.index, shard.count))?;
    Ok(d)
}

/// Joins the journals of sweep shards into the files one sweep writes, as `slipload merge`.
#[pyfunction]
#[pyo3(signature = (dirs, out))]
pub fn merge<'py>(
    py: Python<'py>,
    dirs: Vec<PathBuf>,
    out: PathBuf,
) -> PyResult<Bound<'py, PyDict>> {
    if dirs.is_empty() {
        return Err(input("dirs: give at least one shard folder"));
    }
    let refs: Vec<&Path> = dirs.iter().map(PathBuf::as_path).collect();
    let run = watched(py, None, None, |_| {
        merge_shards(&refs, folder(&out, false), &StudyFigures).py()
    })?;
    let d = report_dict(py, &out, &SweepRun::FILES)?;
    d.set_item("figures", run.drawn)?;
    d.set_item("tasks", run.report.manifest.tasks())?;
    Ok(d)
}

/// Ranks candidate designs over every suite of a study, as `slipload rank` does.
/// `designs` is a candidates file (as `optimize` writes `candidates.json`).
#[pyfunction]
#[pyo3(signature = (study, designs, out="out/rank".into(), *, bootstrap=None, seed=None, progress=None, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn rank<'py>(
    py: Python<'py>,
    study: &PyStudy,
    designs: PathBuf,
    out: PathBuf,
    bootstrap: Option<&Bound<'py, PyAny>>,
    seed: Option<&Bound<'py, PyAny>>,
    progress: Option<&Bound<'py, PyAny>>,
    threads: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let bootstrap = match bootstrap.filter(|b| !b.is_none()) {
        None => 200,
        Some(b) => {
            let b = crate::args::Whole::of(b, "bootstrap", "a whole number of resamples")?;
            if !(1..=1_000_000).contains(&b.value) {
                return Err(input(format!(
                    "bootstrap: {} is not in 1..=1000000 (resamples of the records)",
                    b.text
                )));
            }
            usize::try_from(b.value).unwrap_or(1)
        }
    };
    let seed = crate::args::seed(seed, "seed")?.unwrap_or(1);
    let study = study.inner.clone();
    let ranking = watched(py, threads, progress, |ctl| {
        rank_study(&study, &designs, bootstrap, seed, folder(&out, false), ctl).py()
    })?;
    let d = report_dict(py, &out, &Ranking::FILES)?;
    d.set_item("markdown", ranking.to_markdown())?;
    Ok(d)
}

/// The optimum over a family of buildings and hazard levels, as `slipload table` does.
#[pyfunction]
#[pyo3(signature = (study=None, out="out/table".into(), *, period_scales=vec![0.8, 1.0, 1.25], intensity_scales=vec![0.5, 1.0, 1.5], refine=None, progress=None, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn table<'py>(
    py: Python<'py>,
    study: Option<&PyStudy>,
    out: PathBuf,
    period_scales: Vec<f64>,
    intensity_scales: Vec<f64>,
    refine: Option<&str>,
    progress: Option<&Bound<'py, PyAny>>,
    threads: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let study = match study {
        Some(s) => s.inner.clone(),
        None => Arc::new(guarded(|| Study::benchmark().py())?),
    };
    // an empty list is refused by the library (`check_scales`), in the command line's words
    let method = refine_method(refine)?;
    let report = watched(py, threads, progress, |ctl| {
        family_study(
            &study,
            &period_scales,
            &intensity_scales,
            method,
            folder(&out, false),
            ctl,
        )
        .py()
    })?;
    let d = report_dict(py, &out, &FamilyReport::FILES)?;
    d.set_item("markdown", report.to_markdown())?;
    Ok(d)
}

/// The objective vectors of designs under a study's `objectives`, at the sweep fidelity
/// (`slipload_opt::phases::pareto::evaluate_objectives`): an array (designs, objectives).
#[pyfunction]
#[pyo3(signature = (study, slip_loads, *, progress=None, threads=None))]
pub fn evaluate_objectives<'py>(
    py: Python<'py>,
    study: &PyStudy,
    slip_loads: &Bound<'py, PyAny>,
    progress: Option<&Bound<'py, PyAny>>,
    threads: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    let (nd, nk, loads) = crate::arrays::matrix(slip_loads, "slip_loads")?;
    let designs: Vec<Vec<f64>> = loads.chunks(nk).map(<[f64]>::to_vec).collect();
    let study = study.inner.clone();
    let vectors = watched(py, threads, progress, |ctl| {
        slipload_opt::phases::pareto::evaluate_objectives(&study, &designs, ctl).py()
    })?;
    let m = vectors.first().map_or(0, Vec::len);
    crate::arrays::array2(py, nd, m, vectors.into_iter().flatten().collect())
}

/// The rows of a 2-D float64 array, each a point in objective space.
fn points(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Vec<f64>>> {
    let (_, k, v) = crate::arrays::matrix(obj, what)?;
    Ok(v.chunks(k).map(<[f64]>::to_vec).collect())
}

/// Non-dominated ranks (1 = the front) of the rows of `points` (minimisation).
#[pyfunction]
pub fn nondominated_ranks(points: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
    // a collapsed design scores +inf (evaluate_objectives): it ranks, behind the others
    let (_, k, v) = crate::arrays::matrix_of(points, "points", true)?;
    let p: Vec<Vec<f64>> = v.chunks(k).map(<[f64]>::to_vec).collect();
    Ok(slipload_opt::phases::pareto::nondominated_ranks(&p))
}

/// The hypervolume the rows of `points` dominate up to `reference` (minimisation).
#[pyfunction]
pub fn hypervolume(points: &Bound<'_, PyAny>, reference: &Bound<'_, PyAny>) -> PyResult<f64> {
    let p = self::points(points, "points")?;
    let r = crate::arrays::vector(reference, "reference", true)?;
    if let Some((i, row)) = p.iter().enumerate().find(|(_, row)| row.len() != r.len()) {
        return Err(input(format!(
            "points[{i}] has {} objectives, reference has {}",
            row.len(),
            r.len()
        )));
    }
    if !(1..=4).contains(&r.len()) {
        return Err(input(format!(
            "reference: {} objectives; the hypervolume is computed for 1 to 4",
            r.len()
        )));
    }
    Ok(slipload_opt::phases::pareto::hypervolume(&p, &r))
}

/// The knee of a front (rows of `points`, minimisation): its index, by the rule of the
/// study reports (least sum of objectives normalised over the front); None for an empty
/// front.
#[pyfunction]
pub fn knee(points: &Bound<'_, PyAny>) -> PyResult<Option<usize>> {
    let p = self::points(points, "points")?;
    Ok(slipload_opt::phases::pareto::knee(&p))
}
