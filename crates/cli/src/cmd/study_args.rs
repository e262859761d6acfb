//! Study selection shared by `sweep`, `optimize`, `rank` and `table`: a study file, or
//! the embedded benchmark study ([`slipload_opt::Study::benchmark`]), plus the progress bars these commands draw on stderr, one per phase
//! of the study run, and what `--fresh` did.

use anyhow::Context;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use slipload_opt::Study;
use slipload_opt::eval::progress::{Phase, Progress};
use slipload_opt::store::folder::Discarded;
use std::path::Path;
use std::sync::Mutex;

/// Loads `path`, or the embedded benchmark study. Every check runs here, before any
/// simulation.
pub fn load_study(path: Option<&Path>) -> anyhow::Result<Study> {
    match path {
        Some(p) => {
            let study = Study::load(p).with_context(|| format!("loading study {}", p.display()))?;
            // what looks like kN written as N (the building file's slip loads, a
            // base-shear limit) is said before anything runs
            for w in study.warnings() {
                eprintln!("warning: study {}, {w}", p.display());
            }
            Ok(study)
        }
        None => Ok(Study::benchmark()?),
    }
}

/// A progress bar of `len` steps on stderr; hidden with `--quiet` (and by indicatif when
/// stderr is not a terminal).
fn progress(len: u64, what: &str) -> ProgressBar {
    let pb = ProgressBar::new(len);
    if crate::output::quiet() {
        pb.set_draw_target(ProgressDrawTarget::hidden());
    }
    pb.set_style(
        ProgressStyle::with_template(
            "{bar:40} {pos}/{len} [{elapsed_precise}<{eta_precise}] {msg}",
        )
        .expect("template is a literal"),
    );
    pb.set_message(what.to_string());
    pb
}

/// The progress of a study run on stderr: one bar per phase ([`progress`]), cleared when
/// the phase ends.
#[derive(Debug, Default)]
pub struct PhaseBars {
    bar: Mutex<Option<ProgressBar>>,
}

impl Progress for PhaseBars {
    fn start(&self, phase: Phase, work: usize) {
        if let Ok(mut bar) = self.bar.lock() {
            *bar = Some(progress(work as u64, phase.label()));
        }
    }

    fn tick(&self) {
        if let Ok(bar) = self.bar.lock()
            && let Some(bar) = bar.as_ref()
        {
            bar.inc(1);
        }
    }

    fn finish(&self, _phase: Phase) {
        if let Ok(mut bar) = self.bar.lock()
            && let Some(bar) = bar.take()
        {
            bar.finish_and_clear();
        }
    }

    /// `--fresh`: says what went and which other files stay.
    fn discarded(&self, dir: &Path, d: &Discarded) {
        if !d.removed.is_empty() {
            eprintln!(
                "--fresh: removed {} from {}",
                d.removed.join(", "),
                dir.display()
            );
        }
        if !d.kept.is_empty() {
            eprintln!(
                "--fresh: kept {} in {} (not written by slipload)",
                d.kept.join(", "),
                dir.display()
            );
        }
    }
}
