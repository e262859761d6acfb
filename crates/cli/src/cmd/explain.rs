//! `slipload explain`: print the bare frame's periods and modes and the plan a scene
//! compiles into, after the checks `simulate` makes before its first step (so `explain`
//! refuses what `simulate` refuses). A building file alone is explained too: with no
//! ground motion and no duration the steps are planned over one period, and it says so.

use super::scene_args::SceneArgs;
use anyhow::Context;
use slipload_sim::Plan;

/// Arguments of `slipload explain`.
#[derive(Debug, clap::Args)]
pub struct ExplainArgs {
    #[command(flatten)]
    scene: SceneArgs,
}

/// Runs `slipload explain`.
pub fn run(args: ExplainArgs) -> anyhow::Result<()> {
    if let Some(path) = &args.scene.scene
        && slipload_sim::floorplan::is_in_plan(path)
    {
        let s = &args.scene;
        let mut scene = slipload_sim::floorplan::FloorPlanScene::load(path)?;
        scene.override_with(s.method.map(Into::into), s.dt, s.duration, false)?;
        out!("{}", slipload_sim::floorplan::explain(&scene)?);
        return Ok(());
    }
    let scene = args.scene.load_to_explain()?;
    let plan = Plan::compile(&scene)?;
    slipload_sim::simulate::check(&plan)
        .with_context(|| format!("{} cannot be simulated", scene.name))?;
    out!("{}", scene.building.describe_modes());
    out!("{}", plan.explain());
    Ok(())
}
