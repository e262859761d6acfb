//! `slipload explain`: print the bare frame's periods and modes and the plan a scene
//! compiles into, after the checks `simulate` makes before its first step (so `explain`
//! refuses what `simulate` refuses). A building file alone is explained too: with no
//! ground motion and no duration the steps are planned over one period, and it says so.

use super::scene_args::SceneArgs;
use anyhow::Context;
use slipload_sim::{Building, Plan};
use std::fmt::Write as _;

/// Arguments of `slipload explain`.
#[derive(Debug, clap::Args)]
pub struct ExplainArgs {
    #[command(flatten)]
    scene: SceneArgs,
}

/// Runs `slipload explain`.
pub fn run(args: ExplainArgs) -> anyhow::Result<()> {
    let scene = args.scene.load_to_explain()?;
    let plan = Plan::compile(&scene)?;
    slipload_sim::simulate::check(&plan)
        .with_context(|| format!("{} cannot be simulated", scene.name))?;
    out!("{}", modes(&scene.building));
    out!("{}", plan.explain());
    Ok(())
}

/// The bare frame's natural periods and mode shapes (each scaled to a largest entry of 1,
/// floors bottom to top).
fn modes(b: &Building) -> String {
    let mut s = String::new();
    let periods = b.modes.periods();
    let _ = writeln!(
        s,
        "bare frame of {}: {} floors, periods (s) [{}]",
        b.name,
        b.floors(),
        periods
            .iter()
            .map(|t| format!("{t:.4}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    for (k, t) in periods.iter().enumerate() {
        let col = b.modes.shapes.column(k);
        let peak = col
            .iter()
            .fold(0.0f64, |m, v| if v.abs() > m.abs() { *v } else { m });
        let shape: Vec<String> = col
            .iter()
            .map(|v| format!("{:.4}", if peak != 0.0 { v / peak } else { *v }))
            .collect();
        let _ = writeln!(
            s,
            "  mode {}: T = {t:.4} s, shape [{}]",
            k + 1,
            shape.join(", ")
        );
    }
    s
}
