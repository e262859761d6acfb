//! `slipload opensees`: a scene written as a self-contained OpenSeesPy script
//! ([`slipload_sim::opensees`]), so a reviewer re-runs the design in OpenSees. This front
//! only resolves the scene as `simulate` does, calls the library and writes the file
//! atomically; it refuses an output path that is one of the files it reads.

use super::scene_args::SceneArgs;
use anyhow::{Context, bail};
use std::path::{Path, PathBuf};

/// Arguments of `slipload opensees`.
#[derive(Debug, clap::Args)]
pub struct OpenSeesArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// The script to write (Python; run it with a python that has openseespy)
    #[arg(long, value_name = "FILE.py")]
    out: PathBuf,
}

/// Runs `slipload opensees`.
pub fn run(args: OpenSeesArgs) -> anyhow::Result<()> {
    // a FIFO, a device or a link is refused before any work
    slipload_opt::base::output::write_target(&args.out)
        .with_context(|| format!("--out {}", args.out.display()))?;
    if let Some(path) = &args.scene.scene
        && slipload_sim::floorplan::is_in_plan(path)
    {
        return in_plan(&args, path);
    }
    let scene = args.scene.load(false)?;
    // the scene (or building) file, the building file a scene names, the records
    let mut inputs: Vec<PathBuf> = args.scene.input_files();
    if let Some(r) = &scene.record {
        inputs.push(PathBuf::from(r.name()));
    }
    if let Some(input) = inputs.iter().find(|p| same_file(p, &args.out)) {
        bail!(
            "--out {} is {}, which this command reads: give another file for the script",
            args.out.display(),
            input.display()
        );
    }
    // the error names the scene and what cannot be written
    let script = slipload_sim::opensees_script(&scene)?;
    slipload_opt::base::output::write_atomic(&args.out, script.as_bytes())?;
    eprintln!(
        "wrote {} ({} floors, dt = {:e} s); run it with a python that has openseespy: it prints the peaks as JSON",
        args.out.display(),
        scene.building.floors(),
        scene.method.dt
    );
    Ok(())
}

/// `slipload opensees` on a scene in plan: the script of the library's
/// [`slipload_sim::floorplan::opensees_script`], with `--method`, `--dt`, `--duration`.
fn in_plan(args: &OpenSeesArgs, path: &Path) -> anyhow::Result<()> {
    let s = &args.scene;
    if s.record.is_some() || s.window.is_some() || s.scale.is_some() || s.scale_pga_g.is_some() {
        bail!(
            "{} is a scene in plan: its ground components are the scene's `ground` list (give records, scaling and angles there)",
            path.display()
        );
    }
    let inputs = slipload_sim::floorplan::FloorPlanScene::input_files(path);
    if let Some(input) = inputs.iter().find(|p| same_file(p, &args.out)) {
        bail!(
            "--out {} is {}, which this command reads: give another file for the script",
            args.out.display(),
            input.display()
        );
    }
    let mut scene = slipload_sim::floorplan::FloorPlanScene::load(path)?;
    scene.override_with(s.method.map(Into::into), s.dt, s.duration, false)?;
    let script = slipload_sim::floorplan::opensees_script(&scene)?;
    slipload_opt::base::output::write_atomic(&args.out, script.as_bytes())?;
    eprintln!(
        "wrote {} (building in plan, {} floors, {} lines, dt = {:e} s); run it with a python that has openseespy: it prints the lines' peak drifts as JSON",
        args.out.display(),
        scene.building.storeys(),
        scene.building.lines.len(),
        scene.method.dt
    );
    Ok(())
}

/// Whether `a` and `b` name one existing file.
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}
