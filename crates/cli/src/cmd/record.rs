//! `slipload record …`: read, measure and synthesise ground-motion records.
//!
//! * `info FILE…` — samples, time step, duration and intensity measures of each record;
//!   a folder stands for its `.AT2` files (extension in any case), by name;
//! * `spectrum FILE…` — elastic response spectra (pseudo-acceleration, pseudo-velocity,
//!   displacement); `--plot` draws the suite's spectra, their mean and a design target;
//! * `synth` — Clough–Penzien synthetic records as `time_s,accel_m_s2` CSV.
//!
//! Results go to stdout (or the `--out` files, written atomically), messages to stderr.

use anyhow::{Context, bail};
use slipload_motion::{
    DEFAULT_DAMPING, DEFAULT_SUITE_PGA_G, DEFAULT_SUITE_SEED, DesignSpectrum, G, Intensity, Record,
    RecordFormat, Spectrum, SuiteTarget, Synthetic, Units, default_periods, default_suite,
    format_csv, read_record, synthetic_suite,
};
use slipload_sim::response::csv_field;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Arguments of `slipload record`.
#[derive(Debug, clap::Args)]
pub struct RecordArgs {
    #[command(subcommand)]
    command: RecordCommand,
}

#[derive(Debug, clap::Subcommand)]
enum RecordCommand {
    /// Print NPTS, dt, duration, PGA, PGV, PGD, Arias intensity and D5–95 of records
    Info(InfoArgs),
    /// Print the elastic response spectra of records (and plot them with their mean)
    Spectrum(SpectrumArgs),
    /// Write Clough–Penzien synthetic records as CSV (time_s,accel_m_s2)
    Synth(SynthArgs),
}

/// How a record file is read.
#[derive(Debug, clap::Args)]
struct ReadOptions {
    /// Units of the acceleration values: g, m/s2, cm/s2 (gal) [default: g for .AT2, m/s2 otherwise]
    #[arg(long)]
    units: Option<Units>,
    /// Time step, s (needed for one-column text files; checked against the file otherwise)
    #[arg(long, allow_negative_numbers = true)]
    dt: Option<f64>,
}

impl ReadOptions {
    /// Reads the record in `path`, printing its reader's notes (units that override the
    /// file's own) on stderr.
    fn read(&self, path: &Path) -> anyhow::Result<Record> {
        // MotionError already names the file and line.
        let r = read_record(path, self.units, self.dt).context("reading a ground-motion record")?;
        for note in r.notes() {
            eprintln!("note: {note}");
        }
        Ok(r)
    }
}

/// The record files `paths` name: a file as given, a folder as its `.AT2` files (the
/// extension in any case: `ARL360.at2` as well as `SYL090.AT2`), sorted by name.
fn expand_records(paths: &[PathBuf]) -> anyhow::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for p in paths {
        if !p.is_dir() {
            out.push(p.clone());
            continue;
        }
        let mut found = Vec::new();
        for e in std::fs::read_dir(p).with_context(|| format!("reading folder {}", p.display()))? {
            let path = e
                .with_context(|| format!("reading folder {}", p.display()))?
                .path();
            if path.is_file() && RecordFormat::of_path(&path) == RecordFormat::At2 {
                found.push(path);
            }
        }
        if found.is_empty() {
            bail!(
                "folder {} holds no .AT2 record (name CSV/text records one by one)",
                p.display()
            );
        }
        found.sort();
        out.extend(found);
    }
    Ok(out)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum InfoFormat {
    Table,
    Json,
}

#[derive(Debug, clap::Args)]
struct InfoArgs {
    /// Record files (.AT2, any case, or CSV/text), or folders: every .AT2 file in them
    /// (extension in any case)
    #[arg(required = true)]
    files: Vec<PathBuf>,
    #[command(flatten)]
    read: ReadOptions,
    /// Output format
    #[arg(long, value_enum, default_value_t = InfoFormat::Table)]
    format: InfoFormat,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum SpectrumFormat {
    Csv,
    Json,
}

#[derive(Debug, clap::Args)]
struct SpectrumArgs {
    /// Record files (.AT2, any case, or CSV/text), or folders (every .AT2 file in them,
    /// extension in any case); with several, the CSV gains a leading `record` column and
    /// the JSON is a list
    #[arg(required_unless_present = "synthetic")]
    files: Vec<PathBuf>,
    /// Use the first N records of the embedded synthetic suite (seed 2007, 0.4 g)
    #[arg(long, conflicts_with = "files", value_name = "N")]
    synthetic: Option<usize>,
    #[command(flatten)]
    read: ReadOptions,
    /// Damping ratio (fraction of critical)
    #[arg(long, default_value_t = DEFAULT_DAMPING, allow_negative_numbers = true)]
    damping: f64,
    /// Periods, s, comma-separated [default: 60 log-spaced from 0.02 to 5 s]
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    periods: Option<Vec<f64>>,
    /// Print the spectra on stdout in this format [default: csv; with --plot: none, only
    /// a one-line summary]
    #[arg(long, value_enum)]
    format: Option<SpectrumFormat>,
    /// Draw the pseudo-acceleration spectra, their mean and the target (if given) into
    /// this folder (created when missing): spectra.svg and spectra.png, with the data in
    /// spectra.csv
    #[arg(long, value_name = "DIR")]
    plot: Option<PathBuf>,
    /// Target: ASCE 7-16 design spectrum with this S_DS, g (needs --target-sd1)
    #[arg(
        long,
        requires = "target_sd1",
        value_name = "G",
        allow_negative_numbers = true
    )]
    target_sds: Option<f64>,
    /// Target: S_D1, g (needs --target-sds)
    #[arg(
        long,
        requires = "target_sds",
        value_name = "G",
        allow_negative_numbers = true
    )]
    target_sd1: Option<f64>,
    /// Target: long-period transition T_L, s
    #[arg(
        long,
        default_value_t = 8.0,
        value_name = "S",
        allow_negative_numbers = true
    )]
    target_tl: f64,
}

#[derive(Debug, clap::Args)]
struct SynthArgs {
    /// Seed; record i of a suite uses a seed derived from it (a single record is record 0)
    #[arg(long, default_value_t = DEFAULT_SUITE_SEED)]
    seed: u64,
    /// Peak ground acceleration of every record, g
    #[arg(long, default_value_t = DEFAULT_SUITE_PGA_G, allow_negative_numbers = true)]
    pga_g: f64,
    /// Duration, s
    #[arg(long, default_value_t = 20.0, allow_negative_numbers = true)]
    duration: f64,
    /// Time step, s
    #[arg(long, default_value_t = 0.01, allow_negative_numbers = true)]
    dt: f64,
    /// Number of records; with it, --out is a folder that receives one CSV per record
    #[arg(long)]
    count: Option<usize>,
    /// Output CSV file (or folder with --count); an existing file is not replaced
    /// without --force
    #[arg(long)]
    out: PathBuf,
    /// Replace existing files (--out, or the records of --count in its folder)
    #[arg(long)]
    force: bool,
}

/// Runs `slipload record`.
pub fn run(args: RecordArgs) -> anyhow::Result<()> {
    match args.command {
        RecordCommand::Info(a) => info(&a),
        RecordCommand::Spectrum(a) => spectrum(&a),
        RecordCommand::Synth(a) => synth(&a),
    }
}

/// One row of `record info`.
#[derive(Debug, serde::Serialize)]
struct InfoRow {
    file: String,
    npts: usize,
    dt_s: f64,
    duration_s: f64,
    pga_m_s2: f64,
    pga_g: f64,
    pgv_m_s: f64,
    pgd_m: f64,
    arias_m_s: f64,
    d5_95_s: f64,
}

fn info(args: &InfoArgs) -> anyhow::Result<()> {
    let files = expand_records(&args.files)?;
    let mut rows = Vec::with_capacity(files.len());
    for path in &files {
        let r = args.read.read(path)?;
        let m = Intensity::of(&r);
        rows.push(InfoRow {
            file: path.display().to_string(),
            npts: r.len(),
            dt_s: r.dt(),
            duration_s: r.duration(),
            pga_m_s2: m.pga_m_s2,
            pga_g: m.pga_m_s2 / G,
            pgv_m_s: m.pgv_m_s,
            pgd_m: m.pgd_m,
            arias_m_s: m.arias_m_s,
            d5_95_s: m.d5_95_s,
        });
    }
    let text = match args.format {
        InfoFormat::Json => serde_json::to_string_pretty(&rows).context("formatting JSON")? + "\n",
        InfoFormat::Table => info_table(&rows),
    };
    out!("{text}");
    Ok(())
}

/// The rows as a table: every column as wide as its widest cell (the file column left-,
/// the numbers right-aligned), so that a long value never shifts the columns after it.
fn info_table(rows: &[InfoRow]) -> String {
    const HEAD: [&str; 10] = [
        "file",
        "npts",
        "dt_s",
        "dur_s",
        "pga_m_s2",
        "pga_g",
        "pgv_m_s",
        "pgd_m",
        "arias_m_s",
        "d5_95_s",
    ];
    // the widths the usual records need, so that a table of them reads as it always has
    const MIN_WIDTH: [usize; 10] = [4, 6, 7, 8, 9, 7, 8, 8, 9, 7];
    let cells: Vec<[String; 10]> = rows
        .iter()
        .map(|r| {
            [
                r.file.clone(),
                r.npts.to_string(),
                dt_text(r.dt_s),
                format!("{:.3}", r.duration_s),
                format!("{:.4}", r.pga_m_s2),
                format!("{:.4}", r.pga_g),
                format!("{:.4}", r.pgv_m_s),
                format!("{:.4}", r.pgd_m),
                format!("{:.4}", r.arias_m_s),
                format!("{:.3}", r.d5_95_s),
            ]
        })
        .collect();
    let width: Vec<usize> = (0..HEAD.len())
        .map(|c| {
            cells
                .iter()
                .map(|row| row[c].chars().count())
                .chain([HEAD[c].len(), MIN_WIDTH[c]])
                .max()
                .unwrap_or(MIN_WIDTH[c])
        })
        .collect();
    let line = |row: &[String]| -> String {
        let mut l = String::new();
        for (c, cell) in row.iter().enumerate() {
            let w = width[c];
            if c == 0 {
                let _ = write!(l, "{cell:<w$}");
            } else {
                let _ = write!(l, "  {cell:>w$}");
            }
        }
        l.push('\n');
        l
    };
    let mut s = line(&HEAD.map(str::to_string));
    for row in &cells {
        s.push_str(&line(row));
    }
    s
}

/// A sample interval for the table: four decimals when they hold it exactly (0.0200,
/// 0.0050), else every digit it has (0.00025 s, not 0.0003).
fn dt_text(dt_s: f64) -> String {
    let four = format!("{dt_s:.4}");
    if four.parse::<f64>().is_ok_and(|v| v == dt_s) {
        four
    } else {
        format!("{dt_s}")
    }
}

fn spectrum(args: &SpectrumArgs) -> anyhow::Result<()> {
    if let Some(dir) = &args.plot {
        crate::figures::check_plot_folder(dir)?;
        slipload_figures::check_fonts()?;
    }
    let periods = args.periods.clone().unwrap_or_else(default_periods);
    if periods.is_empty() {
        bail!("--periods needs at least one period");
    }
    let target = match (args.target_sds, args.target_sd1) {
        (Some(sds), Some(sd1)) => Some(
            DesignSpectrum::new(sds, sd1, args.target_tl)
                .context("--target-sds/--target-sd1/--target-tl")?,
        ),
        _ => None,
    };
    // (name shown, record)
    let records: Vec<(String, Record)> = match args.synthetic {
        Some(n) => {
            let suite = default_suite();
            if n == 0 || n > suite.len() {
                bail!(
                    "--synthetic {n}: the embedded suite has {} records (1 to {} allowed)",
                    suite.len(),
                    suite.len()
                );
            }
            suite
                .into_iter()
                .take(n)
                .map(|r| (r.name().to_string(), r))
                .collect()
        }
        None => expand_records(&args.files)?
            .iter()
            .map(|p| Ok((p.display().to_string(), args.read.read(p)?)))
            .collect::<anyhow::Result<_>>()?,
    };
    let spectra: Vec<Spectrum> = records
        .iter()
        .map(|(name, r)| {
            Spectrum::compute(r, args.damping, &periods)
                .with_context(|| format!("computing the spectrum of {name}"))
        })
        .collect::<anyhow::Result<_>>()?;
    let several = records.len() > 1;
    // With --plot the data go to DIR/spectra.csv: stdout gets them only when asked for.
    let format = match (args.format, &args.plot) {
        (Some(f), _) => Some(f),
        (None, None) => Some(SpectrumFormat::Csv),
        (None, Some(_)) => None,
    };
    let text = match format {
        None => String::new(),
        Some(SpectrumFormat::Json) => {
            #[derive(serde::Serialize)]
            struct Out<'a> {
                file: String,
                #[serde(flatten)]
                spectrum: &'a Spectrum,
            }
            let outs: Vec<Out> = records
                .iter()
                .zip(&spectra)
                .map(|((name, _), s)| Out {
                    file: name.clone(),
                    spectrum: s,
                })
                .collect();
            if several {
                serde_json::to_string_pretty(&outs).context("formatting JSON")? + "\n"
            } else {
                serde_json::to_string_pretty(&outs[0]).context("formatting JSON")? + "\n"
            }
        }
        Some(SpectrumFormat::Csv) => {
            let mut t = String::from(if several { "record," } else { "" });
            t.push_str("period_s,sd_m,psv_m_s,psa_m_s2,psa_g\n");
            for ((name, _), s) in records.iter().zip(&spectra) {
                for k in 0..s.periods_s.len() {
                    if several {
                        let _ = write!(t, "{},", csv_field(name));
                    }
                    let _ = writeln!(
                        t,
                        "{},{},{},{},{}",
                        s.periods_s[k],
                        s.sd_m[k],
                        s.psv_m_s[k],
                        s.psa_m_s2[k],
                        s.psa_m_s2[k] / G
                    );
                }
            }
            t
        }
    };
    if let Some(dir) = &args.plot {
        let names: Vec<String> = records.iter().map(|(n, _)| short_name(n)).collect();
        let stem = crate::figures::spectra::write(
            &dir.join(crate::figures::spectra::STEM),
            &names,
            &spectra,
            args.damping,
            target.as_ref(),
        )?;
        if format.is_none() {
            let s = stem.display();
            outln!(
                "{} spectra at {} periods{}{}: {s}.svg, {s}.png, data in {s}.csv",
                spectra.len(),
                periods.len(),
                if several { " and their mean" } else { "" },
                if target.is_some() { ", target" } else { "" },
            );
        }
    }
    out!("{text}");
    Ok(())
}

/// A record's name for legends and CSV headers: its file name without folders.
fn short_name(name: &str) -> String {
    Path::new(name)
        .file_name()
        .map_or_else(|| name.to_string(), |f| f.to_string_lossy().into_owned())
}

fn synth(args: &SynthArgs) -> anyhow::Result<()> {
    let params = Synthetic {
        dt_s: args.dt,
        duration_s: args.duration,
        ..Synthetic::default()
    };
    // the step the readers accept, so that what is written here is read back
    slipload_motion::check_record_dt("--dt", args.dt)?;
    let count = args.count.unwrap_or(1);
    crate::args::count_flag("--count", count, slipload_motion::limits::MAX_SUITE_RECORDS)?;
    slipload_motion::limits::check_suite_count(count)
        .with_context(|| format!("--count {count}"))?;
    if args.count.is_some() {
        crate::args::output_folder("--out", &args.out)?;
    }
    if !slipload_sim::scene::target_pga_in_band(args.pga_g) {
        bail!(
            "--pga-g: the peak ground acceleration must be positive and finite, within {} … {} g (perceptible shaking to the strongest ground motion recorded; a PGA of 0 is the ground at rest), got {} g",
            slipload_sim::scene::TARGET_PGA_BAND_G.0,
            slipload_sim::scene::TARGET_PGA_BAND_G.1,
            slipload_motion::readable(args.pga_g)
        );
    }
    let target = SuiteTarget::Pga {
        pga_m_s2: args.pga_g * G,
    };
    if args.count.is_none() {
        refuse_existing(&args.out, args.force)?;
    }
    let records = synthetic_suite(&params, count, args.seed, target)
        .context("generating synthetic records")?;
    if args.count.is_some() {
        for r in &records {
            refuse_existing(&args.out.join(format!("{}.csv", r.name())), args.force)?;
        }
    }
    match args.count {
        None => {
            let r = &records[0];
            slipload_opt::base::output::write_atomic(&args.out, format_csv(r).as_bytes())?;
            eprintln!(
                "wrote {} ({} samples, PGA {} g)",
                args.out.display(),
                r.len(),
                args.pga_g
            );
        }
        Some(_) => {
            for r in &records {
                let path = args.out.join(format!("{}.csv", r.name()));
                slipload_opt::base::output::write_atomic(&path, format_csv(r).as_bytes())?;
            }
            eprintln!(
                "wrote {} records to {} ({} samples each, PGA {} g)",
                records.len(),
                args.out.display(),
                records[0].len(),
                args.pga_g
            );
        }
    }
    Ok(())
}

/// Refuses to replace an existing `path` (a file, or a symlink to one, a folder …) unless
/// `force`: `record synth` writes where it is told, never over a file it was not told
/// it may replace (a record of the user's own, say).
fn refuse_existing(path: &Path, force: bool) -> anyhow::Result<()> {
    if force || std::fs::symlink_metadata(path).is_err() {
        return Ok(());
    }
    bail!(
        "--out {}: the file exists; record synth does not replace a file without --force (or give another --out)",
        path.display()
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Debug, clap::Parser)]
    struct Cli {
        #[command(flatten)]
        args: RecordArgs,
    }

    fn parse(args: &[&str]) -> Result<RecordArgs, clap::Error> {
        Cli::try_parse_from(std::iter::once("record").chain(args.iter().copied())).map(|c| c.args)
    }

    #[test]
    fn info_parses() {
        let a = parse(&[
            "info", "a.AT2", "b.csv", "--units", "gal", "--dt", "0.01", "--format", "json",
        ])
        .unwrap();
        let RecordCommand::Info(i) = a.command else {
            panic!("not info")
        };
        assert_eq!(i.files.len(), 2);
        assert_eq!(i.read.units, Some(Units::CmPerS2));
        assert_eq!(i.format, InfoFormat::Json);
        assert!(parse(&["info"]).is_err(), "a file is required");
        assert!(parse(&["info", "a.AT2", "--units", "furlong"]).is_err());
    }

    #[test]
    fn spectrum_parses() {
        let a = parse(&[
            "spectrum",
            "a.AT2",
            "--damping",
            "0.02",
            "--periods",
            "0.1,0.5,1",
        ])
        .unwrap();
        let RecordCommand::Spectrum(s) = a.command else {
            panic!("not spectrum")
        };
        assert_eq!(s.periods, Some(vec![0.1, 0.5, 1.0]));
        assert_eq!(s.files.len(), 1);
        assert_eq!(s.format, None, "csv unless --plot");
        assert!(parse(&["spectrum", "a.AT2", "--periods", "0.1,x"]).is_err());
        assert!(parse(&["spectrum"]).is_err(), "records are required");
        assert!(parse(&["spectrum", "--synthetic", "3", "--plot", "s"]).is_ok());
        assert!(parse(&["spectrum", "a.AT2", "--synthetic", "3"]).is_err());
        assert!(
            parse(&["spectrum", "a.AT2", "--target-sds", "1"]).is_err(),
            "S_DS needs S_D1"
        );
    }

    #[test]
    fn synth_parses() {
        let a = parse(&[
            "synth", "--seed", "3", "--pga-g", "0.3", "--count", "4", "--out", "d",
        ])
        .unwrap();
        let RecordCommand::Synth(s) = a.command else {
            panic!("not synth")
        };
        assert_eq!((s.seed, s.pga_g, s.count), (3, 0.3, Some(4)));
        assert!(parse(&["synth"]).is_err(), "--out is required");
    }

    #[test]
    fn synth_writes_readable_csv() {
        let dir = std::env::temp_dir().join(format!("slipload-synth-{}", std::process::id()));
        let args = SynthArgs {
            seed: 5,
            pga_g: 0.25,
            duration: 2.0,
            dt: 0.01,
            count: Some(2),
            out: dir.clone(),
            force: false,
        };
        synth(&args).unwrap();
        let mut names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        names.sort();
        assert_eq!(names.len(), 2);
        let r = read_record(&dir.join(&names[0]), None, None).unwrap();
        assert_eq!(r.len(), 201);
        assert_eq!(r.pga(), 0.25 * G);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
