//! `slipload optimize`: sweep, refine from the best sweep points, verify the finalists
//! at reference accuracy, write the design table ([`slipload_opt::pipeline::optimize_study`]),
//! then draw the figures and print the summary. With no study it runs the embedded
//! benchmark study (`configs/study-benchmark.json`) on the embedded synthetic suite.

use super::study_args::{PhaseBars, load_study};
use super::study_text::{kn, loads_text, on_bound_text, runs_text};
use slipload_figures::StudyFigures;
use slipload_opt::Study;
use slipload_opt::base::collapse::{objective_text, reduction, reduction_text};
use slipload_opt::model::config::RefineMethod;
use slipload_opt::phases::figures::MapRequest;
use slipload_opt::phases::refinement::RefineTarget;
use slipload_opt::pipeline::{OptimizeOptions, StudyReport, optimize_study};
use slipload_opt::store::folder::{FolderRequest, StudyFolder};
use std::path::PathBuf;

/// Arguments of `slipload optimize`.
#[derive(Debug, clap::Args)]
pub struct OptimizeArgs {
    /// Study file (default: the embedded benchmark study)
    pub study: Option<PathBuf>,
    /// Output folder (the sweep's files, refine.csv, optimum.json, design-table.*); a
    /// finished sweep in it is reused, journalled refinement points are replayed
    #[arg(long, default_value = "out/optimize")]
    pub out: PathBuf,
    /// Refiner: auto, model, sqp, trust-region, nelder-mead or random (default: the study's)
    #[arg(long)]
    pub refine: Option<RefineMethod>,
    /// Also draw the objective map over two floors' slip loads (the others at the
    /// optimum): GRID × GRID designs × every record, at the sweep fidelity
    #[arg(long)]
    pub map: bool,
    /// The two floors (from 1) of the objective map
    #[arg(long, value_delimiter = ',', default_value = "1,2")]
    pub map_floors: Vec<usize>,
    /// Grid points per axis of the objective map
    #[arg(long, default_value_t = 11)]
    pub map_grid: usize,
    /// Remove every file a slipload command wrote in the output folder (journals — sweep,
    /// refine, check, pareto —, tables, figures, rankings, report; any other file is kept and
    /// named) and start afresh; without it the journals of the same study (by
    /// fingerprint) are continued and those of another study refused
    #[arg(long)]
    pub fresh: bool,
    #[command(flatten)]
    pub threads: crate::args::ThreadsArg,
}

/// What the optimum costs, from the design table: the mean (over the records) peak base
/// shear and floor acceleration of the optimum beside the building file's slip loads and
/// the bare frame's, rounded as the design table rounds them. `None` without an optimum
/// row.
pub fn costs_line(report: &StudyReport) -> Option<String> {
    let row = |name: &str| report.table.rows.iter().find(|r| r.design == name);
    let opt = row("optimum")?;
    let others: Vec<(&str, &slipload_opt::phases::table::TableRow)> = [
        ("building file's slip loads", "file"),
        ("bare frame", "bare"),
    ]
    .into_iter()
    .filter_map(|(label, name)| row(name).map(|r| (label, r)))
    .collect();
    let beside = |f: &dyn Fn(&slipload_opt::phases::table::TableRow) -> String| {
        if others.is_empty() {
            String::new()
        } else {
            format!(
                " ({})",
                others
                    .iter()
                    .map(|(label, r)| format!("{label} {}", f(r)))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
    };
    let shear =
        |r: &slipload_opt::phases::table::TableRow| format!("{:.2} MN", r.base_shear_mean / 1e6);
    let accel = |r: &slipload_opt::phases::table::TableRow| {
        format!("{:.2} m/s²", r.peak_floor_acceleration_mean)
    };
    Some(format!(
        "what the optimum costs (means over the records of each run's peak, {}): base shear {}{}, floor acceleration {}{}",
        report.table.fidelity,
        shear(opt),
        beside(&shear),
        accel(opt),
        beside(&accel)
    ))
}

/// Runs `slipload optimize`.
pub fn run(args: OptimizeArgs) -> anyhow::Result<()> {
    let started = std::time::Instant::now();
    StudyFolder::check_path("--out", &args.out)?;
    if args.map {
        // GRID² designs × every record: the sweep's own design limit, per axis
        super::count_flag("--map-grid", args.map_grid, 1000)?;
    }
    if let Some(path) = args.study.as_deref()
        && slipload_opt::plan::is_plan_study(path)
    {
        return run_in_plan(&args, path);
    }
    let study = load_study(args.study.as_deref())?;
    let map_floors = match args.map_floors.as_slice() {
        &[a, b] => [a, b],
        other => anyhow::bail!(
            "--map-floors takes two floors, like 1,2 (got {} floor(s): {})",
            other.len(),
            other
                .iter()
                .map(|f| f.to_string())
                .collect::<Vec<_>>()
                .join(",")
        ),
    };
    let options = OptimizeOptions {
        refine: args.refine,
        map: args.map.then_some(MapRequest {
            floors: map_floors,
            grid: args.map_grid,
        }),
    };
    let folder = FolderRequest {
        path: &args.out,
        option: "--out",
        fresh: args.fresh,
    };
    let run = optimize_study(
        &study,
        &options,
        folder,
        &PhaseBars::default(),
        &StudyFigures,
    )?;
    print_summary(&study, &run.report, started.elapsed().as_secs_f64());
    outln!("wrote {}/{{{}}}", args.out.display(), run.files.join(","));
    outln!(
        "figures (SVG, PNG, CSV): {}/{{{}}}",
        args.out.display(),
        run.drawn.join(",")
    );
    if let Some(c) = &run.report.code_check {
        outln!("{}", super::check_summary::verdict(c));
    }
    super::check_summary::outcome(run.report.code_check.as_ref())
}

/// `slipload optimize` on a study in plan ([`slipload_opt::pipeline::optimize_in_plan`]):
/// the summary, then the files and figures written.
fn run_in_plan(args: &OptimizeArgs, path: &std::path::Path) -> anyhow::Result<()> {
    if args.map {
        anyhow::bail!(
            "--map: a study in plan draws no objective map (its figures are the plan view and the drift profiles by line)"
        );
    }
    if let Some(r) = args.refine
        && r != RefineMethod::Model
        && r != RefineMethod::Auto
    {
        anyhow::bail!(
            "--refine {}: a study in plan refines with `model` (its runs compute no sensitivities for sqp)",
            r.as_str()
        );
    }
    let study = slipload_opt::plan::PlanStudy::load(path)?;
    let folder = FolderRequest {
        path: &args.out,
        option: "--out",
        fresh: args.fresh,
    };
    let run = slipload_opt::pipeline::optimize_in_plan(
        &study,
        folder,
        &PhaseBars::default(),
        &StudyFigures,
    )?;
    out!("{}", run.summary);
    if run.report.replayed > 0 {
        outln!(
            "({} of the designs taken from the journal of an earlier run in {})",
            run.report.replayed,
            args.out.display()
        );
    }
    let mut files: Vec<&str> = vec![slipload_opt::pipeline::PLAN_JOURNAL];
    files.extend(run.files.iter().copied());
    outln!("wrote {}/{{{}}}", args.out.display(), files.join(","));
    outln!(
        "figures (SVG, PNG, CSV): {}/{{{}}}",
        args.out.display(),
        run.drawn.join(",")
    );
    Ok(())
}

/// Why the refiners stopped and, for the `model` and `sqp` refiners, whether the optimum is
/// stationary (its post-check of single-floor and profile moves).
fn refine_outcome(r: &slipload_opt::phases::refinement::OptimizeReport) -> String {
    let stops: Vec<&str> = r.stops.iter().map(|s| s.as_str()).collect();
    let mut text = format!(
        "refine stopped on: {}",
        if stops.is_empty() {
            "nothing to refine".to_string()
        } else {
            stops.join(", ")
        }
    );
    if let Some(s) = &r.stationarity {
        text.push_str("; ");
        text.push_str(&post_check_text(s, r.target == RefineTarget::Violation));
    }
    text
}

/// The post-check in words: its moves, and whether the optimum is stationary — the best
/// move and what it gains. While no design passes (`violation`) the objective is the sum
/// of the limits' exceedances, and a move that takes it to zero is said to make the
/// design pass, not to lower it by 100 %.
fn post_check_text(s: &slipload_opt::phases::refine::Stationarity, violation: bool) -> String {
    let pct = |v: f64| 100.0 * v;
    let first_order = s.polls == 0;
    // the move's objective is (1 − gain) × the optimum's: zero (or, linearised, below)
    let to_zero = s.best_gain >= 1.0;
    let verdict = if s.stationary {
        format!(
            "stationary (the best, {}, changes the objective by {:+.3} %; threshold {:.1} %)",
            s.best_move,
            -pct(s.best_gain),
            pct(slipload_opt::phases::refine::STATIONARY_GAIN)
        )
    } else if to_zero {
        let what = if violation {
            "brings the sum of exceedances to zero: the design passes"
        } else {
            "brings the objective to zero"
        };
        if first_order {
            format!("not stationary: to first order {} {what}", s.best_move)
        } else {
            format!(
                "not stationary: {} {what} (at the sweep's fidelity), and is taken",
                s.best_move
            )
        }
    } else if first_order {
        format!(
            "not stationary: {} lowers the objective by {:.3} % to first order",
            s.best_move,
            pct(s.best_gain)
        )
    } else {
        format!(
            "not stationary: {} lowers the objective by {:.3} % and is taken",
            s.best_move,
            pct(s.best_gain)
        )
    };
    let screened = s.screened > 0 && !first_order;
    format!(
        "{}post-check of {} single-floor and profile moves of ±{:.1} % of the range{}{}: {verdict}",
        if first_order {
            "first-order (from the derivatives, no simulation) "
        } else {
            ""
        },
        if screened { s.screened } else { s.moves },
        pct(s.step),
        if screened {
            format!(
                " (screened by the derivatives; the {} they flag simulated)",
                s.moves
            )
        } else {
            String::new()
        },
        if s.polls > 1 {
            format!(" (poll {}: each earlier one's best move taken)", s.polls)
        } else {
            String::new()
        },
    )
}

/// The summary: what ran and what was reused, the optimum against the bare frame and the
/// building file's slip loads, the finalists at reference accuracy.
fn print_summary(study: &Study, report: &StudyReport, seconds: f64) {
    let r = &report.refine;
    let w = &report.work;
    let method = report.method.as_str();
    let floors: Vec<String> = report.damper_floors.iter().map(usize::to_string).collect();
    outln!(
        "{}: {} over {}",
        report.study,
        report.objective,
        runs_text(&report.sweep.manifest)
    );
    outln!(
        "sweep and refinement run {} ({})",
        report.sweep.manifest.method.as_str(),
        report.sweep.manifest.method_reason
    );
    // where the study's check method could not run within its bounds, what ran instead
    if study.check_method.method != study.config.fidelity.check_method {
        outln!(
            "the check runs {} ({})",
            study.check_method.method.as_str(),
            study.check_method.reason
        );
    }
    // on stderr with the progress: the summary on stdout stays what results/ commits
    eprintln!("memory: {}", study.memory.text());
    // What ran now, and what was taken from the journals of an earlier run.
    outln!(
        "sweep: {} designs × {}, {} simulations run ({} reused from journal.jsonl); refine ({}): {} designs, {} run ({} replayed from refine-{}.jsonl)",
        report.sweep.manifest.designs.len(),
        runs_text(&report.sweep.manifest),
        w.sweep.run,
        w.sweep.reused,
        method,
        r.log.len(),
        r.log.len() - r.replayed,
        r.replayed,
        method
    );
    outln!("{}", refine_outcome(r));
    outln!(
        "{} simulations run in {:.1} s: sweep {}, refine {}, check {}, design table {}{}{}",
        w.run(),
        seconds,
        w.sweep.run,
        w.refine.run,
        w.check.run,
        w.table.run,
        format!(
            "{}{}",
            w.map
                .map_or(String::new(), |m| format!(", objective map {}", m.run)),
            w.pareto.map_or(String::new(), |[s, c, t]| format!(
                ", front search {}, front check {}, front table {} ({} reused from pareto.jsonl and check.jsonl)",
                s.run,
                c.run,
                t.run,
                s.reused + c.reused + t.reused
            ))
        ),
        {
            let map_reused = w.map.map_or(0, |m| m.reused);
            match (w.check.reused + w.table.reused > 0, map_reused > 0) {
                (false, false) => String::new(),
                (true, false) => format!(
                    " ({} check and {} design-table runs reused from check.jsonl)",
                    w.check.reused, w.table.reused
                ),
                (_, true) => format!(
                    " ({} check, {} design-table and {map_reused} objective-map runs reused from check.jsonl)",
                    w.check.reused, w.table.reused
                ),
            }
        }
    );
    if r.optimum_loads.len() <= 12 {
        outln!(
            "optimal slip loads, floors {} (kN): {}",
            floors.join(" / "),
            kn(&r.optimum_loads)
        );
    } else {
        outln!(
            "optimal slip loads: {}",
            loads_text(study, &r.optimum_loads)
        );
    }
    if !report.on_bound.is_empty() {
        outln!(
            "on a bound of the design space (the optimum may lie beyond it: widen the bound to see): {}",
            on_bound_text(study, &r.optimum_loads, &report.on_bound)
        );
    }
    // a collapse is said in words, never as a number or a "100 % lower"; a cost (kN,
    // prices) to a tenth
    let digits = if study.objective.cost.is_some() { 1 } else { 6 };
    let obj = |f: f64| objective_text(f, Some(digits));
    // with property bounds every objective value says the case it was read at (a cost
    // is the same in every case)
    let case = match study.checks.objective_case() {
        Some(c) if study.objective.cost.is_none() => format!(" {c}"),
        _ => String::new(),
    };
    // "collapsed", or the value and how much lower the optimum is
    let against = |g: f64| {
        if g.is_finite() {
            format!(
                "{} ({} lower)",
                obj(g),
                reduction_text(reduction(r.optimum.f, g), Some(1))
            )
        } else {
            obj(g)
        }
    };
    let file_design = match study.file_friction() {
        Some(laws) => format!(
            "building file's design (friction law {} kN)",
            laws.iter()
                .map(|l| l.text(1e3))
                .collect::<Vec<_>>()
                .join(" / ")
        ),
        None => format!(
            "building file's slip loads {}",
            loads_text(study, &study.file_slip_loads())
        ),
    };
    if r.target == RefineTarget::Violation {
        outln!(
            "no design of the sweep meets the study's limits: the refiners looked for the closest (the smallest sum of exceedances)"
        );
    } else if study.objective.cost.is_some() {
        // the least dampers that meet the limits: the bare frame is the design without
        // any, which either meets them (no damper needed) or is why dampers are needed
        outln!(
            "objective: {} {} — the bare frame {}; {file_design}: {}",
            study.objective.label(),
            obj(r.optimum.f),
            match r.bare_passes {
                Some(true) => "meets every limit already: no damper is needed",
                _ => "misses the limits",
            },
            against(r.file_objective)
        );
    } else {
        outln!(
            "objective{case} {} — bare frame {}, {file_design}: {}",
            obj(r.optimum.f),
            against(r.bare_objective),
            against(r.file_objective)
        );
        // with limits: whether a study was needed to meet them at all
        if let (Some(bare), Some(file)) = (r.bare_passes, r.file_passes) {
            let says = |passes: bool| {
                if passes {
                    "meets every limit"
                } else {
                    "misses a limit"
                }
            };
            outln!(
                "limits: the bare frame {}, the building file's design {}{}",
                says(bare),
                says(file),
                if bare {
                    " (dampers here only lower the objective; `\"objective\": {\"cost\": …}` finds the least that keep the limits)"
                } else {
                    ""
                }
            );
        }
    }
    if let Some(line) = costs_line(report) {
        outln!("{line}");
    }
    if r.check_reran {
        // the method that ran (not the reference where the study's could not run)
        outln!(
            "{}: finalists' ranking {}",
            slipload_opt::eval::probe::check_label(study),
            if r.ranking_held { "held" } else { "changed" }
        );
    } else {
        outln!(
            "check: the sweep ran the reference (exact), so there is nothing to correct; the finalists were not run again"
        );
    }
    for f in &r.finalists {
        outln!(
            "  {}: objective{case} {} ({} {}){}",
            loads_text(study, &f.slip_loads_n),
            obj(f.f_check),
            if r.target == RefineTarget::Violation {
                "sum of exceedances at the sweep's fidelity"
            } else {
                "sweep"
            },
            obj(f.f_sweep),
            f.check.as_ref().map_or(String::new(), |c| format!(
                ", {}",
                if c.passes() {
                    format!("meets every limit (margin {:.1} %)", 100.0 * c.margin())
                } else {
                    format!("misses the limits by {:.1} %", -100.0 * c.margin())
                }
            ))
        );
    }
    if let Some(c) = &report.code_check {
        for line in super::check_summary::lines(c) {
            outln!("{line}");
        }
    }
    if let Some(d) = &report.devices {
        for line in super::check_summary::device_lines(d) {
            outln!("{line}");
        }
    }
    match &report.pareto {
        Some(p) => {
            for line in super::pareto_summary::front_lines(study, report, p) {
                outln!("{line}");
            }
        }
        None => {
            if let Some(line) = super::pareto_summary::sweep_trade_off(study, report) {
                outln!("{line}");
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::post_check_text;
    use slipload_opt::phases::refine::Stationarity;

    fn poll(best_gain: f64, polls: usize) -> Stationarity {
        Stationarity {
            step: 0.01,
            moves: 22,
            best_gain,
            best_move: "floor7 -".into(),
            stationary: best_gain <= slipload_opt::phases::refine::STATIONARY_GAIN,
            polls,
            screened: 0,
        }
    }

    /// A move that takes the sum of exceedances (the objective while no design passes)
    /// to zero is said to make the design pass, never to lower the objective by 100 %.
    #[test]
    fn a_move_to_zero_exceedance_is_said_to_pass() {
        for polls in [0, 1] {
            let text = post_check_text(&poll(1.0, polls), true);
            assert!(
                text.contains("floor7 - brings the sum of exceedances to zero: the design passes"),
                "{text}"
            );
            assert!(!text.contains("100.000 %"), "{text}");
        }
        let text = post_check_text(&poll(1.0, 1), false);
        assert!(
            text.contains(
                "floor7 - brings the objective to zero (at the sweep's fidelity), and is taken"
            ),
            "{text}"
        );
        // a gain short of the whole objective is stated as the gain it is
        let text = post_check_text(&poll(0.01336, 1), true);
        assert!(
            text.ends_with("not stationary: floor7 - lowers the objective by 1.336 % and is taken"),
            "{text}"
        );
        let text = post_check_text(&poll(-0.0002, 1), false);
        assert!(
            text.contains(": stationary (the best, floor7 -, changes the objective by +0.020 %"),
            "{text}"
        );
    }
}
