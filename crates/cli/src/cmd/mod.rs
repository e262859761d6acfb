//! Subcommands of `slipload`.

pub mod accuracy;
pub mod bench;
pub mod check_summary;
pub mod explain;
pub mod merge;
pub mod opensees;
pub mod optimize;
pub mod pareto_summary;
pub mod rank;
pub mod record;
pub mod report;
pub mod scene_args;
pub mod simulate;
pub mod study_args;
pub mod study_text;
pub mod sweep;
pub mod table;

/// The subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// Simulate one building under one excitation
    Simulate(simulate::SimulateArgs),
    /// Print the bare frame's periods and modes and the plan a scene (or a building file
    /// alone) compiles into: DOFs, contacts, which effects are on and why; refuses what
    /// simulate refuses
    Explain(explain::ExplainArgs),
    /// Ground-motion records: read, measure, synthesise
    Record(record::RecordArgs),
    /// What accuracy costs: every method x time step against the exact integrator
    Accuracy(accuracy::AccuracyArgs),
    /// Sweep a sample of slip-load designs over every record of a study
    Sweep(sweep::SweepArgs),
    /// Join sweep shards into the files one run writes
    Merge(merge::MergeArgs),
    /// Sweep, refine and verify the slip loads of a study (default: the embedded benchmark)
    Optimize(optimize::OptimizeArgs),
    /// Rank candidate designs over every suite of a study, with bootstrap stability
    Rank(rank::RankArgs),
    /// Tabulate a study's optimum over period scale × intensity scale
    Table(table::TableArgs),
    /// Throughput figures beside their targets (simulations per second, memory, scaling)
    Bench(bench::BenchArgs),
    /// One self-contained HTML page (tables, figures, inputs) from an output folder
    Report(report::ReportArgs),
    /// Write a scene as a self-contained OpenSeesPy script (Newmark at the same dt, the
    /// dampers as elastic–perfectly plastic elements) that prints its peaks as JSON
    Opensees(opensees::OpenSeesArgs),
}

impl Command {
    /// The `--threads` given after the name of a command that runs simulations in
    /// parallel (None for the others, and when not given).
    pub fn threads(&self) -> Option<usize> {
        match self {
            Command::Sweep(a) => a.threads.threads,
            Command::Optimize(a) => a.threads.threads,
            Command::Rank(a) => a.threads.threads,
            Command::Table(a) => a.threads.threads,
            _ => None,
        }
    }
}

/// Runs one subcommand.
pub fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Simulate(args) => simulate::run(args),
        Command::Explain(args) => explain::run(args),
        Command::Record(args) => record::run(args),
        Command::Accuracy(args) => accuracy::run(args),
        Command::Sweep(args) => sweep::run(args),
        Command::Merge(args) => merge::run(args),
        Command::Optimize(args) => optimize::run(args),
        Command::Rank(args) => rank::run(args),
        Command::Table(args) => table::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Report(args) => report::run(args),
        Command::Opensees(args) => opensees::run(args),
    }
}

// The argument checks live in `crate::args` (below both the commands and the figures);
// the study commands call this one through its name here.
pub(crate) use crate::args::count_flag;
