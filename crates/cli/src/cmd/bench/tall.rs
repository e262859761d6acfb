//! Tall frames (issue 39): the bench's shear buildings with Rayleigh damping and an m′ = 0
//! damper on every floor ([`shear_building_damped`]), under the bench's 15 s synthetic
//! record, peaks only:
//!
//! - `newmark`'s set-up (the scene with its building's checks and modes, the plan, the
//!   run's checks) and its stepping (the run), timed apart against storeys 10…200, with
//!   their log-log slopes; the set-up beside its target (≤ 0.3 s at 200 storeys);
//! - the peak resident memory of one `newmark` run per fresh process against storeys;
//! - `exact` at 60 and 120 storeys beside `newmark`: peak resident memory (targets ≤ 256 MiB
//!   and ≤ 2 GiB), its memory budget and the bytes its cache held, and its time.
//!
//! - a study of the 100-storey frame (a `storey_shear` profile, 10 synthetic records of
//!   20 s, the default sweep, refinement and check) through `optimize`, on every core:
//!   wall-clock time and peak resident memory beside the targets (≤ 10 min, ≤ 2 GiB).
//!
//! Memory is measured in a child process per run ([`tall_probe`], the hidden flag
//! `--tall-probe METHOD:STOREYS`, or `study:STOREYS`), so each figure is that run's own
//! peak, not the bench's.

use super::figure::Figure;
use super::measure::{Bench, Clock, median_seconds, peak_rss_kb, slope, timed_study};
use super::scenes::{SceneOpts, config, scene};
use anyhow::{Context, bail};
use slipload_sim::bench_scenes::{ShearDamping, shear_building_damped};
use slipload_sim::integrator::exact::MemoryBudget;
use slipload_sim::{BuildingConfig, MethodName, Plan, run_plan};

/// The storeys of the set-up, stepping and memory rows.
pub(super) const STOREYS: [usize; 5] = [10, 20, 50, 100, 200];
/// The step of the set-up and stepping rows, s (the banded rows' step: every size steps
/// 6000 times, where each method's default would take 1500 steps from 50 storeys up).
const STEP: Option<f64> = Some(0.0025);
/// The target on `newmark`'s set-up at 200 storeys, s (issue 39).
const SETUP_TARGET_S: f64 = 0.3;
/// `exact`'s storeys and their peak-memory targets, MiB (issue 39).
const EXACT_TARGETS: [(usize, f64); 2] = [(60, 256.0), (120, 2048.0)];

/// The bench's tall frame of `n` storeys.
fn building(n: usize) -> anyhow::Result<BuildingConfig> {
    config(&shear_building_damped(n, ShearDamping::Rayleigh))
}

/// What happens before `newmark`'s first step: the scene (its building's checks and
/// modes), the plan, the run's checks.
fn set_up(b: &BuildingConfig, method: MethodName, dt: Option<f64>) -> anyhow::Result<Plan> {
    let plan = Plan::compile(&scene(
        b,
        SceneOpts {
            dt,
            ..SceneOpts::new(method)
        },
    )?)?;
    slipload_sim::simulate::check(&plan)?;
    Ok(plan)
}

/// `tall frames: set-up and stepping`: `newmark`'s set-up and run against storeys.
pub(super) fn setup_and_stepping(bench: &mut Bench) -> anyhow::Result<()> {
    let case = "tall frames: set-up and stepping, shear buildings, Rayleigh damping, m'=0 damper on every floor, newmark dt 2.5 ms, 15 s synthetic";
    if !bench.want(case) {
        return Ok(());
    }
    let (mut xs, mut setups, mut steps) = (Vec::new(), Vec::new(), Vec::new());
    for n in STOREYS {
        let b = building(n)?;
        let setup = median_seconds(&bench.clock, bench.budget, || {
            std::hint::black_box(set_up(&b, MethodName::Newmark, STEP)?);
            Ok(())
        })?;
        let plan = set_up(&b, MethodName::Newmark, STEP)?;
        let stepping = median_seconds(&bench.clock, bench.budget, || {
            std::hint::black_box(run_plan(std::hint::black_box(&plan))?);
            Ok(())
        })?;
        let fig = Figure::new(case, &format!("set-up, {n} storeys"), setup * 1e3, "ms");
        bench.figs.push(if n == 200 {
            fig.at_most(SETUP_TARGET_S * 1e3)
        } else {
            fig
        });
        bench.figs.push(Figure::new(
            case,
            &format!("stepping ({} steps), {n} storeys", plan.steps),
            stepping * 1e3,
            "ms",
        ));
        xs.push(n as f64);
        setups.push(setup);
        steps.push(stepping);
    }
    bench.figs.push(
        Figure::new(
            case,
            "exponent of set-up vs storeys, 10-200 (log-log slope)",
            slope(&xs, &setups),
            "-",
        )
        .at_most(3.0),
    );
    bench.figs.push(Figure::new(
        case,
        "exponent of set-up vs storeys, 50-200 (log-log slope)",
        slope(&xs[2..], &setups[2..]),
        "-",
    ));
    // reported, not judged: the banded rows judge the step's O(N) over 10-50 storeys
    bench.figs.push(Figure::new(
        case,
        "exponent of stepping vs storeys, 10-200 (log-log slope)",
        slope(&xs, &steps),
        "-",
    ));
    Ok(())
}

/// One run's figures from its child process.
struct Probe {
    /// Peak resident memory of the child, MiB.
    rss_mib: f64,
    /// CPU seconds of the run (set-up excluded).
    seconds: f64,
    /// `exact`'s memory budget and the bytes its cache held at most, MiB (0 for newmark).
    budget_mib: f64,
    cache_mib: f64,
}

/// Runs `slipload bench --tall-probe METHOD:STOREYS` in a fresh process.
fn probe(method: MethodName, n: usize) -> anyhow::Result<Probe> {
    let arg = format!("{}:{n}", method.as_str());
    let v = probe_child(&arg)?;
    let [kb, seconds, budget, cache] = v;
    const MIB: f64 = 1024.0 * 1024.0;
    Ok(Probe {
        rss_mib: kb / 1024.0,
        seconds,
        budget_mib: budget / MIB,
        cache_mib: cache / MIB,
    })
}

/// The probe's child: one run of `METHOD:STOREYS`, then `peak-RSS-kB run-CPU-seconds
/// budget-bytes cache-peak-bytes` on one line.
pub(super) fn tall_probe(spec: &str) -> anyhow::Result<()> {
    let (method, n) = spec
        .split_once(':')
        .context("--tall-probe takes METHOD:STOREYS, e.g. exact:60")?;
    if method == "study" {
        let n: usize = n
            .parse()
            .with_context(|| format!("--tall-probe {spec}: storeys"))?;
        return study_probe(n);
    }
    let method: MethodName = method
        .parse()
        .map_err(|e| anyhow::anyhow!("--tall-probe {spec}: {e}"))?;
    let n: usize = n
        .parse()
        .with_context(|| format!("--tall-probe {spec}: storeys"))?;
    let plan = set_up(&building(n)?, method, None)?;
    let budget = if method == MethodName::Exact {
        MemoryBudget::for_plan(&plan).bytes as f64
    } else {
        0.0
    };
    let clock = Clock::new();
    let out = run_plan(&plan)?;
    let seconds = clock.now();
    let kb = peak_rss_kb().context("reading VmHWM from /proc/self/status")?;
    outln!(
        "{kb} {seconds} {budget} {}",
        out.diagnostics.cache_peak_bytes
    );
    Ok(())
}

/// `tall frames: peak memory`: one `newmark` run per fresh process against storeys.
pub(super) fn memory(bench: &mut Bench) -> anyhow::Result<()> {
    let case = "tall frames: peak memory, shear buildings, Rayleigh damping, m'=0 damper on every floor, newmark default dt, 15 s synthetic, one process per run";
    if !bench.want(case) {
        return Ok(());
    }
    let (mut xs, mut ys) = (Vec::new(), Vec::new());
    for n in STOREYS {
        let p = probe(MethodName::Newmark, n)?;
        bench.figs.push(Figure::new(
            case,
            &format!("peak RSS, {n} storeys"),
            p.rss_mib,
            "MiB",
        ));
        xs.push(n as f64);
        ys.push(p.rss_mib);
    }
    bench.figs.push(Figure::new(
        case,
        "exponent of peak RSS vs storeys, 10-200 (log-log slope)",
        slope(&xs, &ys),
        "-",
    ));
    Ok(())
}

/// `tall frames: exact`: `exact` at 60 and 120 storeys beside `newmark`, one process per
/// run.
pub(super) fn exact(bench: &mut Bench) -> anyhow::Result<()> {
    let case = "tall frames: exact vs newmark (default dt), shear buildings, Rayleigh damping, m'=0 damper on every floor, 15 s synthetic, one process per run";
    if !bench.want(case) {
        return Ok(());
    }
    for (n, target) in EXACT_TARGETS {
        let e = probe(MethodName::Exact, n)?;
        let nm = probe(MethodName::Newmark, n)?;
        bench.figs.push(
            Figure::new(
                case,
                &format!("exact peak RSS, {n} storeys"),
                e.rss_mib,
                "MiB",
            )
            .at_most(target),
        );
        bench.figs.push(Figure::new(
            case,
            &format!(
                "exact memory budget (cache held at most {:.0} MiB), {n} storeys",
                e.cache_mib
            ),
            e.budget_mib,
            "MiB",
        ));
        bench.figs.push(Figure::new(
            case,
            &format!("newmark peak RSS, {n} storeys"),
            nm.rss_mib,
            "MiB",
        ));
        bench.figs.push(Figure::new(
            case,
            &format!("exact time per simulation, {n} storeys"),
            e.seconds,
            "s",
        ));
        bench.figs.push(Figure::new(
            case,
            &format!("newmark time per simulation (default dt), {n} storeys"),
            nm.seconds,
            "s",
        ));
        bench.figs.push(Figure::new(
            case,
            &format!("exact time / newmark's, {n} storeys"),
            e.seconds / nm.seconds.max(1e-9),
            "x",
        ));
    }
    Ok(())
}

/// The tall-frame study of `n` storeys: the bench's frame, a `storey_shear` profile over a
/// floor-1 slip load of 1 to 60 MN (the frame's own is 5 % of the weight above floor 1),
/// the embedded synthetic suite's 10 records of 20 s at 0.4 g, every other key at its
/// default (sweep, refinement, check).
fn tall_study_json(n: usize) -> String {
    let building = shear_building_damped(n, ShearDamping::Rayleigh);
    format!(
        r#"{{ "name": "tall-{n}", "building": {building},
             "suites": [ {{ "name": "synthetic-0.4g", "synthetic": {{ "count": 10, "seed": 2007, "pga_g": 0.4, "duration_s": 20 }} }} ],
             "space": {{ "profile": {{ "shape": "storey_shear", "scale_kn": [1000, 60000] }} }},
             "objective": {{ "terms": [ {{ "metric": "peak_drift_ratio", "statistic": "mean" }} ] }} }}"#
    )
}

/// The study probe's child: `optimize` of [`tall_study_json`] into a scratch folder on
/// every core, then `peak-RSS-kB wall-seconds simulations threads` on one line.
fn study_probe(n: usize) -> anyhow::Result<()> {
    use slipload_opt::Study;
    use slipload_opt::eval::progress::{Phase, Progress};
    use std::sync::atomic::{AtomicUsize, Ordering};
    /// Counts the simulations (run or reused).
    #[derive(Default)]
    struct Count(AtomicUsize);
    impl Progress for Count {
        fn start(&self, _: Phase, _: usize) {}
        fn tick(&self) {
            self.0.fetch_add(1, Ordering::SeqCst);
        }
        fn finish(&self, _: Phase) {}
    }
    let t = std::time::Instant::now();
    let study = Study::from_json(
        &tall_study_json(n),
        std::path::Path::new("slipload bench (tall-frame study)"),
    )?;
    let count = Count::default();
    let (run, _) = timed_study(&study, "tall", &count);
    // (the wall clock from loading the study: its probes are part of the study's time)
    let wall = t.elapsed().as_secs_f64();
    run?;
    let kb = peak_rss_kb().context("reading VmHWM from /proc/self/status")?;
    outln!(
        "{kb} {wall} {} {}",
        count.0.load(Ordering::SeqCst),
        rayon::current_num_threads()
    );
    Ok(())
}

/// `tall frames: 100-storey study`: wall-clock time and peak RSS of the study, in a child.
pub(super) fn study(bench: &mut Bench) -> anyhow::Result<()> {
    let case = "tall frames: 100-storey study, storey_shear profile, 10 synthetic records of 20 s, default sweep, refinement and check, every core, one process";
    if !bench.want(case) {
        return Ok(());
    }
    let [kb, wall, sims, threads] = probe_child("study:100")?;
    bench.figs.push(
        Figure::new(
            case,
            &format!("wall-clock seconds ({sims} simulations, {threads} thread(s))"),
            wall,
            "s",
        )
        .at_most(600.0),
    );
    bench
        .figs
        .push(Figure::new(case, "peak RSS", kb / 1024.0, "MiB").at_most(2048.0));
    Ok(())
}

/// Runs `slipload bench --tall-probe ARG` in a child process (its peak RSS is its own)
/// and reads the four numbers it answers.
fn probe_child(arg: &str) -> anyhow::Result<[f64; 4]> {
    let exe = std::env::current_exe().context("locating the slipload executable")?;
    let out = std::process::Command::new(&exe)
        .args(["bench", "--tall-probe", arg])
        .output()
        .with_context(|| format!("running {} bench --tall-probe {arg}", exe.display()))?;
    if !out.status.success() {
        bail!(
            "the tall-frame probe {arg} failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let v: Vec<f64> = text
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .with_context(|| format!("reading the tall-frame probe's answer {text:?}"))?;
    match v[..] {
        [a, b, c, d] => Ok([a, b, c, d]),
        _ => bail!("the tall-frame probe {arg} answered {text:?}, not four numbers"),
    }
}
