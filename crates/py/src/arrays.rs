//! numpy arrays in and out. Inputs are taken as they are or refused with what was
//! expected: a float64 array, C-contiguous, of the right shape, every value finite —
//! never cast, copied across strides or truncated behind the caller's back.

use crate::errors::input;
use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

fn describe(obj: &Bound<'_, PyAny>) -> String {
    let dtype = obj
        .getattr("dtype")
        .map(|d| d.to_string())
        .unwrap_or_default();
    let ndim = obj
        .getattr("ndim")
        .map(|d| d.to_string())
        .unwrap_or_default();
    if dtype.is_empty() {
        format!(
            "a {}",
            obj.get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default()
        )
    } else {
        format!("a {ndim}-D array of {dtype}")
    }
}

/// A 1-D float64 array `what` as a vector (finite values when `finite`).
pub fn vector(obj: &Bound<'_, PyAny>, what: &str, finite: bool) -> PyResult<Vec<f64>> {
    let arr: PyReadonlyArray1<'_, f64> = obj.extract().map_err(|_| {
        input(format!(
            "{what}: expected a 1-D numpy array of float64, got {}: convert it with numpy.asarray(x, dtype=float)",
            describe(obj)
        ))
    })?;
    let slice = arr.as_slice().map_err(|_| {
        input(format!(
            "{what}: the array is not contiguous in memory (a strided view); pass numpy.ascontiguousarray(x)"
        ))
    })?;
    if slice.is_empty() {
        return Err(input(format!("{what}: the array is empty")));
    }
    if finite && let Some((i, v)) = slice.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(input(format!(
            "{what}[{i}] is {v}: every value must be a finite number"
        )));
    }
    Ok(slice.to_vec())
}

/// A 2-D float64 array `what` as (rows, columns, row-major values).
pub fn matrix(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(usize, usize, Vec<f64>)> {
    let arr: PyReadonlyArray2<'_, f64> = obj.extract().map_err(|_| {
        input(format!(
            "{what}: expected a 2-D numpy array of float64 (one row per design), got {}: convert it with numpy.asarray(x, dtype=float), and numpy.atleast_2d for one design",
            describe(obj)
        ))
    })?;
    let shape = arr.shape().to_vec();
    let slice = arr.as_slice().map_err(|_| {
        input(format!(
            "{what}: the array is not contiguous in memory (a strided view); pass numpy.ascontiguousarray(x)"
        ))
    })?;
    if slice.is_empty() {
        return Err(input(format!("{what}: the array is empty")));
    }
    if let Some((k, v)) = slice.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(input(format!(
            "{what}[{}, {}] is {v}: every value must be a finite number",
            k / shape[1],
            k % shape[1]
        )));
    }
    Ok((shape[0], shape[1], slice.to_vec()))
}

/// A vector as a 1-D numpy array (moved, not copied).
pub fn array1<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, v)
}

/// Row-major values as a (rows, columns) numpy array (moved, not copied).
pub fn array2<'py>(
    py: Python<'py>,
    rows: usize,
    cols: usize,
    v: Vec<f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let a = numpy::ndarray::Array2::from_shape_vec((rows, cols), v)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    Ok(numpy::IntoPyArray::into_pyarray(a, py))
}

/// Row-major values as a (a, b, c) numpy array (moved, not copied).
pub fn array3<'py>(
    py: Python<'py>,
    shape: (usize, usize, usize),
    v: Vec<f64>,
) -> PyResult<Bound<'py, numpy::PyArray3<f64>>> {
    let a = numpy::ndarray::Array3::from_shape_vec(shape, v)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    Ok(numpy::IntoPyArray::into_pyarray(a, py))
}
