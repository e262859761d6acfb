//! Whole-number arguments (thread counts, record counts, seeds, grid sizes): a Python int
//! has no bound, so an argument is read here rather than by PyO3's conversion, whose
//! `OverflowError` or `TypeError` would not name it; every refusal is an `InputError`
//! naming the parameter and what it expects.

use crate::errors::input;
use pyo3::prelude::*;
use pyo3::types::PyBool;

/// A whole-number argument as given: its value, clamped to the `i128` range (the callers'
/// own bounds lie far inside it, so a clamped value is refused by them as the true one
/// would be), and its text for messages (`2**70` as `1180591620717411303424`).
#[derive(Debug, Clone)]
pub struct Whole {
    /// The value, clamped to the `i128` range.
    pub value: i128,
    /// The value as Python prints it.
    pub text: String,
}

impl Whole {
    /// Reads `obj` (an `int`, or a numpy integer through `__index__`); a bool, a float, a
    /// string or anything else is refused naming `name` and what it `expects`.
    pub fn of(obj: &Bound<'_, PyAny>, name: &str, expects: &str) -> PyResult<Whole> {
        let wrong = || -> PyResult<PyErr> {
            Ok(input(format!(
                "{name}={}: expected {expects}, got a {}",
                obj.repr()?,
                obj.get_type().name()?
            )))
        };
        if obj.is_instance_of::<PyBool>() {
            return Err(wrong()?);
        }
        let Ok(index) = obj.call_method0("__index__") else {
            return Err(wrong()?);
        };
        let text = index.str()?.to_cow()?.into_owned();
        let value = match index.extract::<i128>() {
            Ok(v) => v,
            Err(_) if index.lt(0)? => i128::MIN,
            Err(_) => i128::MAX,
        };
        Ok(Whole { value, text })
    }

    /// The value as a count (≥ 0); a negative one refused naming `name` and what it
    /// `expects`; one past `usize` is `usize::MAX`, for the caller's limit to refuse.
    pub fn count(&self, name: &str, expects: &str) -> PyResult<usize> {
        if self.value < 0 {
            return Err(input(format!("{name}={}: expected {expects}", self.text)));
        }
        Ok(usize::try_from(self.value).unwrap_or(usize::MAX))
    }

    /// The value as a `u64` (a seed): outside 0 … 2⁶⁴ − 1 refused naming `name`.
    pub fn seed(&self, name: &str) -> PyResult<u64> {
        u64::try_from(self.value).map_err(|_| {
            input(format!(
                "{name}={}: expected a whole number from 0 to 2**64 - 1",
                self.text
            ))
        })
    }
}

/// An optional count argument: `None` when not given.
pub fn count(
    obj: Option<&Bound<'_, PyAny>>,
    name: &str,
    expects: &str,
) -> PyResult<Option<(usize, String)>> {
    obj.filter(|o| !o.is_none())
        .map(|o| {
            let w = Whole::of(o, name, expects)?;
            Ok((w.count(name, expects)?, w.text))
        })
        .transpose()
}

/// An optional seed argument: `None` when not given.
pub fn seed(obj: Option<&Bound<'_, PyAny>>, name: &str) -> PyResult<Option<u64>> {
    obj.filter(|o| !o.is_none())
        .map(|o| Whole::of(o, name, "a whole number from 0 to 2**64 - 1")?.seed(name))
        .transpose()
}
