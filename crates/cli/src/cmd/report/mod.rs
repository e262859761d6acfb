//! `slipload report DIR`: one self-contained HTML page from an output folder — a
//! simulation `--plot` folder, an `accuracy --out` folder or a `sweep`/`optimize` study
//! folder. The page holds a title and the kind of folder, the key tables (Markdown, CSV
//! and JSON summaries as HTML tables), every `NAME.svg` in the folder inlined (so new
//! figures appear without code changes), the inputs (scene, study, manifest JSON)
//! pretty-printed in collapsible blocks, and the slipload version. It loads nothing from
//! elsewhere (no scripts, fonts or style sheets from the network) and opens offline.
//!
//! The parts, each by its role: [`folder`] (the files of the folder and what kind of
//! folder they make), [`page`] (the page: its sections in order, its style, its
//! frame), [`svg`] (figures made safe to inline), [`study`] (a study's optimum and
//! trade-off), [`simulation`] (a simulation's run and responses per storey) and
//! [`tables`] (the HTML tables and the JSON numbers they show).

mod folder;
mod page;
mod simulation;
mod study;
mod svg;
mod tables;

use slipload_opt::base::output::write_atomic;
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

/// Writes the report to `out` atomically; into a study folder (one holding the lock file
/// of slipload's study commands) it goes through the folder, so that the page joins the
/// list of the files slipload wrote there (`--fresh` removes it; a user's own file under
/// its name is never overwritten) and is not written while a command holds the folder.
fn write_report(out: &Path, html: &[u8]) -> anyhow::Result<()> {
    use slipload_opt::store::folder::{FolderRequest, LOCK_FILE, StudyFolder, is_output_name};
    let dir = match out.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    // a study's own file (a sweep's table, a journal) is never replaced by a report
    if let Some(name) = out.file_name().and_then(|n| n.to_str())
        && name != "report.html"
        && is_output_name(name)
        && std::fs::symlink_metadata(out).is_ok()
    {
        anyhow::bail!(
            "--out {}: {name} is a file slipload's study commands write there, and the report never replaces it: give another --out (an .html file)",
            out.display()
        );
    }
    if let Some(name) = out.file_name().and_then(|n| n.to_str())
        && dir.join(LOCK_FILE).is_file()
    {
        let (folder, _) = StudyFolder::open(FolderRequest {
            path: dir,
            option: "--out",
            fresh: false,
        })?;
        // a name of the user's choosing (not one the study commands write) is theirs to
        // replace: --out named it
        if !is_output_name(name) {
            folder.claim(&[name])?;
        }
        folder.write(name, html)?;
    } else {
        write_atomic(out, html)?;
    }
    Ok(())
}

/// Runs `slipload report`.
pub fn run(args: ReportArgs) -> anyhow::Result<()> {
    let (kind, html) = page::build(&args.dir, args.max_rows.max(1))?;
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
