//! Records the git commit the binary is built from in `SLIPLOAD_GIT_COMMIT` (read with
//! `option_env!`), so `slipload report` can name it. Uses only `std` and the `git`
//! program; without git (a source tarball) the variable is simply not set.

use std::path::{Path, PathBuf};
use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    if !out.status.success() {
        return None;
    }
    let s = String::from_utf8(out.stdout).ok()?.trim().to_string();
    (!s.is_empty()).then_some(s)
}

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let Some(commit) = git(&["rev-parse", "--short=12", "HEAD"]) else {
        return;
    };
    println!("cargo:rustc-env=SLIPLOAD_GIT_COMMIT={commit}");
    // Rebuild when HEAD moves: HEAD itself (branch switch), the branch's ref file and
    // packed-refs (a commit). In a worktree, HEAD lives in the worktree's git dir and
    // the refs in the common dir.
    let abs = |p: String| -> PathBuf {
        let p = PathBuf::from(p);
        if p.is_absolute() {
            p
        } else {
            Path::new(".").join(p)
        }
    };
    // A path that does not exist would make cargo rerun this script on every build:
    // only existing files are watched.
    let watch = |p: PathBuf| {
        if p.is_file() {
            println!("cargo:rerun-if-changed={}", p.display());
        }
    };
    if let Some(dir) = git(&["rev-parse", "--git-dir"]).map(abs) {
        watch(dir.join("HEAD"));
    }
    if let Some(common) = git(&["rev-parse", "--git-common-dir"]).map(abs) {
        watch(common.join("packed-refs"));
        if let Some(branch) = git(&["symbolic-ref", "-q", "HEAD"]) {
            watch(common.join(branch));
        }
    }
}
