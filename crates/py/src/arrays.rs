//! numpy arrays in and out. Inputs are taken as they are or refused with what was
//! expected: a float64 array of the right shape, contiguous in memory, every value
//! finite — never cast, copied across strides or truncated behind the caller's back.
//! A contiguous array is read by index, in the order numpy shows it, whatever its memory
//! order: C order, Fortran order (`numpy.asfortranarray`) and a transposed view (`x.T`)
//! give the same rows; a strided view (`x[::2]`) is refused naming the parameter.

use crate::errors::input;
use numpy::ndarray::Dimension;
use numpy::{
    PyArray1, PyArray2, PyReadonlyArray, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::prelude::*;

/// The values of `arr` in logical (row-major) order: C-ordered memory as it lies, any
/// other contiguous layout read by index; an array that is not contiguous in memory (or
/// not aligned) is refused, naming `what`.
fn logical_values<D: Dimension>(
    arr: &PyReadonlyArray<'_, f64, D>,
    what: &str,
) -> PyResult<Vec<f64>> {
    let slice = arr.as_slice().map_err(|_| {
        input(format!(
            "{what}: the array is not contiguous in memory (a strided view); pass numpy.ascontiguousarray(x)"
        ))
    })?;
    if arr.is_c_contiguous() {
        Ok(slice.to_vec())
    } else {
        // Fortran order or a transposed view: memory order is not the rows' order
        Ok(arr.as_array().iter().copied().collect())
    }
}

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
    let values = logical_values(&arr, what)?;
    if values.is_empty() {
        return Err(input(format!("{what}: the array is empty")));
    }
    if finite && let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(input(format!(
            "{what}[{i}] is {v}: every value must be a finite number"
        )));
    }
    Ok(values)
}

/// A 2-D float64 array `what` as (rows, columns, row-major values), row i being `x[i]`
/// whatever the array's memory order.
pub fn matrix(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(usize, usize, Vec<f64>)> {
    matrix_of(obj, what, false)
}

/// As [`matrix`], with +∞ taken when `plus_infinity` (the objectives of a design that
/// collapsed); NaN and −∞ are refused all the same.
pub fn matrix_of(
    obj: &Bound<'_, PyAny>,
    what: &str,
    plus_infinity: bool,
) -> PyResult<(usize, usize, Vec<f64>)> {
    let arr: PyReadonlyArray2<'_, f64> = obj.extract().map_err(|_| {
        input(format!(
            "{what}: expected a 2-D numpy array of float64 (one row per design), got {}: convert it with numpy.asarray(x, dtype=float), and numpy.atleast_2d for one design",
            describe(obj)
        ))
    })?;
    let shape = arr.shape().to_vec();
    let values = logical_values(&arr, what)?;
    if values.is_empty() {
        return Err(input(format!("{what}: the array is empty")));
    }
    let taken = |v: f64| v.is_finite() || (plus_infinity && v == f64::INFINITY);
    if let Some((k, v)) = values.iter().enumerate().find(|(_, v)| !taken(**v)) {
        let rule = if plus_infinity {
            "every value must be a number or +inf (a collapsed design)"
        } else {
            "every value must be a finite number"
        };
        return Err(input(format!(
            "{what}[{}, {}] is {v}: {rule}",
            k / shape[1],
            k % shape[1]
        )));
    }
    Ok((shape[0], shape[1], values))
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
