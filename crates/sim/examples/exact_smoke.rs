//! Smoke comparison of `exact` against `newmark` on the shipped configs (development aid).
#![allow(clippy::unwrap_used)]
use slipload_sim::{MethodName, Scene, SceneOverrides, simulate};
use std::path::Path;
fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let args: Vec<String> = std::env::args().collect();
    let cfg = root.join(&args[1]);
    let rec = args.get(2).map(|r| root.join(r));
    for (m, dt) in [
        (MethodName::Exact, 0.01),
        (MethodName::Newmark, 1e-4),
        (MethodName::Newmark, 5e-5),
    ] {
        let over = SceneOverrides {
            method: Some(m),
            dt: Some(dt),
            record: rec.clone(),
            duration: args.get(3).map(|d| d.parse().unwrap()),
            ..Default::default()
        };
        let sc = Scene::load(&cfg, &over).unwrap();
        let t = std::time::Instant::now();
        let o = simulate(&sc).unwrap();
        let e = o.response.energy.unwrap();
        println!(
            "{:?} dt {dt}: {:.3}s drift {:?} sampled {:?} events {} trans {:?}\n   E in {:.12e} fr {:.12e} visc {:.12e} bal {:.3e}",
            m,
            t.elapsed().as_secs_f64(),
            o.response.peak_drift,
            o.diagnostics.sampled_peak_drift,
            o.diagnostics.events,
            o.response.transitions,
            e.input,
            e.friction,
            e.viscous,
            e.balance_error / e.input
        );
    }
}
