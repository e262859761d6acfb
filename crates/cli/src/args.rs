//! Checks of command-line arguments shared by the commands and their figures, said before
//! any work: an output folder flag that names something other than a folder, and a count
//! past what any real run needs. A leaf of the binary: it uses the libraries only, so
//! `cmd` and `figures` both build on it.

/// Refuses an output folder flag (`--out`, `--plot`) that names an existing file, a FIFO
/// or a device: said before any work, naming the flag (a folder that does not exist yet
/// is created later).
pub(crate) fn output_folder(flag: &str, dir: &std::path::Path) -> anyhow::Result<()> {
    Ok(slipload_opt::base::output::check_output_folder(flag, dir)?)
}

/// Refuses a count flag (`--count`, `--repeats`, `--shards` …) of `n` above `limit`,
/// naming the flag and how to lift the limit, unless `--allow-large` lifted it.
pub(crate) fn count_flag(flag: &str, n: usize, limit: usize) -> anyhow::Result<()> {
    if n <= limit || slipload_sim::limits::allow_large() {
        return Ok(());
    }
    anyhow::bail!(
        "{flag} {n}: more than any real run needs (limit {limit}); {}",
        slipload_sim::limits::OVERRIDE_HINT
    )
}

/// Most timed repeats (`accuracy --repeats`, `simulate --repeat`): a median of a few
/// runs is what timing needs.
pub(crate) const MAX_REPEATS: usize = 1000;
