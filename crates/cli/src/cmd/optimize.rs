//! `slipload optimize`: sweep, refine from the best sweep points, verify the finalists at
//! reference accuracy, write the design table. With no study it runs the embedded
//! benchmark study (`configs/study-benchmark.json`) on the embedded synthetic suite.

use super::study_args::{discard_journals, load_study, progress};
use crate::study_figures::{
    RecordScatter, StudyFigures, convergence, drift_profiles, map_dampers, objective_map,
};
use anyhow::Context;
use slipload_opt::evaluate::TaskJournal;
use slipload_opt::optimize::{OptimizeReport, optimize};
use slipload_opt::output::write_atomic;
use slipload_opt::study::RefineMethod;
use slipload_opt::table::{DesignTable, standard_designs};
use slipload_opt::{OnBound, Shard, Study, sweep};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Arguments of `slipload optimize`.
#[derive(Debug, clap::Args)]
pub struct OptimizeArgs {
    /// Study file (default: the embedded benchmark study)
    pub study: Option<PathBuf>,
    /// Output folder (the sweep's files, refine.csv, optimum.json, design-table.*); a
    /// finished sweep in it is reused, journalled refinement points are replayed
    #[arg(long, default_value = "out/optimize")]
    pub out: PathBuf,
    /// Refiner: trust-region, nelder-mead or random (default: the study's)
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
    /// Discard the output folder's journals (sweep, refine, check) and start afresh;
    /// without it the journals of the same study (by fingerprint) are continued and those
    /// of another study refused
    #[arg(long)]
    pub fresh: bool,
}

fn kn(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{:.1}", x / 1e3))
        .collect::<Vec<_>>()
        .join(" / ")
}

/// The design variables of the optimum that sit on a bound of the study's space, said
/// with the floors they set and their slip loads ("floor 1 at its upper bound, 2000.0 kN").
fn on_bound_text(study: &Study, loads: &[f64], on: &[OnBound]) -> String {
    let load_of = |floor: usize| {
        study
            .space
            .dampers
            .iter()
            .position(|&f| f + 1 == floor)
            .map_or(f64::NAN, |k| loads[k] / 1e3)
    };
    on.iter()
        .map(|b| {
            let floors: Vec<String> = b.floors.iter().map(usize::to_string).collect();
            if study.space.shape.is_some() {
                format!(
                    "the profile's {} (floors {}) at its {} bound, {} kN",
                    b.variable,
                    floors.join(", "),
                    b.bound.as_str(),
                    b.floors
                        .iter()
                        .map(|&f| format!("{:.1}", load_of(f)))
                        .collect::<Vec<_>>()
                        .join(" / ")
                )
            } else {
                format!(
                    "floor {} at its {} bound, {:.1} kN",
                    floors.join(", "),
                    b.bound.as_str(),
                    b.floors.first().map_or(f64::NAN, |&f| load_of(f))
                )
            }
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// `refine.csv`: every refinement evaluation with the best objective so far.
fn refine_csv(study: &Study, r: &OptimizeReport) -> String {
    let mut s = String::from("evaluation,refiner,objective,best_so_far");
    for f in &study.space.dampers {
        let _ = write!(s, ",slip_load_kN_{}", f + 1);
    }
    s.push('\n');
    let mut best = r.best_sweep.f;
    for (i, p) in r.log.iter().enumerate() {
        best = best.min(p.f);
        let _ = write!(s, "{},{},{},{}", i + 1, r.method.as_str(), p.f, best);
        for v in study.space.slip_loads(&p.z) {
            let _ = write!(s, ",{}", v / 1e3);
        }
        s.push('\n');
    }
    s
}

/// Writes the design table files into `out`.
pub fn write_table(out: &Path, table: &DesignTable) -> anyhow::Result<()> {
    write_atomic(&out.join("design-table.csv"), table.to_csv().as_bytes())?;
    write_atomic(&out.join("design-table.md"), table.to_markdown().as_bytes())?;
    write_atomic(&out.join("design-table.json"), table.to_json().as_bytes())?;
    Ok(())
}

/// Runs `slipload optimize`.
pub fn run(args: OptimizeArgs) -> anyhow::Result<()> {
    let started = std::time::Instant::now();
    let study = load_study(args.study.as_deref())?;
    let method = args.refine.unwrap_or(study.config.refine.method);
    let map_floors = match args.map_floors.as_slice() {
        &[a, b] => [a, b],
        other => anyhow::bail!("--map-floors takes two floors, like 1,2 (got {other:?})"),
    };
    if args.map {
        map_dampers(&study, map_floors, args.map_grid)?;
        let designs = (args.map_grid as f64).powi(2);
        if designs > slipload_opt::study::MAX_DESIGNS && !slipload_sim::limits::allow_large() {
            anyhow::bail!(
                "--map-grid {}: {designs:.3e} designs exceed the limit of {:.0e} that no real study needs; {}",
                args.map_grid,
                slipload_opt::study::MAX_DESIGNS,
                slipload_sim::limits::OVERRIDE_HINT
            );
        }
    }
    if args.fresh {
        discard_journals(&args.out)?;
    }
    let manifest = sweep::Manifest::of(&study);
    // every journal of the folder must be this study's: never mix another study's numbers
    slipload_opt::journal::check_folder(&args.out, &manifest.fingerprint)
        .with_context(|| format!("optimizing {} into {}", study.name, args.out.display()))?;
    let pb = progress(manifest.tasks() as u64, "sweep");
    let report = sweep::run(&study, &args.out, Shard::ALL, true, &|| pb.inc(1))
        .with_context(|| format!("sweeping {} into {}", study.name, args.out.display()))?;
    pb.finish_and_clear();
    let rows = report.rows.context("the sweep is incomplete")?;
    let nr = study.records.len();
    let rc = study.config.refine;
    // an estimate: refiners may stop before their budget, the trust region's stencil may pass it by a few
    let est = (rc.starts * rc.max_evaluations + rc.finalists + 1) * nr;
    let pb = progress(est as u64, "refine");
    // the check fidelity's runs (finalists, design table) are journalled too
    let check_journal = TaskJournal::open(
        &study,
        &args.out.join("check.jsonl"),
        &report.manifest.fingerprint,
    )?;
    let r = optimize(
        &study,
        &report.manifest,
        &rows,
        method,
        Some(&args.out.join(format!("refine-{}.jsonl", method.as_str()))),
        Some(&check_journal),
        &|| pb.inc(1),
    )
    .context("refining")?;
    pb.finish_and_clear();
    // runs of the finalist check taken from the check journal, not run
    let check_reused = check_journal.reused();
    let designs = standard_designs(&study, &r.optimum_loads);
    let pb = progress(((designs.len() * 3 + 1) * nr) as u64, "design table");
    let (table, runs) =
        DesignTable::build_journalled(&study, &designs, Some(&check_journal), &|| pb.inc(1))
            .context("design table")?;
    pb.finish_and_clear();
    let table_reused = check_journal.reused() - check_reused;
    let map = if args.map {
        let grid = args.map_grid;
        let pb = progress((grid * grid * nr) as u64, "objective map");
        let floors = [args.map_floors[0], args.map_floors[1]];
        let m = objective_map(&study, &r.optimum_loads, &rows[..nr], floors, grid, &|| {
            pb.inc(1)
        })?;
        pb.finish_and_clear();
        Some(m)
    } else {
        None
    };
    write_atomic(
        &args.out.join("refine.csv"),
        refine_csv(&study, &r).as_bytes(),
    )?;
    // A variable on a bound of the space: the optimum may lie beyond it.
    let on_bound = study.space.on_bounds(&r.optimum.z);
    let optimum = serde_json::json!({
        "study": study.name,
        "objective": study.objective.label(),
        "refiner": method.as_str(),
        "damper_floors": study.space.dampers.iter().map(|f| f + 1).collect::<Vec<_>>(),
        "slip_loads_kN": r.optimum_loads.iter().map(|v| v / 1e3).collect::<Vec<_>>(),
        "on_bound": on_bound,
        "objective_value": r.optimum.f,
        "bare_objective": r.bare_objective,
        "file_objective": r.file_objective,
        "sweep_designs": r.sweep_designs,
        "refine_evaluations": r.log.len(),
        "finalists": r.finalists.iter().map(|f| serde_json::json!({
            "slip_loads_kN": f.slip_loads_n.iter().map(|v| v / 1e3).collect::<Vec<_>>(),
            "objective_sweep": f.f_sweep,
            "objective_check": f.f_check,
        })).collect::<Vec<_>>(),
        "ranking_held": r.ranking_held,
    });
    let mut text = serde_json::to_string_pretty(&optimum)?;
    text.push('\n');
    write_atomic(&args.out.join("optimum.json"), text.as_bytes())?;
    write_table(&args.out, &table)?;
    let candidates: Vec<slipload_opt::rank::NamedDesign> = designs
        .iter()
        .map(|(name, loads)| slipload_opt::rank::NamedDesign {
            name: name.clone(),
            slip_loads_kn: loads.iter().map(|v| v / 1e3).collect(),
        })
        .collect();
    let mut text = serde_json::to_string_pretty(&candidates)?;
    text.push('\n');
    write_atomic(&args.out.join("candidates.json"), text.as_bytes())?;
    let figures = StudyFigures {
        map,
        convergence: convergence(&args.out, report.manifest.tasks(), nr, r.best_sweep.f)?,
        profiles: {
            // the designs ranked by the objective (design-table fidelity)
            let mut order: Vec<usize> = (0..designs.len()).collect();
            order.sort_by(|&a, &b| {
                table.rows[a]
                    .objective
                    .total_cmp(&table.rows[b].objective)
                    .then(a.cmp(&b))
            });
            let names: Vec<String> = order.iter().map(|&k| designs[k].0.clone()).collect();
            let rows: Vec<&[slipload_opt::RecordMetrics]> =
                order.iter().map(|&k| runs[1 + 3 * k].as_slice()).collect();
            drift_profiles(&names, &rows)
        },
        scatter: Some(RecordScatter::new(
            &designs[0].0,
            &study
                .records
                .iter()
                .map(|r| r.name().to_string())
                .collect::<Vec<_>>(),
            &runs[0],
            &runs[1],
        )),
        fidelity: table.fidelity.clone(),
    };
    let written = figures.write(&args.out)?;

    let floors: Vec<String> = study
        .space
        .dampers
        .iter()
        .map(|f| format!("{}", f + 1))
        .collect();
    outln!(
        "{}: {} over {} records",
        study.name,
        study.objective.label(),
        nr
    );
    // What ran now, and what was taken from the journals of an earlier run.
    let refined = (r.log.len() - r.replayed) * nr;
    let checked = r.simulations - refined - check_reused;
    let tabled = runs.iter().map(Vec::len).sum::<usize>() - table_reused;
    let mapped = if args.map {
        args.map_grid * args.map_grid * nr
    } else {
        0
    };
    outln!(
        "sweep: {} designs × {} records, {} simulations run ({} reused from journal.jsonl); refine ({}): {} designs, {} run ({} replayed from refine-{}.jsonl)",
        report.manifest.designs.len(),
        nr,
        report.ran,
        report.resumed,
        method.as_str(),
        r.log.len(),
        r.log.len() - r.replayed,
        r.replayed,
        method.as_str()
    );
    outln!(
        "{} simulations run in {:.1} s: sweep {}, refine {}, check {}, design table {}{}{}",
        report.ran + refined + checked + tabled + mapped,
        started.elapsed().as_secs_f64(),
        report.ran,
        refined,
        checked,
        tabled,
        if args.map {
            format!(", objective map {mapped}")
        } else {
            String::new()
        },
        if check_reused + table_reused > 0 {
            format!(
                " ({} check and {} design-table runs reused from check.jsonl)",
                check_reused, table_reused
            )
        } else {
            String::new()
        }
    );
    outln!(
        "optimal slip loads, floors {} (kN): {}",
        floors.join(" / "),
        kn(&r.optimum_loads)
    );
    if !on_bound.is_empty() {
        outln!(
            "on a bound of the design space (the optimum may lie beyond it: widen the bound to see): {}",
            on_bound_text(&study, &r.optimum_loads, &on_bound)
        );
    }
    let pct = |f: f64, g: f64| 100.0 * (1.0 - f / g);
    outln!(
        "objective {:.6} — bare frame {:.6} ({:.1} % lower), building file's slip loads {} kN: {:.6} ({:.1} % lower)",
        r.optimum.f,
        r.bare_objective,
        pct(r.optimum.f, r.bare_objective),
        kn(&study.file_slip_loads()),
        r.file_objective,
        pct(r.optimum.f, r.file_objective)
    );
    outln!(
        "check at reference accuracy ({} at {} × dt): finalists' ranking {}",
        study.config.fidelity.check_method.as_str(),
        study.config.fidelity.check_dt_factor,
        if r.ranking_held { "held" } else { "changed" }
    );
    for f in &r.finalists {
        outln!(
            "  {} kN: objective {:.6} (sweep {:.6})",
            kn(&f.slip_loads_n),
            f.f_check,
            f.f_sweep
        );
    }
    outln!(
        "wrote {}/{{designs.csv,responses.csv,refine.csv,optimum.json,candidates.json,design-table.csv,design-table.md,design-table.json}}",
        args.out.display()
    );
    outln!(
        "figures (SVG, PNG, CSV): {}/{{{}}}",
        args.out.display(),
        written.join(",")
    );
    Ok(())
}
