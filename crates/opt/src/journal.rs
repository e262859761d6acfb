//! The append-only journal of finished (design, record) tasks (`journal.jsonl`, one JSON
//! object per line) and atomic output files.
//!
//! A run appends each task as it finishes; `--resume` reads the finished keys and runs
//! only the rest. A torn last line (a crash mid-write) is ignored and cut off before new
//! lines are appended. Each line carries the design's slip loads and the record's name,
//! so a journal from a changed study is recognised instead of silently mixed in.

use crate::error::OptError;
use crate::metrics::RecordMetrics;
use serde::{Deserialize, Serialize};
use std::fs::{File, OpenOptions};
use std::io::{LineWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// One finished task.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Entry {
    /// Design index in the manifest.
    pub design: usize,
    /// Record index in the manifest.
    pub record: usize,
    /// The record's name.
    pub record_name: String,
    /// The design's slip loads, N per dissipator.
    pub slip_loads_n: Vec<f64>,
    /// The responses.
    pub metrics: RecordMetrics,
}

/// An open journal, appended to from worker threads.
#[derive(Debug)]
pub struct Journal {
    path: PathBuf,
    writer: Mutex<LineWriter<File>>,
}

/// Reads a journal; a last line that does not parse (torn write) is dropped. Returns the
/// entries and the byte length of the intact part.
pub fn read(path: &Path) -> Result<(Vec<Entry>, u64), OptError> {
    read_lines(path)
}

/// Reads a file of one JSON `T` per line; a last line that does not parse (torn write)
/// is dropped. Returns the values and the byte length of the intact part.
pub fn read_lines<T: serde::de::DeserializeOwned>(path: &Path) -> Result<(Vec<T>, u64), OptError> {
    let text = match std::fs::read(path) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok((Vec::new(), 0)),
        Err(source) => {
            return Err(OptError::Io {
                path: path.to_path_buf(),
                source,
            });
        }
    };
    let mut entries = Vec::new();
    let mut good = 0u64;
    let mut pos = 0usize;
    let mut line_no = 0usize;
    while pos < text.len() {
        line_no += 1;
        let end = text[pos..]
            .iter()
            .position(|&b| b == b'\n')
            .map(|i| pos + i);
        let (line, next, complete) = match end {
            Some(e) => (&text[pos..e], e + 1, true),
            None => (&text[pos..], text.len(), false),
        };
        let parsed = std::str::from_utf8(line)
            .ok()
            .and_then(|l| serde_json::from_str::<T>(l).ok());
        match parsed {
            Some(e) if complete => {
                entries.push(e);
                good = next as u64;
            }
            _ if next == text.len() => break, // torn last line
            _ => {
                return Err(OptError::Journal {
                    path: path.to_path_buf(),
                    line: line_no,
                    message: "not a journal entry (only the last line may be torn)".into(),
                });
            }
        }
        pos = next;
    }
    Ok((entries, good))
}

impl Journal {
    /// Opens `path` for appending. Without `resume` an existing non-empty journal is an
    /// error (its results would be mixed with a new run's); with `resume` its entries are
    /// returned and a torn last line is cut off.
    pub fn open(path: &Path, resume: bool) -> Result<(Journal, Vec<Entry>), OptError> {
        let io = |source| OptError::Io {
            path: path.to_path_buf(),
            source,
        };
        let (entries, good) = if resume {
            read(path)?
        } else {
            if std::fs::metadata(path)
                .map(|m| m.len() > 0)
                .unwrap_or(false)
            {
                return Err(OptError::Journal {
                    path: path.to_path_buf(),
                    line: 1,
                    message: "a journal of an earlier run is here: pass --resume to continue it, or choose another --out".into(),
                });
            }
            (Vec::new(), 0)
        };
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(io)?;
        }
        let file = OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(path)
            .map_err(io)?;
        file.set_len(good).map_err(io)?;
        let file = OpenOptions::new().append(true).open(path).map_err(io)?;
        Ok((
            Journal {
                path: path.to_path_buf(),
                writer: Mutex::new(LineWriter::new(file)),
            },
            entries,
        ))
    }

    /// Appends one entry as one line (written whole before the call returns).
    pub fn append(&self, e: &Entry) -> Result<(), OptError> {
        let mut line = serde_json::to_string(e).map_err(|source| OptError::Json {
            path: self.path.clone(),
            source,
        })?;
        line.push('\n');
        let mut w = self
            .writer
            .lock()
            .map_err(|_| OptError::Shard("journal lock poisoned by a failed worker".into()))?;
        w.write_all(line.as_bytes()).map_err(|source| OptError::Io {
            path: self.path.clone(),
            source,
        })
    }
}

/// Writes `bytes` to `path` atomically: a temporary file in the same folder, `sync_all`,
/// rename. An interrupted run never leaves a partial file under the final name.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OptError> {
    let io = |source| OptError::Io {
        path: path.to_path_buf(),
        source,
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir).map_err(io)?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let tmp = dir.join(format!(".{name}.tmp"));
    let result = (|| -> std::io::Result<()> {
        let mut f = File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(io)
}
