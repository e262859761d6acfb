//! What [`super::optimize_study`] found, and the files made from it: `refine.csv`,
//! `optimum.json`, `design-table.{csv,md,json}` and `candidates.json`.

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::model::config::RefineMethod;
use crate::model::space::OnBound;
use crate::phases::figures::FigureData;
use crate::phases::rank::NamedDesign;
use crate::phases::refinement::{OptimizeReport, RefineTarget};
use crate::phases::sweep::SweepReport;
use crate::phases::table::DesignTable;
use crate::store::folder::StudyFolder;
use serde::Serialize;
use std::fmt::Write as _;

/// Simulations of one phase: run now, and taken from its journal.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PhaseWork {
    /// Simulations run in this run.
    pub run: usize,
    /// Simulations taken from the journal of an earlier run.
    pub reused: usize,
}

/// Simulations of every phase of a study run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Work {
    /// The sweep (`journal.jsonl`).
    pub sweep: PhaseWork,
    /// The refinement (`refine-METHOD.jsonl`): one simulation per record and evaluation.
    pub refine: PhaseWork,
    /// The finalists' check (`check.jsonl`).
    pub check: PhaseWork,
    /// The design table (`check.jsonl`).
    pub table: PhaseWork,
    /// The objective map, when asked for (not journalled).
    pub map: Option<PhaseWork>,
    /// A front's search (`pareto.jsonl`), check and design table (`check.jsonl`), when
    /// the study names `objectives`.
    pub pareto: Option<[PhaseWork; 3]>,
}

impl Work {
    /// Simulations run in this run, over every phase.
    pub fn run(&self) -> usize {
        self.sweep.run
            + self.refine.run
            + self.check.run
            + self.table.run
            + self.map.map_or(0, |m| m.run)
            + self.pareto.map_or(0, |p| p.iter().map(|w| w.run).sum())
    }
}

/// Everything a study run found: what the files, the figures and the summary are made of.
#[derive(Debug, Clone)]
pub struct StudyReport {
    /// The study's name.
    pub study: String,
    /// Its objective, as a label.
    pub objective: String,
    /// Floors (from 1) of the dissipators, bottom to top.
    pub damper_floors: Vec<usize>,
    /// The refiner used.
    pub method: RefineMethod,
    /// The sweep: its manifest, what ran and what was reused (its rows are complete).
    pub sweep: SweepReport,
    /// The refinement and the finalists' check.
    pub refine: OptimizeReport,
    /// Slip loads, N per dissipator, of each refinement evaluation (`refine.log`).
    pub refine_loads_n: Vec<Vec<f64>>,
    /// The optimum's variables that sit on a bound of the design space.
    pub on_bound: Vec<OnBound>,
    /// The design table's designs (slip loads, N): the optimum first, then uniform and
    /// storey-shear designs of the same total, the building file's, the bare frame.
    pub designs: Vec<(String, crate::eval::evaluate::DesignLoads)>,
    /// The design table at the check fidelity.
    pub table: DesignTable,
    /// The table's runs: `[0]` the bare frame, then per design its slip loads, × 0.75,
    /// × 1.25 ([`DesignTable::build_with_runs`]).
    pub table_runs: Vec<Vec<RecordMetrics>>,
    /// The candidates for `rank`: the designs, in kN (`candidates.json`).
    pub candidates: Vec<NamedDesign>,
    /// The data of the study figures.
    pub figures: FigureData,
    /// Simulations per phase, run now and reused.
    pub work: Work,
    /// The front, when the study names `objectives` ([`crate::phases::pareto`]).
    pub pareto: Option<crate::phases::pareto::ParetoReport>,
    /// The recommended design's code check, when the study names limits
    /// ([`crate::phases::check`]).
    pub code_check: Option<crate::phases::check::CodeCheck>,
    /// The recommended design's device table, beside its code check
    /// ([`crate::phases::devices`]).
    pub devices: Option<crate::phases::devices::DeviceTable>,
}

/// The check's summary in `optimum.json`.
#[derive(Debug, Clone, Serialize)]
struct CheckEntry {
    passes: bool,
    verdict: String,
    margin: f64,
}

/// A finalist as `optimum.json` lists it.
#[derive(Debug, Clone, Serialize)]
struct FinalistEntry {
    #[serde(rename = "slip_loads_kN")]
    slip_loads_kn: Vec<f64>,
    #[serde(with = "crate::base::collapse::objective_serde")]
    objective_sweep: f64,
    #[serde(with = "crate::base::collapse::objective_serde")]
    objective_check: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    check: Option<CheckEntry>,
}

/// The stationarity post-check in `optimum.json`.
#[derive(Debug, Clone, Serialize)]
struct StationarityEntry<'a> {
    /// The move, scaled variables (relative for the profile move).
    step: f64,
    /// Moves evaluated.
    moves: usize,
    /// The largest relative decrease of the objective among them (≤ 0: none improves).
    best_gain: f64,
    /// The move that gave it.
    best_move: &'a str,
    /// Whether no move gains more than the threshold.
    stationary: bool,
    /// The threshold, relative.
    threshold: f64,
    /// Polls made (more than one when the budget had room after a poll that gained; 0:
    /// the `sqp` refiner's first-order check, from the derivatives, no simulation).
    #[serde(skip_serializing_if = "is_one")]
    polls: usize,
    /// Moves the `sqp` refiner's derivatives screened (with a poll, `moves` are those
    /// they flagged and that were simulated; absent for the other refiners).
    #[serde(skip_serializing_if = "is_zero")]
    screened: usize,
}

/// `optimum.json`.
#[derive(Debug, Clone, Serialize)]
struct OptimumFile<'a> {
    study: &'a str,
    objective: &'a str,
    refiner: &'a str,
    damper_floors: &'a [usize],
    #[serde(rename = "slip_loads_kN")]
    slip_loads_kn: Vec<f64>,
    on_bound: &'a [OnBound],
    #[serde(with = "crate::base::collapse::objective_serde")]
    objective_value: f64,
    /// What `objective_value` is: `objective`, or, where no evaluated design meets the
    /// limits, `sum_of_exceedances` (each limit's Σ max(0, ratio − 1) at its worst case:
    /// what the refiners minimised to find the closest design).
    objective_value_is: &'static str,
    #[serde(with = "crate::base::collapse::objective_serde")]
    bare_objective: f64,
    #[serde(with = "crate::base::collapse::objective_serde")]
    file_objective: f64,
    /// Whether the bare frame meets the limits (a study with limits).
    #[serde(skip_serializing_if = "Option::is_none")]
    bare_passes: Option<bool>,
    /// Whether the building file's design meets them (a study with limits).
    #[serde(skip_serializing_if = "Option::is_none")]
    file_passes: Option<bool>,
    sweep_designs: usize,
    refine_evaluations: usize,
    /// Why each start's refiner stopped (`tolerance`, `budget`, `no_progress`).
    refine_stops: Vec<&'static str>,
    /// The optimum's post-check (the `model` refiner).
    #[serde(skip_serializing_if = "Option::is_none")]
    stationarity: Option<StationarityEntry<'a>>,
    finalists: Vec<FinalistEntry>,
    ranking_held: bool,
    /// Whether the finalists were run again at the check fidelity (not when the sweep
    /// ran `exact`, the check's method: their check objectives are then the sweep's).
    check_reran: bool,
    /// The recommended design's code check (a study with limits).
    #[serde(skip_serializing_if = "Option::is_none")]
    check: Option<CheckEntry>,
}

fn is_one(v: &usize) -> bool {
    *v == 1
}

fn is_zero(v: &usize) -> bool {
    *v == 0
}

/// Pretty JSON with a final newline; through a [`serde_json::Value`], so object keys are
/// in sorted order at every level.
fn sorted_json<T: Serialize>(value: &T, what: &str) -> Result<String, OptError> {
    let json = |source| OptError::Json {
        path: what.into(),
        source,
    };
    let v = serde_json::to_value(value).map_err(json)?;
    let mut s = serde_json::to_string_pretty(&v).map_err(json)?;
    s.push('\n');
    Ok(s)
}

impl StudyReport {
    /// The files [`StudyReport::write_files`] writes, with the sweep's (`designs.csv`,
    /// `responses.csv`), in the order a summary names them.
    pub const FILES: [&str; 8] = [
        "designs.csv",
        "responses.csv",
        "refine.csv",
        "optimum.json",
        "candidates.json",
        "design-table.csv",
        "design-table.md",
        "design-table.json",
    ];

    /// `refine.csv`: every refinement evaluation with the best objective so far.
    pub fn refine_csv(&self) -> String {
        let mut s = String::from("evaluation,refiner,objective,best_so_far");
        for f in &self.damper_floors {
            let _ = write!(s, ",slip_load_kN_{f}");
        }
        s.push('\n');
        let mut best = self.refine.best_sweep.f;
        for (i, (p, loads)) in self.refine.log.iter().zip(&self.refine_loads_n).enumerate() {
            best = best.min(p.f);
            // a design that stands but misses a limit is said so, not "collapsed"
            let value = match &p.limits {
                Some(l) if p.f == f64::INFINITY && l.objective.is_finite() => {
                    "misses a limit".to_string()
                }
                _ => crate::base::collapse::objective_text(p.f, None),
            };
            let _ = write!(
                s,
                "{},{},{},{}",
                i + 1,
                self.method.as_str(),
                value,
                crate::base::collapse::objective_text(best, None)
            );
            for v in loads {
                let _ = write!(s, ",{}", v / 1e3);
            }
            s.push('\n');
        }
        s
    }

    /// `optimum.json`: the optimum, its objective beside the bare frame's and the
    /// building file's, the finalists at both fidelities; keys sorted.
    pub fn optimum_json(&self) -> Result<String, OptError> {
        let r = &self.refine;
        let kn = |v: &[f64]| v.iter().map(|x| x / 1e3).collect::<Vec<_>>();
        sorted_json(
            &OptimumFile {
                study: &self.study,
                objective: &self.objective,
                refiner: self.method.as_str(),
                damper_floors: &self.damper_floors,
                slip_loads_kn: kn(&r.optimum_loads),
                on_bound: &self.on_bound,
                objective_value: r.optimum.f,
                objective_value_is: match r.target {
                    RefineTarget::Violation => "sum_of_exceedances",
                    RefineTarget::Objective | RefineTarget::PassingObjective => "objective",
                },
                bare_objective: r.bare_objective,
                file_objective: r.file_objective,
                bare_passes: r.bare_passes,
                file_passes: r.file_passes,
                sweep_designs: r.sweep_designs,
                refine_evaluations: r.log.len(),
                refine_stops: r.stops.iter().map(|s| s.as_str()).collect(),
                stationarity: r.stationarity.as_ref().map(|s| StationarityEntry {
                    step: s.step,
                    moves: s.moves,
                    best_gain: s.best_gain,
                    best_move: &s.best_move,
                    stationary: s.stationary,
                    threshold: crate::phases::refine::STATIONARY_GAIN,
                    polls: s.polls,
                    screened: s.screened,
                }),
                finalists: r
                    .finalists
                    .iter()
                    .map(|f| FinalistEntry {
                        slip_loads_kn: kn(&f.slip_loads_n),
                        objective_sweep: f.f_sweep,
                        objective_check: f.f_check,
                        check: f.check.as_ref().map(|c| CheckEntry {
                            passes: c.passes(),
                            verdict: c.verdict(),
                            margin: c.margin(),
                        }),
                    })
                    .collect(),
                ranking_held: r.ranking_held,
                check_reran: r.check_reran,
                check: self.code_check.as_ref().map(|c| CheckEntry {
                    passes: c.passes,
                    verdict: c.verdict.clone(),
                    margin: c.margin,
                }),
            },
            "optimum.json",
        )
    }

    /// `candidates.json`: the candidates as `rank --designs` reads them.
    pub fn candidates_json(&self) -> Result<String, OptError> {
        let mut text =
            serde_json::to_string_pretty(&self.candidates).map_err(|source| OptError::Json {
                path: "candidates.json".into(),
                source,
            })?;
        text.push('\n');
        Ok(text)
    }

    /// Writes `refine.csv`, `optimum.json`, `design-table.{csv,md,json}` and
    /// `candidates.json` into `out` (the sweep wrote its own files as it finished), and
    /// the front's files ([`crate::phases::pareto::ParetoReport::write_files`]) when there is one.
    pub fn write_files(&self, folder: &StudyFolder) -> Result<(), OptError> {
        folder.write("refine.csv", self.refine_csv().as_bytes())?;
        folder.write("optimum.json", self.optimum_json()?.as_bytes())?;
        self.table.write_files(folder)?;
        folder.write("candidates.json", self.candidates_json()?.as_bytes())?;
        if let Some(p) = &self.pareto {
            p.write_files(folder)?;
        }
        if let Some(c) = &self.code_check {
            c.write_files(folder)?;
        }
        if let Some(d) = &self.devices {
            d.write_files(folder)?;
        }
        Ok(())
    }
}
