//! Helpers shared by the opt tests: an output folder as the study commands take it and
//! open it.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
#![allow(dead_code)] // each test binary uses its own subset of these helpers

use slipload_opt::store::folder::{FolderRequest, StudyFolder};
use std::path::Path;

/// The output folder `out`, as the library's study commands take it (no `fresh`).
pub fn folder(out: &Path) -> FolderRequest<'_> {
    FolderRequest {
        path: out,
        option: "out",
        fresh: false,
    }
}

/// The sweep's output folder `dir`, opened as a study command opens it (locked until the
/// returned value is dropped).
pub fn open_folder(dir: &Path) -> StudyFolder {
    StudyFolder::open(folder(dir)).unwrap().0
}
