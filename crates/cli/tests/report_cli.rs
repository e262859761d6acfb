//! Contract: `slipload report DIR` writes one self-contained HTML page (default
//! DIR/report.html, or `--out FILE`) naming the kind of folder, with every Markdown table
//! rendered, every `NAME.svg` inlined (with its `NAME.csv` beside it), every JSON input
//! shown, every file's text escaped, no reference to anything outside the page, and the
//! slipload version; the same folder gives the same bytes. A missing folder or one with
//! nothing recognisable is a clear error naming it, with a non-zero exit and no file.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test

mod common;
use common::{root, scratch, slipload};
use std::path::Path;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Every URL the page would fetch: `src=`, `href=` (other than in-page `#…` links) and
/// CSS `url(`/`@import`. The SVG namespace (`xmlns="http://www.w3.org/2000/svg"`) is an
/// identifier, not a fetch.
fn external_references(html: &str) -> Vec<String> {
    let mut found = Vec::new();
    for pat in ["src=\"", "href=\""] {
        for (i, _) in html.match_indices(pat) {
            let rest = &html[i + pat.len()..];
            let url = &rest[..rest.find('"').unwrap()];
            if !url.starts_with('#') {
                found.push(url.to_string());
            }
        }
    }
    for pat in ["url(", "@import"] {
        if html.contains(pat) {
            found.push(pat.to_string());
        }
    }
    found
}

#[test]
fn study_folder_gives_a_page_with_its_tables_and_inputs() {
    let out_dir = scratch("report", "study");
    let page = out_dir.join("page.html");
    let dir = root().join("results/benchmark-3story");
    let out = slipload(&["report", s(&dir), "--out", s(&page)]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // One plain sentence: what the folder is and where the page went.
    let msg = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        msg.trim(),
        format!(
            "report of the design study in {} written to {}",
            dir.display(),
            page.display()
        ),
        "{msg}"
    );
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>"));
    assert!(html.contains("<h1>benchmark-3story</h1>"));
    assert!(html.contains("design study (slipload optimize"));
    assert!(html.contains(&format!("slipload {}", env!("CARGO_PKG_VERSION"))));
    // the design table, the ranking and the family table are rendered as tables
    assert!(
        html.contains("<h3>Design table: benchmark-3story</h3>"),
        "design-table.md"
    );
    // (a heading under the page's; its level depends on whether rank.md has a title)
    assert!(html.contains(">synthetic-0.4g</h"), "rank.md");
    assert!(
        html.contains("<th class=\"num\">period ×</th>"),
        "family.md"
    );
    // the manifest (the study's inputs) is there, pretty-printed and collapsible
    assert!(html.contains("<summary>manifest.json (input)</summary>"));
    assert!(html.contains("&quot;study&quot;: &quot;benchmark-3story&quot;"));
    // every CSV of the folder appears
    for f in [
        "designs.csv",
        "responses.csv",
        "refine.csv",
        "design-table.csv",
    ] {
        assert!(html.contains(&format!("<summary>{f}</summary>")), "{f}");
    }
    assert_eq!(external_references(&html), Vec::<String>::new());
    // the same folder gives the same bytes (no clock, no map order in the page)
    let again = out_dir.join("again.html");
    assert!(
        slipload(&["report", s(&dir), "--out", s(&again)])
            .status
            .success()
    );
    assert!(std::fs::read(&page).unwrap() == std::fs::read(&again).unwrap());
    let _ = std::fs::remove_dir_all(&out_dir);
}

#[test]
fn figures_are_inlined_and_file_text_is_escaped() {
    let dir = scratch("report", "figures");
    std::fs::write(
        dir.join("drift.svg"),
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg width=\"640\" height=\"480\" xmlns=\"http://www.w3.org/2000/svg\"><rect x=\"1\" y=\"2\" width=\"3\" height=\"4\"/></svg>\n",
    )
    .unwrap();
    std::fs::write(dir.join("drift.csv"), "floor,drift_m\n1,<0.5>\n").unwrap();
    std::fs::write(
        dir.join("evil.svg"),
        "<svg width=\"10\" height=\"10\"><script>alert(1)</script></svg>",
    )
    .unwrap();
    std::fs::write(
        dir.join("notes.md"),
        "# Notes <script>alert(2)</script>\n\n| a | b |\n|---|---:|\n| <img src=x onerror=alert(3)> | 1 |\n",
    )
    .unwrap();
    std::fs::write(dir.join("scene.json"), r#"{"name": "a</pre><b>"}"#).unwrap();
    let out = slipload(&["report", s(&dir)]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(dir.join("report.html")).unwrap();
    // the figure is inlined without its XML prolog, with a viewBox so it scales
    assert!(html.contains(
        "<svg viewBox=\"0 0 640 480\" width=\"640\" height=\"480\" xmlns=\"http://www.w3.org/2000/svg\"><rect"
    ));
    assert!(!html.contains("<?xml"));
    assert!(html.contains("drift.svg · data: drift.csv"));
    assert!(html.contains("<td>&lt;0.5&gt;</td>"));
    // the SVG with a script is named but not inlined; no file text is markup
    assert!(html.contains("evil.svg is not inlined"));
    assert!(!html.contains("<script"), "no script reaches the page");
    assert!(!html.contains("<img"));
    assert!(html.contains("&lt;img src=x onerror=alert(3)&gt;"));
    assert!(html.contains("a&lt;/pre&gt;&lt;b&gt;"));
    assert_eq!(external_references(&html), Vec::<String>::new());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn missing_or_unrecognised_folder_is_an_error_without_output() {
    let dir = scratch("report", "bad");
    let page = dir.join("page.html");
    let missing = dir.join("no-such-folder");
    let out = slipload(&["report", s(&missing), "--out", s(&page)]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no-such-folder") && err.contains("does not exist"),
        "{err}"
    );
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    std::fs::write(empty.join("notes.txt"), "hello").unwrap();
    let out = slipload(&["report", s(&empty)]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("empty") && err.contains("holds nothing slipload report recognises"),
        "{err}"
    );
    assert!(!page.exists());
    assert!(!empty.join("report.html").exists());
    let names: Vec<_> = std::fs::read_dir(&empty).unwrap().collect();
    assert_eq!(
        names.len(),
        1,
        "only notes.txt: no report, no temporary file"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
