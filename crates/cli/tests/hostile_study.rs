//! Issue 29, the study commands under hostile inputs (`sweep`, `optimize`, `rank`,
//! `table`): a study or candidate file that is well formed but would give tables that
//! are not answers is refused up front, naming the file, the field and what was
//! expected, with a non-zero exit and no output folder written. One input per failure
//! mode: duplicate, blank or table-breaking names (suites, designs, the study), slip
//! loads beyond the building's bound in a candidate file, intensities below perceptible
//! shaking (study and `table --intensity-scales`), repeated table scales, a study that is
//! not an object or whose `space`/`sweep` is not shaped as one, and `--map-floors` of
//! one floor.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch, slipload_within, stderr};
use std::path::{Path, PathBuf};

/// Seconds any of these runs may take (each refusal comes before any simulation).
const T: u64 = 120;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A small study of the benchmark building with `suites`, `space` and `name` spliced in
/// (JSON text), written to `dir/file`.
fn study(dir: &Path, file: &str, name: &str, suites: &str, space: &str) -> PathBuf {
    let building = root().join("configs/benchmark-3story.json");
    let text = format!(
        r#"{{ {name}
  "building": {building:?},
  "suites": {suites},
  "space": {space},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "sweep": {{ "sampler": "halton", "points": 2, "seed": 5 }}
}}"#
    );
    let p = dir.join(file);
    std::fs::write(&p, text).unwrap();
    p
}

const SUITE: &str = r#"[ { "name": "syn", "synthetic": { "count": 1, "seed": 11, "pga_g": 0.4, "duration_s": 2 } } ]"#;
const SPACE: &str = r#"{ "free": { "lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000] } }"#;

/// Runs `args`, requires a refusal (non-zero exit, no panic) whose message holds every
/// needle, and that `out` was not created.
fn refused(args: &[&str], out: &Path, needles: &[&str]) {
    let o = slipload_within(T, args);
    let err = stderr(&o);
    assert!(!o.status.success(), "slipload {args:?} succeeded: {err}");
    assert!(!err.contains("panicked"), "{err}");
    for n in needles {
        assert!(err.contains(n), "slipload {args:?}: {n:?} not in: {err}");
    }
    assert!(!out.exists(), "slipload {args:?} wrote {}", out.display());
}

fn sweep_refused(dir: &Path, study: &Path, needles: &[&str]) {
    let out = dir.join("out");
    refused(
        &["--quiet", "sweep", s(study), "--out", s(&out)],
        &out,
        needles,
    );
}

#[test]
fn two_suites_of_one_name_are_refused() {
    let d = scratch("hostile-study", "dup-suite");
    let suites = r#"[ { "name": "syn", "synthetic": { "count": 1, "seed": 11, "pga_g": 0.4, "duration_s": 2 } },
                      { "name": "syn", "synthetic": { "count": 1, "seed": 12, "pga_g": 0.4, "duration_s": 2 } } ]"#;
    let p = study(&d, "dup.json", "", suites, SPACE);
    sweep_refused(
        &d,
        &p,
        &[
            "dup.json",
            "suites[1].name",
            "already the name of suites[0]",
        ],
    );
}

#[test]
fn a_suite_name_that_would_split_a_csv_row_is_refused() {
    let d = scratch("hostile-study", "comma-suite");
    let suites = r#"[ { "name": "near,fault", "synthetic": { "count": 1, "seed": 11, "pga_g": 0.4, "duration_s": 2 } } ]"#;
    let p = study(&d, "comma.json", "", suites, SPACE);
    sweep_refused(
        &d,
        &p,
        &["comma.json", "suites[0].name", "may not hold a comma"],
    );
}

#[test]
fn a_blank_study_name_is_refused() {
    let d = scratch("hostile-study", "blank-name");
    let p = study(&d, "blank.json", r#""name": " ","#, SUITE, SPACE);
    sweep_refused(&d, &p, &["blank.json", "field `name`", "blank"]);
}

#[test]
fn an_intensity_below_perceptible_shaking_is_refused() {
    let d = scratch("hostile-study", "tiny-pga");
    let suites = r#"[ { "name": "syn", "synthetic": { "count": 1, "seed": 11, "pga_g": 1e-300, "duration_s": 2 } } ]"#;
    let p = study(&d, "tiny.json", "", suites, SPACE);
    sweep_refused(
        &d,
        &p,
        &["tiny.json", "suites[0].synthetic.pga_g", "outside 0.001"],
    );
}

#[test]
fn a_study_that_is_not_an_object_is_refused_in_its_own_terms() {
    let d = scratch("hostile-study", "array");
    let p = d.join("array.json");
    std::fs::write(&p, "[1, 2]").unwrap();
    sweep_refused(
        &d,
        &p,
        &["array.json", "a study is a JSON object", "an array"],
    );
}

#[test]
fn an_empty_space_is_refused_naming_its_two_forms() {
    let d = scratch("hostile-study", "empty-space");
    let p = study(&d, "space.json", "", SUITE, "{}");
    sweep_refused(
        &d,
        &p,
        &[
            "space.json",
            "field `space`",
            "\"free\" or \"profile\"",
            "empty object",
        ],
    );
}

#[test]
fn a_null_sweep_section_is_refused_without_rust_type_names() {
    let d = scratch("hostile-study", "null-sweep");
    let building = root().join("configs/benchmark-3story.json");
    let text = format!(
        r#"{{ "building": {building:?}, "suites": {SUITE}, "space": {SPACE},
  "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }},
  "sweep": null }}"#
    );
    let p = d.join("null.json");
    std::fs::write(&p, text).unwrap();
    let out = d.join("out");
    let o = slipload_within(T, &["--quiet", "sweep", s(&p), "--out", s(&out)]);
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("field `sweep`") && err.contains("got null"),
        "{err}"
    );
    assert!(!err.contains("SweepConfig"), "{err}");
    assert!(!out.exists());
}

/// `rank` with the candidate file `designs` (JSON text) must be refused with `needles`.
fn rank_refused(name: &str, designs: &str, needles: &[&str]) {
    let d = scratch("hostile-study", name);
    let p = study(&d, "study.json", "", SUITE, SPACE);
    let c = d.join("candidates.json");
    std::fs::write(&c, designs).unwrap();
    let out = d.join("out");
    refused(
        &[
            "--quiet",
            "rank",
            s(&p),
            "--designs",
            s(&c),
            "--bootstrap",
            "5",
            "--out",
            s(&out),
        ],
        &out,
        needles,
    );
}

#[test]
fn rank_refuses_a_candidate_name_that_would_split_a_csv_row() {
    rank_refused(
        "rank-newline",
        r#"[ { "name": "a\nb,c", "slip_loads_kn": [1, 2, 3] } ]"#,
        &["designs[0].name", "control character"],
    );
}

#[test]
fn rank_refuses_an_empty_candidate_name() {
    rank_refused(
        "rank-empty",
        r#"[ { "name": "", "slip_loads_kn": [1, 2, 3] } ]"#,
        &["designs[0].name", "is empty"],
    );
}

#[test]
fn rank_refuses_a_slip_load_beyond_the_buildings_bound() {
    rank_refused(
        "rank-huge",
        r#"[ { "name": "a", "slip_loads_kn": [1e308, 2, 3] } ]"#,
        &["candidates.json", "slip_loads_kn[0]", "building's weight"],
    );
}

fn table_refused(name: &str, flag: &str, value: &str, needles: &[&str]) {
    let d = scratch("hostile-study", name);
    let p = study(&d, "study.json", "", SUITE, SPACE);
    let out = d.join("out");
    refused(
        &["--quiet", "table", s(&p), flag, value, "--out", s(&out)],
        &out,
        needles,
    );
}

#[test]
fn table_refuses_an_intensity_scale_below_perceptible_shaking() {
    table_refused(
        "table-tiny",
        "--intensity-scales",
        "1e-300",
        &["--intensity-scales 1e-300", "0.001"],
    );
}

#[test]
fn table_refuses_an_intensity_scale_beyond_any_ground_motion() {
    table_refused(
        "table-huge",
        "--intensity-scales",
        "1e6",
        &["--intensity-scales 1e6", "20 g"],
    );
}

#[test]
fn table_refuses_a_scale_given_twice() {
    table_refused(
        "table-twice",
        "--period-scales",
        "1,0.8,1",
        &["--period-scales", "given twice", "values 1 and 3"],
    );
}

#[test]
fn optimize_map_floors_of_one_floor_is_refused_without_debug_output() {
    let d = scratch("hostile-study", "map-one");
    let p = study(&d, "study.json", "", SUITE, SPACE);
    let out = d.join("out");
    let args = [
        "--quiet",
        "optimize",
        s(&p),
        "--map",
        "--map-floors",
        "1",
        "--out",
        s(&out),
    ];
    let o = slipload_within(T, &args);
    let err = stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(err.contains("got 1 floor(s): 1"), "{err}");
    assert!(!err.contains("[1]"), "{err}");
}

/// A study of one suite of record files (`records`, JSON array text, paths from the
/// repository root) with `scale` spliced into the suite (JSON text after a comma, or "").
fn record_study(dir: &Path, file: &str, records: &[&str], scale: &str) -> PathBuf {
    let list: Vec<String> = records
        .iter()
        .map(|r| format!("{:?}", s(&root().join(r))))
        .collect();
    let suites = format!(
        r#"[ {{ "name": "rec", "records": [{}]{scale} }} ]"#,
        list.join(", ")
    );
    study(dir, file, "", &suites, SPACE)
}

#[test]
fn one_record_file_twice_in_a_suite_is_refused() {
    let d = scratch("hostile-study", "dup-record");
    let p = record_study(
        &d,
        "twice.json",
        &["records/SYL360.AT2", "records/SYL360.AT2"],
        "",
    );
    sweep_refused(
        &d,
        &p,
        &[
            "twice.json",
            "suites[0].records[1]",
            "SYL360.AT2 is already in this suite (suites[0].records[0])",
        ],
    );
}

#[test]
fn a_folder_named_as_a_record_file_is_called_a_folder() {
    let d = scratch("hostile-study", "record-folder");
    let p = record_study(&d, "folder.json", &["records"], "");
    sweep_refused(
        &d,
        &p,
        &[
            "folder.json",
            "suites[0].records[0]",
            "is a folder, not a record file",
        ],
    );
}

#[test]
fn a_scale_factor_that_leaves_no_shaking_is_refused() {
    let d = scratch("hostile-study", "tiny-factor");
    let p = record_study(
        &d,
        "factor.json",
        &["records/SYL360.AT2"],
        r#", "scale": { "factor": 1e-9 }"#,
    );
    sweep_refused(
        &d,
        &p,
        &["factor.json", "suites[0].scale.factor", "below 0.001 g"],
    );
}

#[test]
fn shards_without_shard_auto_is_refused_rather_than_ignored() {
    let d = scratch("hostile-study", "shards-alone");
    let p = study(&d, "study.json", "", SUITE, SPACE);
    for extra in [&[][..], &["--shard", "0/2"][..]] {
        let out = d.join("out");
        let mut args = vec!["--quiet", "sweep", s(&p), "--out", s(&out), "--shards", "3"];
        args.extend_from_slice(extra);
        refused(&args, &out, &["--shards 3 applies to `--shard auto` only"]);
    }
}

#[test]
fn merge_refuses_one_shard_folder_named_twice() {
    let d = scratch("hostile-study", "merge-twice");
    let p = study(&d, "study.json", "", SUITE, SPACE);
    let (s0, s1) = (d.join("s0"), d.join("s1"));
    for (shard, dir) in [("0/2", &s0), ("1/2", &s1)] {
        let args = ["--quiet", "sweep", s(&p), "--out", s(dir), "--shard", shard];
        let o = slipload_within(T, &args);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let out = d.join("merged");
    refused(
        &["merge", s(&s0), s(&s1), s(&s1), "--out", s(&out)],
        &out,
        &["s1 is named twice", "name each shard folder once"],
    );
}
