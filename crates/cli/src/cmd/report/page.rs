//! The page of `slipload report`: its sections in the order a reader wants them
//! (a study's building, summary, trade-off, run, tables, figures, data, inputs, other
//! files), which file goes
//! where, the style sheet and the frame (title, contents, version).

use super::folder::{Entry, FolderKind, list, read, read_json, recognise};
use super::simulation::simulation_run;
use super::study::{key_results, pareto_section};
use super::svg::inline_svg;
use crate::html::{csv_table, escape, json_table, markdown};
use anyhow::bail;
use std::fmt::Write as _;
use std::path::Path;

/// The version line: the package version and, when the build knew it, the git commit.
pub fn version() -> String {
    match option_env!("SLIPLOAD_GIT_COMMIT") {
        Some(c) => format!("slipload {} (commit {c})", env!("CARGO_PKG_VERSION")),
        None => format!("slipload {}", env!("CARGO_PKG_VERSION")),
    }
}

/// Where a file appears on the page.
#[derive(Default)]
struct Page {
    toc: Vec<(String, String)>,
    body: String,
}

impl Page {
    fn section(&mut self, id: &str, title: &str) {
        self.toc.push((id.to_string(), title.to_string()));
        let _ = writeln!(
            self.body,
            "<section id=\"{}\">\n<h2>{}</h2>",
            escape(id),
            escape(title)
        );
    }
    fn end(&mut self) {
        self.body.push_str("</section>\n");
    }
}

/// A collapsible block (`open`: shown unfolded).
fn details(summary: &str, inner: &str, open: bool) -> String {
    format!(
        "<details{}><summary>{summary}</summary>\n{inner}</details>\n",
        if open { " open" } else { "" }
    )
}

/// Markdown files in the order a reader wants them for this kind of folder.
fn table_order(kind: FolderKind) -> &'static [&'static str] {
    match kind {
        FolderKind::Optimize | FolderKind::Sweep => &[
            "code-check.md",
            "device-table.md",
            "design-table.md",
            "pareto-table.md",
            "rank.md",
            "family.md",
        ],
        FolderKind::PlanStudy => &["plan-check.md", "plan-devices.md", "plan-dampers.md"],
        _ => &[],
    }
}

/// JSON files that are inputs (what produced the folder), shown first among the inputs.
fn is_input(e: &Entry) -> bool {
    e.name == "manifest.json"
        || e.name == "building.json"
        || e.stem.contains("scene")
        || e.stem.contains("study")
        || e.stem.contains("config")
}

/// JSON summaries shown as tables in the tables section (a simulation's
/// `response.json` is shown as its per-storey table instead, [`simulation_run`]).
fn is_summary(e: &Entry) -> bool {
    matches!(e.name.as_str(), "optimum.json" | "candidates.json")
}

/// JSON outputs whose content the page shows as tables already: a study's design table
/// (`design-table.md`, `.csv`), a simulation's responses (the run section).
fn shown_as_table(kind: FolderKind, e: &Entry) -> bool {
    match kind {
        FolderKind::Optimize | FolderKind::Sweep => matches!(
            e.name.as_str(),
            "design-table.json" | "code-check.json" | "device-table.json"
        ),
        FolderKind::Simulation => e.stem.starts_with("response"),
        // the summary and the check, device and damper tables show the optimum's file
        FolderKind::PlanStudy => e.name == "plan-optimum.json",
        _ => false,
    }
}

/// Builds the page for `dir`.
pub(super) fn build(dir: &Path, max_rows: usize) -> anyhow::Result<(FolderKind, String)> {
    if !dir.exists() {
        bail!("report folder {} does not exist", dir.display());
    }
    if !dir.is_dir() {
        bail!(
            "{} is not a folder (give an output folder of slipload)",
            dir.display()
        );
    }
    let files = list(dir)?;
    let Some((kind, title)) = recognise(dir, &files) else {
        bail!(
            "{} holds nothing slipload report recognises: expected a study folder \
             (manifest.json from `sweep`/`optimize --out`), an accuracy folder (NAME.json from \
             `accuracy --out`), a simulation folder (a history CSV from `simulate --plot`) \
             or figures (NAME.svg)",
            dir.display()
        );
    };
    let mut page = Page::default();
    let mut shown: Vec<String> = Vec::new();
    let by_name = |n: &str| files.iter().find(|e| e.name == n);

    // A study's building first: what was designed (building.md, which optimize writes)
    if matches!(
        kind,
        FolderKind::Optimize | FolderKind::Sweep | FolderKind::PlanStudy
    ) && let Some(e) = by_name("building.md")
    {
        page.section("building", "Building");
        let _ = writeln!(
            page.body,
            "<div class=\"file\"><p class=\"src\">{}</p>\n{}</div>",
            escape(&e.name),
            markdown(&read(e)?, 3)
        );
        shown.push(e.name.clone());
        page.end();
    }

    // Summary: summary.txt and the optimum's key numbers
    let summary_txt = by_name("summary.txt").or_else(|| by_name("plan-summary.txt"));
    let optimum = by_name("optimum.json").and_then(read_json);
    let design_table = by_name("design-table.json").and_then(read_json);
    let manifest = by_name("manifest.json").and_then(read_json);
    if summary_txt.is_some() || optimum.is_some() {
        page.section("summary", "Summary");
        if let Some(o) = &optimum {
            page.body
                .push_str(&key_results(o, design_table.as_ref(), manifest.as_ref()));
        }
        if let Some(e) = summary_txt {
            let _ = writeln!(page.body, "<pre>{}</pre>", escape(&read(e)?));
            shown.push(e.name.clone());
        }
        page.end();
    }

    // A study with objectives: its front, the knee and whether the check held it
    if let Some(p) = by_name("pareto.json").and_then(read_json) {
        page.section("trade-off", "Trade-off");
        page.body.push_str(&pareto_section(&p));
        page.end();
    }

    // A simulation: what ran, and its responses per storey in engineering units
    if kind == FolderKind::Simulation
        && let Some(response) = by_name("response.json").and_then(read_json)
    {
        page.section("run", "Run and responses");
        let scene = by_name("scene.json").and_then(read_json);
        let bare = by_name("response-bare.json").and_then(read_json);
        page.body
            .push_str(&simulation_run(scene.as_ref(), &response, bare.as_ref()));
        page.end();
    }

    // Tables: Markdown (in the kind's order, then the rest), then JSON summaries
    let mut md: Vec<&Entry> = Vec::new();
    for n in table_order(kind) {
        if let Some(e) = by_name(n)
            && !md.iter().any(|m| m.name == e.name)
        {
            md.push(e);
        }
    }
    for e in files
        .iter()
        .filter(|e| e.ext == "md" && !shown.contains(&e.name))
    {
        if !md.iter().any(|m| m.name == e.name) {
            md.push(e);
        }
    }
    let summaries: Vec<&Entry> = files
        .iter()
        .filter(|e| e.ext == "json" && is_summary(e))
        .collect();
    if !md.is_empty() || !summaries.is_empty() {
        page.section("tables", "Tables");
        for e in md {
            let _ = writeln!(
                page.body,
                "<div class=\"file\"><p class=\"src\">{}</p>\n{}</div>",
                escape(&e.name),
                markdown(&read(e)?, 3)
            );
            shown.push(e.name.clone());
        }
        for e in summaries {
            let text = read(e)?;
            let inner = match serde_json::from_str::<serde_json::Value>(&text) {
                Ok(v) => format!("<div class=\"scroll\">{}</div>", json_table(&v, 4)),
                Err(_) => format!("<pre>{}</pre>", escape(&text)),
            };
            let _ = writeln!(
                page.body,
                "<div class=\"file\"><h3>{}</h3>\n{inner}</div>",
                escape(&e.name)
            );
        }
        page.end();
    }

    // Figures: every NAME.svg, with NAME.csv (its data) beside it when present
    let svgs: Vec<&Entry> = files.iter().filter(|e| e.ext == "svg").collect();
    if !svgs.is_empty() {
        page.section("figures", "Figures");
        for e in svgs {
            let data = by_name(&format!("{}.csv", e.stem));
            let _ = writeln!(page.body, "<figure id=\"fig-{}\">", escape(&e.stem));
            match inline_svg(&read(e)?) {
                Ok(svg) => page.body.push_str(&svg),
                Err(why) => {
                    let _ = write!(
                        page.body,
                        "<p class=\"note\">{} is not inlined: {why}.</p>",
                        escape(&e.name)
                    );
                }
            }
            let _ = writeln!(
                page.body,
                "\n<figcaption>{}{}</figcaption>",
                escape(&e.name),
                data.map_or(String::new(), |d| format!(" · data: {}", escape(&d.name)))
            );
            if let Some(d) = data {
                page.body.push_str(&details(
                    &format!("data ({})", escape(&d.name)),
                    &csv_table(&read(d)?, max_rows),
                    false,
                ));
                shown.push(d.name.clone());
            }
            page.body.push_str("</figure>\n");
            shown.push(e.name.clone());
        }
        page.end();
    }

    // Data: the other CSV files, collapsed
    let csvs: Vec<&Entry> = files
        .iter()
        .filter(|e| e.ext == "csv" && !shown.contains(&e.name))
        .collect();
    if !csvs.is_empty() {
        page.section("data", "Data");
        for e in csvs {
            page.body.push_str(&details(
                &escape(&e.name),
                &csv_table(&read(e)?, max_rows),
                false,
            ));
            shown.push(e.name.clone());
        }
        page.end();
    }

    // Inputs and raw JSON: pretty-printed, collapsed; inputs first
    // (outputs already shown as tables above are not repeated with every digit)
    let mut jsons: Vec<&Entry> = files
        .iter()
        .filter(|e| e.ext == "json" && !is_summary(e) && !shown_as_table(kind, e))
        .collect();
    jsons.sort_by_key(|e| !is_input(e));
    if !jsons.is_empty() {
        page.section("inputs", "Inputs and JSON files");
        for e in jsons {
            let text = read(e)?;
            let pretty = serde_json::from_str::<serde_json::Value>(&text)
                .ok()
                .and_then(|v| serde_json::to_string_pretty(&v).ok())
                .unwrap_or(text);
            let label = if is_input(e) {
                format!("{} (input)", escape(&e.name))
            } else {
                escape(&e.name)
            };
            page.body.push_str(&details(
                &label,
                &format!("<pre>{}</pre>\n", escape(&pretty)),
                false,
            ));
            shown.push(e.name.clone());
        }
        page.end();
    }

    let others: Vec<&str> = files
        .iter()
        .filter(|e| !shown.contains(&e.name) && e.ext != "html")
        .map(|e| e.name.as_str())
        .collect();
    if !others.is_empty() {
        page.section("files", "Other files in the folder");
        let _ = writeln!(
            page.body,
            "<p>{}</p>",
            others
                .iter()
                .map(|n| format!("<code>{}</code>", escape(n)))
                .collect::<Vec<_>>()
                .join(", ")
        );
        page.end();
    }

    Ok((kind, assemble(kind, &title, dir, &page)))
}

/// The page's style sheet, inline (the page loads nothing from elsewhere).
const STYLE: &str = "
body{font-family:system-ui,-apple-system,'Segoe UI','DejaVu Sans',sans-serif;margin:0 auto;max-width:1200px;padding:1em 2em;color:#222;line-height:1.45}
header{border-bottom:2px solid #345;margin-bottom:1em}
h1{margin:.2em 0}
h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}
nav ul{list-style:none;padding:0;display:flex;flex-wrap:wrap;gap:1.2em}
.meta{color:#555;margin:.2em 0}
table{border-collapse:collapse;margin:.5em 0;font-size:.9em}
th,td{border:1px solid #ccc;padding:.25em .6em;text-align:left;vertical-align:top}
thead th{background:#eef2f6}
td.num,th.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
td.nw{white-space:nowrap;font-variant-numeric:tabular-nums}
td.mid,th.mid{text-align:center}
table.kv th{background:#f6f8fa;font-weight:600}
.scroll{overflow-x:auto}
.file{margin:1.2em 0}
.src{color:#777;font-size:.85em;margin:0}
.note{color:#777;font-style:italic}
figure{margin:1.5em 0;padding:.5em;border:1px solid #e3e3e3}
figure svg{display:block;max-width:100%;height:auto;margin:0 auto}
figcaption{color:#555;font-size:.9em;margin-top:.3em}
details{margin:.4em 0}
summary{cursor:pointer;font-weight:600}
pre{background:#f6f8fa;padding:.6em;overflow-x:auto;font-size:.85em}
code{font-size:.92em}
footer{margin-top:3em;color:#777;font-size:.85em;border-top:1px solid #ccc}
.warn{background:#fff4e0;border-left:4px solid #d08000;padding:.4em .8em}
.scroll{max-width:100%}
.scroll>table{min-width:max-content}
@media print{
@page{size:A4 landscape;margin:12mm}
body{max-width:none;padding:0;font-size:9pt;line-height:1.3}
nav{display:none}
.scroll{overflow:visible}
.scroll>table{min-width:0;width:100%}
table{font-size:7pt;page-break-inside:auto}
tr{break-inside:avoid}
th,td{padding:.1em .3em}
td.num,th.num,td.nw{white-space:nowrap}
thead{display:table-header-group}
figure{break-inside:avoid;border:none}
figure svg{max-height:24cm}
pre{white-space:pre-wrap;word-break:break-all;font-size:7pt}
h2{break-after:avoid}
}
";

/// The whole page: the head with the style, the header with the title and contents,
/// the sections, the footer with the version.
fn assemble(kind: FolderKind, title: &str, dir: &Path, page: &Page) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <meta name=\"generator\" content=\"{}\">\n<title>{} — slipload report</title>\n\
         <style>{STYLE}</style>\n</head>\n<body>",
        escape(&version()),
        escape(title)
    );
    let _ = writeln!(
        s,
        "<header>\n<h1>{}</h1>\n<p class=\"meta\">{} · folder <code>{}</code></p>\n\
         <p class=\"meta\">Generated by {}</p>\n",
        escape(title),
        escape(kind.describe()),
        escape(&dir.display().to_string()),
        escape(&version())
    );
    s.push_str("<nav><ul>");
    for (id, t) in &page.toc {
        let _ = write!(s, "<li><a href=\"#{}\">{}</a></li>", escape(id), escape(t));
    }
    s.push_str("</ul></nav>\n</header>\n<main>\n");
    s.push_str(&page.body);
    let _ = writeln!(
        s,
        "</main>\n<footer><p>{} · <code>slipload report {}</code></p></footer>\n</body>\n</html>",
        escape(&version()),
        escape(&dir.display().to_string())
    );
    s
}
