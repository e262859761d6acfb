//! The figures each command draws from its data (the look lives in [`slipload_figures::plot`]).

pub mod accuracy;
pub mod scene_file;
pub mod simulation;
pub mod spectra;

use anyhow::Context;
use std::path::Path;

/// Checks a `--plot` argument before any work: `--plot` names a FOLDER in every command
/// (created when missing; the figures and their data go into it). An existing file there
/// is refused, with what to give instead.
pub fn check_plot_folder(dir: &Path) -> anyhow::Result<()> {
    crate::args::output_folder("--plot", dir).context(
        "--plot takes a folder (created when missing) that the figures and their data are written into",
    )
}
