//! Output files, written whole or not at all: every file slipload writes outside the
//! append-only journals (the sweep's tables, `optimum.json`, `refine.csv`, the design
//! tables, rankings, figures, histories) goes through [`write_atomic`] — a temporary
//! file in the same folder, synced, then renamed — so an interrupted run never leaves a
//! partial file under the final name.

use crate::error::OptError;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Where an atomic write of `path` goes: `path` itself when it is missing or a regular
/// file, the final target of a symbolic link (written through: the link is kept), and an
/// error for anything else (a FIFO, a device node, a socket, a folder), which a rename
/// would replace — the write must reach a file or not happen.
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
    let target = if meta.file_type().is_symlink() {
        let resolved = std::fs::canonicalize(path).map_err(|_| OptError::NotRegular {
            path: path.to_path_buf(),
            kind: "a symbolic link whose target does not exist".into(),
        })?;
        let m = std::fs::metadata(&resolved).map_err(|source| OptError::Io {
            path: resolved.clone(),
            source,
        })?;
        if !m.file_type().is_file() {
            return Err(OptError::NotRegular {
                path: path.to_path_buf(),
                kind: format!(
                    "a symbolic link to {}, {}",
                    resolved.display(),
                    kind_of(&m.file_type())
                ),
            });
        }
        resolved
    } else if meta.file_type().is_file() {
        path.to_path_buf()
    } else {
        return Err(OptError::NotRegular {
            path: path.to_path_buf(),
            kind: kind_of(&meta.file_type()),
        });
    };
    Ok(target)
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
/// symbolic link is written through; a FIFO, device or folder is refused
/// ([`write_target`]).
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
