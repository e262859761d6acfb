//! Contract: a number the README quotes from a command is what that command prints today,
//! and the committed results of the main job are what it writes today.
//!
//! The README marks each quoted output with a comment naming the command, followed by a
//! fenced block: `<!-- printed by: slipload ARGS -->`. This test runs every such command
//! (in a scratch folder, from the repository root's configs) and requires every line of
//! the block to be a line of what it printed, verbatim. A block marked
//! `<!-- copied from: results/FILE -->` quotes a generated result file the same way: each
//! of its lines is a line of that file (the scripts that regenerate results/ write them). The main job's printed summary
//! must also be the one committed in `results/benchmark-3story/summary.txt` (the same
//! study: `configs/study-benchmark.json` is the embedded one), but for the line that
//! reports the wall-clock time and the lines naming the output folder.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch};
use std::process::Command;

const PRINTED: &str = "<!-- printed by: slipload ";
const COPIED: &str = "<!-- copied from: ";

/// The pages whose quoted result tables are held to their files.
const QUOTING_PAGES: [&str; 2] = ["README.md", "docs/ACCURACY.md"];

/// The blocks of the README that follow a line starting with `mark`: (the rest of that
/// line, split on white space; the non-empty lines of the fenced block after it, or of the
/// Markdown table after it, up to the next blank line).
fn quoted_blocks(readme: &str, mark: &str) -> Vec<(Vec<String>, Vec<String>)> {
    let lines: Vec<&str> = readme.lines().collect();
    let mut found = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some(rest) = line.trim().strip_prefix(mark) else {
            continue;
        };
        let args: Vec<String> = rest
            .trim_end_matches("-->")
            .split_whitespace()
            .map(str::to_string)
            .collect();
        let next = i + 1;
        assert!(
            lines.get(next).is_some_and(|l| !l.trim().is_empty()),
            "README line {}: the quoted block must follow the mark",
            i + 1
        );
        // a fenced block, or (a Markdown table) the lines up to the next blank line
        let body: Vec<&str> = if lines[next].trim_start().starts_with("```") {
            let close = lines[next + 1..]
                .iter()
                .position(|l| l.trim_start().starts_with("```"))
                .unwrap_or_else(|| panic!("README line {}: unclosed block", next + 1));
            lines[next + 1..next + 1 + close].to_vec()
        } else {
            lines[next..]
                .iter()
                .take_while(|l| !l.trim().is_empty())
                .copied()
                .collect()
        };
        let block = body
            .iter()
            .filter(|l| !l.trim().is_empty())
            .map(|l| l.to_string())
            .collect();
        found.push((args, block));
    }
    found
}

/// Runs `slipload ARGS` in a scratch folder with `configs/` reachable as in the README
/// (commands there run from the repository root): relative paths are resolved against
/// the root, and `--out` is pointed into the scratch folder.
fn run(args: &[String], name: &str) -> String {
    let dir = scratch("readme", name);
    let mut argv: Vec<String> = Vec::new();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        if a == "--out" {
            it.next();
            continue;
        }
        argv.push(if a.starts_with("configs/") || a.starts_with("records/") {
            root().join(a).to_string_lossy().into_owned()
        } else {
            a.clone()
        });
    }
    if argv
        .first()
        .is_some_and(|c| c == "optimize" || c == "sweep")
    {
        argv.extend([
            "--out".into(),
            dir.join("out").to_string_lossy().into_owned(),
        ]);
    }
    let out = Command::new(env!("CARGO_BIN_EXE_slipload"))
        .args(&argv)
        .arg("--quiet")
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "slipload {argv:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
    String::from_utf8(out.stdout).unwrap()
}

/// A summary without what changes from run to run or folder to folder: the line with the
/// wall-clock time, and the lines that name where the files went.
fn comparable(summary: &str) -> Vec<String> {
    summary
        .lines()
        .filter(|l| {
            !l.contains(" simulations run in ")
                && !l.starts_with("wrote ")
                && !l.starts_with("figures ")
        })
        .map(str::to_string)
        .collect()
}

#[test]
fn readme_quotes_what_the_commands_print() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let quoted = quoted_blocks(&readme, PRINTED);
    assert!(
        quoted
            .iter()
            .any(|(args, _)| args.first().is_some_and(|c| c == "optimize")),
        "the README quotes the main job's output"
    );
    for (k, (args, block)) in quoted.iter().enumerate() {
        assert!(!block.is_empty(), "slipload {args:?}: empty quoted block");
        let printed = run(args, &format!("q{k}"));
        let lines: Vec<&str> = printed.lines().collect();
        for l in block {
            assert!(
                lines.contains(&l.as_str()),
                "README quotes `slipload {}` as printing\n  {l}\nbut it prints:\n{printed}",
                args.join(" ")
            );
        }
        if args.len() == 1 && args[0] == "optimize" {
            // "about N simulations" in the README is the count the main job prints
            let printed_count = printed
                .lines()
                .find_map(|l| {
                    l.split(" simulations run in ")
                        .next()
                        .filter(|_| l.contains(" simulations run in "))
                })
                .and_then(|head| head.rsplit(' ').next())
                .unwrap_or_else(|| panic!("the main job prints its simulation count:\n{printed}"));
            let claims: Vec<&str> = readme
                .split("about ")
                .skip(1)
                .filter_map(|rest| rest.split_once(" simulations").map(|(n, _)| n))
                .filter(|n| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()))
                .collect();
            assert!(
                !claims.is_empty(),
                "the README says how many simulations the main job runs"
            );
            for n in claims {
                assert_eq!(
                    n, printed_count,
                    "the README says about {n} simulations, the main job prints {printed_count}"
                );
            }
            let committed =
                std::fs::read_to_string(root().join("results/benchmark-3story/summary.txt"))
                    .unwrap();
            assert_eq!(
                comparable(&committed),
                comparable(&printed),
                "results/benchmark-3story/summary.txt is not what the main job prints today: run scripts/design-tables.sh"
            );
        }
    }
}

#[test]
fn readme_quotes_the_committed_results_verbatim() {
    // the README and the page its long accuracy and OpenSees sections moved to
    let mut quoted = Vec::new();
    for page in QUOTING_PAGES {
        let text = std::fs::read_to_string(root().join(page)).unwrap();
        let blocks = quoted_blocks(&text, COPIED);
        assert!(
            !blocks.is_empty(),
            "{page} quotes its result tables from results/"
        );
        quoted.extend(blocks);
    }
    for (path, block) in quoted {
        assert_eq!(path.len(), 1, "one file per mark: {path:?}");
        assert!(
            path[0].starts_with("results/"),
            "{}: not under results/",
            path[0]
        );
        let text = std::fs::read_to_string(root().join(&path[0]))
            .unwrap_or_else(|e| panic!("README quotes {}: {e}", path[0]));
        let lines: Vec<&str> = text.lines().collect();
        assert!(!block.is_empty(), "{}: empty quoted block", path[0]);
        for l in &block {
            assert!(
                lines.contains(&l.as_str()),
                "the docs quote {} as holding\n  {l}\nbut it does not (regenerate results/ and copy the block again)",
                path[0]
            );
        }
    }
}
