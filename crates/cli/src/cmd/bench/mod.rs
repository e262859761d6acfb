//! `slipload bench`: the throughput figures of the project, each beside its target.
//!
//! Every figure is measured in this process, single-threaded unless it says otherwise,
//! on the whole process's CPU time (the sweep's parallel efficiency on wall-clock time,
//! since it compares thread counts). A figure is the median of
//! several repeats after one warm-up run; a repeat runs a batch of simulations long
//! enough that the clock's resolution does not matter.
//!
//! Scenes: the benchmark three-storey building and the ten-storey building (embedded
//! configs), each under a 15 s synthetic record (seed 2007, dt 0.01 s, 0.4 g), peaks only
//! (no energies, no histories), at each method's default time step — and the first
//! figures check that this default is within 1 % of `exact` on every storey's peak drift.
//!
//! The parts, each by its role: [`figure`] (one measured figure, its target and the table
//! they print as), [`measure`] (the clock, the timed runs, the bench's state),
//! [`scenes`] (the bench's buildings and scenes), [`cases`] (the cases of `newmark`, the
//! reductions, the scaling, memory and the sweep) and [`exact`] (the cases of `exact`
//! and the equal-accuracy comparison), [`checked`] (the time to a checked design), [`tall`] (tall frames: set-up, stepping
//! and memory against storeys, `exact` at 60 and 120 storeys, a 100-storey study). The cases run and print in the order `run` calls
//! them.

mod cases;
mod checked;
mod exact;
mod figure;
mod measure;
mod plans;
mod scenes;
mod tall;

use anyhow::bail;
use figure::print_table;
use measure::{Bench, Budget};

/// Arguments of `slipload bench`.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// Output format
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Shorter batches and fewer repeats (a smoke run: figures are noisier)
    #[arg(long)]
    pub quick: bool,
    /// Run only the cases whose name contains this text (repeatable)
    #[arg(long)]
    pub only: Vec<String>,
    /// Internal: run one peaks-only benchmark simulation of this many seconds and print
    /// the process's peak resident memory (kB); used by the memory case
    #[arg(long, hide = true)]
    pub memory_probe: Option<f64>,
    /// Internal: run one peaks-only tall-frame simulation, METHOD:STOREYS (e.g.
    /// `exact:60`), and print the process's peak resident memory (kB), the run's CPU
    /// seconds, `exact`'s memory budget and its cache's peak (bytes); used by the tall
    /// frames' cases
    #[arg(long, hide = true)]
    pub tall_probe: Option<String>,
}

/// Output formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// A list of `{case, metric, value, unit, target, met, status, note}` objects
    Json,
    /// A table for people
    Table,
}

/// Runs `slipload bench`.
pub fn run(args: BenchArgs) -> anyhow::Result<()> {
    if let Some(seconds) = args.memory_probe {
        return cases::memory_probe(seconds);
    }
    if let Some(spec) = &args.tall_probe {
        return tall::tall_probe(spec);
    }
    let budget = if args.quick {
        Budget {
            seconds: 0.05,
            repeats: 3,
        }
    } else {
        Budget {
            seconds: 0.4,
            repeats: 5,
        }
    };
    if let Some(i) = args.only.iter().position(|o| o.trim().is_empty()) {
        bail!(
            "--only: value {} is empty, which every case's name contains: give part of a case's name (e.g. `--only memory`), or leave --only out to run every case",
            i + 1
        );
    }
    let mut bench = Bench::new(budget, &args.only);
    cases::defaults(&mut bench)?;
    cases::energies(&mut bench)?;
    exact::guards(&mut bench)?;
    exact::equal_accuracy(&mut bench)?;
    cases::reductions(&mut bench)?;
    cases::record_length(&mut bench)?;
    cases::storeys(&mut bench)?;
    cases::banded(&mut bench)?;
    cases::memory(&mut bench)?;
    cases::sweep(&mut bench)?;
    tall::setup_and_stepping(&mut bench)?;
    tall::memory(&mut bench)?;
    tall::exact(&mut bench)?;
    tall::study(&mut bench)?;
    plans::plans(&mut bench)?;
    checked::checked_design(&mut bench)?;

    let figs = bench.figs;
    if figs.is_empty() && !args.only.is_empty() {
        let only: Vec<String> = args.only.iter().map(|o| format!("`{o}`")).collect();
        bail!(
            "--only {}: no bench case's name contains it; the cases are:\n  {}",
            only.join(", "),
            bench.cases.join("\n  ")
        );
    }
    let clock_note = "process CPU time";
    match args.format {
        Format::Json => outln!("{}", serde_json::to_string_pretty(&figs)?),
        Format::Table => print_table(&figs, clock_note),
    }
    Ok(())
}
