//! Helpers shared by the opt tests: an output folder as the study commands take it and
//! open it.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
#![allow(dead_code)] // each test binary uses its own subset of these helpers

pub mod valley;

use slipload_opt::store::folder::{FolderRequest, StudyFolder};
use std::path::Path;

/// The output folder `out`, as the library's study commands take it (no `fresh`).
pub fn folder(out: &Path) -> FolderRequest<'_> {
    FolderRequest {
        path: out,
        option: "out",
        fresh: false,
    }
}

/// The sweep's output folder `dir`, opened as a study command opens it (locked until the
/// returned value is dropped).
pub fn open_folder(dir: &Path) -> StudyFolder {
    StudyFolder::open(folder(dir)).unwrap().0
}

/// [0, 1]^n as slip loads 0–3000 kN per floor, with a storey-shear-like profile (1 at the
/// first variable falling to 0.3 at the last): the space of the analytic refiner tests.
pub fn free_space(n: usize) -> slipload_opt::DesignSpace {
    slipload_opt::DesignSpace {
        dampers: (0..n).collect(),
        offset: vec![0.0; n],
        basis: nalgebra::DMatrix::from_diagonal_element(n, n, 3.0e6),
        a: nalgebra::DMatrix::zeros(0, n),
        b: vec![],
        names: (0..n).map(|i| format!("floor{}", i + 1)).collect(),
        shape: None,
        profile: (0..n)
            .map(|i| 1.0 - 0.7 * i as f64 / (n - 1) as f64)
            .collect(),
    }
}

/// `optimize` of `study` into a fresh folder `dir`, no progress, no figures.
pub fn optimize_fresh(
    study: &slipload_opt::Study,
    dir: &Path,
) -> slipload_opt::pipeline::OptimizeRun {
    slipload_opt::pipeline::optimize_study(
        study,
        &slipload_opt::pipeline::OptimizeOptions::default(),
        FolderRequest {
            path: dir,
            option: "--out",
            fresh: true,
        },
        &slipload_opt::eval::progress::NoProgress,
        &slipload_opt::pipeline::NoFigures,
    )
    .unwrap()
}
