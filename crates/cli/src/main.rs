//! The `slipload` command-line program.

/// `print!` to standard output that ends the process quietly (exit 0) when the reader has
/// gone (`slipload … | head`), instead of panicking on the broken pipe.
macro_rules! out {
    ($($arg:tt)*) => { $crate::output::stdout_fmt(format_args!($($arg)*), false) };
}

/// `println!` with the broken-pipe handling of [`out!`].
macro_rules! outln {
    ($($arg:tt)*) => { $crate::output::stdout_fmt(format_args!($($arg)*), true) };
}

mod args;
mod cmd;
mod figures;
mod html;
mod output;

/// Choose friction-damper slip loads for buildings.
#[derive(Debug, clap::Parser)]
#[command(version, about, long_about = None)]
struct Cli {
    /// Worker threads: listed in the help of the commands that use them (sweep,
    /// optimize, rank, table — `args::ThreadsArg`); taken, unlisted, before any command
    /// and after the others, which run one simulation at a time
    #[arg(long, global = true, hide = true, value_name = "N",
          value_parser = args::thread_count, allow_hyphen_values = true)]
    threads: Option<usize>,
    /// No progress: hides progress bars and accuracy's per-scene lines (summaries, results
    /// and errors still print)
    #[arg(long, global = true)]
    quiet: bool,
    /// Lift the work and memory limits no real study needs (steps per simulation, memory
    /// of histories, sweep size, threads); also SLIPLOAD_ALLOW_LARGE=1
    #[arg(long, global = true)]
    allow_large: bool,
    #[command(subcommand)]
    command: cmd::Command,
}

impl Cli {
    /// The program's arguments as clap sees them: every numeric flag takes a negative
    /// number as its value (`args::negative_numbers_as_values`), for its check to refuse
    /// it by name.
    fn command() -> clap::Command {
        args::negative_numbers_as_values(<Cli as clap::CommandFactory>::command())
    }

    /// Parses `args` (the program's name first) with [`Cli::command`].
    fn try_parse_from<I, T>(args: I) -> Result<Cli, clap::Error>
    where
        I: IntoIterator<Item = T>,
        T: Into<std::ffi::OsString> + Clone,
    {
        let mut cmd = Cli::command();
        let matches = cmd.try_get_matches_from_mut(args).map_err(args::clearer)?;
        <Cli as clap::FromArgMatches>::from_arg_matches(&matches).map_err(|e| e.format(&mut cmd))
    }

    /// The worker threads asked for: the command's own `--threads`, else the one given
    /// before the command's name.
    fn threads(&self) -> Option<usize> {
        self.command.threads().or(self.threads)
    }
}

/// An error and its causes on one line, each cause once: a cause whose text the message
/// already holds (a library error that prints its source, then the source itself) is
/// not repeated.
fn message(e: &anyhow::Error) -> String {
    let mut out = String::new();
    for cause in e.chain() {
        let s = cause.to_string();
        if s.is_empty() || out.contains(&s) {
            continue;
        }
        if !out.is_empty() {
            out.push_str(": ");
        }
        out.push_str(&s);
    }
    out
}

fn main() -> std::process::ExitCode {
    let cli = match Cli::try_parse_from(std::env::args_os()) {
        Ok(cli) => cli,
        Err(e) => e.exit(),
    };
    output::set_quiet(cli.quiet);
    if cli.allow_large {
        slipload_sim::limits::set_allow_large(true);
    }
    if let Some(n) = cli.threads() {
        if let Err(e) = slipload_sim::limits::check_threads(n) {
            eprintln!("error: --threads {n}: {e}");
            return std::process::ExitCode::FAILURE;
        }
        if let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
        {
            eprintln!("error: cannot start {n} worker threads: {e}");
            return std::process::ExitCode::FAILURE;
        }
    }
    match cmd::run(cli.command) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) if e.is::<cmd::check_summary::NoAcceptableDesign>() => {
            eprintln!("{}", message(&e));
            std::process::ExitCode::from(cmd::check_summary::NO_ACCEPTABLE_DESIGN)
        }
        Err(e) => {
            eprintln!("error: {}", message(&e));
            std::process::ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cli_is_well_formed() {
        Cli::command().debug_assert();
    }

    #[test]
    fn study_commands_parse() {
        for args in [
            vec![
                "slipload", "sweep", "s.json", "--shard", "1/3", "--resume", "--quiet",
            ],
            vec![
                "slipload",
                "--threads",
                "2",
                "sweep",
                "s.json",
                "--shard",
                "auto",
                "--shards",
                "4",
            ],
            vec!["slipload", "merge", "a", "b", "--out", "m"],
            vec!["slipload", "table", "--period-scales", "0.9,1.1"],
            vec!["slipload", "optimize"],
            vec![
                "slipload",
                "optimize",
                "s.json",
                "--refine",
                "nelder-mead",
                "--out",
                "o",
            ],
            vec![
                "slipload",
                "rank",
                "s.json",
                "--designs",
                "d.json",
                "--bootstrap",
                "50",
            ],
        ] {
            assert!(Cli::try_parse_from(&args).is_ok(), "{args:?}");
        }
        assert!(Cli::try_parse_from(["slipload", "optimize", "--refine", "gradient"]).is_err());
        for args in [
            vec!["slipload", "opensees", "--out", "b.py"],
            vec![
                "slipload",
                "opensees",
                "configs/ten-story-yielding.json",
                "--record",
                "records/I-ELC180.AT2",
                "--scale-pga-g",
                "0.6",
                "--window",
                "1s,4s",
                "--dt",
                "2.5ms",
                "--out",
                "t.py",
            ],
        ] {
            assert!(Cli::try_parse_from(&args).is_ok(), "{args:?}");
        }
        assert!(
            Cli::try_parse_from(["slipload", "opensees"]).is_err(),
            "--out is required"
        );
        assert!(Cli::try_parse_from(["slipload", "simulate", "--method", "verlet"]).is_err());
    }

    /// `--quiet` and `--threads` are taken by every command, before or after its name.
    #[test]
    fn quiet_and_threads_are_global() {
        let commands: [&[&str]; 14] = [
            &["simulate"],
            &["explain"],
            &["record", "info", "a.AT2"],
            &["record", "spectrum", "a.AT2"],
            &["accuracy", "s.json"],
            &["sweep", "s.json"],
            &["merge", "a", "--out", "m"],
            &["optimize"],
            &["rank", "s.json", "--designs", "d.json"],
            &["table"],
            &["bench"],
            &["report", "d"],
            &["record", "synth", "--out", "r.csv"],
            &["opensees", "--out", "o.py"],
        ];
        for c in commands {
            let after: Vec<&str> = std::iter::once("slipload")
                .chain(c.iter().copied())
                .chain(["--quiet", "--threads", "1"])
                .collect();
            let cli = Cli::try_parse_from(&after).unwrap_or_else(|e| panic!("{after:?}: {e}"));
            assert!(cli.quiet && cli.threads == Some(1), "{after:?}");
            let before: Vec<&str> = ["slipload", "--quiet", "--threads", "2"]
                .into_iter()
                .chain(c.iter().copied())
                .collect();
            let cli = Cli::try_parse_from(&before).unwrap_or_else(|e| panic!("{before:?}: {e}"));
            assert!(cli.quiet && cli.threads == Some(2), "{before:?}");
        }
        assert!(Cli::try_parse_from(["slipload", "merge", "--out", "m"]).is_err());
    }
}
