//! Append-only journals (`journal.jsonl` of finished (design, record) tasks,
//! `refine-METHOD.jsonl`, `check.jsonl`; one JSON object per line). Whole files (the
//! merged journal among them) are written by [`crate::base::output::write_atomic`].
//!
//! The first line of a journal is its [`Header`]: its kind and the fingerprint of the
//! study that wrote it ([`crate::model::fingerprint`]). A journal is continued only by a study
//! with the same fingerprint; any other is refused with the components that changed. A
//! run appends each task as it finishes; `--resume` reads the finished keys and runs
//! only the rest. A torn last line (a crash mid-write) is ignored and cut off before new
//! lines are appended. Each sweep line also carries the design's slip loads and the
//! record's name, checked against the manifest.
//!
//! Every line ends with its checksum: the line's JSON object written without it, then
//! `,"crc32":"xxxxxxxx"}` — the CRC-32 (IEEE) of that object's bytes, in hex; an entry's
//! CRC runs over the study's fingerprint hash (the header's) before the object's bytes,
//! so that each line identifies the study that wrote it: a line pasted from another
//! study's journal (the same design and record under another record scaling, say) fails
//! its checksum here. A line whose checksum fails (a flipped bit, a line spliced from
//! another file or another study) is not
//! trusted: it is skipped and its task runs again (`--resume` recomputes it). A line
//! without a checksum, as slipload wrote before checksums, is treated the same way: a
//! journal of an older slipload is continued by recomputing its tasks, never by trusting
//! them. A line that is no journal entry at all, other than the last, is refused with
//! how to recover (delete that line, or `--fresh`).

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::model::fingerprint::Fingerprint;
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

/// The first line of every journal: what kind it is and the fingerprint of the study
/// that wrote it ([`crate::model::fingerprint`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Header {
    /// `sweep`, `refine` or `check`.
    pub journal: String,
    /// The writing study's fingerprint.
    pub fingerprint: Fingerprint,
}

/// What to do with a journal of the same study found in place.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reuse {
    /// Continue it (`--resume`; `optimize` always).
    Resume,
    /// Refuse it: a run without `--resume` must not mix into an earlier one.
    Refuse,
}

/// An open journal, appended to from worker threads.
#[derive(Debug)]
pub struct Appender {
    path: PathBuf,
    writer: Mutex<LineWriter<File>>,
    distrusted: usize,
    /// The study's fingerprint hash each entry's checksum runs over.
    seed: String,
}

impl Appender {
    /// Appends one value as one line with its checksum ([`checked_line`]), written whole
    /// before the call returns.
    pub fn append<T: Serialize>(&self, value: &T) -> Result<(), OptError> {
        let mut line = seeded_line(value, &self.seed).map_err(|source| OptError::Json {
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

    /// The journal's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Complete lines found in the journal when it was opened whose checksum failed or
    /// was missing: not trusted, so their tasks run again.
    pub fn distrusted(&self) -> usize {
        self.distrusted
    }
}

/// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320) of `bytes`: the checksum of a
/// journal line.
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 != 0 {
                (c >> 1) ^ 0xEDB8_8320
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// What a line's checksum field is spelt as: `,"crc32":"` before 8 hex digits and `"}`.
const CRC_TAG: &[u8] = b",\"crc32\":\"";

/// One value as a journal line (no newline): its JSON object, with the CRC-32 of that
/// object's bytes appended as a last field `crc32` (8 lowercase hex digits).
pub fn checked_line<T: Serialize>(value: &T) -> Result<String, serde_json::Error> {
    let body = serde_json::to_string(value)?;
    let crc = crc32(body.as_bytes());
    let open = body.strip_suffix('}').unwrap_or(&body);
    Ok(format!("{open},\"crc32\":\"{crc:08x}\"}}"))
}

/// An entry of the study of fingerprint hash `seed` as a journal line: as
/// [`checked_line`], with the CRC-32 over `seed`'s bytes and then the object's, so the
/// line checks only in a journal of that study.
pub fn seeded_line<T: Serialize>(value: &T, seed: &str) -> Result<String, serde_json::Error> {
    let body = serde_json::to_string(value)?;
    let mut bytes = seed.as_bytes().to_vec();
    bytes.extend_from_slice(body.as_bytes());
    let crc = crc32(&bytes);
    let open = body.strip_suffix('}').unwrap_or(&body);
    Ok(format!("{open},\"crc32\":\"{crc:08x}\"}}"))
}

/// What one complete journal line holds.
enum Line<T> {
    /// Its checksum holds: the value.
    Trusted(T),
    /// An entry whose checksum fails or is missing: not trusted, its task runs again.
    Untrusted,
    /// No journal entry at all.
    NotEntry,
}

fn check_line<T: serde::de::DeserializeOwned>(line: &[u8], seed: &str) -> Line<T> {
    let parse = |b: &[u8]| {
        std::str::from_utf8(b)
            .ok()
            .and_then(|l| serde_json::from_str::<T>(l).ok())
    };
    let at = line.windows(CRC_TAG.len()).rposition(|w| w == CRC_TAG);
    let Some(at) = at else {
        // no checksum: an older slipload's line (recomputed), or not an entry
        return match parse(line) {
            Some(_) => Line::Untrusted,
            None => Line::NotEntry,
        };
    };
    let rest = &line[at + CRC_TAG.len()..];
    let want = (rest.len() == 10 && &rest[8..] == b"\"}")
        .then(|| std::str::from_utf8(&rest[..8]).ok())
        .flatten()
        .and_then(|h| u32::from_str_radix(h, 16).ok());
    let mut body = line[..at].to_vec();
    body.push(b'}');
    let mut seeded = seed.as_bytes().to_vec();
    seeded.extend_from_slice(&body);
    if want != Some(crc32(&seeded)) {
        return Line::Untrusted;
    }
    match parse(&body) {
        Some(v) => Line::Trusted(v),
        None => Line::NotEntry,
    }
}

/// An open sweep journal (`journal.jsonl`).
#[derive(Debug)]
pub struct Journal(Appender);

/// Reads a sweep journal: its entries (the header line skipped) and the byte length of
/// the intact part. A missing file has none.
pub fn read(path: &Path) -> Result<(Vec<Entry>, u64), OptError> {
    Ok(match read_journal::<Entry>(path)? {
        Some((_, entries, good)) => (entries, good),
        None => (Vec::new(), 0),
    })
}

/// The bytes of a journal; a FIFO, device or folder under its name is an error of kind
/// `InvalidInput` instead of a read that blocks or never ends.
fn read_journal_bytes(path: &Path) -> std::io::Result<Vec<u8>> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a regular file (a folder, FIFO or device under a journal's name): remove it or choose another --out",
        ));
    }
    std::fs::read(path)
}

/// The message for a journal that cannot be checked or belongs to another study.
fn refuse(path: &Path, line: usize, why: String) -> OptError {
    OptError::Journal {
        path: path.to_path_buf(),
        line,
        message: format!(
            "{why}; its results cannot be reused: pass --fresh to discard this folder's journals and the files built from them and start afresh, or choose another --out"
        ),
    }
}

/// Reads a journal with its header: `None` for a missing or empty file (or one whose
/// only line, the header, is torn), else the header, the entries and the byte length of
/// the intact part (a torn last line is dropped).
pub fn read_journal<T: serde::de::DeserializeOwned>(
    path: &Path,
) -> Result<Option<(Header, Vec<T>, u64)>, OptError> {
    Ok(read_journal_counted(path)?.map(|(h, e, good, _)| (h, e, good)))
}

/// A journal read whole: its header, trusted entries, the byte length of the intact
/// part and the number of complete lines not trusted.
type Counted<T> = (Header, Vec<T>, u64, usize);

/// As [`read_journal`], also counting the complete lines not trusted (checksum failed
/// or missing).
fn read_journal_counted<T: serde::de::DeserializeOwned>(
    path: &Path,
) -> Result<Option<Counted<T>>, OptError> {
    let text = match read_journal_bytes(path) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(source) => {
            return Err(OptError::Io {
                path: path.to_path_buf(),
                source,
            });
        }
    };
    let Some(nl) = text.iter().position(|&b| b == b'\n') else {
        // empty, or a header torn by a crash before anything else was written
        if text.is_empty() || text.starts_with(b"{\"journal\"") {
            return Ok(None);
        }
        return Err(refuse(
            path,
            1,
            "has no study fingerprint (written by an older slipload, or not a journal)".into(),
        ));
    };
    let first = &text[..nl];
    let header: Header = match check_line::<Header>(first, "") {
        Line::Trusted(h) => h,
        // a header written before line checksums: it names the study all the same
        Line::Untrusted if !first.windows(CRC_TAG.len()).any(|w| w == CRC_TAG) => {
            serde_json::from_slice(first).map_err(|_| {
                refuse(
                    path,
                    1,
                    "has no study fingerprint on its first line (written by an older slipload, or not a journal)".into(),
                )
            })?
        }
        Line::Untrusted => {
            // an entry where the header belongs (its checksum runs over a study's
            // fingerprint, so it fails as a header's): no header at all
            let header_like = std::str::from_utf8(first)
                .ok()
                .and_then(|l| serde_json::from_str::<serde_json::Value>(l).ok())
                .is_some_and(|v| v.get("journal").is_some());
            return Err(refuse(
                path,
                1,
                if header_like {
                    "has a damaged first line (its checksum fails)".into()
                } else {
                    "has no study fingerprint on its first line (written by an older slipload, or not a journal)".into()
                },
            ));
        }
        Line::NotEntry => {
            return Err(refuse(
                path,
                1,
                "has no study fingerprint on its first line (written by an older slipload, or not a journal)".into(),
            ));
        }
    };
    let (entries, good, distrusted) =
        parse_lines::<T>(&text[nl + 1..], path, 1, &header.fingerprint.hash)?;
    Ok(Some((header, entries, good + nl as u64 + 1, distrusted)))
}

/// Reads a file of one JSON `T` per line; a last line that does not parse (torn write)
/// is dropped. Returns the values and the byte length of the intact part.
pub fn read_lines<T: serde::de::DeserializeOwned>(path: &Path) -> Result<(Vec<T>, u64), OptError> {
    let text = match read_journal_bytes(path) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok((Vec::new(), 0)),
        Err(source) => {
            return Err(OptError::Io {
                path: path.to_path_buf(),
                source,
            });
        }
    };
    parse_lines(&text, path, 0, "").map(|(e, good, _)| (e, good))
}

/// Entries of a journal with a header (the header skipped); none for a missing file.
pub fn read_entries<T: serde::de::DeserializeOwned>(path: &Path) -> Result<Vec<T>, OptError> {
    Ok(read_journal::<T>(path)?
        .map(|(_, e, _)| e)
        .unwrap_or_default())
}

/// One JSON `T` per line of `text`, whose first line is line `skipped + 1` of the file,
/// each checked against `seed` ([`seeded_line`]).
fn parse_lines<T: serde::de::DeserializeOwned>(
    text: &[u8],
    path: &Path,
    skipped: usize,
    seed: &str,
) -> Result<(Vec<T>, u64, usize), OptError> {
    let mut distrusted = 0;
    let mut entries = Vec::new();
    let mut good = 0u64;
    let mut pos = 0usize;
    let mut line_no = skipped;
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
        match check_line::<T>(line, seed) {
            Line::Trusted(e) if complete => {
                entries.push(e);
                good = next as u64;
            }
            // a complete line that fails its checksum: kept in the file, not trusted
            Line::Untrusted if complete => {
                good = next as u64;
                distrusted += 1;
            }
            _ if next == text.len() => break, // torn last line
            _ => {
                return Err(OptError::Journal {
                    path: path.to_path_buf(),
                    line: line_no,
                    message: format!(
                        "not a journal entry (only the last line may be torn): the journal is damaged; to recover, delete line {line_no} (--resume then runs its task again) or pass --fresh to discard the folder's journals and the files built from them and start afresh"
                    ),
                });
            }
        }
        pos = next;
    }
    Ok((entries, good, distrusted))
}

/// Opens the journal `path` of kind `kind` for a study of fingerprint `fp`. A missing
/// or empty journal is started with its header. An existing one must carry the same
/// kind and fingerprint — otherwise it is refused, naming what changed — and is then
/// continued (`Reuse::Resume`: its entries are returned, a torn last line cut off) or
/// refused (`Reuse::Refuse`).
pub fn open_journal<T: serde::de::DeserializeOwned>(
    path: &Path,
    kind: &str,
    fp: &Fingerprint,
    reuse: Reuse,
) -> Result<(Appender, Vec<T>), OptError> {
    let io = |source| OptError::Io {
        path: path.to_path_buf(),
        source,
    };
    crate::base::output::refuse_symlink(path)?;
    let found = read_journal_counted::<T>(path)?;
    let (entries, good, distrusted) = match found {
        None => (Vec::new(), 0, 0),
        Some((header, entries, good, distrusted)) => {
            if header.journal != kind {
                return Err(refuse(
                    path,
                    1,
                    format!("is a {} journal, not a {kind} journal", header.journal),
                ));
            }
            if header.fingerprint != *fp {
                return Err(refuse(
                    path,
                    1,
                    format!(
                        "was written for another study (fingerprint {}, this study's {}): the study changed since: {}",
                        header.fingerprint.hash,
                        fp.hash,
                        fp.describe_changes(&header.fingerprint)
                    ),
                ));
            }
            if reuse == Reuse::Refuse && !entries.is_empty() {
                return Err(OptError::Journal {
                    path: path.to_path_buf(),
                    line: 1,
                    message: "a journal of an earlier run of this study is here: pass --resume to continue it, --fresh to start afresh, or choose another --out".into(),
                });
            }
            (entries, good, distrusted)
        }
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
    let appender = Appender {
        path: path.to_path_buf(),
        writer: Mutex::new(LineWriter::new(file)),
        distrusted,
        seed: fp.hash.clone(),
    };
    if good == 0 {
        // the header's own checksum is unseeded: it is what names the study
        let mut line = checked_line(&Header {
            journal: kind.to_string(),
            fingerprint: fp.clone(),
        })
        .map_err(|source| OptError::Json {
            path: path.to_path_buf(),
            source,
        })?;
        line.push('\n');
        let mut w = appender
            .writer
            .lock()
            .map_err(|_| OptError::Shard("journal lock poisoned by a failed worker".into()))?;
        w.write_all(line.as_bytes()).map_err(io)?;
    }
    Ok((appender, entries))
}

/// The text of a whole journal: header line, then one line per value.
pub fn journal_text<T: Serialize>(kind: &str, fp: &Fingerprint, values: &[T]) -> String {
    let header = Header {
        journal: kind.to_string(),
        fingerprint: fp.clone(),
    };
    let mut s = checked_line(&header).expect("a header serialises");
    s.push('\n');
    for v in values {
        s.push_str(&seeded_line(v, &fp.hash).expect("an entry serialises"));
        s.push('\n');
    }
    s
}

/// The journals `slipload` keeps in an output folder: `journal.jsonl` (sweep),
/// `refine-METHOD.jsonl`, `check.jsonl`, `pareto.jsonl` (the front's search).
pub fn is_journal_name(name: &str) -> bool {
    name == "journal.jsonl"
        || name == "check.jsonl"
        || name == "pareto.jsonl"
        || (name.starts_with("refine-") && name.ends_with(".jsonl"))
}

/// Checks every journal of `dir` against the study's fingerprint `fp`: one written for
/// another study (or without a fingerprint) is refused, naming what changed.
pub fn check_folder(dir: &Path, fp: &Fingerprint) -> Result<(), OptError> {
    let Ok(listing) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    let mut paths: Vec<PathBuf> = listing
        .flatten()
        .filter(|e| is_journal_name(&e.file_name().to_string_lossy()))
        .map(|e| e.path())
        .collect();
    paths.sort();
    for path in paths {
        if let Some((header, _, _)) = read_journal::<serde::de::IgnoredAny>(&path)?
            && header.fingerprint != *fp
        {
            return Err(refuse(
                &path,
                1,
                format!(
                    "was written for another study (fingerprint {}, this study's {}): the study changed since: {}",
                    header.fingerprint.hash,
                    fp.hash,
                    fp.describe_changes(&header.fingerprint)
                ),
            ));
        }
    }
    Ok(())
}

impl Journal {
    /// Opens the sweep journal `path` for a study of fingerprint `fp` (see
    /// [`open_journal`]): without `resume` an existing journal of the same study is an
    /// error (its results would be mixed with a new run's); a journal of another study is
    /// always an error.
    pub fn open(
        path: &Path,
        fp: &Fingerprint,
        resume: bool,
    ) -> Result<(Journal, Vec<Entry>), OptError> {
        let reuse = if resume { Reuse::Resume } else { Reuse::Refuse };
        let (a, entries) = open_journal(path, "sweep", fp, reuse)?;
        Ok((Journal(a), entries))
    }

    /// Appends one entry as one line (written whole before the call returns).
    pub fn append(&self, e: &Entry) -> Result<(), OptError> {
        self.0.append(e)
    }

    /// Lines found not trusted when the journal was opened ([`Appender::distrusted`]).
    pub fn distrusted(&self) -> usize {
        self.0.distrusted()
    }
}
