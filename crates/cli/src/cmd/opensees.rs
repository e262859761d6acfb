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

/// Whether `a` and `b` name one existing file.
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}
