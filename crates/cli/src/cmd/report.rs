//! `slipload report DIR`: one self-contained HTML page from an output folder — a
//! simulation `--plot` folder, an `accuracy --out` folder or a `sweep`/`optimize` study
//! folder. The page holds a title and the kind of folder, the key tables (Markdown, CSV
//! and JSON summaries as HTML tables), every `NAME.svg` in the folder inlined (so new
//! figures appear without code changes), the inputs (scene, study, manifest JSON)
//! pretty-printed in collapsible blocks, and the slipload version. It loads nothing from
//! elsewhere (no scripts, fonts or style sheets from the network) and opens offline.

use crate::html::{csv_table, escape, json_table, markdown};
use anyhow::{Context, bail};
use slipload_opt::output::write_atomic;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Arguments of `slipload report`.
#[derive(Debug, clap::Args)]
pub struct ReportArgs {
    /// Output folder to report on: from `simulate --plot`, `accuracy --out`, or
    /// `sweep`/`optimize --out`
    pub dir: PathBuf,
    /// HTML file to write (default: DIR/report.html)
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Data rows shown per CSV table (the files keep them all)
    #[arg(long, default_value_t = 100)]
    pub max_rows: usize,
}

/// What kind of output folder this is, recognised from the files it holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FolderKind {
    /// `slipload optimize --out`: a finished sweep plus `optimum.json`.
    Optimize,
    /// `slipload sweep --out` (or `merge --out`): `manifest.json` of a study.
    Sweep,
    /// `slipload accuracy --out`: `NAME.json` with the median and per-record studies.
    Accuracy,
    /// `slipload simulate --plot`: a time-history CSV (first column `t_s`).
    Simulation,
    /// Only figures (`NAME.svg`).
    Figures,
}

impl FolderKind {
    /// What the folder holds, in a sentence ("the design study").
    pub fn noun(self) -> &'static str {
        match self {
            Self::Optimize => "design study",
            Self::Sweep => "design sweep",
            Self::Accuracy => "accuracy study",
            Self::Simulation => "simulation",
            Self::Figures => "figures",
        }
    }

    /// A description for the page.
    pub fn describe(self) -> &'static str {
        match self {
            Self::Optimize => "design study (slipload optimize: sweep, refinement, design table)",
            Self::Sweep => "design sweep (slipload sweep)",
            Self::Accuracy => {
                "accuracy study (slipload accuracy: error vs cost per method and time step)"
            }
            Self::Simulation => "simulation (slipload simulate --plot)",
            Self::Figures => "figures",
        }
    }
}

/// One file of the folder.
#[derive(Debug, Clone)]
struct Entry {
    name: String,
    stem: String,
    ext: String,
    path: PathBuf,
}

/// The files of the folder, by name, hidden and temporary files left out.
fn list(dir: &Path) -> anyhow::Result<Vec<Entry>> {
    let mut files = Vec::new();
    for e in std::fs::read_dir(dir).with_context(|| format!("reading folder {}", dir.display()))? {
        let e = e.with_context(|| format!("reading folder {}", dir.display()))?;
        let path = e.path();
        let name = e.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') || !path.is_file() {
            continue;
        }
        let (stem, ext) = match name.rsplit_once('.') {
            Some((s, x)) => (s.to_string(), x.to_ascii_lowercase()),
            None => (name.clone(), String::new()),
        };
        files.push(Entry {
            name,
            stem,
            ext,
            path,
        });
    }
    files.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(files)
}

fn read(e: &Entry) -> anyhow::Result<String> {
    std::fs::read_to_string(&e.path).with_context(|| format!("reading {}", e.path.display()))
}

fn read_json(e: &Entry) -> Option<serde_json::Value> {
    serde_json::from_str(&read(e).ok()?).ok()
}

/// The folder's kind and a title for the page, or `None` when nothing is recognised.
fn recognise(dir: &Path, files: &[Entry]) -> Option<(FolderKind, String)> {
    let find = |name: &str| files.iter().find(|e| e.name == name);
    let dir_name = dir
        .canonicalize()
        .ok()
        .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .unwrap_or_else(|| dir.display().to_string());
    if let Some(m) = find("manifest.json").and_then(read_json)
        && m.get("designs").is_some()
        && let Some(study) = m.get("study").and_then(|s| s.as_str())
    {
        let kind = if find("optimum.json").is_some() {
            FolderKind::Optimize
        } else {
            FolderKind::Sweep
        };
        return Some((kind, study.to_string()));
    }
    let accuracy: Vec<&Entry> = files
        .iter()
        .filter(|e| e.ext == "json")
        .filter(|e| {
            read_json(e).is_some_and(|v| v.get("median").is_some() && v.get("records").is_some())
        })
        .collect();
    if !accuracy.is_empty() {
        let title = match accuracy.as_slice() {
            [one] => one.stem.clone(),
            many => format!("{} accuracy studies", many.len()),
        };
        return Some((FolderKind::Accuracy, title));
    }
    let history = files.iter().find(|e| {
        e.ext == "csv"
            && read(e)
                .ok()
                .is_some_and(|t| t.starts_with("t_s,") || t.starts_with("\"t_s\","))
    });
    if history.is_some() {
        let scene_name = files
            .iter()
            .filter(|e| e.ext == "json")
            .filter_map(read_json)
            .find_map(|v| v.get("name").and_then(|n| n.as_str()).map(String::from));
        return Some((FolderKind::Simulation, scene_name.unwrap_or(dir_name)));
    }
    if files.iter().any(|e| e.ext == "svg") {
        return Some((FolderKind::Figures, dir_name));
    }
    None
}

/// The version line: the package version and, when the build knew it, the git commit.
pub fn version() -> String {
    match option_env!("SLIPLOAD_GIT_COMMIT") {
        Some(c) => format!("slipload {} (commit {c})", env!("CARGO_PKG_VERSION")),
        None => format!("slipload {}", env!("CARGO_PKG_VERSION")),
    }
}

/// An SVG file ready to inline: from its `<svg` on (XML prolog and doctype dropped),
/// with a `viewBox` so it scales with the page. `Err` says why it is not inlined:
/// anything that could run code (scripts, event handlers, foreign objects) is refused,
/// since the page must be safe to open.
fn inline_svg(text: &str) -> Result<String, &'static str> {
    let lower = text.to_ascii_lowercase();
    if lower.contains("<script")
        || lower.contains("javascript:")
        || lower.contains("<foreignobject")
        || has_event_handler(&lower)
    {
        return Err("it holds a script, an event handler or a foreign object");
    }
    let start = lower.find("<svg").ok_or("no <svg> element")?;
    let svg = &text[start..];
    let tag_end = svg.find('>').ok_or("unterminated <svg> tag")?;
    let tag = &svg[..tag_end];
    if tag.contains("viewBox") {
        return Ok(svg.to_string());
    }
    let attr = |name: &str| -> Option<f64> {
        let i = tag.find(&format!(" {name}=\""))? + name.len() + 3;
        let rest = &tag[i..];
        let v = &rest[..rest.find('"')?];
        v.trim_end_matches("px").parse().ok()
    };
    match (attr("width"), attr("height")) {
        (Some(w), Some(h)) => Ok(format!(
            "<svg viewBox=\"0 0 {w} {h}\"{}",
            &svg["<svg".len()..]
        )),
        _ => Ok(svg.to_string()),
    }
}

/// ` onload=`, ` onclick=` … anywhere in (lower-cased) markup.
fn has_event_handler(lower: &str) -> bool {
    lower.match_indices(" on").any(|(i, _)| {
        let rest = &lower[i + 3..];
        let name_len = rest.chars().take_while(|c| c.is_ascii_alphabetic()).count();
        name_len > 0 && rest[name_len..].trim_start().starts_with('=')
    })
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

fn details(summary: &str, inner: &str, open: bool) -> String {
    format!(
        "<details{}><summary>{summary}</summary>\n{inner}</details>\n",
        if open { " open" } else { "" }
    )
}

/// Markdown files in the order a reader wants them for this kind of folder.
fn table_order(kind: FolderKind) -> &'static [&'static str] {
    match kind {
        FolderKind::Optimize | FolderKind::Sweep => &["design-table.md", "rank.md", "family.md"],
        _ => &[],
    }
}

/// JSON files that are inputs (what produced the folder), shown first among the inputs.
fn is_input(e: &Entry) -> bool {
    e.name == "manifest.json"
        || e.stem.contains("scene")
        || e.stem.contains("study")
        || e.stem.contains("config")
}

/// JSON summaries shown as tables in the tables section.
fn is_summary(e: &Entry) -> bool {
    matches!(e.name.as_str(), "optimum.json" | "candidates.json") || e.stem.contains("response")
}

/// Builds the page for `dir`.
pub fn build(dir: &Path, max_rows: usize) -> anyhow::Result<(FolderKind, String)> {
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

    // Summary: summary.txt and the optimum's key numbers
    let summary_txt = by_name("summary.txt");
    let optimum = by_name("optimum.json").and_then(read_json);
    if summary_txt.is_some() || optimum.is_some() {
        page.section("summary", "Summary");
        if let Some(o) = &optimum {
            page.body.push_str(&key_results(o));
        }
        if let Some(e) = summary_txt {
            let _ = writeln!(page.body, "<pre>{}</pre>", escape(&read(e)?));
            shown.push(e.name.clone());
        }
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
    for e in files.iter().filter(|e| e.ext == "md") {
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
    let mut jsons: Vec<&Entry> = files.iter().filter(|e| e.ext == "json").collect();
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

/// The optimum's key numbers as a table.
fn key_results(o: &serde_json::Value) -> String {
    let num = |k: &str| o.get(k).and_then(serde_json::Value::as_f64);
    let mut rows: Vec<(String, String)> = Vec::new();
    if let Some(s) = o.get("objective").and_then(|s| s.as_str()) {
        rows.push(("objective".into(), s.to_string()));
    }
    if let Some(loads) = o.get("slip_loads_kN").and_then(|v| v.as_array()) {
        let floors: Vec<String> = o
            .get("damper_floors")
            .and_then(|v| v.as_array())
            .map(|a| a.iter().map(|f| f.to_string()).collect())
            .unwrap_or_default();
        let loads: Vec<String> = loads
            .iter()
            .filter_map(serde_json::Value::as_f64)
            .map(|v| format!("{v:.1}"))
            .collect();
        rows.push((
            format!("optimal slip loads (kN), floors {}", floors.join(" / ")),
            loads.join(" / "),
        ));
    }
    if let Some(f) = num("objective_value") {
        rows.push(("objective at the optimum".into(), format!("{f:.6}")));
    }
    if let (Some(f), Some(b)) = (num("objective_value"), num("bare_objective")) {
        rows.push((
            "bare frame".into(),
            format!("{b:.6} (optimum {:.1} % lower)", 100.0 * (1.0 - f / b)),
        ));
    }
    if let Some(s) = o.get("refiner").and_then(|s| s.as_str()) {
        rows.push(("refiner".into(), s.to_string()));
    }
    if rows.is_empty() {
        return String::new();
    }
    let mut out = String::from("<table class=\"kv\"><tbody>\n");
    for (k, v) in rows {
        let _ = writeln!(
            out,
            "<tr><th>{}</th><td>{}</td></tr>",
            escape(&k),
            escape(&v)
        );
    }
    out.push_str("</tbody></table>\n");
    out
}

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
";

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

/// Runs `slipload report`.
pub fn run(args: ReportArgs) -> anyhow::Result<()> {
    let (kind, html) = build(&args.dir, args.max_rows.max(1))?;
    let out = args.out.unwrap_or_else(|| args.dir.join("report.html"));
    write_atomic(&out, html.as_bytes())?;
    eprintln!(
        "report of the {} in {} written to {}",
        kind.noun(),
        args.dir.display(),
        out.display()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn svg_gets_a_viewbox_and_loses_its_prolog() {
        let s = inline_svg("<?xml version=\"1.0\"?>\n<svg width=\"800\" height=\"600\" xmlns=\"http://www.w3.org/2000/svg\"><rect/></svg>").unwrap();
        assert!(
            s.starts_with("<svg viewBox=\"0 0 800 600\" width=\"800\""),
            "{s}"
        );
        let kept = inline_svg("<svg viewBox=\"0 0 1 1\"></svg>").unwrap();
        assert_eq!(kept, "<svg viewBox=\"0 0 1 1\"></svg>");
    }

    #[test]
    fn svg_with_code_is_refused() {
        for bad in [
            "<svg><script>alert(1)</script></svg>",
            "<svg onload=\"alert(1)\"></svg>",
            "<svg><a href=\"javascript:x\"/></svg>",
            "<svg><foreignObject/></svg>",
        ] {
            assert!(inline_svg(bad).is_err(), "{bad}");
        }
        // text that merely contains " on" is fine
        assert!(inline_svg("<svg><text>based on data</text></svg>").is_ok());
    }
}
