//! Contract: `slipload record spectrum … --plot DIR` writes DIR/spectra.svg and
//! DIR/spectra.png (non-empty) and DIR/spectra.csv (`--plot` names a folder, as in every
//! command; an existing file there is refused), and prints the data on stdout only when
//! `--format` asks for them; the SVG holds one series per record, the mean (with several
//! records) and the target (when given), each matching its CSV column; the period axis is
//! logarithmic.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
mod figures_common;

use common::{root, scratch, slipload};
use figures_common::{Csv, assert_inside, assert_x, assert_y, figure, range};

/// The CSV prints shortest round-trip decimals: values are exact; the mean is the same
/// sum in the same order, so only the last bit may differ.
const TOL: f64 = 1e-12;

#[test]
fn suite_with_mean_and_target() {
    let dir = scratch("figspec", "suite");
    let plot = dir.join("plots");
    let stem = plot.join("spectra");
    let out = slipload(&[
        "record",
        "spectrum",
        "--synthetic",
        "3",
        "--periods",
        "0.05,0.1,0.2,0.5,1,2",
        "--target-sds",
        "1.0",
        "--target-sd1",
        "0.6",
        "--plot",
        plot.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // With --plot and no --format the data go to the CSV only: stdout is one line that
    // names the files.
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(text.lines().count(), 1, "{text}");
    assert!(
        text.contains("spectra.svg") && text.contains("spectra.csv"),
        "{text}"
    );
    let m = figure(&stem);
    let csv = Csv::read(&plot.join("spectra.csv"));
    let p = &m.panels[0];
    assert!(p.x.log, "period axis is logarithmic");
    assert_inside(p);
    // 3 records + mean + target
    assert_eq!(p.series.len(), 5);
    let periods = csv.col("period_s");
    let record_cols: Vec<&String> = csv
        .columns
        .iter()
        .filter(|c| c.starts_with("psa_g:"))
        .collect();
    assert_eq!(record_cols.len(), 3);
    for (s, c) in p.series.iter().zip(&record_cols) {
        assert_eq!(s.points, 6);
        assert_x(s, range(&periods), 0.0);
        assert_y(s, range(&csv.col(c)), TOL);
    }
    let mean = csv.col("mean_psa_g");
    assert_y(&p.series[3], range(&mean), TOL);
    // The mean column is the mean of the record columns.
    for (k, m) in mean.iter().enumerate() {
        let avg = record_cols.iter().map(|c| csv.col(c)[k]).sum::<f64>() / 3.0;
        assert!(
            (avg - m).abs() <= 1e-12 * m.abs(),
            "period {k}: {avg} vs {m}"
        );
    }
    let target = csv.col("target_psa_g");
    assert_y(&p.series[4], range(&target), TOL);
    // ASCE 7 plateau S_DS = 1.0 g between T0 = 0.12 s and TS = 0.6 s (0.2 and 0.5 s here).
    assert_eq!(target[2], 1.0);
    assert_eq!(target[3], 1.0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn record_files_without_target() {
    let dir = scratch("figspec", "files");
    let rec = root().join("records");
    let a = rec.join("elCentro.AT2");
    let b = rec.join("SYL090.AT2");
    let plot = dir.join("two");
    let stem = plot.join("spectra");
    let out = slipload(&[
        "record",
        "spectrum",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--periods",
        "0.1,0.3,1,3",
        "--plot",
        plot.to_str().unwrap(),
        "--format",
        "csv",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // stdout, asked for with --format: long CSV with a record column, 4 periods per record
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.starts_with("record,period_s,"));
    assert_eq!(text.lines().count(), 1 + 2 * 4);
    let m = figure(&stem);
    let csv = Csv::read(&plot.join("spectra.csv"));
    assert!(!csv.has("target_psa_g"));
    let p = &m.panels[0];
    assert_eq!(p.series.len(), 3, "two records and their mean");
    assert_y(&p.series[0], range(&csv.col("psa_g:elCentro.AT2")), TOL);
    assert_y(&p.series[1], range(&csv.col("psa_g:SYL090.AT2")), TOL);
    assert_inside(p);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_requests_fail_cleanly() {
    let dir = scratch("figspec", "bad");
    let stem = dir.join("x");
    let out = slipload(&[
        "record",
        "spectrum",
        "--synthetic",
        "99",
        "--plot",
        stem.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--synthetic 99"));
    // An impossible target (T_L below T_S) names the flags and writes nothing.
    let out = slipload(&[
        "record",
        "spectrum",
        "--synthetic",
        "1",
        "--target-sds",
        "0.5",
        "--target-sd1",
        "1.0",
        "--target-tl",
        "1",
        "--plot",
        stem.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--target-tl"));
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "no partial output"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_existing_file_as_plot_is_refused() {
    let dir = scratch("figspec", "file");
    let file = dir.join("spectra.png");
    std::fs::write(&file, "not a folder").unwrap();
    let out = slipload(&[
        "record",
        "spectrum",
        "--synthetic",
        "1",
        "--plot",
        file.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1), "refused, not a panic");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(&format!("--plot {}", file.display()))
            && err.contains("existing file")
            && err.contains("takes a folder"),
        "{err}"
    );
    // the file is untouched and nothing else was written
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "not a folder");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    std::fs::remove_dir_all(&dir).unwrap();
}
