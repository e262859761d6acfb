//! `slipload report DIR`: one self-contained HTML page from an output folder — a
//! simulation `--plot` folder, an `accuracy --out` folder or a `sweep`/`optimize` study
//! folder. The page holds a title and the kind of folder, the key tables (Markdown, CSV
//! and JSON summaries as HTML tables), every `NAME.svg` in the folder inlined (so new
//! figures appear without code changes), the inputs (scene, study, manifest JSON)
//! pretty-printed in collapsible blocks, and the slipload version. It loads nothing from
//! elsewhere (no scripts, fonts or style sheets from the network) and opens offline.

use crate::html::{csv_table, escape, json_table, markdown, sig};
use anyhow::{Context, bail};
use slipload_opt::base::output::write_atomic;
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
        // the scene `simulate --plot` keeps beside its figures names the page
        let scene_name = find("scene.json")
            .into_iter()
            .chain(files.iter().filter(|e| e.ext == "json"))
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
        FolderKind::Optimize | FolderKind::Sweep => {
            &["design-table.md", "pareto-table.md", "rank.md", "family.md"]
        }
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

/// JSON summaries shown as tables in the tables section (a simulation's
/// `response.json` is shown as its per-storey table instead, [`simulation_run`]).
fn is_summary(e: &Entry) -> bool {
    matches!(e.name.as_str(), "optimum.json" | "candidates.json")
}

/// JSON outputs whose content the page shows as tables already: a study's design table
/// (`design-table.md`, `.csv`), a simulation's responses (the run section).
fn shown_as_table(kind: FolderKind, e: &Entry) -> bool {
    match kind {
        FolderKind::Optimize | FolderKind::Sweep => e.name == "design-table.json",
        FolderKind::Simulation => e.stem.starts_with("response"),
        _ => false,
    }
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
    let design_table = by_name("design-table.json").and_then(read_json);
    if summary_txt.is_some() || optimum.is_some() {
        page.section("summary", "Summary");
        if let Some(o) = &optimum {
            page.body.push_str(&key_results(o, design_table.as_ref()));
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

/// A key/value table.
/// The trade-off of a study with objectives, from `pareto.json`: the objectives, the
/// front's size and cost, the knee and each objective's optimum with their slip loads and
/// objectives, and whether the front held at the check fidelity.
fn pareto_section(p: &serde_json::Value) -> String {
    let text = |v: &serde_json::Value| v.as_str().unwrap_or("").to_string();
    let list = |v: &serde_json::Value, digits: usize| {
        v.as_array()
            .map(|a| {
                a.iter()
                    .map(|x| x.as_f64().map_or("—".into(), |f| format!("{f:.digits$}")))
                    .collect::<Vec<_>>()
                    .join(" / ")
            })
            .unwrap_or_default()
    };
    let names: Vec<String> = p["objectives"]
        .as_array()
        .map(|a| a.iter().map(text).collect())
        .unwrap_or_default();
    let front = p["front"].as_array().cloned().unwrap_or_default();
    let entry = |label: &str| {
        front
            .iter()
            .find(|e| e["label"].as_str() == Some(label))
            .map(|e| {
                format!(
                    "{} — slip loads {} kN; objectives (sweep) {}; (check) {}",
                    label,
                    list(&e["slip_loads_kN"], 1),
                    list(&e["sweep"], 5),
                    list(&e["check"], 5)
                )
            })
            .unwrap_or_else(|| label.to_string())
    };
    let mut rows = vec![
        ("objectives".to_string(), names.join(" vs ")),
        (
            "front".to_string(),
            format!(
                "{} designs non-dominated of {} evaluated ({} sweep-fidelity simulations)",
                front.len(),
                p["sweep_designs"].as_u64().unwrap_or(0)
                    + p["search_designs"].as_u64().unwrap_or(0),
                p["sweep_fidelity_simulations"].as_u64().unwrap_or(0)
            ),
        ),
        ("knee".to_string(), entry(&text(&p["knee"]))),
    ];
    if let Some(ext) = p["extremes"].as_array() {
        for e in ext {
            rows.push((format!("optimum of {}", text(&e[0])), entry(&text(&e[1]))));
        }
    }
    let dominated: Vec<String> = p["dominated_at_check"]
        .as_array()
        .map(|a| a.iter().map(|d| text(&d[0])).collect())
        .unwrap_or_default();
    rows.push((
        "at the check fidelity".to_string(),
        if dominated.is_empty() {
            "the front held: no design became dominated".to_string()
        } else {
            format!("dominated now: {}", dominated.join(", "))
        },
    ));
    rows.push((
        "hypervolume".to_string(),
        format!(
            "{:.6e} against the reference point {}",
            p["hypervolume"].as_f64().unwrap_or(f64::NAN),
            list(&p["reference_point"], 6)
        ),
    ));
    kv_table(&rows)
}

fn kv_table(rows: &[(String, String)]) -> String {
    let mut out = String::from("<div class=\"scroll\"><table class=\"kv\"><tbody>\n");
    for (k, v) in rows {
        let _ = writeln!(out, "<tr><th>{}</th><td>{}</td></tr>", escape(k), escape(v));
    }
    out.push_str("</tbody></table></div>\n");
    out
}

/// An HTML table: a header row, then rows; cells are text (escaped here), numbers (cells
/// that parse as one, or "—") right-aligned.
fn grid(head: &[String], rows: &[Vec<String>]) -> String {
    let num = |c: &str| c == "—" || c.parse::<f64>().is_ok();
    let mut out = String::from("<div class=\"scroll\"><table>\n<thead><tr>");
    for (k, h) in head.iter().enumerate() {
        let class = if k > 0 { " class=\"num\"" } else { "" };
        let _ = write!(out, "<th{class}>{}</th>", escape(h));
    }
    out.push_str("</tr></thead>\n<tbody>\n");
    for r in rows {
        out.push_str("<tr>");
        for (k, c) in r.iter().enumerate() {
            let class = if k > 0 && num(c) {
                " class=\"num\""
            } else {
                ""
            };
            let _ = write!(out, "<td{class}>{}</td>", escape(c));
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</tbody></table></div>\n");
    out
}

fn f64_at(v: &serde_json::Value, key: &str) -> Option<f64> {
    v.get(key).and_then(serde_json::Value::as_f64)
}

fn f64s_at(v: &serde_json::Value, key: &str) -> Option<Vec<f64>> {
    v.get(key)?
        .as_array()?
        .iter()
        .map(serde_json::Value::as_f64)
        .collect()
}

/// `optimum.json`'s `on_bound` entries as a sentence: "floor 2 at its upper bound
/// (2000.0 kN)"; a profile's scale names the floors it sets.
fn on_bound_text(o: &serde_json::Value) -> Option<String> {
    let entries = o.get("on_bound")?.as_array()?;
    if entries.is_empty() {
        return None;
    }
    let floors: Vec<u64> = o
        .get("damper_floors")
        .and_then(|v| v.as_array())
        .map(|a| a.iter().filter_map(serde_json::Value::as_u64).collect())
        .unwrap_or_default();
    let loads = f64s_at(o, "slip_loads_kN").unwrap_or_default();
    let load_of = |f: u64| {
        floors
            .iter()
            .position(|&x| x == f)
            .and_then(|k| loads.get(k))
            .map(|v| format!("{v:.1} kN"))
    };
    let parts: Vec<String> = entries
        .iter()
        .map(|b| {
            let fl: Vec<u64> = b
                .get("floors")
                .and_then(|v| v.as_array())
                .map(|a| a.iter().filter_map(serde_json::Value::as_u64).collect())
                .unwrap_or_default();
            let bound = b.get("bound").and_then(|v| v.as_str()).unwrap_or("?");
            let variable = b.get("variable").and_then(|v| v.as_str()).unwrap_or("?");
            let at: Vec<String> = fl.iter().filter_map(|&f| load_of(f)).collect();
            let names: Vec<String> = fl.iter().map(u64::to_string).collect();
            if fl.len() == 1 && variable.starts_with("floor") {
                format!("floor {} at its {bound} bound ({})", names[0], at.join(""))
            } else {
                format!(
                    "{variable} (floors {}) at its {bound} bound ({})",
                    names.join(", "),
                    at.join(" / ")
                )
            }
        })
        .collect();
    Some(parts.join("; "))
}

/// The optimum's key numbers as a table, the floors on a bound of the design space, and
/// what the optimum costs in base shear and floor acceleration against the building
/// file's slip loads and the bare frame (from `design-table.json`), rounded as the
/// design tables round them.
fn key_results(o: &serde_json::Value, table: Option<&serde_json::Value>) -> String {
    let num = |k: &str| f64_at(o, k);
    let mut rows: Vec<(String, String)> = Vec::new();
    if let Some(s) = o.get("objective").and_then(|s| s.as_str()) {
        rows.push(("objective".into(), s.to_string()));
    }
    if let Some(loads) = f64s_at(o, "slip_loads_kN") {
        let floors: Vec<String> = o
            .get("damper_floors")
            .and_then(|v| v.as_array())
            .map(|a| a.iter().map(|f| f.to_string()).collect())
            .unwrap_or_default();
        let loads: Vec<String> = loads.iter().map(|v| format!("{v:.1}")).collect();
        rows.push((
            format!("optimal slip loads (kN), floors {}", floors.join(" / ")),
            loads.join(" / "),
        ));
    }
    if let Some(f) = num("objective_value") {
        rows.push(("objective at the optimum".into(), format!("{f:.6}")));
    }
    let lower = |f: f64, b: f64| format!("{b:.6} (optimum {:.1} % lower)", 100.0 * (1.0 - f / b));
    if let (Some(f), Some(b)) = (num("objective_value"), num("bare_objective")) {
        rows.push(("bare frame".into(), lower(f, b)));
    }
    if let (Some(f), Some(b)) = (num("objective_value"), num("file_objective")) {
        rows.push(("building file's slip loads".into(), lower(f, b)));
    }
    if let Some(s) = o.get("refiner").and_then(|s| s.as_str()) {
        rows.push(("refiner".into(), s.to_string()));
    }
    let mut out = String::new();
    if let Some(t) = on_bound_text(o) {
        let _ = writeln!(
            out,
            "<p class=\"warn\"><strong>On a bound of the design space</strong> (the optimum may lie beyond it: widen the bound to see): {}</p>",
            escape(&t)
        );
    }
    if !rows.is_empty() {
        out.push_str(&kv_table(&rows));
    }
    if let Some(t) = table {
        out.push_str(&costs(t));
    }
    out
}

/// What the optimum costs: mean peak base shear and floor acceleration of the optimum,
/// the building file's slip loads and the bare frame (rows of `design-table.json`).
fn costs(table: &serde_json::Value) -> String {
    let Some(rows) = table.get("rows").and_then(|r| r.as_array()) else {
        return String::new();
    };
    let row = |name: &str| {
        rows.iter()
            .find(|r| r.get("design").and_then(|d| d.as_str()) == Some(name))
    };
    let mut body: Vec<Vec<String>> = Vec::new();
    for (name, label) in [
        ("optimum", "optimum"),
        ("file", "building file's slip loads"),
        ("bare", "bare frame"),
    ] {
        let Some(r) = row(name) else { continue };
        let loads = f64s_at(r, "slip_load_kn").unwrap_or_default();
        body.push(vec![
            label.to_string(),
            loads
                .iter()
                .map(|v| format!("{v:.1}"))
                .collect::<Vec<_>>()
                .join(" / "),
            f64_at(r, "objective").map_or("—".into(), |v| format!("{v:.5}")),
            f64_at(r, "base_shear_mean").map_or("—".into(), |v| format!("{:.2}", v / 1e6)),
            f64_at(r, "peak_floor_acceleration_mean").map_or("—".into(), |v| format!("{v:.2}")),
        ]);
    }
    if body.is_empty() {
        return String::new();
    }
    let fidelity = table.get("fidelity").and_then(|f| f.as_str()).unwrap_or("");
    format!(
        "<h3>What the optimum costs</h3>\n<p>Means over the records of each run's peak ({}).</p>\n{}",
        escape(fidelity),
        grid(
            &[
                "design".into(),
                "slip loads (kN)".into(),
                "objective".into(),
                "peak base shear (MN)".into(),
                "peak floor acceleration (m/s²)".into(),
            ],
            &body,
        )
    )
}

/// A length in mm: 0.01 mm below 10 mm, 0.1 mm below 1 m, whole mm beyond (a column
/// keeps its decimals, so its values line up).
fn mm(v_m: f64) -> String {
    let v = 1e3 * v_m;
    let s = if v.abs() < 10.0 {
        format!("{v:.2}")
    } else if v.abs() < 1000.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.0}")
    };
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        // round-off of nothing (a storey that never yielded): plainly 0
        "0".to_string()
    } else {
        s
    }
}

/// An energy in kJ: 4 significant digits, whole kJ from 1000 kJ on.
fn kj(v_j: f64) -> String {
    let v = v_j / 1e3;
    if v.abs() >= 1000.0 {
        format!("{v:.0}")
    } else {
        sig(v, 4)
    }
}

/// The floors (from 1) with a damper, from a scene's inline building.
fn damper_floors(scene: &serde_json::Value) -> Option<Vec<u64>> {
    let d = scene.get("building")?.get("dissipators")?.as_array()?;
    Some(
        d.iter()
            .filter_map(|x| x.get("floor").and_then(serde_json::Value::as_u64))
            .collect(),
    )
}

/// Per storey: peak drift (mm, % of the storey height), peak displacement, peak absolute
/// acceleration, residual drift, damper slip and stick↔slip transitions ("—" for a
/// storey without a damper), ductility and plastic drift for a yielding frame.
fn storey_table(r: &serde_json::Value, dampers: Option<&[u64]>) -> String {
    let drift = f64s_at(r, "peak_drift").unwrap_or_default();
    let n = drift.len();
    let col = |k: &str| f64s_at(r, k).filter(|v| v.len() == n);
    let ratio = col("peak_drift_ratio");
    let disp = col("peak_displacement");
    let acc = col("peak_abs_acceleration");
    let resid = col("residual_drift");
    let slip = col("peak_slip");
    let trans = col("transitions");
    let ductility: Option<Vec<Option<f64>>> = r
        .get("peak_ductility")
        .and_then(|v| v.as_array())
        .map(|a| a.iter().map(serde_json::Value::as_f64).collect());
    let plastic = col("peak_plastic_drift");
    let mut head: Vec<String> = vec![
        "storey".into(),
        "peak drift (mm)".into(),
        "drift ratio (%)".into(),
        "peak displacement (mm)".into(),
        "peak abs. acceleration (m/s²)".into(),
        "residual drift (mm)".into(),
        "damper slip (mm)".into(),
        "stick↔slip transitions".into(),
    ];
    if ductility.is_some() {
        head.push("ductility".into());
        head.push("plastic drift (mm)".into());
    }
    let dash = || "—".to_string();
    let at = |v: &Option<Vec<f64>>, i: usize, f: &dyn Fn(f64) -> String| {
        v.as_ref().map_or_else(dash, |v| f(v[i]))
    };
    let rows: Vec<Vec<String>> = (0..n)
        .map(|i| {
            let has_damper = dampers.is_none_or(|d| d.contains(&(i as u64 + 1)));
            let mut row = vec![
                (i + 1).to_string(),
                mm(drift[i]),
                at(&ratio, i, &|v| format!("{:.3}", 100.0 * v)),
                at(&disp, i, &mm),
                at(&acc, i, &|v| format!("{v:.2}")),
                at(&resid, i, &mm),
                if has_damper {
                    at(&slip, i, &mm)
                } else {
                    dash()
                },
                if has_damper {
                    at(&trans, i, &|v| format!("{v:.0}"))
                } else {
                    dash()
                },
            ];
            if let Some(d) = &ductility {
                row.push(
                    d.get(i)
                        .copied()
                        .flatten()
                        .map_or("elastic".into(), |m| format!("{m:.2}")),
                );
                // plastic drift below 1 µm is round-off of a storey that never yielded
                row.push(at(&plastic, i, &mm));
            }
            row
        })
        .collect();
    grid(&head, &rows)
}

/// Whole-run responses: peak base shear (kN) and the energies (kJ).
fn run_totals(r: &serde_json::Value) -> Vec<(String, String)> {
    let mut rows = Vec::new();
    if let Some(v) = f64_at(r, "peak_base_shear") {
        rows.push(("peak base shear (kN)".into(), format!("{:.0}", v / 1e3)));
    }
    if let Some(e) = r.get("energy") {
        for (k, label) in [
            ("input", "input energy (kJ)"),
            ("kinetic", "kinetic energy at the end (kJ)"),
            ("strain", "strain energy at the end (kJ)"),
            ("viscous", "viscous energy (kJ)"),
            ("friction", "friction energy (kJ)"),
            ("plastic", "plastic energy of the frame (kJ)"),
        ] {
            if let Some(v) = f64_at(e, k) {
                rows.push((label.into(), kj(v)));
            }
        }
        if let Some(v) = f64_at(e, "balance_error") {
            rows.push((
                "energy balance error (kJ)".into(),
                format!("{:.1e}", v / 1e3),
            ));
        }
    }
    if let Some(c) = r.get("collapse").filter(|c| !c.is_null()) {
        rows.push((
            "collapse".into(),
            format!(
                "storey {} past its drift limit at t = {} s (peaks up to then)",
                c.get("storey").map_or("?".into(), |v| v.to_string()),
                f64_at(c, "time").map_or("?".into(), |t| sig(t, 4))
            ),
        ));
    }
    rows
}

/// What a scene ran on: building, ground motion (or force), scaling, as the facts of
/// the page's run table.
fn scene_facts(scene: &serde_json::Value, floors: usize) -> Vec<(String, String)> {
    let mut rows = Vec::new();
    let b = scene.get("building");
    let bname = b
        .and_then(|b| b.get("name"))
        .and_then(|n| n.as_str())
        .unwrap_or("(unnamed)");
    let dampers = damper_floors(scene).unwrap_or_default();
    let damper_text = match dampers.len() {
        0 => "no dampers".to_string(),
        1 => format!("a damper on floor {}", dampers[0]),
        _ => format!(
            "dampers on floors {}",
            dampers
                .iter()
                .map(u64::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    rows.push((
        "building".into(),
        format!(
            "{bname}: {floors} {}, {damper_text}",
            if floors == 1 { "storey" } else { "storeys" }
        ),
    ));
    let ex = scene.get("excitation");
    let record = ex.and_then(|e| e.get("record")).filter(|r| !r.is_null());
    let synthetic = ex.and_then(|e| e.get("synthetic")).filter(|r| !r.is_null());
    let (motion, scaling) = if let Some(r) = record {
        let file = r.get("file").and_then(|f| f.as_str()).unwrap_or("?");
        let name = Path::new(file)
            .file_name()
            .map_or(file.to_string(), |n| n.to_string_lossy().into_owned());
        let window = f64s_at(r, "window")
            .filter(|w| w.len() == 2)
            .map_or(String::new(), |w| {
                format!(", window {} s from {} s", sig(w[1], 6), sig(w[0], 6))
            });
        let scaling = match (f64_at(r, "scale_pga_g"), f64_at(r, "scale")) {
            (Some(p), _) => format!("scaled to a PGA of {} g", sig(p, 6)),
            (None, Some(f)) => format!("× {}", sig(f, 6)),
            (None, None) => "none (as recorded)".to_string(),
        };
        (format!("{name}{window}"), scaling)
    } else if let Some(syn) = synthetic {
        let pga = f64_at(syn, "pga_g").unwrap_or(slipload_motion::DEFAULT_SUITE_PGA_G);
        let motion = match (
            syn.get("seed").and_then(serde_json::Value::as_u64),
            syn.get("index").and_then(serde_json::Value::as_u64),
        ) {
            (Some(seed), _) => format!("synthetic record, seed {seed}"),
            (None, i) => format!("synthetic record {} of the embedded suite", i.unwrap_or(0)),
        };
        (motion, format!("scaled to a PGA of {} g", sig(pga, 6)))
    } else {
        ("none".to_string(), "—".to_string())
    };
    rows.push(("ground motion".into(), motion));
    rows.push(("scaling".into(), scaling));
    if let Some(h) = ex.and_then(|e| e.get("harmonic")).filter(|h| !h.is_null()) {
        rows.push(("harmonic force".into(), h.to_string()));
    }
    rows
}

/// The run of a `simulate --plot` folder: what ran (from `scene.json`, which
/// `simulate --plot` writes, and `response.json`), then the per-storey table and the
/// whole-run numbers in engineering units, with the bare frame's when the folder has it.
fn simulation_run(
    scene: Option<&serde_json::Value>,
    r: &serde_json::Value,
    bare: Option<&serde_json::Value>,
) -> String {
    let floors = f64s_at(r, "peak_drift").map_or(0, |v| v.len());
    let mut facts = match scene {
        Some(s) => scene_facts(s, floors),
        None => vec![(
            "scene".to_string(),
            "not in the folder (scene.json is written by simulate --plot)".to_string(),
        )],
    };
    if let Some(m) = r.get("method").and_then(|m| m.as_str()) {
        facts.push(("method".into(), m.to_string()));
    }
    if let Some(dt) = f64_at(r, "dt") {
        let steps = r.get("steps").and_then(serde_json::Value::as_u64);
        facts.push((
            "time step Δt".into(),
            match steps {
                Some(n) => format!(
                    "{} s, {n} steps ({} s simulated)",
                    sig(dt, 6),
                    sig(dt * n as f64, 6)
                ),
                None => format!("{} s", sig(dt, 6)),
            },
        ));
    }
    let dampers = scene.and_then(damper_floors);
    let mut out = kv_table(&facts);
    out.push_str("<h3>Peak responses per storey</h3>\n");
    out.push_str(&storey_table(r, dampers.as_deref()));
    let totals = run_totals(r);
    if !totals.is_empty() {
        out.push_str(&kv_table(&totals));
    }
    if let Some(b) = bare {
        out.push_str("<h3>Bare frame (no braces: every slip load 0)</h3>\n");
        out.push_str(&storey_table(b, Some(&[][..])));
        let totals = run_totals(b);
        if !totals.is_empty() {
            out.push_str(&kv_table(&totals));
        }
    }
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

/// Writes the report to `out` atomically; into a study folder (one holding the lock file
/// of slipload's study commands) it goes through the folder, so that the page joins the
/// list of the files slipload wrote there (`--fresh` removes it; a user's own file under
/// its name is never overwritten) and is not written while a command holds the folder.
fn write_report(out: &Path, html: &[u8]) -> anyhow::Result<()> {
    use slipload_opt::store::folder::{FolderRequest, LOCK_FILE, StudyFolder};
    let dir = match out.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if let Some(name) = out.file_name().and_then(|n| n.to_str())
        && dir.join(LOCK_FILE).is_file()
    {
        let (folder, _) = StudyFolder::open(FolderRequest {
            path: dir,
            option: "--out",
            fresh: false,
        })?;
        folder.write(name, html)?;
    } else {
        write_atomic(out, html)?;
    }
    Ok(())
}

/// Runs `slipload report`.
pub fn run(args: ReportArgs) -> anyhow::Result<()> {
    let (kind, html) = build(&args.dir, args.max_rows.max(1))?;
    let out = args.out.unwrap_or_else(|| args.dir.join("report.html"));
    write_report(&out, html.as_bytes())?;
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
