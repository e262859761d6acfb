//! Output files, written whole or not at all: every file slipload writes outside the
//! append-only journals (the sweep's tables, `optimum.json`, `refine.csv`, the design
//! tables, rankings, figures, histories) goes through [`write_atomic`] — a temporary
//! file in the same folder, synced, then renamed — so an interrupted run never leaves a
//! partial file under the final name.

use crate::base::error::OptError;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Refuses `path` when it is a symbolic link ([`OptError::Symlink`]): an output is
/// never written through a link (it could point anywhere — another study's file, a
/// system file). A missing path, or anything else, passes.
pub fn refuse_symlink(path: &Path) -> Result<(), OptError> {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => Err(OptError::Symlink {
            path: path.to_path_buf(),
            target: std::fs::read_link(path).unwrap_or_default(),
        }),
        _ => Ok(()),
    }
}

/// Where an atomic write of `path` goes: `path` itself when it is missing or a regular
/// file; an error for a symbolic link (never written through: [`refuse_symlink`]) and
/// for anything else (a FIFO, a device node, a socket, a folder), which a rename would
/// replace — the write must reach a file or not happen.
pub fn write_target(path: &Path) -> Result<PathBuf, OptError> {
    let meta = match std::fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(path.to_path_buf()),
        Err(source) => {
            return Err(OptError::Io {
                path: path.to_path_buf(),
                source,
            });
        }
    };
    if meta.file_type().is_symlink() {
        refuse_symlink(path)?;
    }
    if meta.file_type().is_file() {
        Ok(path.to_path_buf())
    } else {
        Err(OptError::NotRegular {
            path: path.to_path_buf(),
            kind: kind_of(&meta.file_type()),
        })
    }
}

fn kind_of(t: &std::fs::FileType) -> String {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO (named pipe)".into();
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device node".into();
        }
        if t.is_socket() {
            return "a socket".into();
        }
    }
    if t.is_dir() {
        "a folder".into()
    } else {
        "not a regular file".into()
    }
}

/// Writes `bytes` to `path` atomically: a temporary file in the same folder, `sync_all`,
/// rename. An interrupted run never leaves a partial file under the final name. A
/// symbolic link, a FIFO, a device or a folder is refused ([`write_target`]).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OptError> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir).map_err(|source| OptError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let target = write_target(path)?;
    let io = |source| OptError::Write {
        path: target.clone(),
        source,
    };
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| OptError::NotRegular {
            path: path.to_path_buf(),
            kind: "not a file path".into(),
        })?;
    let tmp = dir.join(format!(".{name}.tmp"));
    let result = (|| -> std::io::Result<()> {
        let mut f = File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, &target)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(io)
}

/// Checks an output folder before anything runs: a folder, or nothing yet (it is created);
/// an existing file, FIFO, device or socket is refused. `what` names the option that gave
/// it (`--out`, `out`).
pub fn check_output_folder(what: &str, dir: &Path) -> Result<(), OptError> {
    match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => Ok(()),
        Ok(m) => Err(OptError::Argument(format!(
            "{what} {}: {} is {}, not a folder: give a folder (created if missing) for the output files",
            dir.display(),
            dir.display(),
            if m.is_file() {
                "an existing file"
            } else {
                "not a regular folder (a FIFO, device or socket)"
            }
        ))),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(source) => Err(OptError::Io {
            path: dir.to_path_buf(),
            source,
        }
        .context(format!("{what} {}", dir.display()))),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
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
