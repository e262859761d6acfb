//! Ground-motion records: the AT2/CSV readers, records from arrays, the synthetic suites,
//! spectra and intensity measures (`slipload-motion`), as numpy arrays in SI units.

use crate::arrays::{array1, vector};
use crate::errors::{PyResultExt, guarded, input};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use slipload_motion::{Intensity, Record, Spectrum, Units};
use std::path::PathBuf;
use std::sync::Arc;

/// The units of a record's values, from their Python name.
pub fn units(name: Option<&str>) -> PyResult<Option<Units>> {
    name.map(|u| u.parse::<Units>()).transpose().py()
}

/// A ground-motion record: accelerations at a uniform time step, held in m/s².
#[pyclass(name = "Record", module = "slipload", frozen)]
#[derive(Debug, Clone)]
pub struct PyRecord {
    pub(crate) inner: Arc<Record>,
}

impl PyRecord {
    pub(crate) fn of(r: Record) -> PyRecord {
        PyRecord { inner: Arc::new(r) }
    }
}

#[pymethods]
impl PyRecord {
    /// Reads a PEER .AT2 file or a CSV/text file.
    #[staticmethod]
    #[pyo3(signature = (path, units=None, dt=None))]
    fn read(path: PathBuf, units: Option<&str>, dt: Option<f64>) -> PyResult<PyRecord> {
        guarded(|| {
            let u = crate::records::units(units)?;
            let r = slipload_motion::read_record(&path, u, dt).py()?;
            Ok(PyRecord::of(r))
        })
    }

    /// A record from an array of accelerations.
    #[staticmethod]
    #[pyo3(signature = (accel, dt, units="m/s2", name="array"))]
    fn from_array(
        accel: &Bound<'_, PyAny>,
        dt: f64,
        units: &str,
        name: &str,
    ) -> PyResult<PyRecord> {
        guarded(|| {
            let u = crate::records::units(Some(units))?.unwrap_or(Units::MPerS2);
            let values = vector(accel, "accel", true)?;
            // the step every reader accepts (1 µs … 1 s), as `record info` reads a file
            slipload_motion::check_record_dt("dt", dt).py()?;
            let f = u.to_m_s2();
            let r = Record::new(name, dt, values.iter().map(|a| a * f).collect()).py()?;
            r.check_plausible().py()?;
            Ok(PyRecord::of(r.with_provenance("a numpy array")))
        })
    }

    /// The record's name.
    #[getter]
    fn name(&self) -> String {
        self.inner.name().to_string()
    }

    /// Time step, s.
    #[getter]
    fn dt(&self) -> f64 {
        self.inner.dt()
    }

    /// Number of samples.
    #[getter]
    fn npts(&self) -> usize {
        self.inner.len()
    }

    fn __len__(&self) -> usize {
        self.inner.len()
    }

    /// Duration, s.
    #[getter]
    fn duration(&self) -> f64 {
        self.inner.duration()
    }

    /// Peak ground acceleration, m/s².
    #[getter]
    fn pga(&self) -> f64 {
        self.inner.pga()
    }

    /// Peak ground acceleration, g.
    #[getter]
    fn pga_g(&self) -> f64 {
        self.inner.pga() / slipload_motion::G
    }

    /// What the reader said about the file, one sentence each (units given that override
    /// an AT2 title's); empty for most records.
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.inner.notes().to_vec()
    }

    /// The product of the factors the record was scaled by since it was read or built
    /// (1 as read); the PGA before scaling is `pga / scale_factor`.
    #[getter]
    fn scale_factor(&self) -> f64 {
        self.inner.scale_factor()
    }

    /// Accelerations, m/s² (a copy).
    #[getter]
    fn accel<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        array1(py, self.inner.samples().to_vec())
    }

    /// Sample times, s.
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        let dt = self.inner.dt();
        array1(py, (0..self.inner.len()).map(|k| k as f64 * dt).collect())
    }

    /// The record times `factor`.
    fn scaled(&self, factor: f64) -> PyResult<PyRecord> {
        guarded(|| Ok(PyRecord::of(self.inner.try_scaled(factor).py()?)))
    }

    /// The record scaled to a peak ground acceleration, in g.
    fn scaled_to_pga(&self, pga_g: f64) -> PyResult<PyRecord> {
        guarded(|| {
            if !slipload_sim::scene::target_pga_in_band(pga_g) {
                let (lo, hi) = slipload_sim::scene::TARGET_PGA_BAND_G;
                return Err(input(format!(
                    "pga_g: a target PGA must lie within {lo} … {hi} g, got {pga_g}"
                )));
            }
            Ok(PyRecord::of(
                self.inner.scaled_to_pga(pga_g * slipload_motion::G).py()?,
            ))
        })
    }

    /// The part of the record from `start` lasting `duration`, s.
    fn window(&self, start: f64, duration: f64) -> PyResult<PyRecord> {
        guarded(|| {
            // a window of no length is refused, as a scene's and `--window` are
            slipload_sim::scene::check_window(start, duration, "window").py()?;
            Ok(PyRecord::of(self.inner.window(start, duration).py()?))
        })
    }

    /// Response spectrum: a dict of arrays.
    #[pyo3(signature = (periods=None, damping=0.05))]
    fn spectrum<'py>(
        &self,
        py: Python<'py>,
        periods: Option<&Bound<'py, PyAny>>,
        damping: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let periods = match periods {
            Some(p) => vector(p, "periods", true)?,
            None => slipload_motion::default_periods(),
        };
        let rec = self.inner.clone();
        let s: Spectrum =
            crate::run::detached(py, move || Spectrum::compute(&rec, damping, &periods).py())?;
        let d = PyDict::new(py);
        d.set_item("damping", s.damping)?;
        d.set_item("periods", array1(py, s.periods_s))?;
        d.set_item("sd", array1(py, s.sd_m))?;
        d.set_item("psv", array1(py, s.psv_m_s))?;
        d.set_item("psa", array1(py, s.psa_m_s2))?;
        Ok(d)
    }

    /// Intensity measures: a dict of floats.
    fn intensity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let i = Intensity::of(&self.inner);
        let d = PyDict::new(py);
        d.set_item("pga", i.pga_m_s2)?;
        d.set_item("pgv", i.pgv_m_s)?;
        d.set_item("pgd", i.pgd_m)?;
        d.set_item("arias", i.arias_m_s)?;
        d.set_item("d5_95", i.d5_95_s)?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "Record({:?}, npts={}, dt={} s, pga={:.4} g)",
            self.inner.name(),
            self.inner.len(),
            self.inner.dt(),
            self.inner.pga() / slipload_motion::G
        )
    }
}

/// The embedded synthetic suite, or a suite of `count` records drawn from `seed`.
#[pyfunction]
#[pyo3(signature = (count=None, seed=None, pga_g=None, duration=None, dt=None))]
pub fn synthetic_suite(
    py: Python<'_>,
    count: Option<&Bound<'_, PyAny>>,
    seed: Option<&Bound<'_, PyAny>>,
    pga_g: Option<f64>,
    duration: Option<f64>,
    dt: Option<f64>,
) -> PyResult<Vec<PyRecord>> {
    // the command line's rules (`record synth --count`, `--dt`), from the library
    let count = match crate::args::count(count, "count", "a whole number of records, 1 or more")? {
        None => slipload_motion::DEFAULT_SUITE_SIZE,
        Some((c, text)) => {
            slipload_motion::limits::check_suite_count(c)
                .map_err(|e| input(format!("count={text}: {e}")))?;
            c
        }
    };
    let seed = crate::args::seed(seed, "seed")?;
    if let Some(dt) = dt {
        slipload_motion::check_record_dt("dt", dt).py()?;
    }
    let pga = pga_g.unwrap_or(slipload_motion::DEFAULT_SUITE_PGA_G);
    if !slipload_sim::scene::target_pga_in_band(pga) {
        let (lo, hi) = slipload_sim::scene::TARGET_PGA_BAND_G;
        return Err(input(format!(
            "pga_g: a target PGA must lie within {lo} … {hi} g, got {pga}"
        )));
    }
    let mut params = slipload_motion::Synthetic::default();
    if let Some(d) = duration {
        params.duration_s = d;
    }
    if let Some(dt) = dt {
        params.dt_s = dt;
    }
    let seed = seed.unwrap_or(slipload_motion::DEFAULT_SUITE_SEED);
    let records = crate::run::detached(py, move || {
        slipload_motion::synthetic_suite(
            &params,
            count,
            seed,
            slipload_motion::SuiteTarget::Pga {
                pga_m_s2: pga * slipload_motion::G,
            },
        )
        .py()
    })?;
    Ok(records.into_iter().map(PyRecord::of).collect())
}
