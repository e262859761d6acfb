//! Output files: written to a temporary file beside the target, synced, then renamed,
//! so an interrupted run never leaves a partial file under the final name.

use anyhow::Context;
use std::io::Write;
use std::path::Path;
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

/// Writes `bytes` to `path` atomically (temporary file in the same folder, `sync_all`,
/// rename). Creates the parent folder when missing. A symbolic link is written through
/// (its target replaced, the link kept); anything else that is not a regular file (a
/// FIFO, a device, a folder) is refused. The same rules as the library's
/// [`slipload_opt::journal::write_atomic`], which this calls.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    slipload_opt::journal::write_atomic(path, bytes)
        .with_context(|| format!("writing {}", path.display()))
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_whole_file_and_leaves_no_temporary() {
        let dir = std::env::temp_dir().join(format!("slipload-out-{}", std::process::id()));
        let path = dir.join("a.csv");
        write_atomic(&path, b"x,y\n1,2\n").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"x,y\n1,2\n");
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 1, "only the final file remains: {names:?}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
