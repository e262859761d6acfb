//! `slipload accuracy`: what accuracy costs — every method × time step against the
//! `exact` integrator, per record and the median over records, written as CSV, JSON and a
//! Markdown summary (each file atomically), and drawn as the work-precision diagram and
//! error vs Δt (`NAME-work-precision`, `NAME-error-vs-dt`, SVG + PNG) for the median (or
//! the one record).

use super::scene_args::MethodArg;
use anyhow::Context;
use serde::Serialize;
use slipload_motion::Units;
use slipload_opt::base::output::write_atomic;
use slipload_sim::accuracy::{DtSpec, StudyReport, StudySettings, median_report, run_study};
use slipload_sim::kind::Expected;
use slipload_sim::scene::{BuildingRef, ExcitationConfig, SceneConfig, SyntheticConfig};
use slipload_sim::{BuildingConfig, MethodName, Scene, SceneOverrides};
use std::path::{Path, PathBuf};

/// `NAME.json` of `accuracy --out`: the median study (`null` with one record) and the
/// study of each record.
#[derive(Serialize)]
struct AccuracyFile<'a> {
    median: Option<&'a StudyReport>,
    records: &'a [StudyReport],
}

/// Arguments of `slipload accuracy`.
#[derive(Debug, clap::Args)]
pub struct AccuracyArgs {
    /// Scene or building JSON file
    pub scene: PathBuf,
    /// Ground-motion record file(s); several give a study per record and their median
    #[arg(long, num_args = 1..)]
    pub record: Vec<PathBuf>,
    /// Use the first N members of the embedded synthetic suite as the records
    #[arg(long, conflicts_with = "record")]
    pub synthetic: Option<usize>,
    /// Units of the record values: g, m/s2, cm/s2 (AT2 files are in g)
    #[arg(long)]
    pub units: Option<Units>,
    /// Scale every record to this peak ground acceleration, in g
    #[arg(long, allow_negative_numbers = true)]
    pub scale_pga_g: Option<f64>,
    /// Simulated time, in s or with a unit (`10`, `10s`) (default: the record's duration)
    #[arg(long, value_parser = super::scene_args::parse_time, allow_hyphen_values = true)]
    pub duration: Option<f64>,
    /// Methods to compare, comma-separated
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "delacruz,newmark,hht,bilinear,exact"
    )]
    pub methods: Vec<MethodArg>,
    /// Time steps, comma-separated: seconds or T1/k
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "T1/25,T1/50,T1/100,T1/200,T1/400,T1/800,T1/1600,T1/3200"
    )]
    pub dts: Vec<DtSpec>,
    /// Timed repeats per entry (the median is reported, after one warm-up run)
    #[arg(long, default_value_t = 5)]
    pub repeats: usize,
    /// Output folder (created if missing)
    #[arg(long, default_value = "out/accuracy")]
    pub out: PathBuf,
    /// Base name of the output files (default: the scene file's stem)
    #[arg(long, value_parser = base_name)]
    pub name: Option<String>,
}

/// `--name` is the start of file names inside `--out`: it must name files there, not a
/// folder elsewhere (`../x`, `a/b`) nor a hidden or empty stem.
fn base_name(s: &str) -> Result<String, String> {
    const MAX: usize = 200;
    if s.trim().is_empty() {
        return Err("the base name of the output files is empty: give one (e.g. `--name benchmark`), or leave --name out for the scene file's stem".into());
    }
    if s.contains(['/', '\\']) {
        return Err(format!(
            "`{s}` holds a path separator: --name is the base name of files inside --out, not a path (give the folder with --out)"
        ));
    }
    if s.starts_with('.') {
        return Err(format!(
            "`{s}` starts with a dot, which would hide the files or leave --out: give a name starting with a letter or digit"
        ));
    }
    if s.chars().any(char::is_control) {
        return Err("the base name holds a control character: give a plain file name".into());
    }
    if s.chars().count() > MAX {
        return Err(format!(
            "the base name has {} characters; at most {MAX} make file names every file system takes",
            s.chars().count()
        ));
    }
    Ok(s.to_string())
}

fn overrides(args: &AccuracyArgs, record: Option<PathBuf>) -> SceneOverrides {
    SceneOverrides {
        record,
        units: args.units,
        scale_pga_g: args.scale_pga_g,
        duration: args.duration,
        ..Default::default()
    }
}

/// The scene with member `index` of the embedded synthetic suite as its excitation.
fn synthetic_scene(args: &AccuracyArgs, index: usize) -> anyhow::Result<Scene> {
    let path = &args.scene;
    let text = slipload_motion::limits::read_input_text(
        path,
        "scene",
        slipload_motion::limits::MAX_CONFIG_BYTES,
    )
    .with_context(|| format!("reading scene {}", path.display()))?;
    let value: serde_json::Value =
        serde_json::from_str(&text).with_context(|| format!("parsing scene {}", path.display()))?;
    let mut cfg: SceneConfig = if value.get("building").is_some() {
        slipload_sim::kind::parse(&text, path, Expected::SceneOrBuilding)?
    } else {
        let b: BuildingConfig = slipload_sim::kind::parse(&text, path, Expected::SceneOrBuilding)?;
        SceneConfig {
            name: b.name.clone(),
            description: None,
            building: BuildingRef::Inline(Box::new(b)),
            excitation: ExcitationConfig::default(),
            duration: None,
            method: Default::default(),
            outputs: Default::default(),
            reduce: true,
        }
    };
    cfg.excitation.record = None;
    cfg.excitation.synthetic = Some(SyntheticConfig {
        index: Some(index),
        ..Default::default()
    });
    cfg.name = Some(format!(
        "{}, synthetic {index}",
        cfg.name.clone().unwrap_or_else(|| stem(path))
    ));
    Scene::from_config(cfg, path, &overrides(args, None))
        .with_context(|| format!("scene {} with synthetic record {index}", path.display()))
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned())
}

/// Runs `slipload accuracy`.
pub fn run(args: AccuracyArgs) -> anyhow::Result<()> {
    if args.methods.is_empty() || args.dts.is_empty() {
        anyhow::bail!("--methods and --dts need at least one value each");
    }
    crate::args::output_folder("--out", &args.out)?;
    crate::args::count_flag("--repeats", args.repeats, crate::args::MAX_REPEATS)?;
    if let Some(n) = args.synthetic {
        let size = slipload_motion::DEFAULT_SUITE_SIZE;
        if n == 0 || n > size {
            anyhow::bail!(
                "--synthetic {n}: the embedded suite has {size} records (1 to {size} allowed)"
            );
        }
    }
    // The figures need a font: find out before the study runs.
    slipload_figures::check_fonts()?;
    let mut scenes = Vec::new();
    if let Some(count) = args.synthetic {
        for i in 0..count {
            scenes.push(synthetic_scene(&args, i)?);
        }
    } else if args.record.is_empty() {
        scenes.push(
            Scene::load(&args.scene, &overrides(&args, None))
                .with_context(|| format!("loading scene {}", args.scene.display()))?,
        );
    } else {
        for r in &args.record {
            let mut s = Scene::load(&args.scene, &overrides(&args, Some(r.clone()))).with_context(
                || {
                    format!(
                        "loading scene {} with record {}",
                        args.scene.display(),
                        r.display()
                    )
                },
            )?;
            s.name = format!("{} / {}", s.name, stem(r));
            scenes.push(s);
        }
    }
    let settings = StudySettings {
        methods: args.methods.iter().map(|&m| MethodName::from(m)).collect(),
        dts: args.dts.clone(),
        repeats: args.repeats.max(1),
    };
    let mut reports: Vec<StudyReport> = Vec::new();
    for s in &scenes {
        if !crate::output::quiet() {
            eprintln!("accuracy: {} ...", s.name);
        }
        reports.push(
            run_study(s, &settings).with_context(|| format!("accuracy study of {}", s.name))?,
        );
    }
    let name = args.name.clone().unwrap_or_else(|| stem(&args.scene));
    let median = (reports.len() > 1).then(|| {
        median_report(
            &format!("{name}: median over {} records", reports.len()),
            &reports,
            &settings.methods,
        )
    });
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    let mut csv = String::new();
    let mut md = format!(
        "# Accuracy vs cost: {name}\n\nGenerated by `slipload accuracy`; errors are relative to the `exact` integrator.\n\n"
    );
    for (i, r) in median.iter().chain(&reports).enumerate() {
        let c = r.to_csv();
        csv.push_str(if i == 0 {
            &c
        } else {
            c.split_once('\n').map_or("", |(_, rest)| rest)
        });
        md.push_str(&r.to_markdown());
        md.push('\n');
    }
    // Through a JSON value, whose objects sort their keys: the file has always listed
    // every object's keys (the studies' too) in alphabetical order.
    let json = serde_json::to_value(AccuracyFile {
        median: median.as_ref(),
        records: &reports,
    })?;
    // Appended, not `with_extension`: a name like `x-0.40g` keeps its dot.
    let file = |ext: &str| args.out.join(format!("{name}.{ext}"));
    write_atomic(&file("csv"), csv.as_bytes())?;
    write_atomic(
        &file("json"),
        serde_json::to_string_pretty(&json)?.as_bytes(),
    )?;
    write_atomic(&file("md"), md.as_bytes())?;
    let drawn = median.as_ref().unwrap_or(&reports[0]);
    crate::figures::accuracy::write(&args.out, &name, drawn)
        .with_context(|| format!("drawing the accuracy figures into {}", args.out.display()))?;
    out!("{md}");
    Ok(())
}
