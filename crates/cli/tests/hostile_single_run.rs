//! Issue 29's probe, second round, on the single-run commands (`simulate`, `explain`,
//! `record …`, `accuracy`, `bench --only`, `report`) and their inputs: each hostile input
//! found is refused with a message naming the file and the field (or flag) and what was
//! expected, a non-zero status and nothing on stdout.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{refused, root, scratch};
use std::path::Path;

const NIS: &str = "records/NIS000.AT2";

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `simulate` of the building `json` (written to a scratch file) under NIS000: refused,
/// its message holding `needles` and none of `absent`.
fn building_refused(name: &str, json: &str, needles: &[&str], absent: &[&str]) {
    let dir = scratch("hostile-single", name);
    let f = dir.join(format!("{name}.json"));
    std::fs::write(&f, json).unwrap();
    let err = refused(&["simulate", s(&f), "--record", NIS], needles);
    for a in absent {
        assert!(!err.contains(a), "{a:?} in: {err}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A subnormal floor mass used to reach the eigen solve and come back as "frame stiffness
/// must be positive definite", naming `storey_stiffness`: the mass is the culprit.
#[test]
fn a_subnormal_floor_mass_is_named_as_the_mass() {
    building_refused(
        "subnormal-mass",
        r#"{"floor_masses":[1e-320],"storey_stiffness":[1e6],"dissipators":[]}"#,
        &["floor_masses[0]", "1e-320 kg", "outside the physical band"],
        &["storey_stiffness", "positive definite"],
    );
    building_refused(
        "subnormal-mass-matrix",
        r#"{"mass_matrix":[[1e-320]],"storey_stiffness":[1e6],"dissipators":[]}"#,
        &[
            "mass_matrix[0][0]",
            "1e-320 kg",
            "outside the physical band",
        ],
        &["storey_stiffness", "positive definite"],
    );
}

/// `record synth --pga-g 0` wrote an all-zero "record" and exited 0; a negative PGA the
/// same. Both are refused before anything is written.
#[test]
fn a_synthetic_record_of_zero_or_negative_pga_is_refused() {
    for pga in ["0", "-0.3"] {
        let dir = scratch("hostile-single", &format!("synth-pga{pga}"));
        let out = dir.join("s.csv");
        let flag = format!("--pga-g={pga}");
        refused(
            &["record", "synth", "--out", s(&out), &flag],
            &["--pga-g", "positive and finite", &format!("got {pga} g")],
        );
        assert!(!out.exists(), "no record written for --pga-g {pga}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// A synthetic record shorter than its step has one sample (the ground at rest): it
/// used to fail with "cannot scale to a target PGA: the record's PGA is zero", naming
/// neither flag.
#[test]
fn a_synthetic_record_shorter_than_its_step_names_duration_and_step() {
    let dir = scratch("hostile-single", "synth-short");
    let out = dir.join("s.csv");
    let err = refused(
        &[
            "record",
            "synth",
            "--out",
            s(&out),
            "--dt",
            "0.5",
            "--duration",
            "0.1",
        ],
        &["duration / time step", "0.2", "must span one time step"],
    );
    assert!(!err.contains("PGA is zero"), "{err}");
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A tiny sample interval is quoted as 1e-300, not as 300 digits.
#[test]
fn a_tiny_record_step_is_quoted_readably() {
    let dir = scratch("hostile-single", "info-dt");
    let f = dir.join("zeros.csv");
    std::fs::write(&f, "0\n0.1\n-0.1\n0\n").unwrap();
    let err = refused(
        &["record", "info", s(&f), "--dt", "1e-300"],
        &["sample interval 1e-300 s", "shorter than any accelerograph"],
    );
    assert!(!err.contains("0.000000000000"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `bench --only ""` matched every case (a full bench run, minutes); a text no case
/// contains ran nothing and exited 0 with an empty table.
#[test]
fn bench_only_refuses_an_empty_text_and_one_no_case_matches() {
    refused(&["bench", "--only", ""], &["--only", "empty", "every case"]);
    refused(
        &["bench", "--only", "memory", "--only", " "],
        &["--only", "value 2 is empty"],
    );
    // the refusal lists the cases there are, so the next attempt can be right
    refused(
        &["bench", "--only", "no-such-case"],
        &[
            "`no-such-case`",
            "no bench case's name contains it",
            "memory:",
            "sweep:",
        ],
    );
}

/// `accuracy --name ../../x` wrote its seven files two folders above --out, `a/b` into a
/// sub-folder, and `""` files named `-error-vs-dt.png`, `.md`… : --name is a base name.
#[test]
fn accuracy_name_is_a_base_name_inside_out() {
    let dir = scratch("hostile-single", "acc-name");
    let out = dir.join("deep").join("out");
    for (name, needles) in [
        ("../../x", &["`../../x`", "path separator", "--out"][..]),
        ("a/b", &["`a/b`", "path separator"][..]),
        ("a\\b", &["path separator"][..]),
        ("", &["--name", "empty"][..]),
        (".x", &["`.x`", "starts with a dot"][..]),
    ] {
        let flag = format!("--name={name}");
        refused(
            &[
                "accuracy",
                "configs/paper-1story.json",
                "--record",
                NIS,
                "--duration",
                "1",
                "--dts",
                "0.001",
                "--methods",
                "newmark",
                "--quiet",
                "--out",
                s(&out),
                &flag,
            ],
            needles,
        );
    }
    assert!(!dir.join("x.md").exists() && !dir.join("deep").join("x.md").exists());
    assert!(!out.exists(), "nothing written for a refused --name");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A harmonic force of 1e300 rad/s ran and exited 0 with a response to an aliased load
/// (the step sampled sin(ωt) far fewer than twice per period).
#[test]
fn a_harmonic_force_faster_than_the_step_can_sample_is_refused() {
    let dir = scratch("hostile-single", "omega");
    std::fs::copy(
        common::root().join("configs/paper-1story.json"),
        dir.join("paper-1story.json"),
    )
    .unwrap();
    let f = dir.join("fast.json");
    std::fs::write(
        &f,
        r#"{"building":"paper-1story.json","excitation":{"harmonic":{"floor":1,"amplitude":"1 kN","omega":1e300}},"duration":"5 s"}"#,
    )
    .unwrap();
    refused(
        &["simulate", s(&f)],
        &[
            "fast.json",
            "excitation.harmonic.omega",
            "1e300 rad/s",
            "fewer than twice per period",
        ],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A record of one sample lasts 0 s: the refusal used to read "scene: duration 0 s must
/// be positive and finite", naming neither the record nor why.
#[test]
fn a_single_sample_record_is_named() {
    let dir = scratch("hostile-single", "one-sample");
    let f = dir.join("one.at2");
    std::fs::write(&f, "HDR\nHDR\nHDR\nNPTS=  1, DT= .01000 SEC\n 0.1\n").unwrap();
    refused(
        &["simulate", "configs/paper-1story.json", "--record", s(&f)],
        &["one.at2", "single sample", "at least two samples"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A target PGA of 1e-300 g (`--scale-pga-g`, a scene's `scale_pga_g`, `record synth
/// --pga-g`) ran to an all-but-zero response and printed 300-digit numbers: a target
/// below perceptible shaking (1e-3 g) or beyond any ground motion (20 g) is refused,
/// naming the flag or field and quoting the value readably.
#[test]
fn a_target_pga_outside_the_band_of_real_shaking_is_refused() {
    let syl = root().join("records/SYL090.AT2");
    for pga in ["1e-300", "0.0005", "25"] {
        let err = refused(
            &[
                "simulate",
                "configs/benchmark-3story.json",
                "--record",
                s(&syl),
                "--scale-pga-g",
                pga,
            ],
            &["--scale-pga-g", "0.001 … 20 g"],
        );
        assert!(!err.contains("00000000000"), "{err}");
        let dir = scratch("hostile-single", &format!("synth-band{pga}"));
        let out = dir.join("s.csv");
        let flag = format!("--pga-g={pga}");
        refused(
            &["record", "synth", "--out", s(&out), &flag],
            &["--pga-g", "0.001 … 20 g"],
        );
        assert!(!out.exists(), "no record written for --pga-g {pga}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
    // the same band in a scene file's field
    let dir = scratch("hostile-single", "scene-band");
    let scene = dir.join("scene.json");
    std::fs::write(
        &scene,
        format!(
            r#"{{ "building": {:?}, "excitation": {{ "record": {{ "file": {:?}, "scale_pga_g": 1e-300 }} }} }}"#,
            root().join("configs/benchmark-3story.json"),
            syl
        ),
    )
    .unwrap();
    refused(
        &["simulate", s(&scene)],
        &["excitation.record.scale_pga_g", "0.001 … 20 g", "1e-300"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
