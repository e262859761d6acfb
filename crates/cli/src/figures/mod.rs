//! The figures each command draws from its data (the look lives in [`crate::plot`]).

pub mod accuracy;
pub mod scene_file;
pub mod simulation;
pub mod spectra;
