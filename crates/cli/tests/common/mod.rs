//! Helpers shared by the CLI tests: the repository root, running the built binary, and
//! scratch folders.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
#![allow(dead_code)] // each test binary uses its own subset of these helpers

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository root (configs/ and ../shared resolve from here).
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs `slipload ARGS` in `dir`.
pub fn slipload_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_slipload"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

/// Runs `slipload ARGS` at the repository root.
pub fn slipload(args: &[&str]) -> Output {
    slipload_in(&root(), args)
}

/// A fresh, empty scratch folder unique to this process and `name`.
pub fn scratch(prefix: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("slipload-{prefix}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}
