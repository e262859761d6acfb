//! What a new user runs into first, held by tests: a file given to the wrong command
//! says what it is and what to run; `--quiet` and `--threads` are taken by every command;
//! default outputs go under `out/` (parent folders created); a folder of records is read
//! whatever the case of the `.AT2` extension; `--method` lists its values.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch, slipload, slipload_in};
use std::path::Path;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn a_study_given_to_simulate_says_what_to_run() {
    for cmd in ["simulate", "explain"] {
        let o = slipload(&[cmd, "configs/study-benchmark.json"]);
        assert!(!o.status.success(), "{cmd}");
        let err = stderr(&o);
        assert!(
            err.contains("configs/study-benchmark.json is a study, not a scene or a building")
                && err.contains("slipload optimize configs/study-benchmark.json"),
            "{cmd}: {err}"
        );
        assert!(!err.contains("unknown field"), "{cmd}: {err}");
    }
    // accuracy reads scenes the same way (with and without --synthetic)
    let dir = scratch("newcomer", "acc-study");
    for extra in [&[][..], &["--synthetic", "1"][..]] {
        let mut args = vec!["accuracy", "configs/study-benchmark.json", "--out", s(&dir)];
        args.extend_from_slice(extra);
        let o = slipload(&args);
        assert!(!o.status.success());
        assert!(
            stderr(&o).contains("is a study, not a scene"),
            "{}",
            stderr(&o)
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_building_or_a_scene_given_to_a_study_command_says_what_to_run() {
    let dir = scratch("newcomer", "study-cmds");
    for (file, kind) in [
        ("configs/benchmark-3story.json", "a building"),
        ("configs/paper-benchmark-sylmar.json", "a scene"),
    ] {
        for cmd in ["optimize", "sweep"] {
            let out = dir.join(format!("{cmd}-out"));
            let o = slipload(&[cmd, file, "--out", s(&out)]);
            assert!(!o.status.success(), "{cmd} {file}");
            let err = stderr(&o);
            assert!(
                err.contains(&format!("{file} is {kind}, not a study"))
                    && err.contains(&format!("slipload simulate {file}")),
                "{cmd} {file}: {err}"
            );
            assert!(!out.exists(), "{cmd}: nothing written");
        }
    }
    // candidate designs given as a study point to `rank --designs`
    let designs = dir.join("candidates.json");
    std::fs::write(&designs, r#"[{"name": "a", "slip_loads_kn": [1, 2, 3]}]"#).unwrap();
    let o = slipload(&["optimize", s(&designs), "--out", s(&dir.join("o"))]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("--designs") && stderr(&o).contains("candidate designs"),
        "{}",
        stderr(&o)
    );
    // a study given as the candidates of rank says so
    let o = slipload(&[
        "rank",
        "configs/study-benchmark.json",
        "--designs",
        "configs/study-benchmark.json",
        "--out",
        s(&dir.join("r")),
    ]);
    assert!(!o.status.success());
    assert!(
        stderr(&o)
            .contains("configs/study-benchmark.json is a study, not a list of candidate designs"),
        "{}",
        stderr(&o)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn quiet_and_threads_are_taken_by_simulate_and_merge() {
    let o = slipload(&[
        "simulate",
        "configs/paper-1story-free.json",
        "--quiet",
        "--threads",
        "1",
        "--duration",
        "0.5",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // merge of folders that are not shards: an error about the folders, not the flags
    let dir = scratch("newcomer", "merge");
    let o = slipload(&[
        "merge",
        s(&dir.join("a")),
        "--out",
        s(&dir.join("m")),
        "--quiet",
    ]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(
        !err.contains("unexpected argument") && err.contains(s(&dir.join("a"))),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn default_outputs_go_under_out() {
    let dir = scratch("newcomer", "defaults");
    let scene = root().join("configs/paper-1story-harmonic.json");
    let o = slipload_in(
        &dir,
        &[
            "accuracy",
            s(&scene),
            "--duration",
            "0.5",
            "--methods",
            "newmark",
            "--dts",
            "T1/50",
            "--repeats",
            "1",
            "--quiet",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // --quiet hides the per-scene progress line
    assert!(!stderr(&o).contains("accuracy:"), "{}", stderr(&o));
    for ext in ["csv", "json", "md", "svg", "png"] {
        let f = if ["svg", "png"].contains(&ext) {
            format!("out/accuracy/paper-1story-harmonic-work-precision.{ext}")
        } else {
            format!("out/accuracy/paper-1story-harmonic.{ext}")
        };
        assert!(dir.join(&f).is_file(), "{f}");
    }
    assert!(!dir.join("results").exists(), "nothing outside out/");
    // the README's history example: the folder is created
    let free = root().join("configs/paper-1story-free.json");
    let o = slipload_in(&dir, &["simulate", s(&free), "--history", "out/free.csv"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(dir.join("out/free.csv")).unwrap();
    assert!(csv.lines().count() > 10, "{csv}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_folder_of_records_is_read_whatever_the_case_of_the_extension() {
    let dir = scratch("newcomer", "records");
    let shared = root().join("records");
    std::fs::copy(shared.join("ARL360.at2"), dir.join("ARL360.at2")).unwrap();
    std::fs::copy(shared.join("SYL090.AT2"), dir.join("SYL090.AT2")).unwrap();
    std::fs::write(dir.join("README.md"), "not a record\n").unwrap();
    let o = slipload(&["record", "info", s(&dir), "--format", "json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let files: Vec<&str> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["file"].as_str().unwrap())
        .collect();
    assert_eq!(files.len(), 2, "{files:?}");
    assert!(files[0].ends_with("ARL360.at2") && files[1].ends_with("SYL090.AT2"));
    // a folder without records is an error that says so
    let empty = dir.join("empty");
    std::fs::create_dir(&empty).unwrap();
    let o = slipload(&["record", "spectrum", s(&empty)]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("holds no .AT2 record"),
        "{}",
        stderr(&o)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn method_help_lists_the_methods() {
    let o = slipload(&["simulate", "--help"]);
    assert!(o.status.success());
    let help = String::from_utf8_lossy(&o.stdout);
    let at = help.find("--method").unwrap();
    let section = &help[at..help[at..].find("--dt").map_or(help.len(), |e| at + e)];
    for m in ["newmark", "hht", "bilinear", "delacruz", "exact"] {
        assert!(section.contains(m), "--method help lists {m}: {section}");
    }
    // short help: the values on one line; long help: each with what it is
    let o = slipload(&["accuracy", "-h"]);
    let help = String::from_utf8_lossy(&o.stdout);
    assert!(
        help.contains("[possible values: newmark, hht, bilinear, delacruz, exact]"),
        "{help}"
    );
    let o = slipload(&["simulate", "--method", "verlet"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("delacruz"), "{}", stderr(&o));
}

/// The quick start's record states its unit in its header (`accel_g`): `simulate` reads
/// it in g, so its PGA is that of the AT2 file it was cut from (`records/I-ELC180.AT2`,
/// the first 15 s), to the 7 significant digits the CSV keeps; and the quick-start files
/// run as the README shows.
#[test]
fn the_quick_start_record_is_read_in_the_unit_its_header_states() {
    let at2 = std::fs::read_to_string(root().join("records/I-ELC180.AT2")).unwrap();
    let values: Vec<f64> = at2
        .lines()
        .skip(4)
        .flat_map(|l| l.split_whitespace().map(|v| v.parse::<f64>().unwrap()))
        .take(1500)
        .collect();
    let pga_g = values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let o = slipload(&[
        "simulate",
        "examples/quick-start/building.json",
        "--record",
        "examples/quick-start/record.csv",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    let printed: f64 = text
        .split("PGA ")
        .nth(1)
        .and_then(|t| t.split_whitespace().next())
        .unwrap()
        .parse()
        .unwrap();
    // the summary prints 4 decimals of g
    assert!(
        (printed - pga_g).abs() <= 5e-5,
        "{printed} g against {pga_g} g:\n{text}"
    );
    assert!(!stderr(&o).contains("did you mean kN"), "{}", stderr(&o));
}

/// A building file whose slip loads are bare numbers (newtons) where the user meant kN:
/// a study warns about the file's design before it runs, naming the floor and "kN".
#[test]
fn a_study_warns_about_bare_number_slip_loads_in_its_building_file() {
    let dir = scratch("newcomer", "bare-kn");
    let qs = root().join("examples/quick-start");
    let mut b: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(qs.join("building.json")).unwrap()).unwrap();
    for (d, v) in b["dissipators"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .zip([600, 500, 400, 250])
    {
        d["slip_load"] = v.into();
    }
    std::fs::write(dir.join("building.json"), b.to_string()).unwrap();
    let mut st: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(qs.join("study.json")).unwrap()).unwrap();
    st["suites"] = serde_json::json!([
        {"name": "one", "synthetic": {"count": 1, "seed": 2007, "pga_g": 0.4, "duration_s": 2.0}}
    ]);
    st["sweep"] = serde_json::json!({"sampler": "halton", "points": 2, "seed": 2007});
    std::fs::write(dir.join("study.json"), st.to_string()).unwrap();
    let o = slipload_in(&dir, &["sweep", "study.json", "--out", "res", "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("warning: study study.json, the building file's slip loads: floor 1:")
            && err.contains("did you mean kN"),
        "{err}"
    );
    // the file with units says nothing
    std::fs::copy(qs.join("building.json"), dir.join("building.json")).unwrap();
    let o = slipload_in(&dir, &["sweep", "study.json", "--out", "res2", "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("did you mean kN"), "{}", stderr(&o));
}
