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

/// `--threads N` of the commands that run simulations in parallel (sweep, optimize, rank,
/// table): the one place its help is written. The other commands take the flag too (the
/// program's hidden global `--threads`, so that `slipload --threads 2 CMD` keeps working)
/// but do not list it, for it changes nothing there.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct ThreadsArg {
    /// Worker threads of the parallel sweep (default: one per core; at least 1, at most 8
    /// per core and 256 or more without --allow-large)
    #[arg(long, value_name = "N", value_parser = thread_count, allow_hyphen_values = true)]
    pub threads: Option<usize>,
}

/// `--threads`'s value: a whole number; a negative one or a word is refused saying what
/// is expected (the range — at least 1, at most the limit — is the library's check, made
/// in `main` for every command).
pub(crate) fn thread_count(s: &str) -> Result<usize, String> {
    let t = s.trim();
    if let Ok(n) = t.parse::<usize>() {
        return Ok(n);
    }
    if t.parse::<f64>().is_ok() {
        return Err(format!(
            "expected a whole number of worker threads, 1 or more, got {s}"
        ));
    }
    Err(format!(
        "expected a whole number of worker threads, 1 or more, got {s:?}"
    ))
}

/// Whether an argument takes a number (its value parser yields one): those take a
/// negative value as a value, so that `--dt -0.01` or `--count -1` reaches the checks that
/// say what is expected instead of clap's "unexpected argument".
fn takes_a_number(arg: &clap::Arg) -> bool {
    use std::any::TypeId;
    let t = arg.get_value_parser().type_id();
    [
        TypeId::of::<f64>(),
        TypeId::of::<f32>(),
        TypeId::of::<usize>(),
        TypeId::of::<u64>(),
        TypeId::of::<u32>(),
        TypeId::of::<u16>(),
        TypeId::of::<u8>(),
        TypeId::of::<i64>(),
        TypeId::of::<i32>(),
        TypeId::of::<(f64, f64)>(),
    ]
    .into_iter()
    .any(|id| t == id)
}

/// `cmd` and its subcommands with every numeric argument taking negative numbers as
/// values ([`takes_a_number`]; a comma-separated list takes any value starting with '-').
pub(crate) fn negative_numbers_as_values(cmd: clap::Command) -> clap::Command {
    cmd.mut_args(|a| {
        if !(a.get_action().takes_values() && takes_a_number(&a)) {
            a
        } else if a.get_value_delimiter().is_some() {
            // a list (`-1,1`) is no number to clap: every value starting with '-' is taken
            a.allow_hyphen_values(true)
        } else {
            a.allow_negative_numbers(true)
        }
    })
    .mut_subcommands(negative_numbers_as_values)
}

/// A clap error about a negative number given to a flag that takes an unsigned count:
/// the flag, the value and what is expected, in place of "invalid digit found in
/// string". Other errors are returned as they are.
pub(crate) fn clearer(e: clap::Error) -> clap::Error {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if e.kind() != ErrorKind::ValueValidation {
        return e;
    }
    let (Some(ContextValue::String(arg)), Some(ContextValue::String(value))) = (
        e.get(ContextKind::InvalidArg),
        e.get(ContextKind::InvalidValue),
    ) else {
        return e;
    };
    if !(value.starts_with('-') && value.parse::<f64>().is_ok()) || e.to_string().contains(" got ")
    {
        return e;
    }
    let flag = arg.split_whitespace().next().unwrap_or(arg);
    clap::Error::raw(
        ErrorKind::ValueValidation,
        format!("{flag} {value}: expected a whole number, not a negative one\n"),
    )
}
