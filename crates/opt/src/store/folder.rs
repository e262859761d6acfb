//! One study folder, one owner: [`StudyFolder`] is the only way a study command reaches
//! its output folder. Opening it
//! - checks the path (a folder, or nothing yet; never a file, FIFO or device), and refuses
//!   an output name that is a symbolic link (nothing is written through a link);
//! - takes the folder's one-writer lock: an exclusive OS file lock on [`LOCK_FILE`]
//!   ([`std::fs::File::try_lock`]), held until the folder is dropped. A second command into
//!   the same folder — another process, or another thread of the same process — is refused
//!   at once ([`OptError::FolderBusy`]); it never waits and never mixes its files into the
//!   first run's. The operating system releases the lock when the process ends, however it
//!   ends (a `kill -9` included), so a crashed run never leaves the folder stuck;
//! - keeps the list of the files slipload wrote there (inside the lock file, one name a
//!   line under a header), so that `fresh` removes exactly those and nothing else: a
//!   user's own file is kept and named ([`Discarded::kept`]), and a file under an output
//!   name that slipload did not write is never overwritten ([`OptError::NotWritten`]);
//! - hands the phases the paths of their journals ([`StudyFolder::journal`]) and writes
//!   every other file atomically ([`StudyFolder::write`]), adding each name to the list
//!   before the file exists.
//!
//! A folder written by an earlier slipload has no list (its lock file is empty, or absent
//! in a copy such as a clone's `results/`); where it shows that slipload wrote it (a lock
//! file, a journal or a sweep manifest), the files under slipload's output names
//! ([`is_output_name`]) are taken as slipload's, as they always were — but for the names
//! no slipload wrote before the list existed (`building.json`, `building.md`), which are
//! a user's there.

use crate::base::error::OptError;
use crate::base::output::{check_output_folder, refuse_symlink, write_atomic};
use crate::model::fingerprint::Fingerprint;
use crate::store::journal::{check_folder, is_journal_name};
use std::collections::BTreeSet;
use std::fs::{File, OpenOptions, TryLockError};
use std::io::{Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The lock file's name inside an output folder (hidden: reports and listings skip it).
/// It holds the list of the files slipload wrote in the folder.
pub const LOCK_FILE: &str = ".slipload.lock";

/// The first line of the lock file's list.
const LIST_HEADER: &str =
    "# files slipload wrote in this folder (--fresh removes these and no other)";

/// Whether `name` is a file some slipload command writes into an output folder: the
/// journals, the sweep's and `optimize`'s tables, the building the study ran
/// (`building.json`, `building.md`), the design table, the candidates, the
/// code check and the device table, the study figures (`.csv`, `.svg`, `.png`), `rank`'s and `table`'s files, the HTML
/// report, and the hidden temporary file an interrupted atomic write leaves
/// (`.NAME.tmp`).
pub fn is_output_name(name: &str) -> bool {
    if let Some(inner) = name.strip_prefix('.').and_then(|n| n.strip_suffix(".tmp")) {
        return is_output_name(inner);
    }
    is_journal_name(name)
        || OUTPUT_FILES.contains(&name)
        || name
            .rsplit_once('.')
            .is_some_and(|(stem, ext)| is_figure_stem(stem) && matches!(ext, "csv" | "svg" | "png"))
}

/// Whether `stem` names a study figure: one of [`FIGURE_STEMS`], or a per-suite figure
/// (`drift-profiles-SUITE`, `records-scatter-SUITE`;
/// [`PER_SUITE_STEMS`]).
fn is_figure_stem(stem: &str) -> bool {
    FIGURE_STEMS.contains(&stem)
        || PLAN_FIGURE_STEMS.contains(&stem)
        || PER_SUITE_STEMS.iter().any(|b| {
            stem.strip_prefix(b)
                .and_then(|rest| rest.strip_prefix('-'))
                .is_some_and(|label| !label.is_empty())
        })
}

/// The files (other than journals and figures) that slipload's study commands and its
/// report write into an output folder.
const OUTPUT_FILES: [&str; 38] = [
    "manifest.json",
    "building.json",
    "building.md",
    "pareto.csv",
    "pareto.json",
    "pareto-table.csv",
    "pareto-table.md",
    "pareto-table.json",
    "responses.csv",
    "designs.csv",
    "refine.csv",
    "optimum.json",
    "candidates.json",
    "design-table.csv",
    "design-table.md",
    "design-table.json",
    "code-check.csv",
    "code-check.md",
    "code-check.json",
    "device-table.csv",
    "device-table.md",
    "device-table.json",
    "rank.csv",
    "rank.md",
    "rank.json",
    "family.csv",
    "family.md",
    "report.html",
    "plan-journal.jsonl",
    "plan-summary.txt",
    "plan-check.md",
    "plan-optimum.json",
    "plan-designs.csv",
    "plan-dampers.csv",
    "plan-dampers.md",
    "plan-devices.csv",
    "plan-devices.md",
    "plan-profiles.csv",
];

/// Output names no slipload wrote before folders kept their list: in a folder without a
/// list they are never taken as slipload's (a `building.json` there is the user's own
/// building file, and is refused, not overwritten).
const LISTED_ONLY: [&str; 2] = ["building.json", "building.md"];

/// The study figures' names, each written as `.svg`, `.png` and `.csv`.
pub const FIGURE_STEMS: [&str; 6] = [
    "code-spectra",
    "pareto-front",
    "drift-profiles",
    "records-scatter",
    "convergence",
    "objective-map",
];

/// The figures of a study in plan, each written as `.svg`, `.png` and `.csv`.
pub const PLAN_FIGURE_STEMS: [&str; 2] = ["plan-view", "line-drift-profiles"];

/// The study figures drawn per suite where a study has several suites, each as
/// `STEM-LABEL` (the label made of the suite's name).
pub const PER_SUITE_STEMS: [&str; 2] = ["drift-profiles", "records-scatter"];

/// What `fresh` did in a folder.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Discarded {
    /// The files removed (every file slipload wrote there), sorted.
    pub removed: Vec<String>,
    /// The other files, kept (not slipload's, or not files), sorted.
    pub kept: Vec<String>,
}

/// How a command opens its output folder.
#[derive(Debug, Clone, Copy)]
pub struct FolderRequest<'a> {
    /// The folder (created when missing).
    pub path: &'a Path,
    /// The option that named it (`--out`, `out`), for the errors.
    pub option: &'a str,
    /// Remove every file slipload wrote there before the run (its journals among them).
    pub fresh: bool,
}

/// An output folder, opened for one command: locked, its list of slipload's files kept.
#[derive(Debug)]
pub struct StudyFolder {
    dir: PathBuf,
    /// The open lock file: holds the OS lock, and the list.
    lock: Mutex<File>,
    /// The files slipload wrote here (names inside the folder).
    written: Mutex<BTreeSet<String>>,
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> OptError + '_ {
    move |source| OptError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// The entries of `dir` (names), sorted; none when it does not exist.
fn listing(dir: &Path) -> Result<Vec<(String, std::fs::FileType)>, OptError> {
    let entries = match std::fs::read_dir(dir) {
        Ok(l) => l,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(source) => {
            return Err(OptError::Io {
                path: dir.to_path_buf(),
                source,
            });
        }
    };
    let mut out = Vec::new();
    for e in entries.flatten() {
        let t = e.file_type().map_err(io(&e.path()))?;
        out.push((e.file_name().to_string_lossy().into_owned(), t));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(out)
}

impl StudyFolder {
    /// Checks an output folder's path before anything runs: a folder, or nothing yet; an
    /// existing file, FIFO, device or socket is refused, naming `option`.
    pub fn check_path(option: &str, dir: &Path) -> Result<(), OptError> {
        check_output_folder(option, dir)
    }

    /// Opens the folder of `request` for one command, as the module says: checks the path,
    /// takes the lock (refused at once when held, by another process or another thread),
    /// reads the list of slipload's files, refuses output names slipload did not write,
    /// and with `fresh` removes slipload's files. Returns the folder and, with `fresh`,
    /// what was removed and kept.
    pub fn open(request: FolderRequest<'_>) -> Result<(StudyFolder, Option<Discarded>), OptError> {
        let dir = request.path;
        check_output_folder(request.option, dir)?;
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let lock_path = dir.join(LOCK_FILE);
        refuse_symlink(&lock_path)?;
        let before = listing(dir)?;
        // an output name that is a symbolic link is refused before anything runs
        if let Some((name, _)) = before
            .iter()
            .find(|(n, t)| t.is_symlink() && is_output_name(n))
        {
            refuse_symlink(&dir.join(name))?;
        }
        let had_lock = before.iter().any(|(n, _)| n == LOCK_FILE);
        let mut file = OpenOptions::new()
            .create(true)
            .truncate(false)
            .read(true)
            .write(true)
            .open(&lock_path)
            .map_err(io(&lock_path))?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                return Err(OptError::FolderBusy {
                    dir: dir.to_path_buf(),
                });
            }
            Err(TryLockError::Error(source)) => {
                return Err(OptError::Io {
                    path: lock_path,
                    source,
                });
            }
        }
        let mut text = String::new();
        std::io::Read::read_to_string(&mut file, &mut text).map_err(io(&lock_path))?;
        let present: Vec<&str> = before
            .iter()
            .filter(|(n, _)| n != LOCK_FILE)
            .map(|(n, _)| n.as_str())
            .collect();
        let mut written: BTreeSet<String> = BTreeSet::new();
        if text.starts_with(LIST_HEADER) {
            written.extend(
                text.lines()
                    .skip(1)
                    .filter(|l| !l.is_empty())
                    .map(str::to_string),
            );
        } else {
            // an earlier slipload's folder: its files are those under the output names,
            // where something shows that slipload wrote here at all
            let slipload_was_here = had_lock
                || present
                    .iter()
                    .any(|n| is_journal_name(n) || *n == "manifest.json");
            if slipload_was_here {
                written.extend(
                    present
                        .iter()
                        .filter(|n| is_output_name(n) && !LISTED_ONLY.contains(*n))
                        .map(|n| n.to_string()),
                );
            }
        }
        let folder = StudyFolder {
            dir: dir.to_path_buf(),
            lock: Mutex::new(file),
            written: Mutex::new(written),
        };
        // the list is kept from now on, even if this run is refused below: a later run
        // must not take a user's file for an earlier slipload's
        folder.save_list()?;
        // refused before `fresh` removes anything: a refused command changes nothing
        folder.refuse_foreign()?;
        let discarded = if request.fresh {
            let d = folder.discard(&before)?;
            folder.save_list()?;
            Some(d)
        } else {
            None
        };
        Ok((folder, discarded))
    }

    /// The folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// `name` inside the folder.
    pub fn path(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }

    fn written(&self) -> std::sync::MutexGuard<'_, BTreeSet<String>> {
        self.written.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// The files slipload wrote (or is about to write) in the folder, sorted.
    pub fn files(&self) -> Vec<String> {
        self.written().iter().cloned().collect()
    }

    /// Whether `name` is a file slipload wrote in this folder.
    pub fn wrote(&self, name: &str) -> bool {
        self.written().contains(name)
    }

    /// Adds `names` to the list of slipload's files (before they are written, so that an
    /// interrupted write still leaves them slipload's).
    pub fn claim<S: AsRef<str>>(&self, names: &[S]) -> Result<(), OptError> {
        // the list keeps one name a line: a name that would split or hide a line is refused
        if let Some(bad) = names
            .iter()
            .map(AsRef::as_ref)
            .find(|n| n.is_empty() || n.chars().any(char::is_control) || n.contains('/'))
        {
            return Err(OptError::Argument(format!(
                "{bad:?} in {}: an output file's name holds no control character or '/': give a plain file name",
                self.dir.display()
            )));
        }
        let changed = {
            let mut w = self.written();
            let mut changed = false;
            for n in names {
                changed |= w.insert(n.as_ref().to_string());
            }
            changed
        };
        if changed { self.save_list() } else { Ok(()) }
    }

    /// The path of the journal `name` (`journal.jsonl`, `check.jsonl`, …), claimed as
    /// slipload's (refused, as [`StudyFolder::write`] is, when a file slipload did not
    /// write is there under that name).
    pub fn journal(&self, name: &str) -> Result<PathBuf, OptError> {
        self.refuse_unlisted(name)?;
        self.claim(&[name])?;
        Ok(self.path(name))
    }

    /// Checks every journal of the folder against the study's fingerprint `fp`: one
    /// written for another study (or without a fingerprint) is refused, naming what
    /// changed ([`crate::store::journal::check_folder`]).
    pub fn check_journals(&self, fp: &Fingerprint) -> Result<(), OptError> {
        check_folder(&self.dir, fp)
    }

    /// Writes `bytes` to the file `name` of the folder atomically
    /// ([`crate::base::output::write_atomic`]), claimed as slipload's first. A file
    /// already there under `name` that slipload did not write is refused
    /// ([`OptError::NotWritten`]), never overwritten.
    pub fn write(&self, name: &str, bytes: &[u8]) -> Result<(), OptError> {
        self.refuse_unlisted(name)?;
        self.claim(&[name])?;
        write_atomic(&self.path(name), bytes)
    }

    /// Claims the figure files a figure writer may write (every stem of
    /// [`FIGURE_STEMS`] and the per-suite stems `suite_stems` as `.svg`, `.png`, `.csv`).
    pub fn claim_figures(&self, suite_stems: &[String]) -> Result<(), OptError> {
        let names: Vec<String> = FIGURE_STEMS
            .iter()
            .copied()
            .chain(suite_stems.iter().map(String::as_str))
            .flat_map(|s| ["svg", "png", "csv"].map(|e| format!("{s}.{e}")))
            .collect();
        // a name of the list that holds a user's file is refused, not claimed
        let foreign: Vec<&String> = names
            .iter()
            .filter(|n| !self.wrote(n) && std::fs::symlink_metadata(self.path(n)).is_ok())
            .collect();
        if !foreign.is_empty() {
            return Err(not_written(&self.dir, &foreign));
        }
        self.claim(&names)
    }

    /// Refuses `name` when something is there under it that slipload did not write (a
    /// user's own file under a name a command writes).
    fn refuse_unlisted(&self, name: &str) -> Result<(), OptError> {
        let owned = name.to_string();
        if !self.wrote(name) && std::fs::symlink_metadata(self.path(name)).is_ok() {
            return Err(not_written(&self.dir, &[&owned]));
        }
        Ok(())
    }

    /// Refuses files under slipload's output names that slipload did not write here.
    fn refuse_foreign(&self) -> Result<(), OptError> {
        let present = listing(&self.dir)?;
        let foreign: Vec<&String> = present
            .iter()
            .map(|(n, _)| n)
            .filter(|n| is_output_name(n) && !n.starts_with('.') && !self.wrote(n))
            .collect();
        if foreign.is_empty() {
            Ok(())
        } else {
            Err(not_written(&self.dir, &foreign))
        }
    }

    /// Writes the list into the lock file (the lock is held: no one else writes it).
    fn save_list(&self) -> Result<(), OptError> {
        let mut text = String::from(LIST_HEADER);
        text.push('\n');
        for n in self.written().iter() {
            text.push_str(n);
            text.push('\n');
        }
        let lock_path = self.path(LOCK_FILE);
        let mut f = self.lock.lock().unwrap_or_else(|p| p.into_inner());
        (|| -> std::io::Result<()> {
            f.set_len(0)?;
            f.seek(SeekFrom::Start(0))?;
            f.write_all(text.as_bytes())?;
            f.flush()
        })()
        .map_err(io(&lock_path))
    }

    /// `fresh`: removes every file of the list (and the temporary files an interrupted
    /// atomic write of one leaves), names every other entry as kept, and empties the list.
    fn discard(&self, before: &[(String, std::fs::FileType)]) -> Result<Discarded, OptError> {
        let mut out = Discarded::default();
        let listed = self.files();
        for (name, t) in before {
            if name == LOCK_FILE {
                continue;
            }
            let ours = listed.contains(name)
                || name
                    .strip_prefix('.')
                    .and_then(|n| n.strip_suffix(".tmp"))
                    .is_some_and(is_output_name);
            if !ours {
                out.kept.push(name.clone());
                continue;
            }
            let path = self.path(name);
            // a file or a symbolic link of the list is removed (the link, never its
            // target); anything else under such a name is refused here, so that no later
            // error asks for the --fresh that was given
            if !(t.is_file() || t.is_symlink()) {
                return Err(OptError::Argument(format!(
                    "--fresh: {} is {}, not a file slipload wrote: remove it by hand or choose another --out",
                    path.display(),
                    if t.is_dir() {
                        "a folder"
                    } else {
                        "not a regular file (a FIFO, device or socket)"
                    }
                )));
            }
            std::fs::remove_file(&path).map_err(io(&path))?;
            out.removed.push(name.clone());
        }
        self.written().clear();
        Ok(out)
    }
}

fn not_written(dir: &Path, names: &[&String]) -> OptError {
    OptError::NotWritten {
        dir: dir.to_path_buf(),
        names: names
            .iter()
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        them: if names.len() == 1 { "it" } else { "them" },
    }
}

/// Checks that no command is writing into the folder `dir` that a command only reads (a
/// shard folder given to `merge`): refused when its lock is held. A folder without a lock
/// file (never written by a running command) passes; nothing is created.
pub fn check_idle(dir: &Path) -> Result<(), OptError> {
    let path = dir.join(LOCK_FILE);
    let Ok(file) = File::open(&path) else {
        return Ok(());
    };
    match file.try_lock_shared() {
        Ok(()) => Ok(()),
        Err(TryLockError::WouldBlock) => Err(OptError::FolderBusy {
            dir: dir.to_path_buf(),
        }),
        Err(TryLockError::Error(source)) => Err(OptError::Io { path, source }),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
    use super::*;

    #[test]
    fn the_list_keeps_one_plain_name_a_line() {
        let dir = std::env::temp_dir().join(format!("slipload-folder-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let request = FolderRequest {
            path: &dir,
            option: "out",
            fresh: false,
        };
        let (folder, _) = StudyFolder::open(request).unwrap();
        folder.write("a.csv", b"x\n").unwrap();
        // a name that would split a line of the list (and so name another file) is refused
        for bad in ["b.html\nnotes.txt", "", "sub/c.csv", "d\r.csv"] {
            assert!(folder.claim(&[bad]).is_err(), "{bad:?} was claimed");
        }
        drop(folder);
        let (again, _) = StudyFolder::open(request).unwrap();
        assert_eq!(again.files(), vec!["a.csv".to_string()]);
        // a second opening while the first holds the folder is refused, in one process too
        assert!(matches!(
            StudyFolder::open(request),
            Err(OptError::FolderBusy { .. })
        ));
        drop(again);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_file_slipload_did_not_write_is_never_written_over() {
        let dir = std::env::temp_dir().join(format!("slipload-unlisted-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let request = FolderRequest {
            path: &dir,
            option: "out",
            fresh: false,
        };
        let (folder, _) = StudyFolder::open(request).unwrap();
        folder.write("table.md", b"slipload's\n").unwrap();
        // a user's file appears under a name the run is about to write (not one of the
        // output names the opening refuses): the write and the journal are refused
        std::fs::write(dir.join("mine.md"), "the user's").unwrap();
        let e = folder.write("mine.md", b"over").unwrap_err();
        assert!(matches!(e, OptError::NotWritten { .. }), "{e}");
        assert!(e.to_string().contains("mine.md"), "{e}");
        assert!(folder.journal("mine.md").is_err());
        assert_eq!(
            std::fs::read_to_string(dir.join("mine.md")).unwrap(),
            "the user's"
        );
        assert!(!folder.wrote("mine.md"));
        // slipload's own file is rewritten
        folder.write("table.md", b"again\n").unwrap();
        assert_eq!(
            std::fs::read_to_string(dir.join("table.md")).unwrap(),
            "again\n"
        );
        drop(folder);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
