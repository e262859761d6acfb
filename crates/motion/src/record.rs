//! A ground-acceleration record on a uniform time grid.
//!
//! Contract: a [`Record`] holds at least one sample, every sample finite (m/s²), and a
//! finite time step dt > 0 (s). Sample k is the ground acceleration at t = k·dt; between
//! samples the acceleration is linear (the convention of every integrator in slipload),
//! and outside [0, duration] it is zero. Constructors validate; no method produces a
//! record that breaks the contract. A record carries what was done to it since it was
//! read or built: its provenance (free text), its [`Record::scale_factor`] (the product of
//! the factors its samples were multiplied by) and the [`Record::notes`] its reader
//! decided a user should hear about; windows and scalings keep them.

use crate::MotionError;
use crate::units::G;

/// The largest |ground acceleration| a reader accepts and a scaling may produce, in g.
/// The largest recorded ground accelerations are about 4–5 g; a value beyond this bound
/// means wrong units, a corrupt file or a typo, and would give responses that are
/// numbers but not answers.
pub const MAX_ABS_ACCEL_G: f64 = 20.0;

/// The shortest sample interval a reader accepts, s: accelerographs sample at a few
/// hundred to a few thousand hertz, so a step below a microsecond is a units slip (or
/// a typo) that would make every default time step as short.
pub const MIN_RECORD_DT_S: f64 = 1e-6;

/// The longest sample interval a reader accepts, s: accelerographs sample at 50 Hz or
/// faster (0.02 s; old digitised records at 0.02–0.05 s), so a step beyond a second is a
/// units slip or a corrupt header.
pub const MAX_RECORD_DT_S: f64 = 1.0;

/// Checks a record's sample interval `dt_s`, s: finite and positive
/// ([`MotionError::BadTimeStep`]), and within [`MIN_RECORD_DT_S`] …
/// [`MAX_RECORD_DT_S`] ([`MotionError::ImplausibleTimeStep`],
/// [`MotionError::ImplausibleLongTimeStep`]). `name` names the record, file or argument in
/// the error. The one rule for every record whatever its origin — a file's header or time
/// column, an array, a synthetic record's step — so that what one front writes or builds
/// the others read.
pub fn check_record_dt(name: &str, dt_s: f64) -> Result<(), MotionError> {
    if !(dt_s.is_finite() && dt_s > 0.0) {
        return Err(MotionError::BadTimeStep {
            file: name.to_string(),
            dt_s,
        });
    }
    if dt_s < MIN_RECORD_DT_S {
        return Err(MotionError::ImplausibleTimeStep {
            file: name.to_string(),
            dt_s,
            min_s: MIN_RECORD_DT_S,
        });
    }
    if dt_s > MAX_RECORD_DT_S {
        return Err(MotionError::ImplausibleLongTimeStep {
            file: name.to_string(),
            dt_s,
            max_s: MAX_RECORD_DT_S,
        });
    }
    Ok(())
}

/// [`MAX_ABS_ACCEL_G`] in m/s².
pub fn max_abs_accel_m_s2() -> f64 {
    MAX_ABS_ACCEL_G * G
}

/// A uniformly sampled ground-acceleration history.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Record {
    name: String,
    provenance: String,
    dt_s: f64,
    accel_m_s2: Vec<f64>,
    /// Product of the factors the samples were multiplied by since the record was read
    /// or built (1 for none).
    #[serde(skip)]
    scale_factor: f64,
    /// What the reader decided a user should hear about, one sentence each.
    #[serde(skip)]
    notes: Vec<String>,
}

impl Record {
    /// Builds a record from its time step `dt_s` (s) and samples `accel_m_s2` (m/s²).
    ///
    /// Errors: [`MotionError::Empty`] when there are no samples,
    /// [`MotionError::BadTimeStep`] unless dt is finite and > 0,
    /// [`MotionError::NonFiniteSample`] for a NaN or infinite sample.
    pub fn new(
        name: impl Into<String>,
        dt_s: f64,
        accel_m_s2: Vec<f64>,
    ) -> Result<Record, MotionError> {
        let name = name.into();
        if accel_m_s2.is_empty() {
            return Err(MotionError::Empty { file: name });
        }
        if !(dt_s.is_finite() && dt_s > 0.0) {
            return Err(MotionError::BadTimeStep { file: name, dt_s });
        }
        if let Some((index, &value)) = accel_m_s2.iter().enumerate().find(|(_, a)| !a.is_finite()) {
            return Err(MotionError::NonFiniteSample {
                file: name,
                index,
                value,
            });
        }
        Ok(Record {
            name,
            provenance: String::new(),
            dt_s,
            accel_m_s2,
            scale_factor: 1.0,
            notes: Vec::new(),
        })
    }

    /// Returns the record with one more note: a sentence a user should hear about how
    /// it was read (e.g. units given that override the file's own), kept through
    /// windows and scalings.
    pub fn with_note(mut self, note: impl Into<String>) -> Record {
        self.notes.push(note.into());
        self
    }

    /// The notes of [`Record::with_note`], in the order they were added (empty for most
    /// records).
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// The product of the factors the samples were multiplied by ([`Record::try_scaled`],
    /// [`Record::scaled_to_pga`]) since the record was read, built or generated: 1 for a
    /// record as read. The PGA before scaling is `pga() / scale_factor()`.
    pub fn scale_factor(&self) -> f64 {
        self.scale_factor
    }

    /// Returns the record as built from a process that set its amplitude (a generator
    /// scaling its noise to a target): scale factor 1.
    pub(crate) fn generated(mut self) -> Record {
        self.scale_factor = 1.0;
        self
    }

    /// Returns the record with scale factor `factor` (a record combined from records
    /// scaled alike, as a pair's rotated component is).
    pub(crate) fn with_scale_factor(mut self, factor: f64) -> Record {
        self.scale_factor = factor;
        self
    }

    /// A record derived from this one: new samples (and a processing note), the same
    /// name, step and notes, the scale factor multiplied by `factor`.
    fn derived(&self, samples: Vec<f64>, factor: f64, what: &str) -> Result<Record, MotionError> {
        let mut r = Record::new(self.name.clone(), self.dt_s, samples)?;
        r.scale_factor = self.scale_factor * factor;
        r.notes = self.notes.clone();
        r.provenance = self.note(what);
        Ok(r)
    }

    /// Returns the record with its provenance (where it came from, how it was processed)
    /// replaced by `provenance`.
    pub fn with_provenance(mut self, provenance: impl Into<String>) -> Record {
        self.provenance = provenance.into();
        self
    }

    /// Returns the record renamed.
    pub fn with_name(mut self, name: impl Into<String>) -> Record {
        self.name = name.into();
        self
    }

    /// The record's name (a file path, or a generated name).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Where the record came from and what was done to it (free text; empty if unknown).
    pub fn provenance(&self) -> &str {
        &self.provenance
    }

    /// Time step, seconds.
    pub fn dt(&self) -> f64 {
        self.dt_s
    }

    /// Samples, m/s²; sample k is the acceleration at t = k·dt.
    pub fn samples(&self) -> &[f64] {
        &self.accel_m_s2
    }

    /// Number of samples (at least 1).
    pub fn len(&self) -> usize {
        self.accel_m_s2.len()
    }

    /// Always `false`: a record holds at least one sample. Present for API symmetry with `len`.
    pub fn is_empty(&self) -> bool {
        self.accel_m_s2.is_empty()
    }

    /// Duration (len − 1)·dt, seconds: the time of the last sample.
    pub fn duration(&self) -> f64 {
        (self.len() - 1) as f64 * self.dt_s
    }

    /// Ground acceleration at time `t` (s), m/s²: linear between samples, 0 for t < 0,
    /// t > duration and NaN t. O(1). When t/dt is within a few ulps of an integer k the
    /// sample k is returned exactly (so `accel_at(k as f64 * dt)` is `samples()[k]`).
    pub fn accel_at(&self, t: f64) -> f64 {
        if t.is_nan() || t < 0.0 || t > self.duration() {
            return 0.0;
        }
        let x = t / self.dt_s;
        let last = self.len() - 1;
        let k = x.round();
        // t = k·dt computed in floating point gives x within 2 ulps of k.
        if (x - k).abs() <= 4.0 * f64::EPSILON * k.max(1.0) {
            return self.accel_m_s2[(k as usize).min(last)];
        }
        let i = x.floor() as usize;
        if i >= last {
            return self.accel_m_s2[last];
        }
        let frac = x - i as f64;
        let a0 = self.accel_m_s2[i];
        a0 + frac * (self.accel_m_s2[i + 1] - a0)
    }

    /// The acceleration at `t = dt, 2dt, 3dt, …` one value per call, as [`Record::accel_at`]
    /// gives it, without a division per call when `dt` divides the record's step (the usual
    /// case: default integrator steps are chosen so).
    pub fn steps(&self, dt: f64) -> StepSampler<'_> {
        let ratio = self.dt_s / dt;
        let k = ratio.round();
        let k = if k >= 1.0 && (ratio - k).abs() <= 1e-9 * k && k < 1e9 {
            k as usize
        } else {
            0
        };
        StepSampler {
            record: self,
            dt,
            k,
            inv_k: if k > 0 { 1.0 / k as f64 } else { 0.0 },
            i: 0,
            r: 0,
            j: 0,
        }
    }

    /// Peak ground acceleration max |a| over the samples, m/s² (for a piecewise-linear
    /// record the peak over all t is at a sample).
    pub fn pga(&self) -> f64 {
        self.accel_m_s2.iter().fold(0.0, |m, a| m.max(a.abs()))
    }

    /// [`MotionError::ImplausibleScale`] when the record's PGA exceeds
    /// [`MAX_ABS_ACCEL_G`] (a scaled record must stay physical).
    pub fn check_plausible(&self) -> Result<(), MotionError> {
        let pga = self.pga();
        if pga > max_abs_accel_m_s2() {
            return Err(MotionError::ImplausibleScale {
                file: self.name.clone(),
                pga_g: pga / G,
                limit_g: MAX_ABS_ACCEL_G,
            });
        }
        Ok(())
    }

    /// The record with every sample multiplied by `factor` (name and provenance kept,
    /// provenance notes the factor).
    ///
    /// # Panics
    /// If `factor` is not finite or the product overflows or exceeds
    /// [`MAX_ABS_ACCEL_G`] (a scaled record must stay finite and physical); use
    /// [`Record::try_scaled`] for a `Result`.
    pub fn scaled(&self, factor: f64) -> Record {
        match self.try_scaled(factor) {
            Ok(r) => r,
            Err(e) => panic!("Record::scaled: {e}"),
        }
    }

    /// Like [`Record::scaled`], but returns [`MotionError::InvalidArgument`] for a
    /// non-finite factor, [`MotionError::NonFiniteSample`] on overflow and
    /// [`MotionError::ImplausibleScale`] beyond [`MAX_ABS_ACCEL_G`].
    pub fn try_scaled(&self, factor: f64) -> Result<Record, MotionError> {
        if !factor.is_finite() {
            return Err(MotionError::InvalidArgument {
                what: "scale factor",
                value: factor,
                expected: "a finite number",
            });
        }
        let samples = self.accel_m_s2.iter().map(|a| a * factor).collect();
        let r = self.derived(samples, factor, &format!("scaled by {factor}"))?;
        r.check_plausible()?;
        Ok(r)
    }

    /// The record scaled so that its PGA is exactly `pga_m_s2` (m/s², finite, ≥ 0):
    /// bit for bit, `scaled_to_pga(x)?.pga() == x`. Samples are multiplied by
    /// x / PGA; rounding can leave the largest products one ulp off x, so samples at the
    /// old peak are set to ±x and others clamped to [−x, x] (a change of at most one ulp).
    ///
    /// Errors: [`MotionError::InvalidArgument`] for a negative or non-finite target,
    /// [`MotionError::ImplausibleScale`] beyond [`MAX_ABS_ACCEL_G`],
    /// [`MotionError::ZeroMeasure`] for an all-zero record.
    pub fn scaled_to_pga(&self, pga_m_s2: f64) -> Result<Record, MotionError> {
        if !(pga_m_s2.is_finite() && pga_m_s2 >= 0.0) {
            return Err(MotionError::InvalidArgument {
                what: "target PGA (m/s2)",
                value: pga_m_s2,
                expected: "finite and >= 0",
            });
        }
        if pga_m_s2 > max_abs_accel_m_s2() {
            return Err(MotionError::ImplausibleScale {
                file: self.name.clone(),
                pga_g: pga_m_s2 / G,
                limit_g: MAX_ABS_ACCEL_G,
            });
        }
        let pga = self.pga();
        if pga == 0.0 {
            return Err(MotionError::ZeroMeasure {
                file: self.name.clone(),
                measure: "PGA",
            });
        }
        let factor = pga_m_s2 / pga;
        let samples = self
            .accel_m_s2
            .iter()
            .map(|&a| {
                if a.abs() == pga {
                    pga_m_s2.copysign(a)
                } else {
                    (a * factor).clamp(-pga_m_s2, pga_m_s2)
                }
            })
            .collect();
        self.derived(
            samples,
            factor,
            &format!("scaled by {factor} to PGA {pga_m_s2} m/s2"),
        )
    }

    /// The part of the record in [start_s, start_s + duration_s] (seconds), resampled at
    /// the same dt from t = start_s: sample k is `accel_at(start_s + k·dt)`, k = 0..=m with
    /// m = floor(duration/dt) (exact samples when start_s is a multiple of dt). The window
    /// is cut at the record's end.
    ///
    /// Errors: [`MotionError::InvalidArgument`] when start_s is not in [0, duration] or
    /// duration_s is negative or not finite.
    pub fn window(&self, start_s: f64, duration_s: f64) -> Result<Record, MotionError> {
        if !(start_s.is_finite() && start_s >= 0.0 && start_s <= self.duration()) {
            return Err(MotionError::InvalidArgument {
                what: "window start (s)",
                value: start_s,
                expected: "within [0, record duration]",
            });
        }
        if !(duration_s.is_finite() && duration_s >= 0.0) {
            return Err(MotionError::InvalidArgument {
                what: "window duration (s)",
                value: duration_s,
                expected: "finite and >= 0",
            });
        }
        let span = duration_s.min(self.duration() - start_s);
        // A few ulps of slack so that a span that is a whole number of steps keeps its
        // last sample.
        let m = (span / self.dt_s * (1.0 + 4.0 * f64::EPSILON)).floor() as usize;
        // clamp: start + m·dt may round past the end, where accel_at is 0
        let end = self.duration();
        let samples = (0..=m)
            .map(|k| self.accel_at((start_s + k as f64 * self.dt_s).min(end)))
            .collect();
        self.derived(
            samples,
            1.0,
            &format!("window {start_s} s + {duration_s} s"),
        )
    }

    /// Provenance with one more processing note appended.
    fn note(&self, what: &str) -> String {
        if self.provenance.is_empty() {
            what.to_string()
        } else {
            format!("{}; {what}", self.provenance)
        }
    }
}

/// Successive ground accelerations at the steps of an integrator ([`Record::steps`]).
#[derive(Debug, Clone)]
pub struct StepSampler<'a> {
    record: &'a Record,
    dt: f64,
    /// Integrator steps per record step, or 0 when `dt` does not divide the record's step.
    k: usize,
    inv_k: f64,
    /// Record interval and step within it of the last value given.
    i: usize,
    r: usize,
    /// Steps given.
    j: usize,
}

impl StepSampler<'_> {
    /// The acceleration at the next step, m/s² (0 after the record's end, as `accel_at`).
    #[inline]
    pub fn next_accel(&mut self) -> f64 {
        self.j += 1;
        if self.k == 0 {
            return self.record.accel_at(self.j as f64 * self.dt);
        }
        self.r += 1;
        if self.r == self.k {
            self.r = 0;
            self.i += 1;
        }
        let a = &self.record.accel_m_s2;
        if self.r == 0 {
            return a.get(self.i).copied().unwrap_or(0.0);
        }
        match (a.get(self.i), a.get(self.i + 1)) {
            (Some(a0), Some(a1)) => a0 + (self.r as f64 * self.inv_k) * (a1 - a0),
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp() -> Record {
        Record::new("ramp", 0.01, vec![0.0, 1.0, -2.0, 4.0]).unwrap()
    }

    #[test]
    fn validates() {
        assert!(matches!(
            Record::new("x", 0.01, vec![]),
            Err(MotionError::Empty { .. })
        ));
        assert!(matches!(
            Record::new("x", 0.0, vec![1.0]),
            Err(MotionError::BadTimeStep { .. })
        ));
        assert!(matches!(
            Record::new("x", f64::NAN, vec![1.0]),
            Err(MotionError::BadTimeStep { .. })
        ));
        assert!(matches!(
            Record::new("x", 0.01, vec![1.0, f64::INFINITY]),
            Err(MotionError::NonFiniteSample { index: 1, .. })
        ));
    }

    #[test]
    fn interpolates_and_is_zero_outside() {
        let r = ramp();
        assert_eq!(r.duration(), 3.0 * 0.01);
        assert_eq!(r.accel_at(-1e-12), 0.0);
        assert_eq!(r.accel_at(f64::NAN), 0.0);
        assert_eq!(r.accel_at(r.duration() * (1.0 + 1e-12)), 0.0);
        assert_eq!(r.accel_at(r.duration()), 4.0);
        assert!((r.accel_at(0.005) - 0.5).abs() < 1e-14);
        assert!((r.accel_at(0.015) + 0.5).abs() < 1e-14);
        for k in 0..r.len() {
            assert_eq!(r.accel_at(k as f64 * 0.01), r.samples()[k]);
        }
        // 0.1 + 0.2 style rounding: t a few ulps off a sample still returns it exactly
        assert_eq!(r.accel_at(0.01 + 0.02), 4.0);
    }

    #[test]
    fn window_on_grid_keeps_samples() {
        let r = ramp();
        let w = r.window(0.01, 0.02).unwrap();
        assert_eq!(w.samples(), &[1.0, -2.0, 4.0]);
        let w = r.window(0.01, 10.0).unwrap();
        assert_eq!(w.len(), 3);
        // off-grid start: interpolated, and the last sample is not lost to rounding
        let long = Record::new("l", 0.1, (0..=30).map(f64::from).collect()).unwrap();
        let w = long.window(0.7, 100.0).unwrap();
        assert_eq!(w.len(), 24);
        assert_eq!(w.samples()[23], 30.0);
        assert!((w.samples()[0] - 7.0).abs() < 1e-12);
        assert!(r.window(-0.1, 1.0).is_err());
        assert!(r.window(0.0, f64::NAN).is_err());
    }

    #[test]
    fn pga_scaling() {
        let r = ramp();
        assert_eq!(r.pga(), 4.0);
        let s = r.scaled_to_pga(0.3 * G).unwrap();
        assert_eq!(s.pga(), 0.3 * G);
        assert_eq!(r.scaled(-2.0).pga(), 8.0);
        assert!(r.try_scaled(f64::INFINITY).is_err());
        let zero = Record::new("z", 0.01, vec![0.0; 3]).unwrap();
        assert!(matches!(
            zero.scaled_to_pga(1.0),
            Err(MotionError::ZeroMeasure { .. })
        ));
    }

    #[test]
    fn step_sampler_matches_accel_at() {
        let rec = Record::new("t", 0.01, vec![0.0, 1.0, -2.0, 0.5]).expect("valid");
        // dt divides the record step (4 per interval) and does not (0.003).
        for dt in [0.0025, 0.003] {
            let mut s = rec.steps(dt);
            for j in 1..=20 {
                let t = j as f64 * dt;
                let (a, b) = (s.next_accel(), rec.accel_at(t));
                // Interpolation weights r/k vs t/dt − i differ by a few ulps.
                assert!((a - b).abs() <= 1e-14, "dt {dt}, t {t}: {a} vs {b}");
            }
        }
    }
}
