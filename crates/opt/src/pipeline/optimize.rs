//! [`optimize_study`] (`slipload optimize`): sweep, refine, check the finalists, build
//! the design table and the candidates (and the objective map when asked), each phase
//! journalled and resumed under the study's fingerprint; then the files and the figures.

use super::figures::FigureWriter;
use super::report::{PhaseWork, StudyReport, Work};
use crate::base::error::OptError;
use crate::base::shard::Shard;
use crate::eval::evaluate::TaskJournal;
use crate::eval::progress::{Phase, Progress, phase};
use crate::model::config::RefineMethod;
use crate::model::study::Study;
use crate::phases::figures::{FigureData, MapRequest, convergence, objective_map};
use crate::phases::pareto::Search;
use crate::phases::rank::NamedDesign;
use crate::phases::refinement::{FromFront, OptimizeReport, Scored, check_finalists, refine_sweep};
use crate::phases::sweep::{self, Manifest};
use crate::phases::table::{DesignTable, standard_designs};
use crate::store::folder::{Discarded, FolderRequest, StudyFolder};

/// What [`optimize_study`] runs besides the study's own phases.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct OptimizeOptions {
    /// The refiner (default: the study's).
    pub refine: Option<RefineMethod>,
    /// The objective map, when asked for.
    pub map: Option<MapRequest>,
}

impl OptimizeOptions {
    /// Checks the options against `study` before anything runs or is written: the map's
    /// floors and size ([`MapRequest::dampers`]).
    pub fn check(&self, study: &Study) -> Result<(), OptError> {
        if let Some(m) = &self.map {
            m.dampers(study)?;
        }
        Ok(())
    }
}

/// What an `optimize` run did: its report, the figures drawn, what `fresh` removed.
#[derive(Debug, Clone)]
pub struct OptimizeRun {
    /// Everything the run found.
    pub report: StudyReport,
    /// The figures drawn (their names).
    pub drawn: Vec<String>,
    /// The files written besides the figures, in the order a summary names them.
    pub files: Vec<&'static str>,
    /// What `fresh` removed and kept, when it was asked for.
    pub discarded: Option<Discarded>,
}

/// `slipload optimize`: optimises `study` into the folder of `request`. Checks the
/// figures can be drawn and the options, opens the folder (its lock; `fresh`), refuses it
/// if a journal of another study is there, writes the building the study runs
/// (`building.json`, `building.md`: [`crate::phases::building`]), then runs the phases of
/// [`crate::eval::progress::Phase`] — sweep, the front's search (a study with
/// `objectives`: before the refinement, whose starts and finalist candidates its designs
/// join), refine, check, design table, objective map (when asked), the front's check and
/// table (the file's and the refinement's designs its candidates too) — each
/// reporting to `progress`, writes `refine.csv`, `optimum.json`,
/// `design-table.{csv,md,json}` and `candidates.json` ([`StudyReport::write_files`])
/// beside the sweep's files, draws the figures with `figures`, and returns the run.
///
/// Every phase that simulates is resumable: the sweep continues `journal.jsonl`, the
/// refinement replays `refine-METHOD.jsonl`, the check and the design table take their
/// runs from `check.jsonl`; a second run over the same folder reruns nothing and writes
/// the same bytes. The objective map's runs are journalled in `check.jsonl` too (at the
/// sweep's fidelity, which their key carries).
pub fn optimize_study(
    study: &Study,
    options: &OptimizeOptions,
    request: FolderRequest<'_>,
    progress: &dyn Progress,
    figures: &dyn FigureWriter,
) -> Result<OptimizeRun, OptError> {
    StudyFolder::check_path(request.option, request.path)?;
    // the figures are drawn at the end: a missing font is refused before the run
    figures.check()?;
    // a bad map fails before `fresh` discards anything
    options.check(study)?;
    let (folder, discarded) = StudyFolder::open(request)?;
    if let Some(d) = &discarded {
        progress.discarded(folder.dir(), d);
    }
    let report = run_phases(study, &folder, options, progress)?;
    folder.claim_figures(&report.figures.suite_stems())?;
    let mut drawn = figures.study(&report.figures, folder.dir())?;
    if let Some(p) = &report.pareto {
        drawn.extend(figures.front(p, folder.dir())?);
    }
    let mut files: Vec<&'static str> = crate::phases::building::BuildingPage::FILES.to_vec();
    files.extend(StudyReport::FILES);
    if report.pareto.is_some() {
        files.extend(crate::phases::pareto::ParetoReport::FILES);
    }
    if report.code_check.is_some() {
        files.extend(crate::phases::check::CodeCheck::FILES);
    }
    if report.devices.is_some() {
        files.extend(crate::phases::devices::DeviceTable::FILES);
    }
    Ok(OptimizeRun {
        report,
        drawn,
        files,
        discarded,
    })
}

/// The phases of [`optimize_study`] in the opened `folder`, and the report's files.
fn run_phases(
    study: &Study,
    folder: &StudyFolder,
    options: &OptimizeOptions,
    progress: &dyn Progress,
) -> Result<StudyReport, OptError> {
    let out = folder.dir();
    let method = options.refine.unwrap_or(study.config.refine.method);
    let method = study.check_refiner(method)?;
    // every journal of the folder must be this study's: never mix another study's numbers
    let manifest = Manifest::of(study);
    folder
        .check_journals(&manifest.fingerprint)
        .map_err(|e| e.context(format!("optimizing {} into {}", study.name, out.display())))?;
    // the building the study runs, first: a folder of a run cut short states it too
    crate::phases::building::BuildingPage::of(study)?.write_files(folder)?;
    // every design runs each record at each property case; the design table and the
    // objective map read the nominal properties
    let nr = study.runs();
    let nominal = study.nominal();
    let records = study.records.len();

    let sweep = phase(progress, Phase::Sweep, manifest.tasks(), |tick| {
        sweep::run(study, folder, Shard::ALL, true, tick)
            .map_err(|e| e.context(format!("sweeping {} into {}", study.name, out.display())))
    })?;
    let rows = sweep
        .rows
        .as_deref()
        .ok_or_else(|| OptError::Missing("the sweep is incomplete".into()))?;

    // the check fidelity's runs (finalists, design table) are journalled together
    let check_journal = TaskJournal::open(
        study,
        &folder.journal("check.jsonl")?,
        &manifest.fingerprint,
    )?;
    // a study with a front searches it before refining: the refiners start from, and
    // pick their optimum among, the search's designs too
    let front_search = if study.objectives.is_empty() {
        None
    } else {
        Some(search_front(
            study,
            folder,
            &sweep.manifest,
            rows,
            progress,
        )?)
    };
    let front_designs: Vec<Scored> = front_search.as_ref().map_or(Vec::new(), |(s, _)| {
        s.evaluated
            .iter()
            .filter_map(|e| e.scalar.as_ref().map(|(f, c)| (e.z.clone(), *f, c.clone())))
            .collect()
    });
    let rc = study.config.refine;
    let refinement = phase(
        progress,
        Phase::Refine,
        rc.starts * rc.max_evaluations * nr,
        |tick| {
            let journal = folder.journal(&format!("refine-{}.jsonl", method.as_str()))?;
            refine_sweep(
                study,
                &sweep.manifest,
                rows,
                method,
                Some(&journal),
                FromFront {
                    designs: &front_designs,
                    journal: front_search.as_ref().map(|(_, j)| j),
                },
                tick,
            )
            .map_err(|e| e.context("refining"))
        },
    )?;

    let refined = phase(progress, Phase::Check, (rc.finalists + 1) * nr, |tick| {
        check_finalists(study, refinement, Some(&check_journal), tick)
            .map_err(|e| e.context("refining"))
    })?;
    let check_reused = check_journal.reused();

    let designs = standard_designs(study, &refined.optimum_loads);
    let (table, table_runs) = phase(
        progress,
        Phase::DesignTable,
        (designs.len() * 3 + 1) * records,
        |tick| {
            DesignTable::build_journalled(&nominal, &designs, Some(&check_journal), tick)
                .map_err(|e| e.context("design table"))
        },
    )?;
    let table_reused = check_journal.reused() - check_reused;

    let before_map = check_journal.reused();
    let map = match &options.map {
        Some(request) => Some(phase(
            progress,
            Phase::ObjectiveMap,
            request.grid * request.grid * records,
            |tick| {
                objective_map(
                    &nominal,
                    &refined.optimum_loads,
                    &rows[..records],
                    request,
                    Some(&check_journal),
                    tick,
                )
            },
        )?),
        None => None,
    };
    let map_reused = check_journal.reused() - before_map;

    let pareto = match front_search {
        None => None,
        Some((search, journal)) => Some(finish_front(
            study,
            &sweep.manifest,
            rows,
            search,
            &refined,
            &journal,
            &check_journal,
            progress,
        )?),
    };

    let refine_run = (refined.log.len() - refined.replayed) * nr;
    // the bare frame and the finalists, unless the sweep ran the reference itself
    let check_total = if refined.check_reran {
        (refined.finalists.len() + 1) * nr
    } else {
        0
    };
    let table_total: usize = table_runs.iter().map(Vec::len).sum();
    let work = Work {
        sweep: PhaseWork {
            run: sweep.ran,
            reused: sweep.resumed,
        },
        refine: PhaseWork {
            run: refine_run,
            reused: refined.replayed * nr,
        },
        check: PhaseWork {
            run: check_total - check_reused,
            reused: check_reused,
        },
        table: PhaseWork {
            run: table_total - table_reused,
            reused: table_reused,
        },
        map: map.as_ref().map(|m| PhaseWork {
            run: m.objective.len() * records - map_reused,
            reused: map_reused,
        }),
        pareto: pareto.as_ref().map(|(_, w)| *w),
    };
    let mut code_check = crate::phases::check::CodeCheck::of(study, &refined)?;
    // where the bounds are built from their parts, the widest specification band the
    // recommended design still passes at
    if let (Some(c), Some(first)) = (code_check.as_mut(), refined.finalists.first())
        && c.passes
        && crate::phases::tolerance::derivation(study).is_some()
    {
        c.tolerance = phase(progress, Phase::Check, 8 * nr, |tick| {
            crate::phases::tolerance::widest(study, &first.slip_loads_n, tick)
                .map_err(|e| e.context("the specification tolerance"))
        })?;
    }
    let devices = match (
        &code_check,
        &refined.recommended_runs,
        refined.finalists.first(),
    ) {
        (Some(c), Some((runs, _)), Some(first)) => Some(crate::phases::devices::DeviceTable::of(
            study,
            &first.slip_loads_n,
            runs,
            c.fidelity.clone(),
        )?),
        _ => None,
    };
    let figures = FigureData::of_design_table(
        study,
        &designs,
        &table,
        &table_runs,
        convergence(out, sweep.manifest.tasks(), nr, refined.best_sweep.f)?,
        map,
    )
    .with_spectra(&study.suites);
    let report = StudyReport {
        study: study.name.clone(),
        objective: study.objective.label(),
        damper_floors: study.space.dampers.iter().map(|f| f + 1).collect(),
        method,
        refine_loads_n: refined
            .log
            .iter()
            .map(|p| study.space.slip_loads(&p.z))
            .collect(),
        // a variable on a bound of the space: the optimum may lie beyond it
        on_bound: study.space.on_bounds(&refined.optimum.z),
        candidates: designs
            .iter()
            .map(|(name, loads)| NamedDesign {
                name: name.clone(),
                slip_loads_kn: loads.slip_loads_n.iter().map(|v| v / 1e3).collect(),
                friction_kn: loads
                    .friction_n
                    .as_ref()
                    .map(|l| l.iter().map(|x| x.scaled(1e-3)).collect()),
            })
            .collect(),
        designs,
        table,
        table_runs,
        figures,
        work,
        refine: refined,
        sweep,
        pareto: pareto.map(|(p, _)| p),
        code_check,
        devices,
    };
    report.write_files(folder)?;
    Ok(report)
}

/// The front's search ([`Phase::Pareto`]) from the sweep, journalled in `pareto.jsonl`
/// (the journal is returned for the front's other runs).
fn search_front(
    study: &Study,
    folder: &StudyFolder,
    manifest: &Manifest,
    rows: &[crate::base::metrics::RecordMetrics],
    progress: &dyn Progress,
) -> Result<(Search, TaskJournal), OptError> {
    let cfg = study.config.pareto.unwrap_or_default();
    let journal = TaskJournal::open_kind(
        study,
        &folder.journal("pareto.jsonl")?,
        "pareto",
        &manifest.fingerprint,
    )?;
    let search = phase(
        progress,
        Phase::Pareto,
        cfg.designs * study.runs(),
        |tick| {
            crate::phases::pareto::search(study, manifest, rows, Some(&journal), tick)
                .map_err(|e| e.context("searching the front"))
        },
    )?;
    Ok((search, journal))
}

/// The rest of the front's phases, after the refinement: the file's and the
/// refinement's designs join the search's as candidates (the runs of replayed refinement
/// evaluations from `journal`, `pareto.jsonl`), the front at the check fidelity
/// ([`Phase::ParetoCheck`]) and the design table of a few front designs
/// ([`Phase::ParetoTable`], both `check.jsonl`), and the simulations of each.
#[allow(clippy::too_many_arguments)]
fn finish_front(
    study: &Study,
    manifest: &Manifest,
    rows: &[crate::base::metrics::RecordMetrics],
    mut search: Search,
    refined: &OptimizeReport,
    journal: &TaskJournal,
    check_journal: &TaskJournal,
    progress: &dyn Progress,
) -> Result<(crate::phases::pareto::ParetoReport, [PhaseWork; 3]), OptError> {
    use crate::phases::pareto::candidates::{RefinedDesign, add_candidates, missing_runs};
    use crate::phases::pareto::report::{build, knee_and_extremes, table_designs};
    let nr = study.runs();
    let offered: Vec<RefinedDesign<'_>> = refined
        .log
        .iter()
        .map(|p| (p.z.as_slice(), refined.refined_runs.get(&p.z)))
        .collect();
    // replayed refinement evaluations have no runs in memory: the only runs here
    let missing = missing_runs(study, &search, &offered);
    let mut add = |tick: &(dyn Fn() + Sync)| {
        add_candidates(
            study,
            manifest,
            rows,
            &mut search,
            &offered,
            Some(journal),
            tick,
        )
    };
    let (ran, reused) = if missing > 0 {
        phase(progress, Phase::Pareto, missing, |tick| add(tick))?
    } else {
        add(&|| {})?
    };
    search.ran += ran;
    search.reused += reused;
    let front_size = crate::phases::pareto::first_front(
        &search
            .evaluated
            .iter()
            .map(|e| e.objectives.clone())
            .collect::<Vec<_>>(),
    )
    .len();
    let certified = phase(
        progress,
        Phase::ParetoCheck,
        (front_size + 1) * nr,
        |tick| {
            crate::phases::pareto::certify(study, &search, Some(check_journal), tick)
                .map_err(|e| e.context("checking the front"))
        },
    )?;
    let (knee, extremes) = knee_and_extremes(&search, &certified);
    let designs = table_designs(study, &search, &certified, knee, &extremes);
    let before = check_journal.reused();
    let table = phase(
        progress,
        Phase::ParetoTable,
        (designs.len() * 3 + 1) * study.records.len(),
        |tick| {
            DesignTable::build_journalled(&study.nominal(), &designs, Some(check_journal), tick)
                .map_err(|e| e.context("the front's design table"))
        },
    )?;
    let table_reused = check_journal.reused() - before;
    let table_total: usize = table.1.iter().map(Vec::len).sum();
    let work = [
        PhaseWork {
            run: search.ran,
            reused: search.reused,
        },
        PhaseWork {
            run: certified.ran,
            reused: certified.reused,
        },
        PhaseWork {
            run: table_total - table_reused,
            reused: table_reused,
        },
    ];
    Ok((build(study, search, certified, table, designs), work))
}
