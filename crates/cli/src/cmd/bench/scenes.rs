//! The scenes of `slipload bench`: the embedded buildings and the edits that make the
//! bench's variants of them (massless dampers, damped braces, locked dampers, one damper),
//! the bench's shear buildings, and the peaks-only scenes and plans under the 15 s
//! synthetic record or the record of the equal-accuracy comparison with OpenSees.

use anyhow::Context;
use slipload_sim::bench_scenes::{ShearDamping, shear_building_damped};
use slipload_sim::{MethodName, Plan, Scene, SceneOverrides};
use std::path::Path;

/// The ten-storey building, embedded so `slipload bench` runs with no files.
pub(super) const TEN_STORY_BUILDING: &str = include_str!("../../../../../configs/ten-story.json");
/// The paper's one-storey building, embedded.
pub(super) const PAPER_1STORY_BUILDING: &str =
    include_str!("../../../../../configs/paper-1story.json");

/// A building JSON with `edit` applied to each dissipator (with its index).
fn edit_dissipators(
    building: &str,
    mut edit: impl FnMut(usize, &mut serde_json::Value),
) -> anyhow::Result<String> {
    let mut v: serde_json::Value = serde_json::from_str(building)?;
    if let Some(ds) = v["dissipators"].as_array_mut() {
        for (i, d) in ds.iter_mut().enumerate() {
            edit(i, d);
        }
    }
    Ok(v.to_string())
}

/// A building JSON with every dissipator mass set to 0 (the m′ = 0 design model).
pub(super) fn massless(building: &str) -> anyhow::Result<String> {
    edit_dissipators(building, |_, d| d["mass"] = 0.into())
}

/// A building JSON with a brace dashpot c′ = 10⁵ N·s/m on every dissipator (under 1 % of
/// critical on the shipped frames): a massless dissipator then keeps a velocity of its
/// own, and its condensation into an EPP element is exact, so the reduced and full plans
/// agree to round-off. (With c′ = 0 the reduced plan steps the algebraic element by the
/// return mapping, more accurately than the full plan's zero-mass DOF: docs/MODEL.md.)
pub(super) fn damped_braces(building: &str) -> anyhow::Result<String> {
    edit_dissipators(building, |_, d| d["brace_damping"] = 1e5.into())
}

/// A building JSON with every dissipator's slip load at 1e12 N, far above any force its
/// brace carries under the bench records: the dissipators never slip.
pub(super) fn locked(building: &str) -> anyhow::Result<String> {
    edit_dissipators(building, |_, d| d["slip_load"] = "1e12 N".into())
}

/// A building JSON with the slip load of every dissipator but the first set to 0.
pub(super) fn first_damper_only(building: &str) -> anyhow::Result<String> {
    edit_dissipators(building, |i, d| {
        if i > 0 {
            d["slip_load"] = 0.into();
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

/// A scene of `building` (JSON) under the 15 s (or `duration`) synthetic record, peaks
/// only unless energies are asked for.
pub(super) fn scene(building: &str, o: SceneOpts) -> anyhow::Result<Scene> {
    let json = format!(
        r#"{{ "name": "bench", "building": {building},
             "excitation": {{ "synthetic": {{ "seed": 2007, "duration": {}, "dt": 0.01 }} }},
             "outputs": {{ "energies": {}, "histories": false }}, "reduce": {} }}"#,
        o.duration, o.energies, o.reduce
    );
    let over = SceneOverrides {
        method: Some(o.method),
        dt: o.dt,
        ..Default::default()
    };
    Ok(Scene::from_json(
        &json,
        Path::new("slipload bench (embedded scene)"),
        &over,
    )?)
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
    slipload_opt::output::write_atomic(&path, format_csv(record).as_bytes())?;
    Ok(path)
}

/// The peaks-only scene of `building` (JSON) under the record file `record` (m/s²).
pub(super) fn record_plan(
    building: &str,
    record: &Path,
    method: MethodName,
    dt: Option<f64>,
) -> anyhow::Result<Plan> {
    let json = serde_json::json!({
        "name": "bench",
        "building": serde_json::from_str::<serde_json::Value>(building)?,
        "excitation": { "record": { "file": record, "units": "m/s2" } },
        "outputs": { "energies": false, "histories": false },
    });
    let over = SceneOverrides {
        method: Some(method),
        dt,
        ..Default::default()
    };
    let scene = Scene::from_json(
        &json.to_string(),
        Path::new("slipload bench (embedded scene)"),
        &over,
    )?;
    Ok(Plan::compile(&scene)?)
}

pub(super) fn plan(building: &str, o: SceneOpts) -> anyhow::Result<Plan> {
    Ok(Plan::compile(&scene(building, o)?)?)
}
