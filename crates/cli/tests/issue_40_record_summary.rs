//! Issue 40 §2 and §5, what a run says about its record: `simulate`'s table names the
//! ground motion with its PGA (and its scaling), so that a record read in the wrong unit
//! shows; units that override an AT2 title's, and a time step that runs past
//! `--duration`, are noted on stderr; `record info` reads a CSV header's unit, refuses a
//! contradiction naming the file and line, and keeps its columns aligned whatever the
//! values.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{scratch, slipload, stderr};

const B: &str = "configs/benchmark-3story.json";

fn stdout(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn ok(args: &[&str]) -> std::process::Output {
    let o = slipload(args);
    assert!(o.status.success(), "slipload {args:?}: {}", stderr(&o));
    o
}

#[test]
fn the_table_names_the_ground_motion_with_its_pga_and_scaling() {
    let o = ok(&[
        "simulate",
        B,
        "--record",
        "records/SYL090.AT2",
        "--duration",
        "2",
    ]);
    let table = stdout(&o);
    assert!(
        table.contains("ground motion records/SYL090.AT2: PGA 0.6045 g (5.9280 m/s2)\n"),
        "{table}"
    );
    assert!(!table.contains("scaled by"), "{table}");
    let o = ok(&[
        "simulate",
        B,
        "--record",
        "records/SYL090.AT2",
        "--scale-pga-g",
        "0.3",
        "--duration",
        "2",
    ]);
    let table = stdout(&o);
    assert!(
        table.contains(
            "ground motion records/SYL090.AT2: PGA 0.3000 g (2.9420 m/s2), scaled by 0.496286 from PGA 0.6045 g\n"
        ),
        "{table}"
    );
    // the JSON output contract is unchanged: no such line, no new key
    let o = ok(&[
        "simulate",
        B,
        "--record",
        "records/SYL090.AT2",
        "--duration",
        "2",
        "--format",
        "json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v.get("pga").is_none() && v.get("record").is_none(), "{v}");
}

#[test]
fn a_csv_header_in_g_is_read_in_g_and_the_summary_shows_it() {
    let dir = scratch("issue40", "csv-g");
    let csv = dir.join("pulse.csv");
    let mut text = String::from("time_s,accel_g\n");
    for k in 0..=200 {
        let t = k as f64 * 0.01;
        let a = 0.25 * (std::f64::consts::PI * t).sin();
        text.push_str(&format!("{t},{a}\n"));
    }
    std::fs::write(&csv, text).unwrap();
    let path = csv.to_str().unwrap();
    let o = ok(&["simulate", B, "--record", path]);
    let table = stdout(&o);
    // 0.25 g, not 0.25 m/s2 = 0.0255 g
    assert!(table.contains(": PGA 0.2500 g (2.4517 m/s2)\n"), "{table}");
    // units that contradict the header are refused naming the file and the line
    let o = slipload(&["simulate", B, "--record", path, "--units", "m/s2"]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(
        err.contains(&format!("{path}:1: the header `time_s,accel_g` says the values are in g, but units m/s2 were given")),
        "{err}"
    );
    let o = slipload(&["record", "info", path, "--units", "cm/s2"]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains(&format!("{path}:1: ")),
        "{}",
        stderr(&o)
    );
    // agreeing units read alike
    let info = stdout(&ok(&["record", "info", path, "--units", "g"]));
    assert!(info.contains(" 0.2500 "), "{info}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn units_that_override_an_at2_title_say_so_on_stderr() {
    let o = ok(&[
        "simulate",
        B,
        "--record",
        "records/SYL090.AT2",
        "--units",
        "cm/s2",
        "--duration",
        "1",
    ]);
    let err = stderr(&o);
    assert!(
        err.contains("note: records/SYL090.AT2: values read in cm/s2 as given, not in g as its header says (line 3: `ACCELERATION TIME HISTORY IN UNITS OF G`)"),
        "{err}"
    );
    let o = ok(&["record", "info", "records/SYL090.AT2", "--units", "cm/s2"]);
    assert!(
        stderr(&o).contains("values read in cm/s2 as given"),
        "{}",
        stderr(&o)
    );
    // the title's own unit, given or not: no note
    let o = ok(&["record", "info", "records/SYL090.AT2", "--units", "g"]);
    assert!(!stderr(&o).contains("note:"), "{}", stderr(&o));
}

#[test]
fn a_step_that_does_not_divide_the_duration_is_noted() {
    let o = ok(&[
        "simulate",
        B,
        "--record",
        "records/SYL090.AT2",
        "--duration",
        "1",
        "--dt",
        "0.003",
    ]);
    let err = stderr(&o);
    assert!(
        err.contains("warning: dt = 0.003 s does not divide the duration 1 s: the run takes 334 steps and ends at t = 1.002 s, 0.002 s past it"),
        "{err}"
    );
    // the same in JSON: the note is on stderr, stdout stays the output contract
    let o = ok(&[
        "simulate",
        B,
        "--record",
        "records/SYL090.AT2",
        "--duration",
        "1",
        "--dt",
        "0.003",
        "--format",
        "json",
    ]);
    assert!(stderr(&o).contains("does not divide the duration"));
    assert_eq!(
        serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap()["steps"],
        334
    );
    // a step that divides it: nothing to say
    let o = ok(&[
        "simulate",
        B,
        "--record",
        "records/SYL090.AT2",
        "--duration",
        "1",
        "--dt",
        "0.0025",
    ]);
    assert!(!stderr(&o).contains("does not divide"), "{}", stderr(&o));
}

/// The character offsets where the cells of a table line end.
fn cell_ends(line: &str) -> Vec<usize> {
    let chars: Vec<char> = line.chars().collect();
    (0..chars.len())
        .filter(|&i| chars[i] != ' ' && chars.get(i + 1).is_none_or(|c| *c == ' '))
        .map(|i| i + 1)
        .collect()
}

#[test]
fn record_info_columns_align_whatever_the_values() {
    let dir = scratch("issue40", "info-align");
    // a long record at dt = 1 s (duration 10 000 s: wider than the column's usual
    // width) and one at 4 kHz, whose dt rounded to four decimals would read 0.0003
    let long = dir.join("long.csv");
    let mut text = String::new();
    for k in 0..=10_000 {
        text.push_str(&format!("{}\n", 0.01 * ((k % 7) as f64 - 3.0)));
    }
    std::fs::write(&long, text).unwrap();
    let fast = dir.join("fast.csv");
    std::fs::write(&fast, "0.1\n-0.2\n0.3\n0.05\n").unwrap();
    let o = ok(&["record", "info", long.to_str().unwrap(), "--dt", "1"]);
    let long_table = stdout(&o);
    let o = ok(&["record", "info", fast.to_str().unwrap(), "--dt", "0.00025"]);
    let fast_table = stdout(&o);
    assert!(fast_table.contains(" 0.00025 "), "{fast_table}");
    for table in [&long_table, &fast_table] {
        let lines: Vec<&str> = table.lines().collect();
        assert_eq!(lines.len(), 2, "{table}");
        // the file column is left-aligned, the others end together
        assert_eq!(
            cell_ends(lines[0])[1..],
            cell_ends(lines[1])[1..],
            "{table}"
        );
        assert_eq!(cell_ends(lines[0]).len(), 10, "{table}");
    }
    assert!(long_table.contains(" 10000.000 "), "{long_table}");
    // the repository's records: a table that reads as it always has
    let o = ok(&["record", "info", "records"]);
    let table = stdout(&o);
    let lines: Vec<&str> = table.lines().collect();
    assert!(lines.len() > 20);
    assert!(
        lines[0].starts_with("file  ") && lines[0].ends_with("  arias_m_s  d5_95_s"),
        "{table}"
    );
    assert!(
        lines.iter().any(|l| l.ends_with(
            "  1559   0.0200    31.160     3.1266   0.3188    0.3614    0.2135     1.7236   23.864"
        )),
        "{table}"
    );
    let ends = cell_ends(lines[0]);
    assert!(
        lines.iter().all(|l| cell_ends(l)[1..] == ends[1..]),
        "{table}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
