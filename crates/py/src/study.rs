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
use slipload_opt::Study;
use slipload_opt::folder_lock::FolderLock;
use slipload_opt::pipeline::{
    MapRequest, OptimizeOptions, StudyReport, SweepRun, family_study, merge_shards, optimize_study,
    rank_study, sweep_study,
};
use slipload_opt::study::RefineMethod;
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
                inner: Arc::new(Study::from_json(text, Path::new(name)).py()?),
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
        slipload_opt::sweep::Manifest::of(&self.inner)
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

/// `--fresh`: the journals and outputs of earlier runs removed (the folder locked).
fn fresh(out: &Path, d: &Bound<'_, PyDict>) -> PyResult<()> {
    let gone = slipload_opt::journal::discard_journals(out).py()?;
    d.set_item("removed", gone.removed)?;
    d.set_item("kept", gone.kept)?;
    Ok(())
}

fn figures(data: &slipload_opt::pipeline::FigureData, out: &Path) -> PyResult<Vec<String>> {
    crate::figures::write(data, out)
}

/// Optimises a study into `out`, as `slipload optimize` does.
#[pyfunction]
#[pyo3(signature = (study=None, out="out/optimize".into(), *, refine=None, map_floors=None, map_grid=11, fresh=false, progress=None, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn optimize<'py>(
    py: Python<'py>,
    study: Option<&PyStudy>,
    out: PathBuf,
    refine: Option<&str>,
    map_floors: Option<(usize, usize)>,
    map_grid: usize,
    fresh: bool,
    progress: Option<&Bound<'py, PyAny>>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let study = match study {
        Some(s) => s.inner.clone(),
        None => Arc::new(guarded(|| Study::benchmark().py())?),
    };
    slipload_opt::output::check_output_folder("out", &out).py()?;
    crate::figures::check_fonts()?;
    let options = OptimizeOptions {
        refine: refine_method(refine)?,
        map: map_floors.map(|(a, b)| MapRequest {
            floors: [a, b],
            grid: map_grid,
        }),
    };
    options.check(&study).py()?;
    let d = PyDict::new(py);
    let _lock = FolderLock::acquire(&out).py()?;
    if fresh {
        self::fresh(&out, &d)?;
    }
    let (report, written) = watched(py, threads, progress, |ctl| {
        let report = optimize_study(&study, &out, &options, ctl).py()?;
        let written = crate::figures::write_optimized(&report, &out)?;
        Ok((report, written))
    })?;
    let mut names: Vec<&str> = StudyReport::FILES.to_vec();
    names.extend(SweepRun::FILES);
    if report.pareto.is_some() {
        names.extend(slipload_opt::pareto::ParetoReport::FILES);
    }
    let files = report_dict(py, &out, &names)?;
    for (k, v) in files.iter() {
        d.set_item(k, v)?;
    }
    d.set_item("figures", written)?;
    let w = &report.work;
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
    d.set_item("sweep_method", report.sweep.manifest.method.as_str())?;
    d.set_item(
        "sweep_method_reason",
        report.sweep.manifest.method_reason.clone(),
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
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    if resume && fresh {
        return Err(input(
            "resume and fresh exclude each other: resume continues the journal, fresh removes it",
        ));
    }
    slipload_opt::output::check_output_folder("out", &out).py()?;
    crate::figures::check_fonts()?;
    let shard = match shard {
        None => slipload_opt::Shard::ALL,
        Some(spec) => slipload_opt::Shard::parse(spec, None, &|k| std::env::var(k).ok()).py()?,
    };
    let d = PyDict::new(py);
    let _lock = FolderLock::acquire(&out).py()?;
    if fresh {
        self::fresh(&out, &d)?;
    }
    let study = study.inner.clone();
    let (run, written) = watched(py, threads, progress, |ctl| {
        let run = sweep_study(&study, &out, shard, resume, ctl).py()?;
        let written = match &run.figures {
            Some(f) => figures(f, &out)?,
            None => Vec::new(),
        };
        Ok((run, written))
    })?;
    let r = &run.report;
    for (k, v) in report_dict(py, &out, &SweepRun::FILES)?.iter() {
        d.set_item(k, v)?;
    }
    d.set_item("figures", written)?;
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
    slipload_opt::output::check_output_folder("out", &out).py()?;
    let refs: Vec<&Path> = dirs.iter().map(PathBuf::as_path).collect();
    slipload_opt::sweep::check_merge_folders(&refs, &out).py()?;
    crate::figures::check_fonts()?;
    let (run, written) = watched(py, None, None, |_| {
        let run = merge_shards(&refs, &out).py()?;
        let written = match &run.figures {
            Some(f) => figures(f, &out)?,
            None => Vec::new(),
        };
        Ok((run, written))
    })?;
    let d = report_dict(py, &out, &SweepRun::FILES)?;
    d.set_item("figures", written)?;
    d.set_item("tasks", run.report.manifest.tasks())?;
    Ok(d)
}

/// Ranks candidate designs over every suite of a study, as `slipload rank` does.
/// `designs` is a candidates file (as `optimize` writes `candidates.json`).
#[pyfunction]
#[pyo3(signature = (study, designs, out="out/rank".into(), *, bootstrap=200, seed=1, progress=None, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn rank<'py>(
    py: Python<'py>,
    study: &PyStudy,
    designs: PathBuf,
    out: PathBuf,
    bootstrap: usize,
    seed: u64,
    progress: Option<&Bound<'py, PyAny>>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    if !(1..=1_000_000).contains(&bootstrap) {
        return Err(input(format!(
            "bootstrap: {bootstrap} is not in 1..=1000000 (resamples of the records)"
        )));
    }
    let study = study.inner.clone();
    let candidates = guarded(|| slipload_opt::rank::load_designs(&study, &designs).py())?;
    slipload_opt::output::check_output_folder("out", &out).py()?;
    let _lock = FolderLock::acquire(&out).py()?;
    let ranking = watched(py, threads, progress, |ctl| {
        rank_study(&study, &candidates, bootstrap, seed, &out, ctl).py()
    })?;
    let d = report_dict(py, &out, &slipload_opt::rank::Ranking::FILES)?;
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
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let study = match study {
        Some(s) => s.inner.clone(),
        None => Arc::new(guarded(|| Study::benchmark().py())?),
    };
    slipload_opt::output::check_output_folder("out", &out).py()?;
    slipload_opt::family::check_scales(&study, &period_scales, &intensity_scales).py()?;
    let method = refine_method(refine)?.unwrap_or(study.config.refine.method);
    let _lock = FolderLock::acquire(&out).py()?;
    let report = watched(py, threads, progress, |ctl| {
        family_study(&study, &period_scales, &intensity_scales, method, &out, ctl).py()
    })?;
    let d = report_dict(py, &out, &slipload_opt::family::FamilyReport::FILES)?;
    d.set_item("markdown", report.to_markdown())?;
    Ok(d)
}

/// The objective vectors of designs under a study's `objectives`, at the sweep fidelity
/// (`slipload_opt::pareto::evaluate_objectives`): an array (designs, objectives).
#[pyfunction]
#[pyo3(signature = (study, slip_loads, *, progress=None, threads=None))]
pub fn evaluate_objectives<'py>(
    py: Python<'py>,
    study: &PyStudy,
    slip_loads: &Bound<'py, PyAny>,
    progress: Option<&Bound<'py, PyAny>>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    let (nd, nk, loads) = crate::arrays::matrix(slip_loads, "slip_loads")?;
    let designs: Vec<Vec<f64>> = loads.chunks(nk).map(<[f64]>::to_vec).collect();
    let study = study.inner.clone();
    let vectors = watched(py, threads, progress, |ctl| {
        slipload_opt::pareto::evaluate_objectives(&study, &designs, ctl).py()
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
    let p = self::points(points, "points")?;
    Ok(slipload_opt::pareto::nondominated_ranks(&p))
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
    Ok(slipload_opt::pareto::hypervolume(&p, &r))
}

/// The knee of a front (rows of `points`, minimisation): its index, by the rule of the
/// study reports (least sum of objectives normalised over the front); None for an empty
/// front.
#[pyfunction]
pub fn knee(points: &Bound<'_, PyAny>) -> PyResult<Option<usize>> {
    let p = self::points(points, "points")?;
    Ok(slipload_opt::pareto::knee(&p))
}
