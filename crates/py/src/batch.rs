//! Many simulations in one call, in parallel on rayon with the GIL released: a list of
//! scenes, or one building × a suite of records × an array of slip-load vectors.

use crate::arrays::{array3, matrix};
use crate::errors::{guarded, input};
use crate::records::PyRecord;
use crate::run::{Control, watched};
use crate::scene::{PyOutcome, PyScene, for_call, per_floor_loads};
use numpy::PyArrayMethods;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use slipload_sim::{Outcome, Scene, SimError};
use std::sync::Arc;

/// Runs `tasks` in parallel, in task order, stopping early when `ctl` is cancelled; the
/// first failure (in task order) is the error, named by `label(k)`.
fn run_all(
    ctl: &Control,
    count: usize,
    run: &(dyn Fn(usize) -> Result<Outcome, SimError> + Sync),
    label: &(dyn Fn(usize) -> String + Sync),
) -> PyResult<Vec<Outcome>> {
    ctl.begin("simulate", count);
    let results: Vec<Option<Result<Outcome, SimError>>> = (0..count)
        .into_par_iter()
        .map(|k| {
            if ctl.cancelled() {
                return None;
            }
            let r = run(k);
            ctl.count();
            Some(r)
        })
        .collect();
    let mut out = Vec::with_capacity(count);
    for (k, r) in results.into_iter().enumerate() {
        match r {
            // a stop was asked for; the watcher raises KeyboardInterrupt
            None => return Ok(Vec::new()),
            Some(Ok(o)) => out.push(o),
            Some(Err(e)) => return Err(crate::errors::sim_error(&e, &label(k))),
        }
    }
    Ok(out)
}

/// Runs every scene of a list.
#[pyfunction]
#[pyo3(signature = (scenes, *, outputs=None, progress=None, threads=None))]
pub fn batch(
    py: Python<'_>,
    scenes: Vec<Bound<'_, PyScene>>,
    outputs: Option<&Bound<'_, PyAny>>,
    progress: Option<&Bound<'_, PyAny>>,
    threads: Option<&Bound<'_, PyAny>>,
) -> PyResult<Vec<PyOutcome>> {
    let runs: Vec<Arc<Scene>> = guarded(|| {
        scenes
            .iter()
            .map(|s| for_call(s.get(), None, None, None, outputs))
            .collect()
    })?;
    if runs.is_empty() {
        return Err(input("scenes: the list is empty"));
    }
    let outs = watched(py, threads, progress, |ctl| {
        run_all(
            ctl,
            runs.len(),
            &|k| slipload_sim::simulate(&runs[k]),
            &|k| format!("scenes[{k}] ({})", runs[k].name),
        )
    })?;
    Ok(outs
        .into_iter()
        .zip(&runs)
        .map(|(o, run)| PyOutcome::of(o).warned(crate::scene::plausibility(run)))
        .collect())
}

/// Runs one building under every record of a suite for every row of `slip_loads`.
#[pyfunction]
#[pyo3(signature = (scene, records, slip_loads, *, method=None, dt=None, outputs=None, progress=None, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn batch_designs<'py>(
    py: Python<'py>,
    scene: &PyScene,
    records: Vec<Bound<'py, PyRecord>>,
    slip_loads: &Bound<'py, PyAny>,
    method: Option<&str>,
    dt: Option<f64>,
    outputs: Option<&Bound<'py, PyAny>>,
    progress: Option<&Bound<'py, PyAny>>,
    threads: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    if records.is_empty() {
        return Err(input("records: the list is empty"));
    }
    let (nd, nk, loads) = matrix(slip_loads, "slip_loads")?;
    // one resolved scene per record: the record's own step and duration, its rules
    let bases: Vec<Arc<Scene>> = guarded(|| {
        records
            .iter()
            .map(|r| {
                let s = scene.with_record(r.get())?;
                for_call(&s, method, dt, None, outputs)
            })
            .collect()
    })?;
    if bases.iter().any(|s| s.outputs.histories) {
        return Err(input(
            "outputs: batch_designs returns peaks, not histories; run simulate on the designs whose histories you want",
        ));
    }
    let per_floor: Vec<Vec<Option<f64>>> = guarded(|| {
        (0..nd)
            .map(|d| {
                per_floor_loads(
                    &bases[0],
                    &loads[d * nk..(d + 1) * nk],
                    &format!("slip_loads[{d}]"),
                )
            })
            .collect()
    })?;
    let nr = bases.len();
    let outs = watched(py, threads, progress, |ctl| {
        run_all(
            ctl,
            nd * nr,
            &|k| {
                let (d, r) = (k / nr, k % nr);
                let base = &bases[r];
                // the base scene with this design's building: one clone of the building
                let s = Scene {
                    name: base.name.clone(),
                    building: base.building.with_slip_loads(&per_floor[d]),
                    record: base.record.clone(),
                    harmonic: base.harmonic,
                    initial: base.initial.clone(),
                    duration: base.duration,
                    method: base.method,
                    outputs: base.outputs,
                    reduce: base.reduce,
                    notes: Vec::new(),
                };
                slipload_sim::simulate(&s)
            },
            &|k| {
                format!(
                    "design {} (slip loads {} N), record {}",
                    k / nr,
                    loads[(k / nr) * nk..(k / nr + 1) * nk]
                        .iter()
                        .map(|v| format!("{v:e}"))
                        .collect::<Vec<_>>()
                        .join(" / "),
                    bases[k % nr].record.as_ref().map_or("?", |r| r.name())
                )
            },
        )
    })?;
    let ns = bases[0].building.floors();
    let per_storey =
        |f: &dyn Fn(&Outcome) -> Vec<f64>| -> Vec<f64> { outs.iter().flat_map(f).collect() };
    let d = PyDict::new(py);
    d.set_item(
        "peak_drift",
        array3(
            py,
            (nd, nr, ns),
            per_storey(&|o| o.response.peak_drift.clone()),
        )?,
    )?;
    if outs.iter().all(|o| o.response.peak_drift_ratio.is_some()) {
        d.set_item(
            "peak_drift_ratio",
            array3(
                py,
                (nd, nr, ns),
                per_storey(&|o| o.response.peak_drift_ratio.clone().unwrap_or_default()),
            )?,
        )?;
    }
    d.set_item(
        "peak_displacement",
        array3(
            py,
            (nd, nr, ns),
            per_storey(&|o| o.response.peak_displacement.clone()),
        )?,
    )?;
    d.set_item(
        "peak_abs_acceleration",
        array3(
            py,
            (nd, nr, ns),
            per_storey(&|o| o.response.peak_abs_acceleration.clone()),
        )?,
    )?;
    d.set_item(
        "residual_drift",
        array3(
            py,
            (nd, nr, ns),
            per_storey(&|o| o.response.residual_drift.clone()),
        )?,
    )?;
    d.set_item(
        "peak_slip",
        array3(
            py,
            (nd, nr, ns),
            per_storey(&|o| o.response.peak_slip.clone()),
        )?,
    )?;
    d.set_item(
        "transitions",
        array3(
            py,
            (nd, nr, ns),
            per_storey(&|o| o.response.transitions.iter().map(|&t| t as f64).collect()),
        )?,
    )?;
    let per_run = |f: &dyn Fn(&Outcome) -> f64| -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        crate::arrays::array2(py, nd, nr, outs.iter().map(f).collect())
    };
    d.set_item("peak_base_shear", per_run(&|o| o.response.peak_base_shear)?)?;
    let collapsed: Vec<bool> = outs.iter().map(|o| o.response.collapse.is_some()).collect();
    d.set_item(
        "collapsed",
        numpy::PyArray1::from_vec(py, collapsed).reshape([nd, nr])?,
    )?;
    if outs.iter().all(|o| o.response.energy.is_some()) {
        let e = |f: fn(&slipload_sim::Energy) -> f64| {
            per_run(&move |o: &Outcome| o.response.energy.as_ref().map_or(f64::NAN, f))
        };
        d.set_item("energy_input", e(|e| e.input)?)?;
        d.set_item("energy_friction", e(|e| e.friction)?)?;
        d.set_item("energy_viscous", e(|e| e.viscous)?)?;
        d.set_item("energy_balance_error", e(|e| e.balance_error)?)?;
    }
    d.set_item("cpu_seconds", per_run(&|o| o.response.cpu_seconds)?)?;
    d.set_item(
        "records",
        bases
            .iter()
            .map(|s| {
                s.record
                    .as_ref()
                    .map_or(String::new(), |r| r.name().to_string())
            })
            .collect::<Vec<_>>(),
    )?;
    d.set_item("slip_loads", crate::arrays::array2(py, nd, nk, loads)?)?;
    d.set_item("damper_floors", crate::scene::damper_floors(&bases[0]))?;
    Ok(d)
}
