//! slipload for Python: the native half of the `slipload` package (`slipload._slipload`).
//!
//! A second thin front beside the command line: records, scenes and simulations come from
//! `slipload-motion` and `slipload-sim`, studies from the study pipeline of `slipload-opt`
//! (`slipload_opt::pipeline`), through the same loaders, rules and errors. This crate owns
//! no study logic: it converts arguments and results (numpy arrays, dicts), releases the
//! GIL around every run, reports progress to a Python callback, stops on Ctrl-C and turns
//! library errors and panics into Python exceptions.
//!
//! The Python half (`crates/py/python/slipload/`) holds the documented public API, the
//! exception classes and the type stubs.

mod args;
mod arrays;
mod batch;
mod dicts;
mod errors;
mod json_path;
mod plan;
mod records;
mod run;
mod scene;
mod study;

use pyo3::prelude::*;

/// The native module.
#[pymodule]
fn _slipload(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("NUMERICS_VERSION", slipload_sim::NUMERICS_VERSION)?;
    m.add_class::<records::PyRecord>()?;
    m.add_class::<scene::PyScene>()?;
    m.add_class::<scene::PyOutcome>()?;
    m.add_class::<scene::PyHistory>()?;
    m.add_class::<study::PyStudy>()?;
    m.add_function(wrap_pyfunction!(records::synthetic_suite, m)?)?;
    m.add_function(wrap_pyfunction!(scene::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(plan::simulate_in_plan, m)?)?;
    m.add_function(wrap_pyfunction!(plan::is_in_plan, m)?)?;
    m.add_function(wrap_pyfunction!(plan::is_plan_study, m)?)?;
    m.add_function(wrap_pyfunction!(plan::optimize_in_plan, m)?)?;
    m.add_function(wrap_pyfunction!(batch::batch, m)?)?;
    m.add_function(wrap_pyfunction!(batch::batch_designs, m)?)?;
    m.add_function(wrap_pyfunction!(study::optimize, m)?)?;
    m.add_function(wrap_pyfunction!(study::sweep, m)?)?;
    m.add_function(wrap_pyfunction!(study::merge, m)?)?;
    m.add_function(wrap_pyfunction!(study::rank, m)?)?;
    m.add_function(wrap_pyfunction!(study::table, m)?)?;
    m.add_function(wrap_pyfunction!(study::evaluate_objectives, m)?)?;
    m.add_function(wrap_pyfunction!(study::nondominated_ranks, m)?)?;
    m.add_function(wrap_pyfunction!(study::hypervolume, m)?)?;
    m.add_function(wrap_pyfunction!(study::knee, m)?)?;
    m.add_function(wrap_pyfunction!(allow_large, m)?)?;
    m.add_function(wrap_pyfunction!(dicts::dict_json, m)?)?;
    m.add(
        "MAX_CONFIG_BYTES",
        slipload_motion::limits::MAX_CONFIG_BYTES,
    )?;
    Ok(())
}

/// Lifts (or restores) the size limits on inputs, as the command line's --allow-large.
#[pyfunction]
fn allow_large(on: bool) {
    slipload_sim::limits::set_allow_large(on);
}
