//! Ground motions for slipload: record readers, synthetic generators, scaling, spectra.
//!
//! All accelerations are m/s², times seconds, lengths metres. A [`Record`] is a uniformly
//! sampled ground acceleration, linear between samples (the convention every slipload
//! integrator uses). Errors are the typed [`MotionError`].
//!
//! ```
//! use slipload_motion::{G, Intensity, Record, Spectrum, default_suite};
//!
//! // a record from samples (m/s²) at dt = 0.01 s
//! let r = Record::new("pulse", 0.01, vec![0.0, 1.0, 2.0, 1.0, 0.0])?;
//! assert_eq!(r.accel_at(0.015), 1.5); // linear between samples
//! assert_eq!(Intensity::of(&r).pga_m_s2, 2.0);
//!
//! // the embedded default suite: 10 synthetic records scaled to PGA = 0.4 g exactly
//! let suite = default_suite();
//! assert!(suite.iter().all(|r| r.pga() == 0.4 * G));
//! let s = Spectrum::compute(&suite[0], 0.05, &[0.2, 0.4, 1.0])?;
//! assert!(s.psa_m_s2.iter().all(|&sa| sa > 0.0));
//! # Ok::<(), slipload_motion::MotionError>(())
//! ```

mod at2;
mod design_spectrum;
mod en1998;
mod envelope;
mod error;
mod intensity;
pub mod limits;
mod number;
mod pair;
mod propagator;
mod reader;
mod record;
mod rng;
mod scaling;
mod spectrum;
mod synthetic;
mod target;
mod text;
mod unit_label;
mod units;

pub use at2::{parse_at2, parse_at2_in};
pub use design_spectrum::DesignSpectrum;
pub use en1998::{
    EN1998_MAX_PERIOD_S, EN1998_MIN_ETA, En1998Corners, En1998Spectrum, GroundType, en1998_eta,
};
pub use envelope::Envelope;
pub use error::{MotionError, readable};
pub use intensity::{
    Intensity, arias_intensity, ground_displacement, ground_velocity, significant_duration,
};
pub use pair::{
    PairScaling, RecordPair, rotd100_spectrum, scale_pairs, scale_pairs_over_range,
    scale_pairs_over_range_each,
};
pub use reader::{RecordFormat, read_record};
pub use record::{
    MAX_ABS_ACCEL_G, MAX_RECORD_DT_S, MIN_RECORD_DT_S, Record, StepSampler, check_record_dt,
    max_abs_accel_m_s2,
};
pub use scaling::{
    ASCE7_FRACTION, Asce7Scaling, REFINE_MARGIN, SCALING_POINTS_PER_DECADE, ScaledSuite,
    ScalingOptions, TargetMatch, ZeroPeriod, fit_to_target, scale_suite, scale_suite_asce7,
    scale_suite_over_range, scale_suite_over_range_each, scale_to_spectral_acceleration,
    smallest_factor,
};
pub use spectrum::{
    DEFAULT_DAMPING, Spectrum, default_periods, log_spaced_periods, sdof_displacement,
    spectral_acceleration,
};
pub use synthetic::{
    DEFAULT_SUITE_PGA_G, DEFAULT_SUITE_SEED, DEFAULT_SUITE_SIZE, SuiteTarget, Synthetic,
    default_suite, derive_seed, synthetic_suite,
};
pub use target::{SpectrumTable, Target, TargetSpectrum, check_span};
pub use text::{format_csv, parse_text};
pub use units::{G, Units};
