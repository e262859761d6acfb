//! Helpers shared by the CLI tests: the repository root, running the built binary, and
//! scratch folders.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
#![allow(dead_code)] // each test binary uses its own subset of these helpers

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository root (configs/ and records/ resolve from here).
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

/// Runs `slipload ARGS` at the repository root and fails the test if it has not ended
/// after `secs` seconds (the process is killed): for inputs that once ran for ever.
pub fn slipload_within(secs: u64, args: &[&str]) -> Output {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_slipload"))
        .args(args)
        .current_dir(root())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut out = child.stdout.take().unwrap();
    let mut err = child.stderr.take().unwrap();
    let t_out = std::thread::spawn(move || {
        let mut b = Vec::new();
        let _ = out.read_to_end(&mut b);
        b
    });
    let t_err = std::thread::spawn(move || {
        let mut b = Vec::new();
        let _ = err.read_to_end(&mut b);
        b
    });
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(secs);
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if std::time::Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!("slipload {args:?} still running after {secs} s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    Output {
        status,
        stdout: t_out.join().unwrap(),
        stderr: t_err.join().unwrap(),
    }
}

/// Standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs `slipload ARGS` at the repository root under a 60 s guard (every refusal is
/// up front; one that blocks on a FIFO or reads a device for ever is killed and fails)
/// and asserts the refusal: non-zero exit, nothing on stdout, no panic, and each of
/// `needles` in the message. Returns the message.
pub fn refused(args: &[&str], needles: &[&str]) -> String {
    let o = slipload_within(60, args);
    let err = stderr(&o);
    assert!(!o.status.success(), "slipload {args:?} succeeded: {err}");
    assert!(o.stdout.is_empty(), "no answer on stdout: {args:?}");
    for n in needles {
        assert!(err.contains(n), "slipload {args:?}: {n:?} not in: {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
    err
}

/// A study of seconds, written into `dir/study.json`: the benchmark building on two 2-s
/// synthetic records, two Halton points (for the tests of study folders: locks, --fresh,
/// links).
pub fn tiny_study(dir: &Path) -> PathBuf {
    let building = root().join("configs/benchmark-3story.json");
    let text = format!(
        r#"{{ "building": {building:?},
  "suites": [ {{ "name": "syn", "synthetic": {{ "count": 2, "seed": 11, "pga_g": 0.4, "duration_s": 2 }} }} ],
  "space": {{ "free": {{ "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] }} }},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "fidelity": {{ "method": "newmark" }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }} }}"#
    );
    let p = dir.join("study.json");
    std::fs::write(&p, text).unwrap();
    p
}

/// A path as the `&str` an argument list takes.
pub fn utf8(p: &Path) -> &str {
    p.to_str().unwrap()
}
