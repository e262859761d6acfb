//! The project's documentation stands on its own: every relative link of README.md and
//! docs/*.md leads to a file of the repository (and, with a `#fragment`, to one of its
//! headings), every repository path the README and docs/MODEL.md name in backticks
//! exists, and nothing points to a design note outside the repository.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::root;
use std::path::Path;

/// The targets of the Markdown links `[text](target)` of `text`.
fn links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("](") {
        rest = &rest[i + 2..];
        if let Some(j) = rest.find(')') {
            out.push(rest[..j].to_string());
            rest = &rest[j..];
        }
    }
    out
}

/// GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn anchors(markdown: &str) -> Vec<String> {
    markdown
        .lines()
        .filter(|l| l.starts_with('#'))
        .map(|l| anchor(l.trim_start_matches('#')))
        .collect()
}

/// Checks the relative links of the Markdown file `rel` (relative to the root).
fn check_links(rel: &str) -> usize {
    let path = root().join(rel);
    let text = std::fs::read_to_string(&path).unwrap();
    let dir = path.parent().unwrap();
    let mut checked = 0;
    for target in links(&text) {
        if target.contains("://") || target.starts_with("mailto:") {
            continue;
        }
        let (file, fragment) = match target.split_once('#') {
            Some((f, a)) => (f, Some(a)),
            None => (target.as_str(), None),
        };
        let file_path = if file.is_empty() {
            path.clone()
        } else {
            dir.join(file)
        };
        assert!(
            file_path.exists(),
            "{rel}: link ({target}) leads to {}, which does not exist",
            file_path.display()
        );
        if let Some(a) = fragment {
            let headings = anchors(&std::fs::read_to_string(&file_path).unwrap());
            assert!(
                headings.iter().any(|h| h == a),
                "{rel}: link ({target}): no heading with anchor #{a} in {} (anchors: {headings:?})",
                file_path.display()
            );
        }
        checked += 1;
    }
    checked
}

#[test]
fn readme_and_docs_links_lead_to_files_of_the_repository() {
    assert!(check_links("README.md") >= 6, "README.md has its links");
    let docs: Vec<String> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".md"))
        .collect();
    assert!(docs.iter().any(|d| d == "MODEL.md"), "{docs:?}");
    for d in docs {
        check_links(&format!("docs/{d}"));
    }
}

/// The repository paths named in backticks in `rel`: words starting with one of the
/// repository's top-level folders, without placeholders, patterns or hidden (generated)
/// folders such as `scripts/.venv`.
fn named_paths(rel: &str) -> Vec<String> {
    let text = std::fs::read_to_string(root().join(rel)).unwrap();
    let mut out = Vec::new();
    for (k, span) in text.split('`').enumerate() {
        if k % 2 == 0 {
            continue; // outside backticks
        }
        for word in span.split_whitespace() {
            let word = word.trim_end_matches([',', ';', ':', ')']);
            let top = ["docs/", "configs/", "crates/", "scripts/", "results/"];
            if top.iter().any(|t| word.starts_with(t))
                && !word.contains(['*', '{', '<', '…', '$'])
                && !word.contains("DIR")
                && !word.contains("NAME")
                && !word.contains("/.")
            {
                out.push(word.to_string());
            }
        }
    }
    out
}

#[test]
fn paths_named_by_the_readme_and_the_model_exist() {
    for rel in ["README.md", "docs/MODEL.md"] {
        let paths = named_paths(rel);
        assert!(paths.len() >= 5, "{rel}: {paths:?}");
        let missing: Vec<&String> = paths.iter().filter(|p| !root().join(p).exists()).collect();
        assert!(
            missing.is_empty(),
            "{rel} names paths that are not in the repository: {missing:?}"
        );
    }
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    assert!(
        readme.contains("docs/MODEL.md"),
        "the README points to the model"
    );
}

/// Every text file of these folders (recursively).
fn files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            if p.file_name().is_some_and(|n| n == "node_modules") {
                continue;
            }
            files(&p, out);
        } else if p.extension().is_some_and(|x| {
            ["rs", "md", "json", "sh", "py", "toml", "mjs"].contains(&x.to_str().unwrap_or(""))
        }) {
            out.push(p);
        }
    }
}

#[test]
fn nothing_points_to_a_design_note_outside_the_repository() {
    let mut all = vec![root().join("README.md")];
    for d in ["configs", "crates", "scripts", "docs"] {
        files(&root().join(d), &mut all);
    }
    assert!(all.len() > 50, "{} files", all.len());
    // Spelled in two parts so this file does not name it.
    let name = format!("{}.md", "DESIGN");
    for f in all {
        let text = std::fs::read_to_string(&f).unwrap_or_default();
        assert!(
            !text.contains(&name),
            "{} points to {name}, which is not in the repository: point to docs/MODEL.md",
            f.display()
        );
    }
}
