//! Scenes (a building under a ground motion, a method and its outputs) and one
//! simulation's results, through the same loader and rules as `slipload simulate`.

use crate::arrays::{array1, array2, vector};
use crate::errors::{PyResultExt, guarded, input};
use crate::records::PyRecord;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use slipload_motion::Record;
use slipload_sim::scene::SceneConfig;
use slipload_sim::{MethodName, Outcome, Scene, SceneOverrides};
use std::path::PathBuf;
use std::sync::Arc;

/// The methods by their names in scene files and on the command line.
pub const METHODS: [MethodName; 5] = [
    MethodName::Newmark,
    MethodName::Hht,
    MethodName::Bilinear,
    MethodName::Delacruz,
    MethodName::Exact,
];

/// A method from its name.
pub fn method(name: &str) -> PyResult<MethodName> {
    METHODS
        .into_iter()
        .find(|m| m.as_str() == name)
        .ok_or_else(|| {
            input(format!(
                "method: {name:?} is not a method; give one of {}",
                METHODS.map(|m| m.as_str()).join(", ")
            ))
        })
}

/// What a scene was resolved from: kept so that a changed method, step or duration
/// goes through the same rules again.
#[derive(Debug, Clone)]
struct Source {
    config: SceneConfig,
    path: PathBuf,
    over: SceneOverrides,
    record: Option<Arc<Record>>,
    slip_loads: Option<Vec<Option<f64>>>,
}

impl Source {
    fn resolve(&self) -> PyResult<Scene> {
        let mut scene = Scene::from_config_with_record(
            self.config.clone(),
            &self.path,
            &self.over,
            self.record.clone(),
        )
        .py()?;
        if let Some(loads) = &self.slip_loads {
            scene.building = scene.building.with_slip_loads(loads);
        }
        Ok(scene)
    }
}

/// A resolved scene.
#[pyclass(name = "Scene", module = "slipload", frozen)]
#[derive(Debug, Clone)]
pub struct PyScene {
    source: Source,
    pub(crate) scene: Arc<Scene>,
}

/// The keyword overrides every scene constructor takes.
#[allow(clippy::too_many_arguments)]
fn overrides(
    record: Option<&Bound<'_, PyAny>>,
    units: Option<&str>,
    scale_pga_g: Option<f64>,
    scale: Option<f64>,
    window: Option<(f64, f64)>,
    method_name: Option<&str>,
    dt: Option<f64>,
    duration: Option<f64>,
) -> PyResult<(SceneOverrides, Option<Arc<Record>>)> {
    let mut over = SceneOverrides {
        units: crate::records::units(units)?,
        scale_pga_g,
        scale,
        window,
        method: method_name.map(method).transpose()?,
        dt,
        duration,
        ..Default::default()
    };
    if let Some((s, d)) = window {
        // the command line's rule (`--window`), from the library
        slipload_sim::scene::check_window(s, d, "window").py()?;
    }
    let mut given = None;
    if let Some(r) = record {
        if let Ok(r) = r.cast::<PyRecord>() {
            given = Some(r.get().inner.clone());
        } else if let Ok(p) = r.extract::<PathBuf>() {
            over.record = Some(p);
        } else {
            return Err(input(format!(
                "record: expected a slipload.Record or a path to a record file, got a {}",
                r.get_type().name()?
            )));
        }
    }
    Ok((over, given))
}

impl PyScene {
    /// The same scene under another ground motion (its rules applied again).
    pub(crate) fn with_record(&self, record: &PyRecord) -> PyResult<PyScene> {
        let mut source = self.source.clone();
        source.record = Some(record.inner.clone());
        source.over.record = None;
        PyScene::build(source)
    }

    fn build(source: Source) -> PyResult<PyScene> {
        let scene = source.resolve()?;
        Ok(PyScene {
            source,
            scene: Arc::new(scene),
        })
    }

    fn from_text(
        text: &str,
        path: PathBuf,
        over: SceneOverrides,
        given: Option<Arc<Record>>,
    ) -> PyResult<PyScene> {
        let config = SceneConfig::from_json(text, &path).py()?;
        PyScene::build(Source {
            config,
            path,
            over,
            record: given,
            slip_loads: None,
        })
    }
}

/// Reads a text file the way the command line reads a scene (size-bounded, named).
fn read_scene_text(path: &std::path::Path) -> PyResult<String> {
    slipload_motion::limits::read_input_text(
        path,
        "scene",
        slipload_motion::limits::MAX_CONFIG_BYTES,
    )
    .py()
}

#[pymethods]
impl PyScene {
    /// Loads a scene or building file.
    #[staticmethod]
    #[pyo3(signature = (path, *, record=None, units=None, scale_pga_g=None, scale=None, window=None, method=None, dt=None, duration=None))]
    #[allow(clippy::too_many_arguments)]
    fn load(
        path: PathBuf,
        record: Option<&Bound<'_, PyAny>>,
        units: Option<&str>,
        scale_pga_g: Option<f64>,
        scale: Option<f64>,
        window: Option<(f64, f64)>,
        method: Option<&str>,
        dt: Option<f64>,
        duration: Option<f64>,
    ) -> PyResult<PyScene> {
        guarded(|| {
            let (over, given) = overrides(
                record,
                units,
                scale_pga_g,
                scale,
                window,
                method,
                dt,
                duration,
            )?;
            let text = read_scene_text(&path)?;
            PyScene::from_text(&text, path, over, given)
        })
    }

    /// A scene from JSON text (a scene file's or a building file's).
    #[staticmethod]
    #[pyo3(signature = (text, name="scene", *, record=None, units=None, scale_pga_g=None, scale=None, window=None, method=None, dt=None, duration=None))]
    #[allow(clippy::too_many_arguments)]
    fn from_json(
        text: &str,
        name: &str,
        record: Option<&Bound<'_, PyAny>>,
        units: Option<&str>,
        scale_pga_g: Option<f64>,
        scale: Option<f64>,
        window: Option<(f64, f64)>,
        method: Option<&str>,
        dt: Option<f64>,
        duration: Option<f64>,
    ) -> PyResult<PyScene> {
        guarded(|| {
            let (over, given) = overrides(
                record,
                units,
                scale_pga_g,
                scale,
                window,
                method,
                dt,
                duration,
            )?;
            PyScene::from_text(text, PathBuf::from(name), over, given)
                .map_err(|e| crate::json_path::located(e, text, name))
        })
    }

    /// The embedded benchmark building under the first record of the embedded synthetic
    /// suite (the command line's default scene).
    #[staticmethod]
    #[pyo3(signature = (*, record=None, units=None, scale_pga_g=None, scale=None, window=None, method=None, dt=None, duration=None))]
    #[allow(clippy::too_many_arguments)]
    fn benchmark(
        record: Option<&Bound<'_, PyAny>>,
        units: Option<&str>,
        scale_pga_g: Option<f64>,
        scale: Option<f64>,
        window: Option<(f64, f64)>,
        method: Option<&str>,
        dt: Option<f64>,
        duration: Option<f64>,
    ) -> PyResult<PyScene> {
        guarded(|| {
            let (over, given) = overrides(
                record,
                units,
                scale_pga_g,
                scale,
                window,
                method,
                dt,
                duration,
            )?;
            PyScene::build(Source {
                config: slipload_sim::scene::benchmark_scene_config().py()?,
                path: PathBuf::from(slipload_sim::scene::BENCHMARK_ORIGIN),
                over,
                record: given,
                slip_loads: None,
            })
        })
    }

    /// The same scene with other overrides (those not given are kept).
    #[pyo3(signature = (*, record=None, units=None, scale_pga_g=None, scale=None, window=None, method=None, dt=None, duration=None))]
    #[allow(clippy::too_many_arguments)]
    fn replace(
        &self,
        record: Option<&Bound<'_, PyAny>>,
        units: Option<&str>,
        scale_pga_g: Option<f64>,
        scale: Option<f64>,
        window: Option<(f64, f64)>,
        method: Option<&str>,
        dt: Option<f64>,
        duration: Option<f64>,
    ) -> PyResult<PyScene> {
        guarded(|| {
            let (o, given) = overrides(
                record,
                units,
                scale_pga_g,
                scale,
                window,
                method,
                dt,
                duration,
            )?;
            let mut source = self.source.clone();
            let over = &mut source.over;
            if o.record.is_some() {
                over.record = o.record;
                source.record = None;
            }
            if given.is_some() {
                source.record = given;
                over.record = None;
            }
            over.units = o.units.or(over.units);
            // one way of scaling: a new one replaces the other
            if o.scale_pga_g.is_some() || o.scale.is_some() {
                over.scale_pga_g = o.scale_pga_g;
                over.scale = o.scale;
            }
            over.window = o.window.or(over.window);
            over.method = o.method.or(over.method);
            over.dt = o.dt.or(over.dt);
            over.duration = o.duration.or(over.duration);
            PyScene::build(source)
        })
    }

    /// The same scene with other slip loads, N: one per floor with a dissipator, in floor
    /// order.
    fn with_slip_loads(&self, slip_loads: &Bound<'_, PyAny>) -> PyResult<PyScene> {
        guarded(|| {
            let loads = vector(slip_loads, "slip_loads", true)?;
            let per_floor = per_floor_loads(&self.scene, &loads, "slip_loads")?;
            let mut source = self.source.clone();
            source.slip_loads = Some(per_floor);
            PyScene::build(source)
        })
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> String {
        self.scene.name.clone()
    }

    /// Number of storeys.
    #[getter]
    fn floors(&self) -> usize {
        self.scene.building.floors()
    }

    /// Floors (from 1) that carry a dissipator.
    #[getter]
    fn damper_floors(&self) -> Vec<usize> {
        damper_floors(&self.scene)
    }

    /// Slip loads of the dissipators, N, in floor order (inf: locked; asymmetric bounds
    /// give their upper bound).
    #[getter]
    fn slip_loads<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        array1(
            py,
            self.scene
                .building
                .dissipators
                .iter()
                .flatten()
                .map(|d| d.upper)
                .collect(),
        )
    }

    /// Natural periods of the bare frame, s (longest first).
    #[getter]
    fn periods<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        array1(py, self.scene.building.modes.periods())
    }

    /// The integration method's name.
    #[getter]
    fn method(&self) -> &'static str {
        self.scene.method.name.as_str()
    }

    /// Time step, s.
    #[getter]
    fn dt(&self) -> f64 {
        self.scene.method.dt
    }

    /// Simulated time, s.
    #[getter]
    fn duration(&self) -> f64 {
        self.scene.duration
    }

    /// Number of steps.
    #[getter]
    fn steps(&self) -> usize {
        self.scene.steps()
    }

    /// The ground motion (None for a scene without one).
    #[getter]
    fn record(&self) -> Option<PyRecord> {
        self.scene.record.clone().map(|inner| PyRecord { inner })
    }

    /// Notes the loader made (a run past the record's end, say).
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.scene.notes.clone()
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene({:?}, floors={}, method={}, dt={} s, duration={} s)",
            self.scene.name,
            self.scene.building.floors(),
            self.scene.method.name.as_str(),
            self.scene.method.dt,
            self.scene.duration
        )
    }
}

/// Floors (from 1) of `scene` that carry a dissipator.
pub fn damper_floors(scene: &Scene) -> Vec<usize> {
    scene
        .building
        .dissipators
        .iter()
        .enumerate()
        .filter(|(_, d)| d.is_some())
        .map(|(i, _)| i + 1)
        .collect()
}

/// Slip loads given per dissipator (floor order) as the per-floor list the building takes;
/// each must be finite and ≥ 0.
pub fn per_floor_loads(scene: &Scene, loads: &[f64], what: &str) -> PyResult<Vec<Option<f64>>> {
    let floors = damper_floors(scene);
    if loads.len() != floors.len() {
        return Err(input(format!(
            "{what}: {} value(s) given, the building has {} dissipator(s) (floors {}): give one slip load per dissipator, in N",
            loads.len(),
            floors.len(),
            floors
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    if let Some((i, v)) = loads
        .iter()
        .enumerate()
        .find(|(_, v)| !(v.is_finite() && **v >= 0.0))
    {
        return Err(input(format!(
            "{what}[{i}] is {v}: a slip load is a force >= 0, in N"
        )));
    }
    let weight = scene.building.mass.sum() * slipload_motion::G;
    let max = slipload_sim::building::MAX_SLIP_LOAD_PER_WEIGHT * weight;
    if let Some((i, v)) = loads.iter().enumerate().find(|(_, v)| **v > max) {
        return Err(input(format!(
            "{what}[{i}] is {v:e} N, more than {} × the building's weight ({weight:.4e} N): no friction device comes near it (check the units: slip loads are in N)",
            slipload_sim::building::MAX_SLIP_LOAD_PER_WEIGHT
        )));
    }
    let mut per_floor = vec![None; scene.building.floors()];
    for (f, v) in floors.iter().zip(loads) {
        per_floor[f - 1] = Some(*v);
    }
    Ok(per_floor)
}

/// The outputs asked for: `None` keeps the scene's; else a list of names.
pub fn outputs(scene: &mut Scene, asked: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
    let Some(asked) = asked else {
        return Ok(());
    };
    let names: Vec<String> = if let Ok(s) = asked.extract::<String>() {
        vec![s]
    } else {
        asked.extract().map_err(|_| {
            input("outputs: expected a list of names among \"histories\", \"energies\"")
        })?
    };
    scene.outputs.histories = false;
    scene.outputs.energies = false;
    for n in names {
        match n.as_str() {
            "histories" => scene.outputs.histories = true,
            "energies" => scene.outputs.energies = true,
            other => {
                return Err(input(format!(
                    "outputs: {other:?} is not an output; give names among \"histories\", \"energies\" (peaks, residuals, slips and transitions are always computed)"
                )));
            }
        }
    }
    Ok(())
}

/// The scene a call runs: `scene` re-resolved when the method, step or duration changes,
/// with the outputs asked for.
pub fn for_call(
    scene: &PyScene,
    method_name: Option<&str>,
    dt: Option<f64>,
    duration: Option<f64>,
    asked: Option<&Bound<'_, PyAny>>,
) -> PyResult<Arc<Scene>> {
    let mut run = if method_name.is_some() || dt.is_some() || duration.is_some() {
        let mut source = scene.source.clone();
        if let Some(m) = method_name {
            source.over.method = Some(method(m)?);
        }
        if dt.is_some() {
            source.over.dt = dt;
        }
        if duration.is_some() {
            source.over.duration = duration;
        }
        source.resolve()?
    } else if asked.is_some() {
        Scene::clone(&scene.scene)
    } else {
        return Ok(scene.scene.clone());
    };
    outputs(&mut run, asked)?;
    Ok(Arc::new(run))
}

/// Runs one scene.
#[pyfunction]
#[pyo3(signature = (scene, *, method=None, dt=None, duration=None, outputs=None))]
pub fn simulate(
    py: Python<'_>,
    scene: &PyScene,
    method: Option<&str>,
    dt: Option<f64>,
    duration: Option<f64>,
    outputs: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyOutcome> {
    let run = guarded(|| for_call(scene, method, dt, duration, outputs))?;
    let warnings = plausibility(&run);
    let out = crate::run::detached(py, move || slipload_sim::simulate(&run).py())?;
    Ok(PyOutcome::of(out).warned(warnings))
}

/// What the scene's inputs make doubtful without making them wrong (a slip load that
/// looks like kN written as N, a step that runs past the duration), in the words
/// `slipload simulate` prints after "warning: ".
pub fn plausibility(scene: &Scene) -> Vec<String> {
    slipload_sim::building::plausibility(
        &scene.building,
        scene.method.dt,
        scene.duration,
        scene.steps(),
    )
    .iter()
    .map(ToString::to_string)
    .collect()
}

/// One simulation's responses (SI units), as `slipload simulate` reports them.
#[pyclass(name = "Result", module = "slipload", frozen)]
#[derive(Debug)]
pub struct PyOutcome {
    out: Outcome,
    // taken out of `out`: shared with the History objects handed out, never copied
    history: Option<Arc<slipload_sim::History>>,
    warnings: Vec<String>,
}

impl PyOutcome {
    pub(crate) fn of(mut out: Outcome) -> PyOutcome {
        let history = out.history.take().map(Arc::new);
        PyOutcome {
            out,
            history,
            warnings: Vec::new(),
        }
    }

    /// The result with the warnings of its scene ([`plausibility`]).
    pub(crate) fn warned(mut self, warnings: Vec<String>) -> PyOutcome {
        self.warnings = warnings;
        self
    }
}

#[pymethods]
impl PyOutcome {
    /// The method that ran.
    #[getter]
    fn method(&self) -> String {
        self.out.response.method.clone()
    }
    /// What the run's inputs make doubtful without making them wrong, as `slipload
    /// simulate` prints them (`slipload.simulate` and `batch` also warn them as
    /// `UserWarning`s).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }
    /// Time step, s.
    #[getter]
    fn dt(&self) -> f64 {
        self.out.response.dt
    }
    /// Steps taken.
    #[getter]
    fn steps(&self) -> usize {
        self.out.response.steps
    }
    /// CPU time of the run, s.
    #[getter]
    fn cpu_seconds(&self) -> f64 {
        self.out.response.cpu_seconds
    }
    /// Peak |interstorey drift| per storey, m.
    #[getter]
    fn peak_drift<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        array1(py, self.out.response.peak_drift.clone())
    }
    /// Peak drift ratio per storey (drift / storey height); None without storey heights.
    #[getter]
    fn peak_drift_ratio<'py>(&self, py: Python<'py>) -> Option<Bound<'py, numpy::PyArray1<f64>>> {
        self.out
            .response
            .peak_drift_ratio
            .clone()
            .map(|v| array1(py, v))
    }
    /// Peak |floor displacement| relative to the ground per floor, m.
    #[getter]
    fn peak_displacement<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        array1(py, self.out.response.peak_displacement.clone())
    }
    /// Peak |absolute floor acceleration| per floor, m/s².
    #[getter]
    fn peak_abs_acceleration<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        array1(py, self.out.response.peak_abs_acceleration.clone())
    }
    /// Interstorey drift at the end of the run per storey, m.
    #[getter]
    fn residual_drift<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        array1(py, self.out.response.residual_drift.clone())
    }
    /// Peak |base shear|, N.
    #[getter]
    fn peak_base_shear(&self) -> f64 {
        self.out.response.peak_base_shear
    }
    /// Peak |slip| of each storey's dissipator, m (0 without one).
    #[getter]
    fn peak_slip<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        array1(py, self.out.response.peak_slip.clone())
    }
    /// Stick↔slip transitions per storey.
    #[getter]
    fn transitions<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<u64>> {
        numpy::PyArray1::from_vec(py, self.out.response.transitions.clone())
    }
    /// Energies at the end, J (None unless asked): input, kinetic, strain, viscous,
    /// friction, plastic, balance_error.
    #[getter]
    fn energy<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(e) = &self.out.response.energy else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        d.set_item("input", e.input)?;
        d.set_item("kinetic", e.kinetic)?;
        d.set_item("strain", e.strain)?;
        d.set_item("viscous", e.viscous)?;
        d.set_item("friction", e.friction)?;
        d.set_item("plastic", e.plastic)?;
        d.set_item("balance_error", e.balance_error)?;
        Ok(Some(d))
    }
    /// Peak ductility per storey (NaN for a storey without a yield law); None for an
    /// elastic frame.
    #[getter]
    fn peak_ductility<'py>(&self, py: Python<'py>) -> Option<Bound<'py, numpy::PyArray1<f64>>> {
        self.out
            .response
            .peak_ductility
            .as_ref()
            .map(|v| array1(py, v.iter().map(|x| x.unwrap_or(f64::NAN)).collect()))
    }
    /// Peak plastic drift per storey, m; None for an elastic frame.
    #[getter]
    fn peak_plastic_drift<'py>(&self, py: Python<'py>) -> Option<Bound<'py, numpy::PyArray1<f64>>> {
        self.out
            .response
            .peak_plastic_drift
            .clone()
            .map(|v| array1(py, v))
    }
    /// The collapse the run stopped on (storey from 1, time s, drift m, limit m), or None.
    #[getter]
    fn collapse<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(c) = &self.out.response.collapse else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        d.set_item("storey", c.storey)?;
        d.set_item("time", c.time)?;
        d.set_item("drift", c.drift)?;
        d.set_item("limit", c.limit)?;
        Ok(Some(d))
    }
    /// Whether the run stopped on the collapse limit.
    #[getter]
    fn collapsed(&self) -> bool {
        self.out.response.collapse.is_some()
    }
    /// The histories (None unless asked for with outputs=["histories"]).
    #[getter]
    fn history(&self) -> Option<PyHistory> {
        self.history.clone().map(|inner| PyHistory { inner })
    }
    /// The output contract's JSON text, as `slipload simulate --format json` prints it.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&self.out.response)
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))
    }
    fn __repr__(&self) -> String {
        let r = &self.out.response;
        format!(
            "Result(method={}, steps={}, peak drift {} m, base shear {:.4e} N{})",
            r.method,
            r.steps,
            r.peak_drift
                .iter()
                .map(|d| format!("{d:.4e}"))
                .collect::<Vec<_>>()
                .join(" / "),
            r.peak_base_shear,
            if r.collapse.is_some() {
                ", collapsed"
            } else {
                ""
            }
        )
    }
}

/// Time histories: one row per step (time first), one column per quantity.
#[pyclass(name = "History", module = "slipload", frozen)]
#[derive(Debug)]
pub struct PyHistory {
    inner: Arc<slipload_sim::History>,
}

#[pymethods]
impl PyHistory {
    /// Column names with their units.
    #[getter]
    fn columns(&self) -> Vec<String> {
        self.inner.columns.clone()
    }
    /// The values, shape (steps + 1, columns).
    #[getter]
    fn array<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        let w = self.inner.columns.len().max(1);
        array2(py, self.inner.rows.len() / w, w, self.inner.rows.clone())
    }
    /// Time, s (the first column).
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        self.column(py, 0)
    }
    fn __len__(&self) -> usize {
        self.inner.rows.len() / self.inner.columns.len().max(1)
    }
    /// One column by name.
    fn __getitem__<'py>(
        &self,
        py: Python<'py>,
        name: &str,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        let j = self
            .inner
            .columns
            .iter()
            .position(|c| c == name)
            .ok_or_else(|| {
                pyo3::exceptions::PyKeyError::new_err(format!(
                    "{name:?}: no such column; the columns are {}",
                    self.inner.columns.join(", ")
                ))
            })?;
        self.column(py, j)
    }
    /// A pandas DataFrame of the histories (needs pandas).
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let pandas = py.import("pandas").map_err(|_| {
            pyo3::exceptions::PyImportError::new_err("to_pandas needs pandas: pip install pandas")
        })?;
        let kwargs = PyDict::new(py);
        kwargs.set_item("columns", PyList::new(py, &self.inner.columns)?)?;
        pandas
            .getattr("DataFrame")?
            .call((self.array(py)?,), Some(&kwargs))
    }
    /// The history as CSV text, as `slipload simulate --history` writes it.
    fn to_csv(&self) -> String {
        self.inner.to_csv()
    }
    fn __repr__(&self) -> String {
        format!(
            "History({} steps × {} columns)",
            self.__len__(),
            self.inner.columns.len()
        )
    }
}

impl PyHistory {
    fn column<'py>(&self, py: Python<'py>, j: usize) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        let w = self.inner.columns.len().max(1);
        Ok(array1(
            py,
            self.inner.rows.chunks(w).map(|r| r[j]).collect(),
        ))
    }
}
