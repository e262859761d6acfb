//! Subcommands of `slipload`.

pub mod accuracy;
pub mod explain;
pub mod record;
pub mod scene_args;
pub mod simulate;

/// The subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// Simulate one building under one excitation
    Simulate(simulate::SimulateArgs),
    /// Print the plan a scene compiles into: DOFs, contacts, which effects are on and why
    Explain(explain::ExplainArgs),
    /// Ground-motion records: read, measure, synthesise
    Record(record::RecordArgs),
    /// What accuracy costs: every method x time step against the exact integrator
    Accuracy(accuracy::AccuracyArgs),
}

/// Runs one subcommand.
pub fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Simulate(args) => simulate::run(args),
        Command::Explain(args) => explain::run(args),
        Command::Record(args) => record::run(args),
        Command::Accuracy(args) => accuracy::run(args),
    }
}
