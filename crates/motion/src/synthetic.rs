//! Synthetic ground motions: filtered, modulated white noise, reproducible from a seed.
//!
//! Contract: [`Synthetic::generate`] draws unit-variance Gaussian samples wₖ (xoshiro256**
//! and Box–Muller, see `rng.rs`), multiplies them by a time [`Envelope`], and passes them
//! through the Clough–Penzien filter: a Kanai–Tajimi soil oscillator (Kanai 1957, Tajimi
//! 1960; ẍ_g + 2ζ_gω_gẋ_g + ω_g²x_g = −w) followed by the Clough & Penzien (1993, Dynamics
//! of Structures, 2nd ed.) high-pass oscillator (ẍ_f + 2ζ_fω_fẋ_f + ω_f²x_f =
//! ω_g²x_g + 2ζ_gω_gẋ_g). The ground acceleration is a_g = ẍ_f, whose power spectrum is
//! the Clough–Penzien one, S(ω) = S₀ · KT(ω) · ω⁴/((ω_f² − ω²)² + 4ζ_f²ω_f²ω²). Because
//! a_g = ẍ_f, the ground velocity and displacement are ẋ_f and x_f: they stay bounded, with
//! no baseline drift. The noise is linear between samples (the [`Record`] convention) and
//! the four-state filter is integrated exactly for that input (`propagator.rs`), so the
//! samples are exact for the discrete input, with no step-size error.
//!
//! Reproducibility: only integer arithmetic, IEEE +, −, ×, ÷ and the pure-Rust `libm`
//! crate are used, so a seed gives the same bits on every platform. The unscaled amplitude
//! is arbitrary (unit-variance noise); scale with [`SuiteTarget`] or [`Record::scaled_to_pga`].

use crate::propagator::Propagator;
use crate::rng::{Rng, splitmix64};
use crate::{Envelope, G, MotionError, Record, spectral_acceleration};

/// Parameters of a Clough–Penzien synthetic motion. The defaults are firm soil:
/// ω_g = 5π rad/s, ζ_g = 0.6 (Kanai 1957 / Tajimi 1960 values for firm ground), high-pass
/// ω_f = 0.1·ω_g = π/2 rad/s and ζ_f = ζ_g (the usual Clough–Penzien choice), 20 s at
/// dt = 0.01 s, Saragoni–Hart envelope with ε = 0.2, η = 0.05 (Boore 2003).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Synthetic {
    /// Time step, s (default 0.01).
    pub dt_s: f64,
    /// Duration, s (default 20); the record has round(duration/dt) + 1 samples.
    pub duration_s: f64,
    /// Kanai–Tajimi ground frequency ω_g, rad/s (default 5π).
    pub ground_freq_rad_s: f64,
    /// Kanai–Tajimi ground damping ratio ζ_g (default 0.6).
    pub ground_damping: f64,
    /// Clough–Penzien high-pass frequency ω_f, rad/s (default π/2).
    pub highpass_freq_rad_s: f64,
    /// Clough–Penzien high-pass damping ratio ζ_f (default 0.6).
    pub highpass_damping: f64,
    /// Time envelope (default Saragoni–Hart, ε = 0.2, η = 0.05).
    pub envelope: Envelope,
}

impl Default for Synthetic {
    fn default() -> Synthetic {
        Synthetic {
            dt_s: 0.01,
            duration_s: 20.0,
            ground_freq_rad_s: 5.0 * std::f64::consts::PI,
            ground_damping: 0.6,
            highpass_freq_rad_s: 0.5 * std::f64::consts::PI,
            highpass_damping: 0.6,
            envelope: Envelope::default(),
        }
    }
}

/// How a synthetic suite is scaled.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SuiteTarget {
    /// As generated (arbitrary amplitude).
    Unscaled,
    /// Each record scaled to this PGA exactly, m/s².
    Pga {
        /// Target PGA, m/s².
        pga_m_s2: f64,
    },
    /// Each record scaled to this pseudo-spectral acceleration at one period.
    SpectralAcceleration {
        /// Period, s.
        period_s: f64,
        /// Damping ratio.
        damping: f64,
        /// Target pseudo-spectral acceleration, m/s².
        sa_m_s2: f64,
    },
}

/// Seed of the embedded default suite.
pub const DEFAULT_SUITE_SEED: u64 = 2007;
/// Number of records in the embedded default suite.
pub const DEFAULT_SUITE_SIZE: usize = 10;
/// PGA of every record in the embedded default suite, g.
pub const DEFAULT_SUITE_PGA_G: f64 = 0.4;

/// Most samples a synthetic record may have (10⁸, 800 MB).
const MAX_SAMPLES: f64 = 1e8;

impl Synthetic {
    /// Checks every parameter; [`MotionError::InvalidArgument`] names the bad one, and the
    /// time step is held to the readers' band ([`crate::check_record_dt`]).
    pub fn validate(&self) -> Result<(), MotionError> {
        let positive = |what, value: f64| {
            if value.is_finite() && value > 0.0 {
                Ok(())
            } else {
                Err(MotionError::InvalidArgument {
                    what,
                    value,
                    expected: "finite and > 0",
                })
            }
        };
        // the step of every record, whatever made it: what is written here is read back
        crate::record::check_record_dt("synthetic record", self.dt_s)?;
        positive("duration (s)", self.duration_s)?;
        positive("ground frequency (rad/s)", self.ground_freq_rad_s)?;
        positive("ground damping ratio", self.ground_damping)?;
        positive("high-pass frequency (rad/s)", self.highpass_freq_rad_s)?;
        positive("high-pass damping ratio", self.highpass_damping)?;
        if self.duration_s < self.dt_s {
            return Err(MotionError::InvalidArgument {
                what: "duration / time step",
                value: self.duration_s / self.dt_s,
                expected: "at least 1: the duration must span one time step (a single sample is the ground at rest)",
            });
        }
        if self.duration_s / self.dt_s > MAX_SAMPLES {
            return Err(MotionError::InvalidArgument {
                what: "duration / time step",
                value: self.duration_s / self.dt_s,
                expected: "at most 1e8 samples",
            });
        }
        self.envelope.validate()
    }

    /// One record from `seed`, named `name` (unscaled: unit-variance input noise).
    pub fn generate(&self, seed: u64, name: &str) -> Result<Record, MotionError> {
        self.validate()?;
        let n = (self.duration_s / self.dt_s).round() as usize + 1;
        let duration = (n - 1) as f64 * self.dt_s;
        let (wg, zg, wf, zf) = (
            self.ground_freq_rad_s,
            self.ground_damping,
            self.highpass_freq_rad_s,
            self.highpass_damping,
        );
        // state (x_g, ẋ_g, x_f, ẋ_f); input w enters the soil oscillator
        let a = [
            [0.0, 1.0, 0.0, 0.0],
            [-wg * wg, -2.0 * zg * wg, 0.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
            [wg * wg, 2.0 * zg * wg, -wf * wf, -2.0 * zf * wf],
        ];
        let output =
            |x: &[f64; 4]| a[3][0] * x[0] + a[3][1] * x[1] + a[3][2] * x[2] + a[3][3] * x[3];
        let prop = Propagator::new(a, [0.0, -1.0, 0.0, 0.0], self.dt_s);
        let mut rng = Rng::new(seed);
        let mut x = [0.0; 4];
        let mut accel = Vec::with_capacity(n);
        accel.push(output(&x));
        let mut p0 = self.envelope.at(0.0, duration) * rng.normal();
        for k in 1..n {
            let p1 = self.envelope.at(k as f64 * self.dt_s, duration) * rng.normal();
            x = prop.step(&x, p0, p1);
            accel.push(output(&x));
            p0 = p1;
        }
        let provenance = format!(
            "synthetic Clough-Penzien motion, seed {seed}: wg = {wg} rad/s, zg = {zg}, wf = {wf} rad/s, zf = {zf}, envelope {:?}, dt = {} s, {n} samples",
            self.envelope, self.dt_s
        );
        Ok(Record::new(name, self.dt_s, accel)?.with_provenance(provenance))
    }
}

/// The seed of record `index` of a suite generated from `seed` (SplitMix64 of both, so
/// neighbouring seeds and indices give unrelated streams).
pub fn derive_seed(seed: u64, index: u64) -> u64 {
    let mut s = seed;
    let base = splitmix64(&mut s);
    let mut t = base ^ index.wrapping_mul(0xD1B5_4A32_D192_ED03);
    splitmix64(&mut t)
}

/// `count` records from `params`, record i generated from `derive_seed(seed, i)` and named
/// `synthetic-{seed}-{i:03}`, then scaled to `target`. A count beyond
/// [`crate::limits::MAX_SUITE_RECORDS`], or a suite of more than
/// [`crate::limits::MAX_SUITE_SAMPLES`] samples, is refused
/// ([`MotionError::TooMany`]) unless the limits are lifted.
pub fn synthetic_suite(
    params: &Synthetic,
    count: usize,
    seed: u64,
    target: SuiteTarget,
) -> Result<Vec<Record>, MotionError> {
    use crate::limits;
    limits::check_suite_count(count)?;
    params.validate()?;
    let samples = count as f64 * ((params.duration_s / params.dt_s).round() + 1.0);
    if samples > limits::MAX_SUITE_SAMPLES && !limits::allow_large() {
        return Err(MotionError::TooMany {
            what: format!("samples in {count} synthetic records"),
            count: samples,
            limit: limits::MAX_SUITE_SAMPLES,
        });
    }
    (0..count)
        .map(|i| {
            let r = params.generate(
                derive_seed(seed, i as u64),
                &format!("synthetic-{seed}-{i:03}"),
            )?;
            match target {
                SuiteTarget::Unscaled => Ok(r),
                SuiteTarget::Pga { pga_m_s2 } => r.scaled_to_pga(pga_m_s2),
                SuiteTarget::SpectralAcceleration {
                    period_s,
                    damping,
                    sa_m_s2,
                } => {
                    let sa = spectral_acceleration(&r, period_s, damping)?;
                    if sa == 0.0 {
                        return Err(MotionError::ZeroMeasure {
                            file: r.name().to_string(),
                            measure: "spectral acceleration",
                        });
                    }
                    r.try_scaled(sa_m_s2 / sa)
                }
            }
            // scaling the unit-variance noise to the target is part of making the record
            .map(Record::generated)
        })
        .collect()
}

/// The embedded default suite, used whenever a user names no records:
/// [`DEFAULT_SUITE_SIZE`] = 10 Clough–Penzien records with the [`Synthetic::default`]
/// parameters (firm soil, 20 s, dt = 0.01 s), seed [`DEFAULT_SUITE_SEED`] = 2007, each
/// scaled to PGA = [`DEFAULT_SUITE_PGA_G`] = 0.4 g exactly.
pub fn default_suite() -> Vec<Record> {
    synthetic_suite(
        &Synthetic::default(),
        DEFAULT_SUITE_SIZE,
        DEFAULT_SUITE_SEED,
        SuiteTarget::Pga {
            pga_m_s2: DEFAULT_SUITE_PGA_G * G,
        },
    )
    .expect("the default parameters are valid and give non-zero records")
}
