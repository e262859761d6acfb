//! The cases of `slipload bench` but `exact`'s: the accuracy and throughput of
//! `newmark`'s defaults, what energies cost, what the plan reductions buy, the cost
//! against record length and storeys (dense and banded steps), the memory of a long run
//! (in a child process, [`memory_probe`]) and the parallel sweep.

use super::figure::Figure;
use super::measure::{Bench, max_rel, peak_rss_kb, seconds_banded_dense, seconds_per_run, slope};
use super::scenes::{
    SceneOpts, TEN_STORY_BUILDING, config, damped_braces, first_damper_only, massless, plan,
    shear_building,
};
use crate::cmd::scene_args::BENCHMARK_BUILDING;
use crate::cmd::study_args::load_study;
use anyhow::{Context, bail};
use slipload_opt::eval::evaluate::{Task, run_tasks};
use slipload_opt::model::fidelity::Fidelity;
use slipload_sim::bench_scenes::{ShearDamping, shear_building_damped};
use slipload_sim::{MethodName, Plan, run_plan};
use std::time::Instant;

/// Accuracy of `newmark`'s default step against `exact`, then its throughput, on the
/// benchmark and the ten-storey building.
pub(super) fn defaults(bench: &mut Bench) -> anyhow::Result<()> {
    let (b3, b10) = (config(BENCHMARK_BUILDING)?, config(TEN_STORY_BUILDING)?);
    // Accuracy of the defaults, then throughput. The benchmark's 5000/s target is
    // withdrawn; 3500/s guards against regressions (results/performance/README.md).
    for (name, building, target, withdrawn) in [
        ("benchmark-3story", &b3, 3500.0, Some(5000.0)),
        ("ten-story", &b10, 500.0, None),
    ] {
        let case = format!("{name}, 15 s synthetic, newmark default dt");
        if bench.want(&case) {
            let p = plan(building, SceneOpts::new(MethodName::Newmark))?;
            let reference = run_plan(&plan(building, SceneOpts::new(MethodName::Exact))?)?;
            let out = run_plan(&p)?;
            let err = max_rel(&out.response.peak_drift, &reference.response.peak_drift);
            bench.figs.push(
                Figure::new(&case, "max rel. peak-drift error vs exact", err, "-").at_most(0.01),
            );
            bench
                .figs
                .push(Figure::new(&case, "time step", p.method.dt, "s"));
            let s = seconds_per_run(&p, &bench.clock, bench.budget)?;
            bench.figs.push(
                Figure::new(&case, "simulations per second per core", 1.0 / s, "1/s")
                    .at_least(target),
            );
            if let Some(t) = withdrawn {
                bench.figs.push(
                    Figure::new(&case, "simulations per second per core", 1.0 / s, "1/s")
                        .at_least(t)
                        .withdrawn(),
                );
            }
            bench.figs.push(Figure::new(
                &case,
                "time per step",
                s / p.steps as f64 * 1e9,
                "ns",
            ));
        }
    }
    Ok(())
}

/// What energies cost, and that they balance.
pub(super) fn energies(bench: &mut Bench) -> anyhow::Result<()> {
    let (b3, b10) = (config(BENCHMARK_BUILDING)?, config(TEN_STORY_BUILDING)?);
    // What asking for energies costs (peaks-only runs pay nothing for them), and that the
    // energies balance: Newmark's average acceleration balances them to round-off.
    for (name, building) in [("benchmark-3story", &b3), ("ten-story", &b10)] {
        let case = format!("outputs: {name} newmark default dt, energies vs peaks only");
        if bench.want(&case) {
            let opts = SceneOpts::new(MethodName::Newmark);
            let p = plan(building, opts)?;
            let pe = plan(
                building,
                SceneOpts {
                    energies: true,
                    ..opts
                },
            )?;
            let s = seconds_per_run(&p, &bench.clock, bench.budget)?;
            let se = seconds_per_run(&pe, &bench.clock, bench.budget)?;
            bench.figs.push(Figure::new(
                &case,
                "time per simulation, peaks only",
                s * 1e3,
                "ms",
            ));
            bench.figs.push(Figure::new(
                &case,
                "time per simulation, with energies",
                se * 1e3,
                "ms",
            ));
            bench
                .figs
                .push(Figure::new(&case, "cost of the energies", se / s, "x"));
            let out = run_plan(&pe)?;
            let e = out
                .response
                .energy
                .ok_or_else(|| anyhow::anyhow!("{case}: the run returned no energies"))?;
            let scale = e.input.abs() + out.diagnostics.initial_energy;
            bench.figs.push(
                Figure::new(
                    &case,
                    "|energy balance error| / input",
                    e.balance_error.abs() / scale.max(f64::MIN_POSITIVE),
                    "-",
                )
                .at_most(1e-9),
            );
        }
    }
    Ok(())
}

/// The plan reductions: the same answers as the full plans, in less time.
pub(super) fn reductions(bench: &mut Bench) -> anyhow::Result<()> {
    let (b3, b10) = (config(BENCHMARK_BUILDING)?, config(TEN_STORY_BUILDING)?);
    // The plan reductions pay: same answers, less time.
    for (case, building) in [
        (
            "reductions: benchmark-3story m'=0, c'>0 (EPP elements vs 2N DOFs)",
            damped_braces(massless(b3.clone())),
        ),
        (
            "reductions: ten-story m'=0, c'>0 (EPP elements vs 2N DOFs)",
            damped_braces(massless(b10.clone())),
        ),
        (
            "reductions: benchmark-3story m'=0, c'>0, damper on floor 1 only",
            first_damper_only(damped_braces(massless(b3.clone()))),
        ),
    ] {
        if !bench.want(case) {
            continue;
        }
        let mut o = SceneOpts::new(MethodName::Newmark);
        let reduced = plan(&building, o)?;
        o.reduce = false;
        let full = plan(&building, o)?;
        let (a, b) = (run_plan(&reduced)?, run_plan(&full)?);
        bench.figs.push(
            Figure::new(
                case,
                "max rel. peak-drift difference reduced vs full",
                max_rel(&a.response.peak_drift, &b.response.peak_drift),
                "-",
            )
            .at_most(1e-9),
        );
        let (sr, sf) = (
            seconds_per_run(&reduced, &bench.clock, bench.budget)?,
            seconds_per_run(&full, &bench.clock, bench.budget)?,
        );
        bench.figs.push(
            Figure::new(
                case,
                &format!("speed-up ({} vs {} DOFs)", reduced.dofs(), full.dofs()),
                sf / sr,
                "x",
            )
            .at_least(1.0),
        );
    }
    Ok(())
}

/// Cost against record length (linear).
pub(super) fn record_length(bench: &mut Bench) -> anyhow::Result<()> {
    let b3 = config(BENCHMARK_BUILDING)?;
    // Cost against record length (linear) and storeys (as measured).
    let case = "benchmark-3story newmark, record length 15/30/60/120 s";
    if bench.want(case) {
        let mut xs = Vec::new();
        let mut ys = Vec::new();
        for d in [15.0, 30.0, 60.0, 120.0] {
            let p = plan(
                &b3,
                SceneOpts {
                    duration: d,
                    ..SceneOpts::new(MethodName::Newmark)
                },
            )?;
            let s = seconds_per_run(&p, &bench.clock, bench.budget)?;
            bench.figs.push(Figure::new(
                case,
                &format!("time per simulation, {d} s"),
                s * 1e3,
                "ms",
            ));
            xs.push(d);
            ys.push(s);
        }
        bench.figs.push(
            Figure::new(
                case,
                "exponent of cost vs length (log-log slope)",
                slope(&xs, &ys),
                "-",
            )
            .between(0.9, 1.1),
        );
    }
    Ok(())
}

/// The plan of a cost-vs-storeys scene: `building(n)` under newmark at Δt = 2.5 ms.
fn storey_plan(building: &dyn Fn(usize) -> String, n: usize) -> anyhow::Result<Plan> {
    plan(
        &config(&building(n))?,
        SceneOpts {
            dt: Some(0.0025),
            ..SceneOpts::new(MethodName::Newmark)
        },
    )
}

/// The cost-vs-storeys cases' common loop: time per simulation of `building(n)` at each
/// size at Δt = 2.5 ms (and its rate when asked), returning the sizes and the times.
fn storey_costs(
    bench: &mut Bench,
    case: &str,
    sizes: &[usize],
    building: &dyn Fn(usize) -> String,
    rates: bool,
) -> anyhow::Result<(Vec<f64>, Vec<f64>)> {
    let mut xs = Vec::new();
    let mut ys = Vec::new();
    for &n in sizes {
        let p = storey_plan(building, n)?;
        let s = seconds_per_run(&p, &bench.clock, bench.budget)?;
        bench.figs.push(Figure::new(
            case,
            &format!("time per simulation, {n} storeys"),
            s * 1e3,
            "ms",
        ));
        if rates {
            bench.figs.push(Figure::new(
                case,
                &format!("simulations per second, {n} storeys"),
                1.0 / s,
                "1/s",
            ));
        }
        xs.push(n as f64);
        ys.push(s);
    }
    Ok((xs, ys))
}

/// Cost against storeys (as measured) of the shear buildings with 2 % modal damping.
pub(super) fn storeys(bench: &mut Bench) -> anyhow::Result<()> {
    let case = "shear buildings with m'=0 dampers, newmark dt 2.5 ms, 15 s";
    if bench.want(case) {
        let (xs, ys) = storey_costs(bench, case, &[3, 6, 10, 20, 50], &shear_building, false)?;
        bench.figs.push(Figure::new(
            case,
            "exponent of cost vs storeys, 3-50 (log-log slope)",
            slope(&xs, &ys),
            "-",
        ));
        bench.figs.push(Figure::new(
            case,
            "exponent of cost vs storeys, 10-50 (log-log slope)",
            slope(&xs[2..], &ys[2..]),
            "-",
        ));
    }
    Ok(())
}

/// Cost against storeys on banded frames (Rayleigh or storey damping): O(N) steps, and
/// what the banded step buys over the dense one.
pub(super) fn banded(bench: &mut Bench) -> anyhow::Result<()> {
    for (case, damping) in [
        (
            "shear buildings with m'=0 dampers, Rayleigh damping, newmark dt 2.5 ms, 15 s",
            ShearDamping::Rayleigh,
        ),
        (
            "shear buildings with m'=0 dampers, storey damping, newmark dt 2.5 ms, 15 s",
            ShearDamping::Storey,
        ),
    ] {
        if !bench.want(case) {
            continue;
        }
        let building = |n: usize| shear_building_damped(n, damping);
        let (xs, ys) = storey_costs(bench, case, &[10, 20, 30, 40, 50], &building, true)?;
        bench.figs.push(
            Figure::new(
                case,
                "exponent of cost vs storeys, 10-50 (log-log slope)",
                slope(&xs, &ys),
                "-",
            )
            .at_most(1.2),
        );
        // What the banded step buys: the same plans on the dense step (what every frame
        // ran before it), timed in alternation with the banded one.
        // At 50 storeys the 6× target holds; at 10 the 3× target is withdrawn (below the
        // floor of the banded step: results/performance/README.md, "Issue 30's speed
        // targets: option A decided") and the row guards against regressions at 20 %
        // under the recorded floor of 1.39×, as the exact rows' guards are set.
        for (n, target, withdrawn) in [(10, 1.11, Some(3.0)), (50, 6.0, None)] {
            let p = storey_plan(&building, n)?;
            let (banded, dense) = seconds_banded_dense(&p, &bench.clock, bench.budget)?;
            bench.figs.push(Figure::new(
                case,
                &format!("time per simulation on the dense step, {n} storeys"),
                dense * 1e3,
                "ms",
            ));
            let speed_up = || {
                Figure::new(
                    case,
                    &format!("banded step's speed-up over the dense step, {n} storeys"),
                    dense / banded,
                    "x",
                )
            };
            bench.figs.push(speed_up().at_least(target));
            if let Some(t) = withdrawn {
                bench.figs.push(speed_up().at_least(t).withdrawn());
            }
        }
    }
    Ok(())
}

/// Memory: peak RSS of a 15 s and a 300 s peaks-only run, each in a fresh process.
pub(super) fn memory(bench: &mut Bench) -> anyhow::Result<()> {
    let case = "memory: benchmark-3story newmark peaks only, 15 s vs 300 s record";
    if bench.want(case) {
        let exe = std::env::current_exe().context("locating the slipload executable")?;
        let mut rss = Vec::new();
        for d in [15.0, 300.0] {
            let out = std::process::Command::new(&exe)
                .args(["bench", "--memory-probe", &d.to_string()])
                .output()
                .with_context(|| format!("running {} bench --memory-probe {d}", exe.display()))?;
            if !out.status.success() {
                bail!(
                    "memory probe of {d} s failed: {}",
                    String::from_utf8_lossy(&out.stderr)
                );
            }
            let kb: f64 = String::from_utf8_lossy(&out.stdout)
                .trim()
                .parse()
                .context("reading the memory probe's answer")?;
            bench.figs.push(Figure::new(
                case,
                &format!("peak RSS, {d} s"),
                kb / 1024.0,
                "MiB",
            ));
            rss.push(kb);
        }
        bench.figs.push(
            Figure::new(
                case,
                "peak RSS difference",
                (rss[1] - rss[0]) / 1024.0,
                "MiB",
            )
            .at_most(1.0),
        );
    }
    Ok(())
}

/// The memory case's child: one peaks-only run, then the process's peak RSS in kB.
pub(super) fn memory_probe(seconds: f64) -> anyhow::Result<()> {
    let p = plan(
        &config(BENCHMARK_BUILDING)?,
        SceneOpts {
            duration: seconds,
            ..SceneOpts::new(MethodName::Newmark)
        },
    )?;
    std::hint::black_box(run_plan(&p)?);
    let kb = peak_rss_kb().context("reading VmHWM from /proc/self/status")?;
    outln!("{kb}");
    Ok(())
}

/// Sweep: parallel efficiency from 1 to 2 threads (wall-clock).
pub(super) fn sweep(bench: &mut Bench) -> anyhow::Result<()> {
    let case = "sweep: benchmark study, 8 designs x 10 records of 20 s";
    if bench.want(case) {
        let study = load_study(None)?;
        let fid = Fidelity::sweep(&study);
        let tasks: Vec<Task> = (0..8)
            .flat_map(|d| {
                (0..study.records.len()).map(move |r| Task {
                    label: format!("#{d}"),
                    slip_loads: vec![250e3 * (d + 1) as f64; 3],
                    friction: None,
                    record: r,
                })
            })
            .collect();
        // Wall-clock on a shared machine: the two thread counts alternate round by round
        // (so both meet the same machine states), and each keeps its fastest round, the
        // one least disturbed by other jobs (a median of one count's rounds taken in a
        // block had a disturbed 1-thread block report an efficiency of 1.5).
        let pools = [1usize, 2]
            .map(|threads| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .context("building a thread pool")
            })
            .into_iter()
            .collect::<anyhow::Result<Vec<_>>>()?;
        let mut best = [f64::INFINITY; 2];
        for round in 0..=bench.budget.repeats.min(3) {
            for (pool, best) in pools.iter().zip(best.iter_mut()) {
                let t = Instant::now();
                pool.install(|| run_tasks(&study, &tasks, &fid, &|_, _| Ok(())))?;
                // Round 0 warms up (records decoded, pages touched).
                if round > 0 {
                    *best = best.min(t.elapsed().as_secs_f64());
                }
            }
        }
        let rates = best.map(|t| tasks.len() as f64 / t);
        for (threads, rate) in [1, 2].iter().zip(rates) {
            bench.figs.push(Figure::new(
                case,
                &format!("tasks per second, {threads} thread(s), wall-clock (fastest round)"),
                rate,
                "1/s",
            ));
        }
        bench.figs.push(
            Figure::new(
                case,
                "parallel efficiency 1 -> 2 threads",
                rates[1] / (2.0 * rates[0]),
                "-",
            )
            .at_least(0.9),
        );
    }
    Ok(())
}
