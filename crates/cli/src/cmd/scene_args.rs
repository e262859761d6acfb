//! Scene selection shared by `simulate` and `explain`: a scene or building file, or the
//! embedded default (the benchmark building under the first record of the embedded
//! synthetic suite), with the flags that override the file.

use anyhow::Context;
use slipload_motion::Units;
use slipload_sim::scene::{BuildingRef, ExcitationConfig, SceneConfig, SyntheticConfig};
use slipload_sim::{BuildingConfig, MethodName, Scene, SceneOverrides};
use std::path::{Path, PathBuf};

/// The benchmark building, embedded so the program runs with no files.
pub const BENCHMARK_BUILDING: &str = include_str!("../../../../configs/benchmark-3story.json");

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
    /// Use only the window START,DURATION of the record (seconds)
    #[arg(long, value_parser = parse_window, allow_hyphen_values = true)]
    pub window: Option<(f64, f64)>,
    /// Integration method
    #[arg(long, value_enum)]
    pub method: Option<MethodArg>,
    /// Time step, s (default: T1/400, delacruz T1/200, rounded to divide the record's dt)
    #[arg(long, allow_negative_numbers = true)]
    pub dt: Option<f64>,
    /// Simulated time, s (default: the record's duration)
    #[arg(long, allow_negative_numbers = true)]
    pub duration: Option<f64>,
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

fn parse_window(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s
        .split_once(',')
        .ok_or_else(|| format!("expected START,DURATION in seconds, got {s:?}"))?;
    let a: f64 = a
        .trim()
        .parse()
        .map_err(|_| format!("window start {a:?} is not a number"))?;
    let b: f64 = b
        .trim()
        .parse()
        .map_err(|_| format!("window duration {b:?} is not a number"))?;
    if !(a >= 0.0 && b > 0.0 && a.is_finite() && b.is_finite()) {
        return Err(format!(
            "window needs START >= 0 and DURATION > 0, got {a},{b}"
        ));
    }
    Ok((a, b))
}

impl SceneArgs {
    /// Resolves the scene with `histories` as asked.
    pub fn load(&self, histories: bool) -> anyhow::Result<Scene> {
        let over = SceneOverrides {
            record: self.record.clone(),
            units: self.units,
            scale_pga_g: self.scale_pga_g,
            window: self.window,
            method: self.method.map(MethodName::from),
            dt: self.dt,
            duration: self.duration,
            histories: Some(histories),
            energies: None,
        };
        match &self.scene {
            Some(path) => Scene::load(path, &over)
                .with_context(|| format!("loading scene {}", path.display())),
            None => {
                let origin = Path::new("configs/benchmark-3story.json (embedded)");
                let building: BuildingConfig = serde_json::from_str(BENCHMARK_BUILDING)
                    .context("embedded benchmark building")?;
                let cfg = SceneConfig {
                    name: Some("benchmark-3story, synthetic record 0".into()),
                    description: None,
                    building: BuildingRef::Inline(Box::new(building)),
                    excitation: ExcitationConfig {
                        synthetic: Some(SyntheticConfig::default()),
                        ..Default::default()
                    },
                    duration: None,
                    method: Default::default(),
                    outputs: Default::default(),
                    reduce: true,
                };
                Ok(Scene::from_config(cfg, origin, &over)?)
            }
        }
    }
}
