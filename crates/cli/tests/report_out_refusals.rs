//! Contract: `report --out` never replaces a file a study command wrote (a sweep's
//! table, a journal): it is refused naming the file, which stays as it was; the default
//! `report.html` in a study folder joins the folder's list of slipload's files, so that
//! `--fresh` removes it.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{slipload_within, tiny_study as study, utf8 as s};

#[test]
fn report_out_onto_a_sweeps_table_is_refused_and_the_report_joins_the_list() {
    let dir = common::scratch("report-out", "table");
    let st = study(&dir);
    let out = dir.join("out");
    let o = slipload_within(300, &["sweep", s(&st), "--out", s(&out), "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let table = std::fs::read(out.join("designs.csv")).unwrap();
    let target = out.join("designs.csv");
    let o = slipload_within(300, &["report", s(&out), "--out", s(&target)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "report over designs.csv ran: {err}");
    assert!(
        err.contains("designs.csv") && err.contains("never replaces"),
        "{err}"
    );
    assert!(std::fs::read(out.join("designs.csv")).unwrap() == table);
    // the default report goes into the folder's list: --fresh then removes it
    let o = slipload_within(300, &["report", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let list = std::fs::read_to_string(out.join(".slipload.lock")).unwrap();
    assert!(list.lines().any(|l| l == "report.html"), "{list}");
    let o = slipload_within(
        300,
        &["sweep", s(&st), "--out", s(&out), "--fresh", "--quiet"],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("report.html"),
        "--fresh names the report it removed: {err}"
    );
    assert!(!out.join("report.html").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
