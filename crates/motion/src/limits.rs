//! Input limits: a file or a count a user gives is bounded before anything is read or
//! allocated, with limits no real input comes near (a typo, a device or a corrupt file
//! would otherwise block, abort on an allocation or run for days). The limits can be
//! lifted for one process with [`set_allow_large`] (the CLI's `--allow-large`) or the
//! environment variable [`ALLOW_LARGE_ENV`]`=1`; the simulation crate's work limits use
//! the same switch.

use crate::MotionError;
use std::io::Read;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

/// Largest record file read, bytes (64 MiB): the largest PEER AT2 files are 2–3 MB.
pub const MAX_RECORD_BYTES: u64 = 64 * 1024 * 1024;

/// Largest JSON input (scene, building, study, designs) read, bytes (16 MiB): the
/// largest real ones are a few kilobytes.
pub const MAX_CONFIG_BYTES: u64 = 16 * 1024 * 1024;

/// Most records of a generated synthetic suite (real suites hold tens to hundreds).
pub const MAX_SUITE_RECORDS: usize = 10_000;

/// Most samples of a generated suite, all records together (2 × 10⁸, 1.6 GB).
pub const MAX_SUITE_SAMPLES: f64 = 2e8;

/// The environment variable that lifts the limits (`1`, `true` or `yes`).
pub const ALLOW_LARGE_ENV: &str = "SLIPLOAD_ALLOW_LARGE";

/// How to go beyond a limit, for error messages (the text the errors of this crate end
/// with, defined beside them).
pub const OVERRIDE_HINT: &str = crate::error::OVERRIDE_HINT;

static ALLOW_LARGE: AtomicBool = AtomicBool::new(false);

/// Lifts (or restores) the limits for this process.
pub fn set_allow_large(on: bool) {
    ALLOW_LARGE.store(on, Ordering::Relaxed);
}

/// Whether the limits are lifted (by [`set_allow_large`] or [`ALLOW_LARGE_ENV`]).
pub fn allow_large() -> bool {
    ALLOW_LARGE.load(Ordering::Relaxed)
        || std::env::var(ALLOW_LARGE_ENV).is_ok_and(|v| matches!(v.trim(), "1" | "true" | "yes"))
}

/// What a path names when it is not a regular file, for error messages (`None` for a
/// regular file).
fn kind_of(meta: &std::fs::Metadata) -> Option<&'static str> {
    let t = meta.file_type();
    if t.is_file() {
        return None;
    }
    if t.is_dir() {
        return Some("a folder");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return Some("a named pipe (FIFO)");
        }
        if t.is_char_device() {
            return Some("a character device");
        }
        if t.is_block_device() {
            return Some("a block device");
        }
        if t.is_socket() {
            return Some("a socket");
        }
    }
    Some("not a regular file")
}

/// Checks that `path` is a regular file of at most `max_bytes` (unless the limits are
/// lifted) without opening it, then reads it. `what` names the input in errors
/// ("record", "scene", …). A FIFO, a device or a folder is refused by kind
/// ([`MotionError::NotAFile`]) — opening a FIFO would block, reading `/dev/zero` never
/// ends — and a larger file by size ([`MotionError::FileTooLarge`]) before any of it is
/// read. At most `max_bytes + 1` bytes are read even if the file grows meanwhile.
pub fn read_input_file(
    path: &Path,
    what: &'static str,
    max_bytes: u64,
) -> Result<Vec<u8>, MotionError> {
    let io = |source| MotionError::Io {
        path: path.to_path_buf(),
        source,
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if let Some(kind) = kind_of(&meta) {
        return Err(MotionError::NotAFile {
            path: path.to_path_buf(),
            what,
            kind,
        });
    }
    let limit = if allow_large() { u64::MAX } else { max_bytes };
    let too_large = |size: u64| MotionError::FileTooLarge {
        path: path.to_path_buf(),
        what,
        size: bytes(size as f64),
        limit: bytes(max_bytes as f64),
    };
    if meta.len() > limit {
        return Err(too_large(meta.len()));
    }
    let file = std::fs::File::open(path).map_err(io)?;
    let mut buf = Vec::with_capacity(usize::try_from(meta.len()).unwrap_or(0).min(1 << 26));
    file.take(limit.saturating_add(1))
        .read_to_end(&mut buf)
        .map_err(io)?;
    if buf.len() as u64 > limit {
        return Err(too_large(buf.len() as u64));
    }
    Ok(buf)
}

/// [`read_input_file`] as text: bytes that are not UTF-8 are replaced.
pub fn read_input_text(
    path: &Path,
    what: &'static str,
    max_bytes: u64,
) -> Result<String, MotionError> {
    let bytes = read_input_file(path, what, max_bytes)?;
    Ok(match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
    })
}

/// Refuses a count beyond `limit` (unless the limits are lifted):
/// [`MotionError::TooMany`] names `what` and both numbers.
pub fn check_count(what: &str, count: usize, limit: usize) -> Result<(), MotionError> {
    if count <= limit || allow_large() {
        return Ok(());
    }
    Err(MotionError::TooMany {
        what: what.to_string(),
        count: count as f64,
        limit: limit as f64,
    })
}

/// Checks the number of records of a generated suite, the one rule of every front
/// (`record synth --count`, Python's `synthetic_suite(count=…)`): at least 1
/// ([`MotionError::InvalidArgument`]: a suite of none is a typo, not a study) and at most
/// [`MAX_SUITE_RECORDS`] unless the limits are lifted ([`MotionError::TooMany`]).
pub fn check_suite_count(count: usize) -> Result<(), MotionError> {
    if count == 0 {
        return Err(MotionError::InvalidArgument {
            what: "number of records",
            value: 0.0,
            expected: "at least 1",
        });
    }
    check_count("synthetic records", count, MAX_SUITE_RECORDS)
}

/// A number of bytes for people (KiB … EiB).
pub fn bytes(b: f64) -> String {
    let units = ["B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut v = b;
    let mut u = 0;
    while v >= 1024.0 && u + 1 < units.len() {
        v /= 1024.0;
        u += 1;
    }
    if u == 0 {
        format!("{v:.0} B")
    } else {
        format!("{v:.1} {}", units[u])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_folder_is_refused_by_kind() {
        let e = read_input_file(Path::new("."), "record", MAX_RECORD_BYTES).unwrap_err();
        assert!(e.to_string().contains("is a folder"), "{e}");
    }

    #[test]
    fn counts_beyond_the_limit_are_refused() {
        assert!(check_count("records", 10, 10).is_ok());
        let e = check_count("records", 11, 10).unwrap_err();
        assert!(e.to_string().contains("11 records"), "{e}");
    }
}
