//! The scenes of `slipload bench`: the embedded buildings and the edits that make the
//! bench's variants of them (massless dampers, damped braces, locked dampers, one damper),
//! the bench's shear buildings, and the peaks-only scenes and plans under the 15 s
//! synthetic record or the record of the equal-accuracy comparison with OpenSees. Built
//! from the library's config types (a building's config, a scene's), as a scene file
//! would be read.

use anyhow::Context;
use slipload_sim::bench_scenes::{ShearDamping, shear_building_damped};
use slipload_sim::building::{DissipatorConfig, SlipLoad};
use slipload_sim::scene::{
    BuildingRef, ExcitationConfig, MethodConfig, OutputsConfig, RecordConfig, SceneConfig,
    SyntheticConfig,
};
use slipload_sim::units::{Damping, Mass, Time};
use slipload_sim::{BuildingConfig, MethodName, Plan, Scene, SceneOverrides};
use std::path::Path;

/// The ten-storey building, embedded so `slipload bench` runs with no files.
pub(super) const TEN_STORY_BUILDING: &str = include_str!("../../../../../configs/ten-story.json");
/// The paper's one-storey building, embedded.
pub(super) const PAPER_1STORY_BUILDING: &str =
    include_str!("../../../../../configs/paper-1story.json");

/// The config of a building file's JSON (an embedded building, a shear building).
pub(super) fn config(building: &str) -> anyhow::Result<BuildingConfig> {
    Ok(serde_json::from_str(building)?)
}

/// `building` with `edit` applied to each dissipator (with its index).
fn edit_dissipators(
    mut building: BuildingConfig,
    mut edit: impl FnMut(usize, &mut DissipatorConfig),
) -> BuildingConfig {
    for (i, d) in building.dissipators.iter_mut().enumerate() {
        edit(i, d);
    }
    building
}

/// `building` with every dissipator mass set to 0 (the m′ = 0 design model).
pub(super) fn massless(building: BuildingConfig) -> BuildingConfig {
    edit_dissipators(building, |_, d| d.mass = Some(Mass(0.0)))
}

/// `building` with a brace dashpot c′ = 10⁵ N·s/m on every dissipator (under 1 % of
/// critical on the shipped frames): a massless dissipator then keeps a velocity of its
/// own, and its condensation into an EPP element is exact, so the reduced and full plans
/// agree to round-off. (With c′ = 0 the reduced plan steps the algebraic element by the
/// return mapping, more accurately than the full plan's zero-mass DOF: docs/MODEL.md.)
pub(super) fn damped_braces(building: BuildingConfig) -> BuildingConfig {
    edit_dissipators(building, |_, d| d.brace_damping = Some(Damping(1e5)))
}

/// `building` with every dissipator's slip load at 1e12 N, far above any force its
/// brace carries under the bench records: the dissipators never slip.
pub(super) fn locked(building: BuildingConfig) -> BuildingConfig {
    edit_dissipators(building, |_, d| d.slip_load = Some(SlipLoad::Force(1e12)))
}

/// `building` with the slip load of every dissipator but the first set to 0.
pub(super) fn first_damper_only(building: BuildingConfig) -> BuildingConfig {
    edit_dissipators(building, |i, d| {
        if i > 0 {
            d.slip_load = Some(SlipLoad::Force(0.0));
        }
    })
}

/// The bench's shear building of `n` storeys ([`shear_building_damped`]) with 2 % modal
/// damping.
pub(super) fn shear_building(n: usize) -> String {
    shear_building_damped(n, ShearDamping::Modal)
}

/// Options of one bench scene.
#[derive(Debug, Clone, Copy)]
pub(super) struct SceneOpts {
    pub(super) method: MethodName,
    pub(super) duration: f64,
    pub(super) dt: Option<f64>,
    pub(super) reduce: bool,
    pub(super) energies: bool,
}

impl SceneOpts {
    pub(super) fn new(method: MethodName) -> SceneOpts {
        SceneOpts {
            method,
            duration: 15.0,
            dt: None,
            reduce: true,
            energies: false,
        }
    }
}

/// The name and origin of every bench scene (the origin names it in errors).
const NAME: &str = "bench";
const ORIGIN: &str = "slipload bench (embedded scene)";

/// A scene of `building` under the 15 s (or `duration`) synthetic record, peaks only
/// unless energies are asked for.
pub(super) fn scene(building: &BuildingConfig, o: SceneOpts) -> anyhow::Result<Scene> {
    let cfg = SceneConfig {
        name: Some(NAME.into()),
        description: None,
        building: BuildingRef::Inline(Box::new(building.clone())),
        excitation: ExcitationConfig {
            synthetic: Some(SyntheticConfig {
                seed: Some(2007),
                duration: Some(Time(o.duration)),
                dt: Some(Time(0.01)),
                ..SyntheticConfig::default()
            }),
            ..ExcitationConfig::default()
        },
        duration: None,
        method: MethodConfig::default(),
        outputs: OutputsConfig {
            energies: o.energies,
            histories: false,
            dampers: false,
            sensitivities: false,
        },
        reduce: o.reduce,
    };
    let over = SceneOverrides {
        method: Some(o.method),
        dt: o.dt,
        ..Default::default()
    };
    Ok(Scene::from_config(cfg, Path::new(ORIGIN), &over)?)
}

/// The record of the equal-accuracy comparison with OpenSees
/// (scripts/compare-opensees-precision.py): what `slipload record synth --duration 15
/// --dt 0.01` writes (record 0 of the seeded suite, seed 2007, PGA 0.4 g), as a CSV in the
/// temporary folder, so the bench steps the very samples that comparison read.
pub(super) fn comparison_record() -> anyhow::Result<std::path::PathBuf> {
    use slipload_motion::{
        DEFAULT_SUITE_PGA_G, DEFAULT_SUITE_SEED, G, SuiteTarget, Synthetic, format_csv,
        synthetic_suite,
    };
    let params = Synthetic {
        dt_s: 0.01,
        duration_s: 15.0,
        ..Synthetic::default()
    };
    let target = SuiteTarget::Pga {
        pga_m_s2: DEFAULT_SUITE_PGA_G * G,
    };
    let records = synthetic_suite(&params, 1, DEFAULT_SUITE_SEED, target)?;
    let record = records
        .first()
        .context("the synthetic suite of one record is empty")?;
    let path = std::env::temp_dir().join(format!(
        "slipload-bench-comparison-{}.csv",
        std::process::id()
    ));
    slipload_opt::base::output::write_atomic(&path, format_csv(record).as_bytes())?;
    Ok(path)
}

/// The peaks-only plan of `building` under the record file `record` (m/s²).
pub(super) fn record_plan(
    building: &BuildingConfig,
    record: &Path,
    method: MethodName,
    dt: Option<f64>,
) -> anyhow::Result<Plan> {
    let cfg = SceneConfig {
        name: Some(NAME.into()),
        description: None,
        building: BuildingRef::Inline(Box::new(building.clone())),
        excitation: ExcitationConfig {
            record: Some(RecordConfig {
                file: record.to_path_buf(),
                units: Some("m/s2".into()),
                dt: None,
                scale: None,
                scale_pga_g: None,
                window: None,
            }),
            ..ExcitationConfig::default()
        },
        duration: None,
        method: MethodConfig::default(),
        outputs: OutputsConfig {
            energies: false,
            histories: false,
            dampers: false,
            sensitivities: false,
        },
        reduce: true,
    };
    let over = SceneOverrides {
        method: Some(method),
        dt,
        ..Default::default()
    };
    let scene = Scene::from_config(cfg, Path::new(ORIGIN), &over)?;
    Ok(Plan::compile(&scene)?)
}

/// The plan of [`scene`].
pub(super) fn plan(building: &BuildingConfig, o: SceneOpts) -> anyhow::Result<Plan> {
    Ok(Plan::compile(&scene(building, o)?)?)
}
