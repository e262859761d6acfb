//! `slipload opensees --out` never writes over a file the command reads: the scene, the
//! building file the scene names, the record the scene names and `--record`'s. Each
//! refusal exits non-zero, names the input, and leaves the file byte for byte as it was.
//! The script it writes is ASCII, its first two lines fixed text.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{refused, root, scratch, slipload, stderr, utf8};

#[test]
fn out_onto_any_input_is_refused_and_the_input_kept() {
    let dir = scratch("opensees-out", "inputs");
    let building = dir.join("building.json");
    std::fs::copy(
        root().join("configs/benchmark-3story-massless.json"),
        &building,
    )
    .unwrap();
    let record = dir.join("record.AT2");
    std::fs::copy(root().join("records/I-ELC180.AT2"), &record).unwrap();
    let other = dir.join("other.AT2");
    std::fs::copy(root().join("records/I-ELC180.AT2"), &other).unwrap();
    let scene = dir.join("scene.json");
    std::fs::write(
        &scene,
        r#"{ "name": "s", "building": "building.json",
             "excitation": { "record": { "file": "record.AT2", "window": [0, 1] } } }"#,
    )
    .unwrap();
    let before: Vec<Vec<u8>> = [&scene, &building, &record, &other]
        .iter()
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    for target in [&scene, &building, &record] {
        refused(
            &["opensees", utf8(&scene), "--out", utf8(target)],
            &["--out", "which this command reads"],
        );
    }
    refused(
        &[
            "opensees",
            utf8(&scene),
            "--record",
            utf8(&other),
            "--out",
            utf8(&other),
        ],
        &["--out", "which this command reads"],
    );
    let after: Vec<Vec<u8>> = [&scene, &building, &record, &other]
        .iter()
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    assert!(before == after, "an input changed");

    let out = dir.join("design.py");
    let o = slipload(&["opensees", utf8(&scene), "--out", utf8(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let script = std::fs::read(&out).unwrap();
    assert!(script.is_ascii());
    assert!(script.starts_with(b"#!/usr/bin/env python3\n# -*- coding: utf-8 -*-\n"));
}
