//! `slipload record …`: read, measure and synthesise ground-motion records.

/// Arguments of `slipload record`.
#[derive(Debug, clap::Args)]
pub struct RecordArgs {}

/// Runs `slipload record`.
pub fn run(_args: RecordArgs) -> anyhow::Result<()> {
    anyhow::bail!("not implemented yet")
}
