//! One study folder, one writer: every command that writes into an output folder
//! (`sweep`, `optimize`, `merge`, `rank`, `table`) first takes an exclusive OS file lock
//! ([`std::fs::File::try_lock`]) on the folder's lock file [`LOCK_FILE`], and holds it
//! until it has written its last file. A second command into the same folder is refused
//! at once, saying the folder is in use; it never waits and never mixes its files into
//! the first run's.
//!
//! The lock belongs to the open file, not to the file's existence: the operating system
//! releases it when the process ends, however it ends (a `kill -9` included), so a
//! crashed run never leaves the folder stuck. The lock file itself stays (empty) and is
//! reused by the next run.
//!
//! Within one process the lock is re-entrant: a command that takes it and then calls a
//! library entry point that takes it again shares the one lock.

use crate::error::OptError;
use std::fs::{File, OpenOptions, TryLockError};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, Weak};

/// The lock file's name inside an output folder (hidden: reports and listings skip it).
pub const LOCK_FILE: &str = ".slipload.lock";

#[derive(Debug)]
struct Held {
    // the open file holds the OS lock; dropping it releases the lock
    _file: File,
}

/// Locks held by this process, by canonical folder path (re-entrancy).
static HELD: Mutex<Vec<(PathBuf, Weak<Held>)>> = Mutex::new(Vec::new());

/// An exclusive lock on an output folder, held until dropped.
#[derive(Debug, Clone)]
pub struct FolderLock {
    _held: Arc<Held>,
}

fn busy(dir: &Path) -> OptError {
    OptError::FolderBusy {
        dir: dir.to_path_buf(),
    }
}

impl FolderLock {
    /// Takes the lock of the output folder `dir` (created if missing), or refuses at once
    /// ([`OptError::FolderBusy`]) when another process holds it.
    pub fn acquire(dir: &Path) -> Result<FolderLock, OptError> {
        let io = |path: &Path| {
            let path = path.to_path_buf();
            move |source| OptError::Io { path, source }
        };
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let key = std::fs::canonicalize(dir).map_err(io(dir))?;
        let mut held = HELD.lock().unwrap_or_else(|p| p.into_inner());
        held.retain(|(_, w)| w.strong_count() > 0);
        if let Some(h) = held
            .iter()
            .find(|(k, _)| *k == key)
            .and_then(|(_, w)| w.upgrade())
        {
            return Ok(FolderLock { _held: h });
        }
        let path = dir.join(LOCK_FILE);
        crate::output::refuse_symlink(&path)?;
        // an output name that is a symbolic link is refused before anything runs
        if let Ok(listing) = std::fs::read_dir(dir) {
            let mut links: Vec<PathBuf> = listing
                .flatten()
                .filter(|e| e.file_type().is_ok_and(|t| t.is_symlink()))
                .filter(|e| crate::journal::is_output_name(&e.file_name().to_string_lossy()))
                .map(|e| e.path())
                .collect();
            links.sort();
            if let Some(link) = links.first() {
                crate::output::refuse_symlink(link)?;
            }
        }
        let file = OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path)
            .map_err(io(&path))?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => return Err(busy(dir)),
            Err(TryLockError::Error(source)) => return Err(OptError::Io { path, source }),
        }
        let h = Arc::new(Held { _file: file });
        held.push((key, Arc::downgrade(&h)));
        Ok(FolderLock { _held: h })
    }

    /// Checks that no other process is writing into the folder `dir` that this process
    /// only reads (a shard folder given to `merge`): refused when its lock is held. A
    /// folder without a lock file (never written by a running command) passes; nothing
    /// is created.
    pub fn check_idle(dir: &Path) -> Result<(), OptError> {
        let path = dir.join(LOCK_FILE);
        let Ok(file) = File::open(&path) else {
            return Ok(());
        };
        if let Ok(key) = std::fs::canonicalize(dir) {
            let held = HELD.lock().unwrap_or_else(|p| p.into_inner());
            if held.iter().any(|(k, w)| *k == key && w.strong_count() > 0) {
                return Ok(()); // this process holds it
            }
        }
        match file.try_lock_shared() {
            Ok(()) => Ok(()),
            Err(TryLockError::WouldBlock) => Err(busy(dir)),
            Err(TryLockError::Error(source)) => Err(OptError::Io { path, source }),
        }
    }
}
