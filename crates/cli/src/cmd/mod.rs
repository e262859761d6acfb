//! Subcommands of `slipload`.

pub mod record;

/// The subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// Ground-motion records: read, measure, synthesise
    Record(record::RecordArgs),
}

/// Runs one subcommand.
pub fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Record(args) => record::run(args),
    }
}
