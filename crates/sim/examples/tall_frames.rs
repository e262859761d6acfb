//! Issue 39's two measurements on tall shear buildings (the bench's generator,
//! `bench_scenes::shear_building_damped`: Rayleigh damping, a massless damper on every
//! floor) under the first 10 s of Sylmar (SYL090), run by hand, never by the tests:
//!
//! - `setup`: the set-up before the first step of `newmark` (the scene: its building's
//!   checks and modes; the plan; the refusals `explain` makes), against storeys 10…200,
//!   with the log-log slope of each part, beside the run of one step and the whole run;
//!   the fastest of a few repetitions (the machine is shared);
//! - `memory`: the peak resident memory (`VmHWM` of /proc/self/status) of one `exact` run
//!   per fresh process, at 60 storeys within its default memory budget and unbounded (what
//!   it kept before the budget), and at 120 storeys within its budget, with its time.
//!
//! Run (release): `cargo run --release -p slipload-sim --example tall_frames -- setup`
//! and `… -- memory`. Figures: results/performance/README.md, "Issue 39".
#![allow(clippy::unwrap_used, clippy::expect_used)] // a measurement script: failing is the report

use slipload_sim::bench_scenes::{ShearDamping, shear_building_damped};
use slipload_sim::integrator::exact::{MemoryBudget, working_set_bytes};
use slipload_sim::{Exact, Plan, Scene, SceneOverrides, run_plan};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

const MIB: f64 = 1024.0 * 1024.0;

/// The scene's JSON: `storeys` floors under 10 s of Sylmar, with `method`.
fn scene_json(storeys: usize, method: &str, energies: bool, duration: Option<f64>) -> String {
    let building = shear_building_damped(storeys, ShearDamping::Rayleigh);
    let duration = duration.map_or(String::new(), |d| format!(r#""duration": "{d} s","#));
    format!(
        r#"{{ "building": {building},
             "excitation": {{ "record": {{ "file": "../records/SYL090.AT2", "window": [0, 10] }} }},
             {duration}
             "method": {{ "name": "{method}" }},
             "outputs": {{ "energies": {energies}, "histories": false }} }}"#
    )
}

fn scene(json: &str) -> Scene {
    let configs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs");
    Scene::from_json(
        json,
        &configs.join("tall-frames.json"),
        &SceneOverrides::default(),
    )
    .expect("the bench scene is valid")
}

/// Least-squares slope of log y against log x.
fn slope(xs: &[f64], ys: &[f64]) -> f64 {
    let lx: Vec<f64> = xs.iter().map(|x| x.ln()).collect();
    let ly: Vec<f64> = ys.iter().map(|y| y.ln()).collect();
    let n = lx.len() as f64;
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// Fastest of `reps` timings of `f`, seconds.
fn fastest(reps: usize, mut f: impl FnMut()) -> f64 {
    (0..reps)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn setup() {
    let sizes = [10usize, 20, 30, 50, 60, 100, 120, 150, 200];
    println!(
        "newmark on shear buildings, Rayleigh damping, m'=0 dampers on every floor, SYL090 10 s (fastest of 5)"
    );
    println!(
        "{:>8} {:>12} {:>12} {:>12} {:>12} {:>14} {:>12}",
        "storeys", "scene ms", "plan ms", "checks ms", "set-up ms", "one step ms", "run ms"
    );
    let (mut xs, mut parts) = (Vec::new(), vec![Vec::new(); 4]);
    for n in sizes {
        let full = scene_json(n, "newmark", false, None);
        let s = scene(&full);
        let one = scene_json(n, "newmark", false, Some(s.method.dt));
        let plan = Plan::compile(&s).unwrap();
        let t_scene = fastest(5, || drop(scene(&full)));
        let t_plan = fastest(5, || drop(Plan::compile(&s).unwrap()));
        let t_check = fastest(5, || slipload_sim::simulate::check(&plan).unwrap());
        let one_plan = Plan::compile(&scene(&one)).unwrap();
        let t_one = fastest(5, || drop(run_plan(&one_plan).unwrap()));
        let t_run = fastest(5, || drop(run_plan(&plan).unwrap()));
        let set_up = t_scene + t_plan + t_check;
        println!(
            "{n:>8} {:>12.3} {:>12.3} {:>12.3} {:>12.3} {:>14.3} {:>12.3}",
            t_scene * 1e3,
            t_plan * 1e3,
            t_check * 1e3,
            set_up * 1e3,
            t_one * 1e3,
            t_run * 1e3
        );
        xs.push(n as f64);
        for (p, t) in parts.iter_mut().zip([t_scene, set_up, t_one, t_run]) {
            p.push(t);
        }
    }
    // from 100 storeys up, where the O(N³) eigen solves outweigh the fixed costs
    let tall = xs
        .iter()
        .position(|&x| x >= 100.0)
        .expect("sizes reach 100");
    for (name, ys) in ["scene", "set-up", "one step", "run"].iter().zip(&parts) {
        println!(
            "log-log slope of {name} against storeys: {:.2} over 10-200, {:.2} over 100-200",
            slope(&xs, ys),
            slope(&xs[tall..], &ys[tall..])
        );
    }
}

/// VmHWM of this process, bytes.
fn peak_rss() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").expect("Linux /proc");
    let kb: f64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .expect("VmHWM in kB");
    kb * 1024.0
}

/// One `exact` run in this process: `storeys`, energies, budget (`default`, `unbounded`).
fn exact_run(storeys: usize, energies: bool, budget: &str) {
    let plan = Plan::compile(&scene(&scene_json(storeys, "exact", energies, None))).unwrap();
    let b = match budget {
        "unbounded" => MemoryBudget::unbounded(),
        _ => MemoryBudget::for_plan(&plan),
    };
    let t = Instant::now();
    let out = Exact.run_within(&plan, b).unwrap();
    let secs = t.elapsed().as_secs_f64();
    let shown = if b == MemoryBudget::unbounded() {
        "unbounded".to_string()
    } else {
        format!("{:.0}", b.bytes as f64 / MIB)
    };
    println!(
        "{storeys:>8} {energies:>9} {shown:>11} {:>13.0} {:>12.0} {:>10.0} {secs:>8.2} {:>7}",
        working_set_bytes(&plan) as f64 / MIB,
        out.diagnostics.cache_peak_bytes as f64 / MIB,
        peak_rss() / MIB,
        out.diagnostics.events
    );
}

fn memory() {
    println!(
        "exact on shear buildings, m'=0 dampers on every floor, SYL090 10 s; one process per run"
    );
    println!(
        "{:>8} {:>9} {:>11} {:>13} {:>12} {:>10} {:>8} {:>7}",
        "storeys",
        "energies",
        "budget MiB",
        "working MiB",
        "cache MiB",
        "VmHWM MiB",
        "time s",
        "events"
    );
    let exe = std::env::current_exe().expect("this example's path");
    for (storeys, energies, budget) in [
        (60, false, "default"),
        (60, false, "unbounded"),
        (60, true, "default"),
        (60, true, "unbounded"),
        (120, false, "default"),
        (120, true, "default"),
    ] {
        let out = Command::new(&exe)
            .args([
                "exact-run",
                &storeys.to_string(),
                &energies.to_string(),
                budget,
            ])
            .output()
            .expect("running the example again");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        print!("{}", String::from_utf8_lossy(&out.stdout));
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("setup") => setup(),
        Some("memory") => memory(),
        Some("exact-run") => {
            exact_run(args[1].parse().unwrap(), args[2].parse().unwrap(), &args[3])
        }
        _ => eprintln!("usage: tall_frames setup | memory"),
    }
}
