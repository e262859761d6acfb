//! Contract: the README's examples run as written on a plain clone, after its install
//! line. Every command line of its code blocks that starts with `slipload` or
//! `cargo run --release --` names only files that are in the repository (configs/,
//! records/, results/, examples/) or that an earlier example wrote (out/); the same for
//! docs/ACCURACY.md, where the long accuracy and OpenSees sections live; the examples that run in
//! seconds are run — in a scratch folder where configs/ and records/ are the repository's
//! and out/ is fresh — and must exit 0. The study commands (optimize, sweep, rank, table)
//! and the accuracy studies are held to their files only here: the main job runs in
//! readme_numbers.rs, the others in their own tests.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch, slipload_in};

/// The command lines of the README's code blocks (continuation lines joined), as the
/// arguments after `slipload` (a `cargo run --release --` prefix taken as `slipload`);
/// `&& …` tails split off (the tail is its own example), and whether its `#` comment says
/// it stops with an error (an example of a refusal).
fn examples(readme: &str) -> Vec<(Vec<String>, bool)> {
    let mut out = Vec::new();
    let mut in_block = false;
    let mut pending = String::new();
    for line in readme.lines() {
        if line.trim_start().starts_with("```") {
            in_block = !in_block;
            pending.clear();
            continue;
        }
        if !in_block {
            continue;
        }
        let (line, comment) = line.split_once(" #").unwrap_or((line, ""));
        let line = line.trim_end();
        let refused = comment.contains("error");
        if let Some(head) = line.strip_suffix('\\') {
            pending.push_str(head);
            pending.push(' ');
            continue;
        }
        let full = format!("{pending}{line}");
        pending.clear();
        for part in full.split("&&") {
            let part = part.trim();
            let rest = part
                .strip_prefix("cargo run --release -- ")
                .or_else(|| part.strip_prefix("cargo run --release --"))
                .or_else(|| part.strip_prefix("slipload "))
                .or_else(|| (part == "slipload").then_some(""));
            if let Some(rest) = rest {
                out.push((
                    rest.split_whitespace().map(str::to_string).collect(),
                    refused,
                ));
            }
        }
    }
    out
}

/// A usage synopsis (STUDY, [--out DIR], SHARD_DIR...), not an example.
fn is_synopsis(args: &[String]) -> bool {
    args.iter().any(|a| {
        a.starts_with('[')
            || a.ends_with("...")
            || (a.len() > 1 && a.chars().all(|c| c.is_ascii_uppercase() || c == '_'))
    })
}

#[test]
fn readme_examples_name_files_of_the_repository_and_run() {
    // the README and the page its long accuracy and OpenSees sections moved to
    let mut all = Vec::new();
    for page in ["README.md", "docs/ACCURACY.md"] {
        all.extend(examples(
            &std::fs::read_to_string(root().join(page)).unwrap(),
        ));
    }
    assert!(
        all.len() >= 15,
        "found only {} examples: {all:?}",
        all.len()
    );
    let dir = scratch("readme-examples", "run");
    for sub in ["configs", "records", "results", "examples"] {
        std::os::unix::fs::symlink(root().join(sub), dir.join(sub)).unwrap();
    }
    let mut ran = 0;
    for (args, refused) in all.iter().filter(|(a, _)| !is_synopsis(a)) {
        let shown = format!("slipload {}", args.join(" "));
        // every file it names is there (what a plain clone has, or an output folder)
        for a in args.iter().filter(|a| !a.starts_with('-')) {
            if ["configs/", "records/", "results/", "examples/"]
                .iter()
                .any(|t| a.starts_with(t))
            {
                assert!(
                    root().join(a).exists(),
                    "README example `{shown}` names {a}, which is not in the repository"
                );
            }
        }
        let heavy = matches!(
            args.first().map(String::as_str),
            Some("optimize" | "sweep" | "rank" | "table" | "accuracy" | "bench")
        );
        // `report` reads a folder that a study example writes
        let needs_study = args.first().is_some_and(|c| c == "report");
        if heavy || needs_study {
            continue;
        }
        let argv: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = slipload_in(&dir, &argv);
        assert_eq!(
            o.status.success(),
            !refused,
            "README example `{shown}` (the README says it {}):\n{}",
            if *refused {
                "stops with an error"
            } else {
                "runs"
            },
            String::from_utf8_lossy(&o.stderr)
        );
        ran += 1;
    }
    assert!(ran >= 8, "ran only {ran} README examples");
}
