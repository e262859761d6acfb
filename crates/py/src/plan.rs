//! Scenes in plan from Python: `slipload.simulate(path)` runs a scene in plan as
//! `slipload simulate PATH` does (the library's [`slipload_sim::floorplan`] run), and
//! gives the same `Result` (its `to_json()` the command line's JSON, `in_plan` included).

use crate::errors::{PyResultExt, guarded, input};
use crate::scene::{PyOutcome, method};
use pyo3::prelude::*;
use slipload_sim::floorplan::FloorPlanScene;
use std::path::PathBuf;

/// Whether the file is a scene in plan or a building in plan.
#[pyfunction]
pub fn is_in_plan(path: PathBuf) -> bool {
    slipload_sim::floorplan::is_in_plan(&path)
}

/// Runs the scene in plan at `path`, with the command line's overrides.
#[pyfunction]
#[pyo3(signature = (path, *, method=None, dt=None, duration=None, outputs=None))]
pub fn simulate_in_plan(
    py: Python<'_>,
    path: PathBuf,
    method: Option<&str>,
    dt: Option<f64>,
    duration: Option<f64>,
    outputs: Option<Vec<String>>,
) -> PyResult<PyOutcome> {
    let scene = guarded(|| {
        let mut scene = FloorPlanScene::load(&path).py()?;
        let name = method.map(self::method_name).transpose()?;
        let histories = outputs
            .as_ref()
            .is_some_and(|o| o.iter().any(|x| x == "histories"));
        if let Some(o) = &outputs {
            if let Some(bad) = o.iter().find(|x| *x != "histories" && *x != "energies") {
                return Err(input(format!(
                    "outputs: {bad:?} is not an output; give names among \"histories\", \"energies\""
                )));
            }
            scene.outputs.energies = o.iter().any(|x| x == "energies");
        }
        scene.override_with(name, dt, duration, histories).py()?;
        Ok(scene)
    })?;
    let out = crate::run::detached(py, move || slipload_sim::floorplan::simulate(&scene).py())?;
    Ok(PyOutcome::of(out))
}

fn method_name(name: &str) -> PyResult<slipload_sim::MethodName> {
    method(name)
}

/// Whether the file is a study in plan (its building is a building in plan).
#[pyfunction]
pub fn is_plan_study(path: PathBuf) -> bool {
    slipload_opt::plan::is_plan_study(&path)
}

/// Optimises the study in plan at `path` into `out`, as `slipload optimize PATH --out OUT`
/// does ([`slipload_opt::pipeline::optimize_in_plan`]): the same files, byte for byte.
#[pyfunction]
#[pyo3(signature = (path, out, *, fresh=false, progress=None, threads=None))]
pub fn optimize_in_plan<'py>(
    py: Python<'py>,
    path: PathBuf,
    out: PathBuf,
    fresh: bool,
    progress: Option<&Bound<'py, PyAny>>,
    threads: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
    let study = guarded(|| slipload_opt::plan::PlanStudy::load(&path).py())?;
    let run = crate::run::watched(py, threads, progress, |ctl| {
        slipload_opt::pipeline::optimize_in_plan(
            &study,
            slipload_opt::store::folder::FolderRequest {
                path: &out,
                option: "out",
                fresh,
            },
            ctl,
            &slipload_figures::StudyFigures,
        )
        .py()
    })?;
    let d = pyo3::types::PyDict::new(py);
    d.set_item("out", out.display().to_string())?;
    d.set_item("summary", run.summary.clone())?;
    let mut files: Vec<&str> = vec![slipload_opt::pipeline::PLAN_JOURNAL];
    files.extend(run.files.iter().copied());
    d.set_item("files", files)?;
    d.set_item("figures", run.drawn.clone())?;
    d.set_item("replayed", run.report.replayed)?;
    d.set_item("sweep_designs", run.report.sweep_designs)?;
    d.set_item("refine_designs", run.report.refine_designs)?;
    Ok(d)
}
