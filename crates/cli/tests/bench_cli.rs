//! `slipload bench` as scripts use it: `--format json` prints a list of
//! `{case, metric, value, unit, target, met}` objects; the plan reductions it times give
//! the same peak drifts as the full 2N model, and the energies it times balance to
//! round-off (properties, so asserted; its timings are not — they are benchmarks on a
//! shared machine, not tests).
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::slipload;

#[test]
fn json_lists_figures_and_reductions_keep_answers() {
    let out = slipload(&[
        "bench",
        "--quick",
        "--only",
        "reductions",
        "--only",
        "memory",
        "--only",
        "outputs",
        "--format",
        "json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let figs = v.as_array().unwrap();
    assert!(figs.len() >= 8, "{v:#}");
    for f in figs {
        let mut keys: Vec<&str> = f.as_object().unwrap().keys().map(String::as_str).collect();
        keys.sort_unstable();
        assert_eq!(keys, ["case", "met", "metric", "target", "unit", "value"]);
        assert!(f["value"].as_f64().unwrap().is_finite(), "{f}");
    }
    let diffs: Vec<&serde_json::Value> = figs
        .iter()
        .filter(|f| {
            f["metric"]
                .as_str()
                .unwrap()
                .contains("difference reduced vs full")
        })
        .collect();
    assert_eq!(diffs.len(), 3, "{v:#}");
    for f in diffs {
        // Reduced plans are exact condensations: equal to round-off (1e-9 is the target).
        assert_eq!(f["met"], true, "{f}");
    }
    // Average-acceleration Newmark balances its energies to round-off (an identity of the
    // method), in the fixed-size loop the bench times as in the general one.
    let balances: Vec<&serde_json::Value> = figs
        .iter()
        .filter(|f| f["metric"] == "|energy balance error| / input")
        .collect();
    assert_eq!(balances.len(), 2, "{v:#}");
    for f in balances {
        assert_eq!(f["met"], true, "{f}");
    }
    // The memory probe ran in child processes and reported both sizes.
    assert!(
        figs.iter().any(|f| f["metric"] == "peak RSS, 300 s"),
        "{v:#}"
    );
}
