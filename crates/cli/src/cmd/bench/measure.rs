//! Measuring for `slipload bench`: the process's CPU clock and peak memory, the median
//! time per run of a plan, the fits and differences the figures report, and [`Bench`],
//! the state of one bench run (its budget, the cases asked for, the figures so far).

use super::figure::Figure;
use anyhow::{Context, ensure};
use slipload_sim::accuracy::{median, observed_order};
use slipload_sim::integrator::newmark::{StepPath, run_on_path};
use slipload_sim::{Plan, run_plan};

/// CPU time of the whole process, s (`CLOCK_PROCESS_CPUTIME_ID` on Linux, ns resolution).
pub(super) struct Clock {
    start: cpu_time::ProcessTime,
}

impl Clock {
    pub(super) fn new() -> Clock {
        Clock {
            start: cpu_time::ProcessTime::now(),
        }
    }
    pub(super) fn now(&self) -> f64 {
        self.start.elapsed().as_secs_f64()
    }
}

/// Peak resident set size of this process, kB (Linux `VmHWM`).
pub(super) fn peak_rss_kb() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = text.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Budgets of one measurement.
#[derive(Debug, Clone, Copy)]
pub(super) struct Budget {
    /// CPU seconds per repeat.
    pub(super) seconds: f64,
    /// Repeats (the median is reported).
    pub(super) repeats: usize,
}

/// One run of the bench: the clock and budget every case measures with, the cases asked
/// for (`--only`), every case's name asked about (to say which exist when `--only`
/// matches none), and the figures measured so far, in the order they print.
pub(super) struct Bench<'a> {
    pub(super) clock: Clock,
    pub(super) budget: Budget,
    only: &'a [String],
    pub(super) cases: Vec<String>,
    pub(super) figs: Vec<Figure>,
}

impl<'a> Bench<'a> {
    /// A run with `budget` per measurement, of the cases whose name contains one of
    /// `only` (every case when it is empty); its clock starts now.
    pub(super) fn new(budget: Budget, only: &'a [String]) -> Bench<'a> {
        Bench {
            clock: Clock::new(),
            budget,
            only,
            cases: Vec::new(),
            figs: Vec::new(),
        }
    }

    /// Whether `case` is to run (its name is kept, asked or not).
    pub(super) fn want(&mut self, case: &str) -> bool {
        self.cases.push(case.to_string());
        self.only.is_empty() || self.only.iter().any(|o| case.contains(o))
    }
}

/// Median CPU seconds per run of `plan` on `newmark`'s banded and dense steps, the two
/// timed in alternating batches (so both meet the same machine states; one warm-up run
/// of each first): (banded, dense).
pub(super) fn seconds_banded_dense(
    plan: &Plan,
    clock: &Clock,
    b: Budget,
) -> anyhow::Result<(f64, f64)> {
    let run = |path: StepPath| -> anyhow::Result<f64> {
        let t = clock.now();
        let (_, stats) = run_on_path(std::hint::black_box(plan), path)
            .with_context(|| format!("running {} on the {path:?} step", plan.name))?;
        ensure!(
            stats.is_some() == (path == StepPath::Banded),
            "{}: the {path:?} step did not run",
            plan.name
        );
        Ok((clock.now() - t).max(1e-6))
    };
    let first = run(StepPath::Banded)?.max(run(StepPath::Dense)?);
    let batch = ((b.seconds / first).ceil() as usize).max(1);
    let mut times = [Vec::with_capacity(b.repeats), Vec::with_capacity(b.repeats)];
    for _ in 0..b.repeats {
        for (path, times) in [StepPath::Banded, StepPath::Dense]
            .iter()
            .zip(times.iter_mut())
        {
            let mut total = 0.0;
            for _ in 0..batch {
                total += run(*path)?;
            }
            times.push(total / batch as f64);
        }
    }
    let [mut banded, mut dense] = times;
    Ok((median(&mut banded), median(&mut dense)))
}

/// Median CPU seconds of `f` (one warm-up call, then batches long enough for the clock).
pub(super) fn median_seconds(
    clock: &Clock,
    b: Budget,
    mut f: impl FnMut() -> anyhow::Result<()>,
) -> anyhow::Result<f64> {
    let t0 = clock.now();
    f()?;
    let first = (clock.now() - t0).max(1e-6);
    let batch = ((b.seconds / first).ceil() as usize).max(1);
    let mut times = Vec::with_capacity(b.repeats);
    for _ in 0..b.repeats {
        let t = clock.now();
        for _ in 0..batch {
            f()?;
        }
        times.push((clock.now() - t) / batch as f64);
    }
    Ok(median(&mut times))
}

/// Median CPU seconds per run of `plan` (one warm-up run first).
pub(super) fn seconds_per_run(plan: &Plan, clock: &Clock, b: Budget) -> anyhow::Result<f64> {
    median_seconds(clock, b, || {
        std::hint::black_box(
            run_plan(std::hint::black_box(plan))
                .with_context(|| format!("running {}", plan.name))?,
        );
        Ok(())
    })
}

/// `slipload optimize` of `study` into a fresh scratch folder named after `name` (removed
/// after), reporting to `progress`, without figures: the run and its wall-clock seconds.
pub(super) fn timed_study(
    study: &slipload_opt::Study,
    name: &str,
    progress: &dyn slipload_opt::eval::progress::Progress,
) -> (
    Result<slipload_opt::pipeline::OptimizeRun, slipload_opt::OptError>,
    f64,
) {
    use slipload_opt::pipeline::{NoFigures, OptimizeOptions, optimize_study};
    let dir = std::env::temp_dir().join(format!("slipload-bench-{name}-{}", std::process::id()));
    let t = std::time::Instant::now();
    let run = optimize_study(
        study,
        &OptimizeOptions::default(),
        slipload_opt::store::folder::FolderRequest {
            path: &dir,
            option: "scratch folder",
            fresh: true,
        },
        progress,
        &NoFigures,
    );
    let wall = t.elapsed().as_secs_f64();
    let _ = std::fs::remove_dir_all(&dir);
    (run, wall)
}

/// Max relative difference of two peak-drift vectors.
pub(super) fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / y.abs().max(f64::MIN_POSITIVE))
        .fold(0.0, f64::max)
}

/// Least-squares slope of log y on log x (the accuracy study's order fit; NaN if undefined).
pub(super) fn slope(x: &[f64], y: &[f64]) -> f64 {
    let pts: Vec<(f64, f64)> = x.iter().copied().zip(y.iter().copied()).collect();
    observed_order(&pts).unwrap_or(f64::NAN)
}
