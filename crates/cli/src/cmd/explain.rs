//! `slipload explain`: print the plan a scene compiles into.

use super::scene_args::SceneArgs;
use slipload_sim::Plan;

/// Arguments of `slipload explain`.
#[derive(Debug, clap::Args)]
pub struct ExplainArgs {
    #[command(flatten)]
    scene: SceneArgs,
}

/// Runs `slipload explain`.
pub fn run(args: ExplainArgs) -> anyhow::Result<()> {
    let scene = args.scene.load(false)?;
    let plan = Plan::compile(&scene)?;
    out!("{}", plan.explain());
    Ok(())
}
