//! Ground motions for slipload: record readers, synthetic generators, scaling, spectra.
//!
//! All accelerations are m/s², times seconds, lengths metres. A [`Record`] is a uniformly
//! sampled ground acceleration, linear between samples (the convention every slipload
//! integrator uses). Errors are the typed [`MotionError`].

mod at2;
mod error;
mod number;
mod reader;
mod record;
mod text;
mod units;

pub use at2::{parse_at2, parse_at2_in};
pub use error::MotionError;
pub use reader::{RecordFormat, read_record};
pub use record::{G, Record};
pub use text::parse_text;
pub use units::Units;
