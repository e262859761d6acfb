//! Terminal output: `--quiet` and standard output that survives a closed pipe. Files are
//! written by [`slipload_opt::base::output::write_atomic`] (temporary file, sync, rename).

use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};

/// `--quiet`: no progress output on stderr.
static QUIET: AtomicBool = AtomicBool::new(false);

/// Sets `--quiet` for the whole process (once, from the parsed command line).
pub fn set_quiet(quiet: bool) {
    QUIET.store(quiet, Ordering::Relaxed);
}

/// Whether `--quiet` was given: progress bars and progress lines are hidden.
pub fn quiet() -> bool {
    QUIET.load(Ordering::Relaxed)
}

/// Writes to standard output; a closed pipe ends the process with success (everything the
/// reader wanted has been read, and every output file is written before the summary is
/// printed), any other write error ends it with an error message and status 1.
pub fn stdout_fmt(args: std::fmt::Arguments<'_>, newline: bool) {
    let mut out = std::io::stdout().lock();
    let result = out
        .write_fmt(args)
        .and_then(|()| {
            if newline {
                out.write_all(b"\n")
            } else {
                Ok(())
            }
        })
        .and_then(|()| out.flush());
    if let Err(e) = result {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        eprintln!("error: cannot write to standard output: {e}");
        std::process::exit(1);
    }
}
