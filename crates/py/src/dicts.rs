//! Dicts and lists given for a file (a scene, a building, a study, a list of designs),
//! written as the JSON text the library's loaders read, and refused on the way as the
//! command line refuses the same file: larger than any real one
//! ([`slipload_motion::limits::MAX_CONFIG_BYTES`], counted while the text is written, so
//! nothing huge is built first), nested deeper than the JSON reader goes, or holding a
//! value a JSON file cannot hold (NaN, ±inf, a set, an object). Numpy numbers and arrays
//! are taken as the Python numbers and nested lists they show (an array in its logical
//! order, whatever its memory order). Every refusal names the field path
//! (`dissipators[0].slip_load`), as the loaders' own errors do ([`crate::json_path`]).

use crate::errors::input;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// How deep containers may nest: the JSON reader's own limit (serde_json's), so a file
/// the command line would refuse as too deep is refused here too, naming the field.
pub const MAX_DEPTH: usize = 128;

/// One step of a field path: a key of an object or an index of a list.
enum Step {
    Key(String),
    Index(usize),
}

/// The text being written, with where it is and what it may hold.
struct Writer<'a> {
    out: String,
    path: Vec<Step>,
    /// The input's name in errors (`scene (a dict)`).
    name: &'a str,
    /// What the file would hold (`scene`), for the size limit's message.
    what: &'a str,
    limit: u64,
}

impl Writer<'_> {
    /// The field path as the loaders name it (`dissipators[0].slip_load`).
    fn path(&self) -> String {
        crate::json_path::render(self.path.iter().map(|step| match step {
            Step::Key(k) => crate::json_path::Step::Key(k),
            Step::Index(i) => crate::json_path::Step::Index(*i),
        }))
    }

    /// An `InputError` naming the input and the field.
    fn refuse(&self, why: impl std::fmt::Display) -> PyErr {
        let path = self.path();
        if path.is_empty() {
            input(format!("{}: {why}", self.name))
        } else {
            input(format!("{}: field `{path}`: {why}", self.name))
        }
    }

    /// Appends `text`, refusing the input once its text passes the limit.
    fn push(&mut self, text: &str) -> PyResult<()> {
        self.room(text.len())?;
        self.out.push_str(text);
        Ok(())
    }

    /// Refuses the input when `more` bytes would take its text past the limit (checked
    /// before a long string is escaped, so nothing past the limit is ever written).
    fn room(&mut self, more: usize) -> PyResult<()> {
        if (self.out.len() as u64).saturating_add(more as u64) > self.limit {
            let limit = slipload_motion::limits::bytes(self.limit as f64);
            let what = self.what;
            self.path.clear();
            return Err(self.refuse(format!(
                "more than {limit} as JSON text, more than any real {what} file (limit {limit}): not a {what}, or call slipload.allow_large(True) to run it anyway"
            )));
        }
        Ok(())
    }

    fn value(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        if v.is_none() {
            return self.push("null");
        }
        if let Ok(b) = v.cast::<PyBool>() {
            return self.push(if b.is_true() { "true" } else { "false" });
        }
        if v.is_instance_of::<PyInt>() {
            // as written: a number past the loader's integers is refused by the loader,
            // naming this field, as the command line refuses it in a file
            return self.push(&v.str()?.to_cow()?);
        }
        if let Ok(f) = v.cast::<PyFloat>() {
            let x = f.value();
            if !x.is_finite() {
                return Err(self.refuse(format!(
                    "{} is not a finite number (a JSON file cannot hold it either); give a finite number",
                    if x.is_nan() { "NaN".to_string() } else { x.to_string() }
                )));
            }
            let text = serde_json::to_string(&x).map_err(|e| self.refuse(e))?;
            return self.push(&text);
        }
        if let Ok(s) = v.cast::<PyString>() {
            let raw = s.to_cow()?;
            // its text is at least the string and its quotes
            self.room(raw.len().saturating_add(2))?;
            let text = serde_json::to_string(&*raw).map_err(|e| self.refuse(e))?;
            return self.push(&text);
        }
        if let Ok(d) = v.cast::<PyDict>() {
            self.open()?;
            self.push("{")?;
            for (k, (key, item)) in d.iter().enumerate() {
                let Ok(key) = key.cast::<PyString>() else {
                    return Err(self.refuse(format!(
                        "the key {} is not a string ({}): the keys of a JSON object are strings",
                        key.repr()?,
                        key.get_type().name()?
                    )));
                };
                let key = key.to_cow()?.into_owned();
                if k > 0 {
                    self.push(",")?;
                }
                let text = serde_json::to_string(&key).map_err(|e| self.refuse(e))?;
                self.push(&text)?;
                self.push(":")?;
                self.path.push(Step::Key(key));
                self.value(&item)?;
                self.path.pop();
            }
            return self.push("}");
        }
        if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
            self.open()?;
            self.push("[")?;
            for (i, item) in v.try_iter()?.enumerate() {
                if i > 0 {
                    self.push(",")?;
                }
                self.path.push(Step::Index(i));
                self.value(&item?)?;
                self.path.pop();
            }
            return self.push("]");
        }
        // a numpy number or array: the Python numbers and lists it shows, in logical order
        if v.hasattr("dtype")? && v.hasattr("tolist")? {
            let plain = v.call_method0("tolist")?;
            if plain.is(v) {
                return Err(self.refuse("a numpy value that gives no Python value"));
            }
            let dtype = v.getattr("dtype")?;
            let kind: String = dtype.getattr("kind")?.extract()?;
            let size: usize = dtype.getattr("itemsize")?.extract()?;
            if kind == "f" && size == 4 {
                // float32: the decimals numpy shows (np.float32(0.1) is 0.1, not the
                // 0.10000000149011612 its bits are as a double)
                let shown = shown_f32(&plain)?;
                return self.value(&shown);
            }
            if kind == "f" && size < 4 {
                return Err(self
                    .refuse("a float16 value keeps about three digits; give float32 or float64"));
            }
            return self.value(&plain);
        }
        Err(self.refuse(format!(
            "a {} is not a value a JSON file holds; give numbers, strings, booleans, None, lists and dicts (numpy numbers and arrays are taken)",
            v.get_type().name()?
        )))
    }

    /// A container opens one level deeper: refused past [`MAX_DEPTH`].
    fn open(&self) -> PyResult<()> {
        // every container above this one added one step to the path
        if self.path.len() + 1 > MAX_DEPTH {
            return Err(self.refuse(format!(
                "nested more than {MAX_DEPTH} levels deep, deeper than the JSON reader goes (a file nested so is refused too)"
            )));
        }
        Ok(())
    }
}

/// `value` (a dict or list given for a file) as JSON text; `name` names it in errors
/// (`scene (a dict)`), `what` is what its file would hold (`scene`).
#[pyfunction]
pub fn dict_json(value: &Bound<'_, PyAny>, name: &str, what: &str) -> PyResult<String> {
    let limit = if slipload_motion::limits::allow_large() {
        u64::MAX
    } else {
        slipload_motion::limits::MAX_CONFIG_BYTES
    };
    let mut w = Writer {
        out: String::new(),
        path: Vec::new(),
        name,
        what,
        limit,
    };
    w.value(value)?;
    Ok(w.out)
}

/// `plain` (a float32 value or array as `tolist` gives it, nested lists of Python floats)
/// with every float replaced by the shortest decimal that reads back to the same float32
/// — the number numpy shows — read as a double.
fn shown_f32<'py>(plain: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let py = plain.py();
    if let Ok(x) = plain.cast::<PyFloat>() {
        // exact: a float32 widened to a double narrows back to itself
        let single = x.value() as f32;
        let shown: f64 = if single.is_finite() {
            format!("{single}").parse().unwrap_or(x.value())
        } else {
            x.value()
        };
        return Ok(PyFloat::new(py, shown).into_any());
    }
    if let Ok(list) = plain.cast::<PyList>() {
        let items = list
            .iter()
            .map(|item| shown_f32(&item))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(PyList::new(py, items)?.into_any());
    }
    Ok(plain.clone())
}
