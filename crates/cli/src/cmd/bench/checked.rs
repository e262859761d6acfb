//! The time to a checked design: `optimize` of the worked example
//! `configs/study-ten-story-check.json` (the ten-storey yielding frame, two hazard levels ×
//! 11 code-scaled records × 3 property cases, limits, free slip loads) into a scratch
//! folder, on every core, in wall-clock seconds — in all and per phase, with the
//! simulations of each. One run (it takes tens of seconds): a shared machine's load shows
//! in it, so it is reported beside the aim, not averaged away.

use super::figure::Figure;
use super::measure::{Bench, timed_study};
use anyhow::Context;
use slipload_opt::Study;
use slipload_opt::eval::progress::{Phase, Progress};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// The example, where a clone of the project holds it.
const EXAMPLE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../configs/study-ten-story-check.json"
);

/// Wall-clock seconds and simulations (run or reused) per phase.
#[derive(Default)]
struct PhaseClock {
    started: Mutex<Option<(Phase, Instant)>>,
    ticks: AtomicUsize,
    done: Mutex<Vec<(Phase, f64, usize)>>,
}

impl Progress for PhaseClock {
    fn start(&self, phase: Phase, _work: usize) {
        self.ticks.store(0, Ordering::SeqCst);
        if let Ok(mut s) = self.started.lock() {
            *s = Some((phase, Instant::now()));
        }
    }
    fn tick(&self) {
        self.ticks.fetch_add(1, Ordering::SeqCst);
    }
    fn finish(&self, phase: Phase) {
        let since = self
            .started
            .lock()
            .ok()
            .and_then(|s| *s)
            .map_or(0.0, |(_, t)| t.elapsed().as_secs_f64());
        if let Ok(mut d) = self.done.lock() {
            d.push((phase, since, self.ticks.load(Ordering::SeqCst)));
        }
    }
}

/// The example on pairs of components (each pair rotated, the worst orientation kept).
const PAIRS_EXAMPLE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../configs/study-ten-story-pairs.json"
);

/// `checked design`: the examples' `optimize` (on single components, and on pairs of
/// components each rotated to four orientations), in all and per phase.
pub(super) fn checked_design(bench: &mut Bench) -> anyhow::Result<()> {
    one_example(
        bench,
        EXAMPLE,
        "checked design: configs/study-ten-story-check.json, 2 hazard levels x 11 records x 3 property cases",
        Some(60.0),
    )?;
    one_example(
        bench,
        PAIRS_EXAMPLE,
        "checked design on pairs: configs/study-ten-story-pairs.json, 2 hazard levels x 11 pairs x 4 orientations x 3 property cases",
        None,
    )
}

/// One example's `optimize` into a scratch folder, against the aim `aim` (s) if any.
fn one_example(bench: &mut Bench, path: &str, case: &str, aim: Option<f64>) -> anyhow::Result<()> {
    if !bench.want(case) {
        return Ok(());
    }
    let study = Study::load(std::path::Path::new(path)).with_context(|| {
        format!("the worked example {path} (run the bench from a clone of the project)")
    })?;
    let clock = PhaseClock::default();
    let (run, wall) = timed_study(&study, "checked", &clock);
    let run = run?;
    let threads = rayon::current_num_threads();
    let figure = Figure::new(
        case,
        &format!("wall-clock seconds to the checked design, {threads} thread(s)"),
        wall,
        "s",
    );
    bench.figs.push(match aim {
        Some(a) => figure.at_most(a),
        None => figure,
    });
    let done = clock.done.lock().map(|d| d.clone()).unwrap_or_default();
    for (phase, seconds, sims) in done {
        bench.figs.push(Figure::new(
            case,
            &format!("{}: wall-clock seconds ({sims} simulations)", phase.label()),
            seconds,
            "s",
        ));
    }
    bench.figs.push(Figure::new(
        case,
        &format!(
            "verdict: {} (1 = every limit met)",
            run.report
                .code_check
                .as_ref()
                .map_or("no check", |c| if c.passes { "PASS" } else { "FAIL" })
        ),
        f64::from(u8::from(
            run.report.code_check.as_ref().is_some_and(|c| c.passes),
        )),
        "",
    ));
    Ok(())
}
