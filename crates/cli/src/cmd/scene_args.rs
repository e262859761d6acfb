//! Scene selection shared by `simulate`, `explain` and `opensees`: a scene or building
//! file, or the embedded default (the benchmark building under the first record of the
//! embedded synthetic suite), with the flags that override the file; or one run of a
//! study's design (`--study`, `--designs`, `--design`, `--run`).

use anyhow::Context;
use slipload_motion::Units;
use slipload_sim::units::{Dimension, parse_quantity};
use slipload_sim::{MethodName, Scene, SceneOverrides};
use std::path::{Path, PathBuf};

/// The benchmark building, embedded so the program runs with no files.
pub use slipload_sim::scene::BENCHMARK_BUILDING;

/// Flags that pick and override a scene.
#[derive(Debug, clap::Args)]
pub struct SceneArgs {
    /// Scene or building JSON file (default: the embedded benchmark building under the
    /// first record of the embedded synthetic suite)
    pub scene: Option<PathBuf>,
    /// Ground-motion record file (PEER .AT2, or CSV/text)
    #[arg(long)]
    pub record: Option<PathBuf>,
    /// Units of the record values: g, m/s2, cm/s2 (AT2 files are in g)
    #[arg(long)]
    pub units: Option<Units>,
    /// Scale the record to this peak ground acceleration, in g
    #[arg(long, allow_negative_numbers = true)]
    pub scale_pga_g: Option<f64>,
    /// Multiply the ground motion by this factor (a suite's scale factor; in place of the
    /// scene's own `scale` or `scale_pga_g`; not with --scale-pga-g)
    #[arg(long, allow_negative_numbers = true)]
    pub scale: Option<f64>,
    /// Use only the window START,DURATION of the ground motion, in s or with a unit
    /// (`2,10`, `2s,10s`, `"500 ms,10 s"`). Replaces the scene's window; a window past the
    /// record's end is padded with the ground at rest, as a longer --duration is (a note
    /// on stderr says so)
    #[arg(long, value_parser = parse_window, allow_hyphen_values = true)]
    pub window: Option<(f64, f64)>,
    /// Integration method
    #[arg(long, value_enum)]
    pub method: Option<MethodArg>,
    /// Time step, in s or with a unit (`0.005`, `5ms`) (default: T1/400, delacruz T1/200,
    /// rounded to divide the record's dt)
    #[arg(long, value_parser = parse_time, allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Simulated time, in s or with a unit (`10`, `10s`) (default: the window's duration,
    /// else the record's; past the record's end the ground is at rest, and a note on
    /// stderr says so)
    #[arg(long, value_parser = parse_time, allow_hyphen_values = true)]
    pub duration: Option<f64>,
    /// Run a design of a study instead of a scene: the study file; with --designs (its
    /// output folder), --design and --run, the run is the one the study's check made
    /// (the suite's scaled record, the property case, the check's method and step;
    /// --method changes the method only)
    #[arg(long, value_name = "STUDY.json", requires_all = ["designs", "run"],
          conflicts_with_all = ["scene", "record", "units", "scale_pga_g", "scale", "window", "dt", "duration"])]
    pub study: Option<PathBuf>,
    /// With --study: the study's output folder (its candidates.json) or a candidates file
    #[arg(long, value_name = "DIR", requires = "study")]
    pub designs: Option<PathBuf>,
    /// With --study: the design's name in the candidates (optimum, uniform, storey-shear,
    /// file, bare, or a name of your candidates file)
    #[arg(long, default_value = "optimum", requires = "study")]
    pub design: String,
    /// With --study: the run, as the study's tables name it: a record's name (or its file
    /// name, or stem), with ` [lower]` or ` [upper]` after it at a property bound
    #[arg(long, requires = "study")]
    pub run: Option<String>,
    /// With --study: the suite of the run, where its record is in several suites (each
    /// scales it its own way)
    #[arg(long, requires = "study")]
    pub suite: Option<String>,
}

/// The integration methods as command-line values (help lists them with what they are).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MethodArg {
    /// Newmark average acceleration, friction solved exactly each step (the default)
    Newmark,
    /// HHT-α (α = −0.05) with the same friction solve: damps the high modes
    Hht,
    /// Brace + damper as one elastic–perfectly plastic spring, dissipator mass ignored
    Bilinear,
    /// The paper's method: three nested fixed-point loops, conditionally stable
    Delacruz,
    /// Event-driven reference: each stick/slip mode integrated exactly
    Exact,
}

impl From<MethodArg> for MethodName {
    fn from(m: MethodArg) -> MethodName {
        match m {
            MethodArg::Newmark => MethodName::Newmark,
            MethodArg::Hht => MethodName::Hht,
            MethodArg::Bilinear => MethodName::Bilinear,
            MethodArg::Delacruz => MethodName::Delacruz,
            MethodArg::Exact => MethodName::Exact,
        }
    }
}

/// A time: seconds, or a number with a unit (`"10 s"`, `"5ms"`), by the units parser
/// of the scene files.
pub(crate) fn parse_time(s: &str) -> Result<f64, String> {
    parse_quantity(s, Dimension::Time)
}

fn parse_window(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s.split_once(',').ok_or_else(|| {
        format!("expected START,DURATION in seconds or with a unit (2,10 or 2s,10s), got {s:?}")
    })?;
    let a = parse_time(a).map_err(|e| format!("window start: {e}"))?;
    let b = parse_time(b).map_err(|e| format!("window duration: {e}"))?;
    // the library's rule, the Python package's too
    slipload_sim::scene::check_window(a, b, "window").map_err(|e| e.to_string())?;
    Ok((a, b))
}

impl SceneArgs {
    /// Resolves the scene with `histories` as asked, printing its notes (a run past the
    /// record's end) on stderr.
    pub fn load(&self, histories: bool) -> anyhow::Result<Scene> {
        let scene = self.resolve(histories, false)?;
        for note in &scene.notes {
            eprintln!("note: {note}");
        }
        Ok(scene)
    }

    /// Resolves the scene to be explained: a building alone (no ground motion, no
    /// duration) is planned over one period instead of refused.
    pub fn load_to_explain(&self) -> anyhow::Result<Scene> {
        self.resolve(false, true)
    }

    /// The files the scene is read from: the scene or building file, the building file a
    /// scene names, the record a scene names and `--record`'s (as given, relative paths
    /// of a scene anchored at its folder). A scene that cannot be read adds only its own
    /// path: loading it then says what is wrong.
    pub fn input_files(&self) -> Vec<PathBuf> {
        use slipload_sim::scene::{BuildingRef, SceneConfig};
        let mut files: Vec<PathBuf> = self.record.iter().cloned().collect();
        if let Some(study) = &self.study {
            files.push(study.clone());
            if let Some(d) = &self.designs {
                files.push(d.clone());
                files.push(d.join("candidates.json"));
                files.push(d.join("manifest.json"));
            }
        }
        if let Some(path) = &self.scene {
            files.push(path.clone());
            let text = slipload_motion::limits::read_input_text(
                path,
                "scene",
                slipload_motion::limits::MAX_CONFIG_BYTES,
            );
            if let Ok(cfg) = text
                .map_err(|_| ())
                .and_then(|t| SceneConfig::from_json(&t, path).map_err(|_| ()))
            {
                let base = path.parent().unwrap_or(Path::new("."));
                if let BuildingRef::Path(p) = &cfg.building {
                    files.push(base.join(p));
                }
                if let Some(r) = &cfg.excitation.record {
                    files.push(base.join(&r.file));
                }
            }
        }
        files
    }

    fn resolve(&self, histories: bool, plan_only: bool) -> anyhow::Result<Scene> {
        if let (Some(study), Some(designs), Some(run)) = (&self.study, &self.designs, &self.run) {
            let loaded = super::study_args::load_study(Some(study))?;
            let mut scene = slipload_opt::pipeline::design_run_scene(
                &loaded,
                &slipload_opt::pipeline::DesignRun {
                    designs,
                    design: &self.design,
                    run,
                    suite: self.suite.as_deref(),
                    method: self.method.map(MethodName::from),
                },
            )
            .with_context(|| format!("the design of study {}", study.display()))?;
            scene.outputs.histories = histories;
            return Ok(scene);
        }
        let over = SceneOverrides {
            record: self.record.clone(),
            units: self.units,
            scale_pga_g: self.scale_pga_g,
            scale: self.scale,
            window: self.window,
            method: self.method.map(MethodName::from),
            dt: self.dt,
            duration: self.duration,
            histories: Some(histories),
            energies: None,
            dampers: None,
            plan_only,
        };
        match &self.scene {
            Some(path) => Scene::load(path, &over)
                .with_context(|| format!("loading scene {}", path.display())),
            None => {
                let origin = Path::new(slipload_sim::scene::BENCHMARK_ORIGIN);
                let cfg = slipload_sim::scene::benchmark_scene_config()?;
                Ok(Scene::from_config(cfg, origin, &over)?)
            }
        }
    }
}
