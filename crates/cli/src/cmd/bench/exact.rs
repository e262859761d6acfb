//! The cases of `exact` in `slipload bench`: its regression guards (its speed targets
//! are withdrawn) and what an engineer buys from it, the time to reach a peak-drift error
//! against `newmark` along a ladder of steps, beside OpenSees's from the committed
//! equal-accuracy comparison.

use super::figure::Figure;
use super::measure::{Bench, Budget, max_rel, seconds_per_run};
use super::scenes::{
    PAPER_1STORY_BUILDING, SceneOpts, TEN_STORY_BUILDING, comparison_record, config, locked,
    massless, plan, record_plan,
};
use crate::cmd::scene_args::BENCHMARK_BUILDING;
use slipload_sim::{MethodName, Plan, run_plan};
use std::path::Path;

/// The regression guards of one `exact` bench scene: at least 0.8× the simulation rate
/// and at most 1.2× the time ratio to `newmark` measured when its speed targets were
/// withdrawn, on each machine the project runs on (results/performance/README.md,
/// "`exact`: guards and equal accuracy"): the slower machine's rate and the larger ratio
/// set them, so today's code passes on either and a 20 % regression fails on either.
#[derive(Debug, Clone, Copy)]
struct ExactGuard {
    /// Least simulations per second per core.
    rate: f64,
    /// Largest time per simulation over newmark's at its default step.
    ratio: f64,
}

impl ExactGuard {
    /// Guards 20 % away from the measured (rate 1/s, ratio ×) of each machine.
    fn across<const N: usize>(measured: [(f64, f64); N]) -> ExactGuard {
        let rate = measured.iter().map(|m| m.0).fold(f64::INFINITY, f64::min);
        let ratio = measured.iter().map(|m| m.1).fold(0.0, f64::max);
        ExactGuard {
            rate: round3(0.8 * rate),
            ratio: round3(1.2 * ratio),
        }
    }
}

/// `v` to three significant digits (a guard prints as the number it is judged against).
fn round3(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let scale = 10f64.powi(2 - v.abs().log10().floor() as i32);
    (v * scale).round() / scale
}

/// Time to reach a peak-drift error `target` along a ladder of (Δt, error, seconds),
/// coarse to fine, as the equal-accuracy comparison with OpenSees defines it
/// (scripts/compare-opensees-precision.py): the first step from which on every finer step
/// stays at or below the target; its time interpolated linearly in log(time) against
/// log(error) between it and the coarser step before it. `None` when the finest step is
/// above the target; `(seconds, true)` when the coarsest step already reaches it (its
/// time is then an upper bound).
fn time_to_reach(ladder: &[(f64, f64, f64)], target: f64) -> Option<(f64, bool)> {
    let first = (0..ladder.len()).find(|&i| ladder[i..].iter().all(|p| p.1 <= target))?;
    if first == 0 {
        return Some((ladder[0].2, true));
    }
    let (_, e0, t0) = ladder[first - 1];
    let (_, e1, t1) = ladder[first];
    if e1 <= 0.0 || e0 <= e1 {
        return Some((t1, false));
    }
    let w = (e0.ln() - target.ln()) / (e0.ln() - e1.ln());
    Some(((t0.ln() + w * (t1.ln() - t0.ln())).exp(), false))
}

/// The least speed-up over OpenSees at equal accuracy measured on the bench's synthetic
/// record, per target (1e-3, 1e-4): 313× and 328× in the committed comparison
/// (`opensees-precision.md`; 324–332× and 331–341× in the bench's quiet runs). Issue 30's
/// 500× target was retired by option A (results/performance/README.md, "Issue 30's speed
/// targets: option A decided"): the row is a regression guard 20 % under this floor, as
/// the `exact` rows and the banded step's ten-storey row are, with the 500× beside it as
/// withdrawn.
const OPENSEES_FLOORS: [(f64, f64); 2] = [(1e-3, 313.0), (1e-4, 328.0)];

/// Issue 30's target on the speed-up over OpenSees at equal accuracy, withdrawn.
const OPENSEES_WITHDRAWN: f64 = 500.0;

/// The regression guard of the speed-up over OpenSees at `target`: 0.8× its floor
/// ([`OPENSEES_FLOORS`]); `None` for a target without one.
fn opensees_guard(target: f64) -> Option<f64> {
    OPENSEES_FLOORS
        .iter()
        .find(|f| f.0 == target)
        .map(|f| round3(0.8 * f.1))
}

/// The equal-accuracy times of OpenSees on the synthetic record, from the committed
/// comparison (`results/performance/opensees-precision.json`, written by
/// scripts/compare-opensees-precision.py): (target, seconds, whether an upper bound).
/// Empty when the file is not there (a binary run outside its repository).
fn opensees_equal_accuracy() -> Vec<(f64, f64, bool)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../results/performance/opensees-precision.json");
    let Ok(text) = std::fs::read_to_string(path) else {
        return Vec::new();
    };
    let Ok(v) = serde_json::from_str::<serde_json::Value>(&text) else {
        return Vec::new();
    };
    let Some(rec) = v["records"]
        .as_array()
        .and_then(|r| r.iter().find(|r| r["slug"] == "synthetic"))
    else {
        return Vec::new();
    };
    rec["targets"]
        .as_array()
        .map(|ts| {
            ts.iter()
                .filter_map(|t| {
                    let o = &t["opensees"];
                    Some((
                        t["target"].as_f64()?,
                        o["time_s"].as_f64()?,
                        o["status"] == "at most",
                    ))
                })
                .collect()
        })
        .unwrap_or_default()
}

/// The rows of `exact` on each bench building: simulation rate and time ratio to
/// `newmark` against their guards (and the withdrawn targets beside them), stick-slip
/// events, and the counted work beside what a unit of it costs.
pub(super) fn guards(bench: &mut Bench) -> anyhow::Result<()> {
    let (b3, b10) = (config(BENCHMARK_BUILDING)?, config(TEN_STORY_BUILDING)?);
    // `exact`: its speed targets of issue 17 are withdrawn (the method's floor is above
    // them, results/performance/README.md); its rows are regression guards with 20 %
    // headroom on the rates and ratios to newmark measured on the two machines the
    // project runs on (an AMD EPYC when the targets were withdrawn, an Intel Xeon since):
    // rate ≥ 0.8× the slower machine's, ratio ≤ 1.2× the larger. What an engineer buys
    // from it is the equal-accuracy case below.
    for (name, building, guard, withdrawn) in [
        (
            "benchmark-3story",
            b3.clone(),
            ExactGuard::across([(69.2, 42.42), (52.95, 54.71)]),
            (Some(1000.0), Some(5.0)),
        ),
        (
            "benchmark-3story m'=0",
            massless(b3.clone()),
            ExactGuard::across([(477.7, 6.954), (361.3, 8.700)]),
            (Some(5000.0), Some(1.5)),
        ),
        // The same frame with its dampers locked (slip loads far above any brace force):
        // no events, so its ratio is what the stepping and the sampled outputs cost alone,
        // the floor under the m′ = 0 ratio.
        (
            "benchmark-3story m'=0 locked",
            locked(massless(b3.clone())),
            ExactGuard::across([(943.1, 3.946), (752.1, 4.710)]),
            (None, None),
        ),
        // Its ratio is to `newmark` since the return mapping (numerics version 3), which
        // made `newmark` 35 % faster on this building (547-555 against 744-747 runs per
        // second, the binaries before and after interleaved on the Intel Xeon) while
        // `exact` ran as before (70.9-71.8 against 70.9 per second): its ratio 7.8 went to
        // 10.37-10.57, which sets the guard; the rate guard is unchanged.
        (
            "ten-story",
            b10,
            ExactGuard {
                ratio: ExactGuard::across([(70.94, 10.57)]).ratio,
                ..ExactGuard::across([(98.14, 6.500), (74.06, 7.593)])
            },
            (None, Some(2.0)),
        ),
        (
            "paper-1story",
            config(PAPER_1STORY_BUILDING)?,
            ExactGuard::across([(2575.6, 0.567), (2234.4, 0.6574)]),
            (None, None),
        ),
    ] {
        let case = format!("{name}, 15 s synthetic, exact");
        if !bench.want(&case) {
            continue;
        }
        let p = plan(&building, SceneOpts::new(MethodName::Exact))?;
        let s = seconds_per_run(
            &p,
            &bench.clock,
            Budget {
                repeats: 3,
                ..bench.budget
            },
        )?;
        let rate = Figure::new(&case, "simulations per second per core", 1.0 / s, "1/s");
        bench.figs.push(rate.clone().at_least(guard.rate));
        if let Some(t) = withdrawn.0 {
            bench.figs.push(rate.at_least(t).withdrawn());
        }
        let out = run_plan(&p)?;
        bench.figs.push(Figure::new(
            &case,
            "stick-slip events",
            out.response.transitions.iter().sum::<u64>() as f64,
            "-",
        ));
        let pn = plan(&building, SceneOpts::new(MethodName::Newmark))?;
        let newmark = seconds_per_run(&pn, &bench.clock, bench.budget)?;
        let ratio = Figure::new(
            &case,
            "time per simulation / newmark's at its default dt",
            s / newmark,
            "x",
        );
        bench.figs.push(ratio.clone().at_most(guard.ratio));
        if let Some(t) = withdrawn.1 {
            bench.figs.push(ratio.at_most(t).withdrawn());
        }
        // The counted work a study chooses its sweep method by (at most twice newmark's
        // for exact), beside what a unit of it costs in time for each method.
        let work_n = run_plan(&pn)?.diagnostics.work as f64;
        let work_e = out.diagnostics.work as f64;
        bench.figs.push(Figure::new(
            &case,
            "work per simulation / newmark's (counted)",
            work_e / work_n.max(1.0),
            "x",
        ));
        bench.figs.push(Figure::new(
            &case,
            "time per unit of work, exact",
            s / work_e.max(1.0) * 1e9,
            "ns",
        ));
        bench.figs.push(Figure::new(
            &case,
            "time per unit of work, newmark",
            newmark / work_n.max(1.0) * 1e9,
            "ns",
        ));
    }
    Ok(())
}

/// The equal-accuracy case: `exact` and `newmark` along a ladder of steps on the scene
/// of the comparison with OpenSees, and the times to reach 1e-3 and 1e-4.
pub(super) fn equal_accuracy(bench: &mut Bench) -> anyhow::Result<()> {
    let b3 = config(BENCHMARK_BUILDING)?;
    // What an engineer buys: the time to reach a peak-drift error of 1e-3 and 1e-4 against
    // `exact` (continuous peaks), newmark along a ladder of steps against exact at its
    // default step, on the scene of the equal-accuracy comparison with OpenSees (the
    // benchmark with m′ = 0 under that comparison's 15 s synthetic record, the same
    // samples), and OpenSees's times from that comparison beside them.
    let case = "equal accuracy: benchmark-3story m'=0, 15 s synthetic";
    if bench.want(case) {
        let building = massless(b3);
        let record = comparison_record()?;
        let plans = (|| -> anyhow::Result<(Plan, Vec<(f64, Plan)>)> {
            let pe = record_plan(&building, &record, MethodName::Exact, None)?;
            let mut ps = Vec::new();
            for dt in [0.01, 0.005, 0.0025, 0.00125, 0.000625, 0.0003125] {
                ps.push((
                    dt,
                    record_plan(&building, &record, MethodName::Newmark, Some(dt))?,
                ));
            }
            Ok((pe, ps))
        })();
        // the plans hold the samples: the file has done its work either way
        let _ = std::fs::remove_file(&record);
        let (pe, newmark_plans) = plans?;
        let reference = run_plan(&pe)?.response.peak_drift;
        let exact_s = seconds_per_run(
            &pe,
            &bench.clock,
            Budget {
                repeats: 3,
                ..bench.budget
            },
        )?;
        let mut ladder = Vec::new();
        for (dt, p) in newmark_plans {
            let err = max_rel(&run_plan(&p)?.response.peak_drift, &reference);
            let s = seconds_per_run(&p, &bench.clock, bench.budget)?;
            let at = format!("newmark at dt {} ms", dt * 1e3);
            bench.figs.push(Figure::new(
                case,
                &format!("{at}, max rel. peak-drift error"),
                err,
                "-",
            ));
            bench.figs.push(Figure::new(
                case,
                &format!("{at}, time per simulation"),
                s * 1e3,
                "ms",
            ));
            ladder.push((dt, err, s));
        }
        let opensees = opensees_equal_accuracy();
        bench.figs.push(Figure::new(
            case,
            "exact, time per simulation (any target)",
            exact_s * 1e3,
            "ms",
        ));
        for target in [1e-3, 1e-4] {
            let Some((newmark_s, bound)) = time_to_reach(&ladder, target) else {
                bench.figs.push(Figure::new(
                    case,
                    &format!("newmark, finest step's error above {target:.0e}"),
                    ladder.last().map_or(f64::NAN, |l| l.1),
                    "-",
                ));
                continue;
            };
            let le = if bound { "at most " } else { "" };
            bench.figs.push(Figure::new(
                case,
                &format!("newmark, {le}time to reach {target:.0e}"),
                newmark_s * 1e3,
                "ms",
            ));
            bench.figs.push(Figure::new(
                case,
                &format!("exact / newmark at {target:.0e}"),
                exact_s / newmark_s,
                "x",
            ));
            if let Some(&(_, os, os_bound)) = opensees.iter().find(|o| o.0 == target) {
                let le = if os_bound { "at most " } else { "" };
                bench.figs.push(Figure::new(
                    case,
                    &format!("OpenSees, {le}time to reach {target:.0e} (opensees-precision.json)"),
                    os * 1e3,
                    "ms",
                ));
                // a guard at the floor of option A, the 500× beside it withdrawn
                let speed_up = || {
                    Figure::new(
                        case,
                        &format!("OpenSees / newmark at {target:.0e}"),
                        os / newmark_s,
                        "x",
                    )
                };
                match opensees_guard(target) {
                    Some(g) => {
                        bench.figs.push(speed_up().at_least(g));
                        bench
                            .figs
                            .push(speed_up().at_least(OPENSEES_WITHDRAWN).withdrawn());
                    }
                    None => bench.figs.push(speed_up()),
                }
                bench.figs.push(Figure::new(
                    case,
                    &format!("OpenSees / exact at {target:.0e}"),
                    os / exact_s,
                    "x",
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The interpolation of the equal-accuracy comparison: log(time) linear in log(error)
    /// between the two steps that bracket the target, an upper bound when the coarsest
    /// step already reaches it, none when the finest does not, and a step whose error
    /// rises again on a finer step does not count as reaching it.
    #[test]
    fn time_to_reach_interpolates_log_log() {
        // errors 1e-2, 1e-3, 1e-4 at times 1, 2, 4: 1e-3 is reached at step 2 exactly,
        // 10^-3.5 halfway in log between steps 2 and 3 (time √8)
        let ladder = [(4.0, 1e-2, 1.0), (2.0, 1e-3, 2.0), (1.0, 1e-4, 4.0)];
        let (t, bound) = time_to_reach(&ladder, 1e-3).unwrap();
        assert!((t - 2.0).abs() < 1e-12 && !bound);
        let (t, _) = time_to_reach(&ladder, 10f64.powf(-3.5)).unwrap();
        assert!((t - 8f64.sqrt()).abs() < 1e-12, "{t}");
        assert_eq!(time_to_reach(&ladder, 0.1), Some((1.0, true)));
        assert_eq!(time_to_reach(&ladder, 1e-5), None);
        // not monotone: 5e-4 is met at step 2 but not at step 3
        let bumpy = [
            (4.0, 1e-2, 1.0),
            (2.0, 4e-4, 2.0),
            (1.0, 6e-4, 4.0),
            (0.5, 1e-4, 8.0),
        ];
        let (t, _) = time_to_reach(&bumpy, 5e-4).unwrap();
        assert!(t > 4.0 && t < 8.0, "{t}");
    }

    #[test]
    fn guards_are_twenty_percent_from_the_measured_figures() {
        let g = ExactGuard::across([(69.2, 42.42)]);
        assert_eq!((g.rate, g.ratio), (55.4, 50.9));
        // the slower rate and the larger ratio of two machines
        let g = ExactGuard::across([(69.2, 42.42), (52.95, 54.71)]);
        assert_eq!((g.rate, g.ratio), (42.4, 65.7));
        assert_eq!(round3(2575.6 * 0.8), 2060.0);
        assert_eq!(round3(0.567 * 1.2), 0.68);
    }

    /// The speed-up over OpenSees is guarded 20 % under its recorded floor at both
    /// targets (option A), below the floor and far below the withdrawn 500×.
    #[test]
    fn the_opensees_rows_are_guards_under_their_floors() {
        for (target, floor) in OPENSEES_FLOORS {
            let g = opensees_guard(target).unwrap();
            assert!(
                g < floor && g >= 0.79 * floor,
                "{target}: {g} against {floor}"
            );
            assert!(g < OPENSEES_WITHDRAWN);
        }
        assert_eq!(opensees_guard(1e-3), Some(250.0));
        assert_eq!(opensees_guard(1e-4), Some(262.0));
        assert_eq!(opensees_guard(1e-2), None);
    }
}
