//! The certified front: the search's non-dominated designs run again at the check
//! fidelity, whether the front held there, the knee, a design table of a few front
//! designs, and the files `pareto.csv`, `pareto.json`, `pareto-table.{csv,md,json}`.

use super::front::{crowding_distance, hypervolume, knee, nondominated_ranks};
use super::search::{Search, Source};
use super::vector::objective_vector;
use crate::base::collapse::objective_text;
use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::eval::evaluate::{DesignLoads, TaskJournal, run_designs_journalled, suite_ranges};
use crate::model::fidelity::Fidelity;
use crate::model::objectives::ParetoObjective;
use crate::model::study::Study;
use crate::phases::table::DesignTable;
use crate::store::folder::StudyFolder;
use serde::Serialize;
use std::fmt::Write as _;

/// The reference point of a front's hypervolume in the files: per objective, the
/// front's nadir plus this share of its range (its ideal-to-nadir span), so the ends of
/// the front count.
pub const REFERENCE_MARGIN: f64 = 0.1;

/// The reference point [`REFERENCE_MARGIN`] beyond the nadir of `front`.
pub fn reference_point(front: &[Vec<f64>]) -> Vec<f64> {
    let k = front.first().map_or(0, Vec::len);
    (0..k)
        .map(|m| {
            let lo = front.iter().map(|p| p[m]).fold(f64::INFINITY, f64::min);
            let hi = front.iter().map(|p| p[m]).fold(f64::NEG_INFINITY, f64::max);
            let span = hi - lo;
            // a front flat in this objective: a margin of its size instead
            let span = if span > 0.0 {
                span
            } else {
                hi.abs().max(1e-300)
            };
            hi + REFERENCE_MARGIN * span
        })
        .collect()
}

/// The front's designs at the check fidelity.
#[derive(Debug, Clone, PartialEq)]
pub struct Certified {
    /// Indices into [`Search::evaluated`] of the front (rank 1 at the sweep fidelity),
    /// sorted by the first objective.
    pub front: Vec<usize>,
    /// Each front design's objective vector at the check fidelity.
    pub check: Vec<Vec<f64>>,
    /// Each front design's rank among the front at the check fidelity (1: still
    /// non-dominated).
    pub check_ranks: Vec<usize>,
    /// Each front design's largest relative change of an objective, check against sweep.
    pub moved: Vec<f64>,
    /// How far each front design is dominated at the check fidelity: the least
    /// relative improvement in every objective that would leave it dominated by none of
    /// the front designs that dominate it there (the multiplicative ε of ε-dominance;
    /// 0 for a design still non-dominated).
    pub dominated_by: Vec<f64>,
    /// Simulations run now and taken from `check.jsonl`.
    pub ran: usize,
    /// Simulations taken from `check.jsonl`.
    pub reused: usize,
}

impl Certified {
    /// Whether the front held at the check fidelity: no design of it became dominated.
    pub fn held(&self) -> bool {
        self.check_ranks.iter().all(|&r| r == 1)
    }
}

/// Runs the front of `search` again at the study's check fidelity (with the bare frame),
/// taking runs from `journal` (`check.jsonl`) and appending the others.
pub fn certify(
    study: &Study,
    search: &Search,
    journal: Option<&TaskJournal>,
    tick: &(dyn Fn() + Sync),
) -> Result<Certified, OptError> {
    let ev = &search.evaluated;
    let vectors: Vec<Vec<f64>> = ev.iter().map(|e| e.objectives.clone()).collect();
    let ranks = nondominated_ranks(&vectors);
    let mut front: Vec<usize> = (0..ev.len())
        .filter(|&i| ranks[i] == 1 && vectors[i].iter().all(|v| v.is_finite()))
        .collect();
    front.sort_by(|&a, &b| {
        vectors[a][0]
            .total_cmp(&vectors[b][0])
            .then(vectors[a][1].total_cmp(&vectors[b][1]))
            .then(a.cmp(&b))
    });
    let m = study.space.dampers.len();
    let mut designs = vec![vec![0.0; m]];
    designs.extend(front.iter().map(|&i| ev[i].slip_loads_n.clone()));
    let before = journal.map_or(0, TaskJournal::reused);
    let mut runs = run_designs_journalled(study, &designs, &Fidelity::check(study), journal, tick)?;
    let reused = journal.map_or(0, TaskJournal::reused) - before;
    let bare = runs.remove(0);
    let ranges = suite_ranges(study);
    let check = front
        .iter()
        .zip(&runs)
        .map(|(&i, r)| objective_vector(study, &ev[i].slip_loads_n, r, Some(&bare), &ranges))
        .collect::<Result<Vec<_>, _>>()?;
    let check_ranks = nondominated_ranks(&check);
    let moved = front
        .iter()
        .zip(&check)
        .map(|(&i, c)| {
            ev[i]
                .objectives
                .iter()
                .zip(c)
                .map(|(s, c)| {
                    if s == c {
                        0.0
                    } else {
                        (c - s).abs() / s.abs().max(f64::MIN_POSITIVE)
                    }
                })
                .fold(0.0, f64::max)
        })
        .collect();
    let dominated_by = check
        .iter()
        .map(|ci| {
            check
                .iter()
                .filter(|cj| super::front::dominates(cj, ci))
                .map(|cj| {
                    ci.iter()
                        .zip(cj)
                        .map(|(a, b)| (a - b) / a.abs().max(f64::MIN_POSITIVE))
                        .fold(f64::INFINITY, f64::min)
                })
                .fold(0.0, f64::max)
        })
        .collect();
    Ok(Certified {
        front,
        dominated_by,
        ran: designs.len() * study.runs() - reused,
        reused,
        check,
        check_ranks,
        moved,
    })
}

/// The front a study run found and certified.
#[derive(Debug, Clone)]
pub struct ParetoReport {
    /// The objectives.
    pub objectives: Vec<ParetoObjective>,
    /// Floors (from 1) of the dissipators.
    pub damper_floors: Vec<usize>,
    /// Everything the search evaluated.
    pub search: Search,
    /// Rank of every evaluated design (non-dominated sorting, sweep fidelity).
    pub ranks: Vec<usize>,
    /// Crowding distance of every evaluated design within its rank's front.
    pub crowding: Vec<f64>,
    /// The front at the check fidelity.
    pub certified: Certified,
    /// Position in `certified.front` of the knee ([`super::knee`], sweep fidelity).
    pub knee: usize,
    /// Position in `certified.front` of the design minimising each objective.
    pub extremes: Vec<usize>,
    /// The reference point of the front's hypervolume ([`reference_point`]).
    pub reference: Vec<f64>,
    /// The front's hypervolume at the sweep fidelity.
    pub hypervolume: f64,
    /// The design table's designs (`min-METRIC`…, `knee`, `file`, `bare`).
    pub table_designs: Vec<(String, DesignLoads)>,
    /// The design table of those designs at the check fidelity.
    pub table: DesignTable,
    /// Its runs ([`DesignTable::build_with_runs`]).
    pub table_runs: Vec<Vec<RecordMetrics>>,
}

/// Ranks and crowding distances of every evaluated design.
pub fn ranks_and_crowding(vectors: &[Vec<f64>]) -> (Vec<usize>, Vec<f64>) {
    let ranks = nondominated_ranks(vectors);
    let mut crowd = vec![0.0; vectors.len()];
    let top = ranks.iter().copied().max().unwrap_or(0);
    for r in 1..=top {
        let members: Vec<usize> = (0..vectors.len()).filter(|&i| ranks[i] == r).collect();
        let pts: Vec<Vec<f64>> = members.iter().map(|&i| vectors[i].clone()).collect();
        for (&i, d) in members.iter().zip(crowding_distance(&pts)) {
            crowd[i] = d;
        }
    }
    (ranks, crowd)
}

/// The knee and the extremes of a certified front (positions in `certified.front`).
pub fn knee_and_extremes(search: &Search, certified: &Certified) -> (usize, Vec<usize>) {
    let fv: Vec<Vec<f64>> = certified
        .front
        .iter()
        .map(|&i| search.evaluated[i].objectives.clone())
        .collect();
    let k = fv.first().map_or(0, Vec::len);
    let extremes = (0..k)
        .map(|m| {
            (0..fv.len())
                .min_by(|&a, &b| fv[a][m].total_cmp(&fv[b][m]).then(a.cmp(&b)))
                .unwrap_or(0)
        })
        .collect();
    (knee(&fv).unwrap_or(0), extremes)
}

/// The design table's designs of a front: the design minimising each objective
/// (`min-METRIC`), the knee, the building file's design and the bare frame; a design
/// already listed under another name is not repeated.
pub fn table_designs(
    study: &Study,
    search: &Search,
    certified: &Certified,
    knee: usize,
    extremes: &[usize],
) -> Vec<(String, DesignLoads)> {
    let loads = |pos: usize| -> DesignLoads {
        search.evaluated[certified.front[pos]]
            .slip_loads_n
            .clone()
            .into()
    };
    let mut all: Vec<(String, DesignLoads)> = Vec::new();
    if certified.front.is_empty() {
        return all;
    }
    for (o, &pos) in study.objectives.iter().zip(extremes) {
        all.push((format!("min-{}", o.metric.as_str()), loads(pos)));
    }
    all.push(("knee".into(), loads(knee)));
    all.push(("file".into(), DesignLoads::file(study)));
    all.push(("bare".into(), vec![0.0; study.space.dampers.len()].into()));
    let mut out: Vec<(String, DesignLoads)> = Vec::new();
    for (name, d) in all {
        if !out.iter().any(|(_, e)| *e == d) {
            out.push((name, d));
        }
    }
    out
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

#[derive(Serialize)]
struct FrontEntry {
    label: String,
    #[serde(rename = "slip_loads_kN")]
    slip_loads_kn: Vec<f64>,
    sweep: Vec<f64>,
    check: Vec<f64>,
    check_rank: usize,
    moved: f64,
    crowding: Option<f64>,
    knee: bool,
}

#[derive(Serialize)]
struct ParetoFile<'a> {
    study: &'a str,
    objectives: Vec<String>,
    units: Vec<&'static str>,
    damper_floors: &'a [usize],
    sweep_designs: usize,
    search_designs: usize,
    #[serde(skip_serializing_if = "is_zero")]
    refine_designs: usize,
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    file_design: bool,
    sweep_fidelity_simulations: usize,
    front: Vec<FrontEntry>,
    knee: String,
    knee_rule: &'static str,
    extremes: Vec<(String, String)>,
    reference_point: &'a [f64],
    hypervolume: f64,
    held: bool,
    dominated_at_check: Vec<(String, f64)>,
    largest_move: f64,
    bare: &'a [f64],
    file: &'a [f64],
}

impl ParetoReport {
    /// The files [`ParetoReport::write_files`] writes.
    pub const FILES: [&str; 5] = [
        "pareto.csv",
        "pareto.json",
        "pareto-table.csv",
        "pareto-table.md",
        "pareto-table.json",
    ];

    /// The front designs' labels, in front order.
    pub fn front_labels(&self) -> Vec<&str> {
        self.certified
            .front
            .iter()
            .map(|&i| self.search.evaluated[i].label.as_str())
            .collect()
    }

    /// `pareto.csv`: every evaluated design (the sweep's, the search's, the file's, then
    /// the refinement's: its `source`) with its
    /// slip loads (kN), each objective at the sweep fidelity, its rank and crowding
    /// distance, whether it is on the front or the knee, and, for the front, each
    /// objective at the check fidelity and its rank there.
    pub fn csv(&self) -> String {
        let mut s = String::from("label,source");
        for f in &self.damper_floors {
            let _ = write!(s, ",slip_load_kN_{f}");
        }
        for o in &self.objectives {
            let _ = write!(s, ",{}", o.column());
        }
        s.push_str(",rank,crowding,front,knee");
        for o in &self.objectives {
            let _ = write!(s, ",{}_check", o.column());
        }
        s.push_str(",check_rank\n");
        let knee = self.certified.front.get(self.knee).copied();
        for (i, e) in self.search.evaluated.iter().enumerate() {
            let _ = write!(s, "{},{}", e.label, e.source.as_str());
            for v in &e.slip_loads_n {
                let _ = write!(s, ",{}", v / 1e3);
            }
            for v in &e.objectives {
                let _ = write!(s, ",{}", objective_text(*v, None));
            }
            let pos = self.certified.front.iter().position(|&f| f == i);
            let _ = write!(
                s,
                ",{},{},{},{}",
                self.ranks[i],
                self.crowding[i],
                u8::from(pos.is_some()),
                u8::from(knee == Some(i))
            );
            match pos {
                Some(p) => {
                    for v in &self.certified.check[p] {
                        let _ = write!(s, ",{}", objective_text(*v, None));
                    }
                    let _ = write!(s, ",{}", self.certified.check_ranks[p]);
                }
                None => {
                    for _ in 0..=self.objectives.len() {
                        s.push(',');
                    }
                }
            }
            s.push('\n');
        }
        s
    }

    /// `pareto.json`: the front (sweep and check), the knee and the rule that chose it,
    /// the extremes, the hypervolume and its reference point, whether the front held.
    pub fn json(&self) -> Result<String, OptError> {
        let c = &self.certified;
        let ev = &self.search.evaluated;
        let front = c
            .front
            .iter()
            .enumerate()
            .map(|(p, &i)| FrontEntry {
                label: ev[i].label.clone(),
                slip_loads_kn: ev[i].slip_loads_n.iter().map(|v| v / 1e3).collect(),
                sweep: ev[i].objectives.clone(),
                check: c.check[p].clone(),
                check_rank: c.check_ranks[p],
                moved: c.moved[p],
                crowding: self.crowding[i].is_finite().then_some(self.crowding[i]),
                knee: p == self.knee,
            })
            .collect();
        let file = ParetoFile {
            study: &self.table.study,
            objectives: self.objectives.iter().map(ParetoObjective::label).collect(),
            units: self.objectives.iter().map(ParetoObjective::unit).collect(),
            damper_floors: &self.damper_floors,
            sweep_designs: self.search.sweep_designs,
            search_designs: self.search.search_designs,
            refine_designs: ev.iter().filter(|e| e.source == Source::Refine).count(),
            file_design: ev.iter().any(|e| e.source == Source::File),
            sweep_fidelity_simulations: self.search.simulations(self.table.records),
            front,
            knee: self
                .front_labels()
                .get(self.knee)
                .map_or(String::new(), |l| l.to_string()),
            knee_rule: "least sum of the objectives normalised to the front's ideal (0) and nadir (1): the front point farthest from the hyperplane through the normalised extremes",
            extremes: self
                .objectives
                .iter()
                .zip(&self.extremes)
                .map(|(o, &p)| (o.label(), ev[c.front[p]].label.clone()))
                .collect(),
            reference_point: &self.reference,
            hypervolume: self.hypervolume,
            held: c.held(),
            dominated_at_check: c
                .front
                .iter()
                .zip(c.check_ranks.iter().zip(&c.dominated_by))
                .filter(|(_, (r, _))| **r > 1)
                .map(|(&i, (_, by))| (ev[i].label.clone(), *by))
                .collect(),
            largest_move: c.moved.iter().copied().fold(0.0, f64::max),
            bare: &self.search.bare,
            file: &self.search.file,
        };
        let json = |source| OptError::Json {
            path: "pareto.json".into(),
            source,
        };
        let v = serde_json::to_value(&file).map_err(json)?;
        let mut s = serde_json::to_string_pretty(&v).map_err(json)?;
        s.push('\n');
        Ok(s)
    }

    /// Writes `pareto.csv`, `pareto.json` and `pareto-table.{csv,md,json}` into the study folder.
    pub fn write_files(&self, folder: &StudyFolder) -> Result<(), OptError> {
        folder.write("pareto.csv", self.csv().as_bytes())?;
        folder.write("pareto.json", self.json()?.as_bytes())?;
        self.table.write_files_as(folder, "pareto-table")
    }
}

/// Builds the report of a searched front: ranks, certification, knee, design table.
pub fn build(
    study: &Study,
    search: Search,
    certified: Certified,
    table: (DesignTable, Vec<Vec<RecordMetrics>>),
    table_designs: Vec<(String, DesignLoads)>,
) -> ParetoReport {
    let vectors: Vec<Vec<f64>> = search
        .evaluated
        .iter()
        .map(|e| e.objectives.clone())
        .collect();
    let (ranks, crowding) = ranks_and_crowding(&vectors);
    let (knee, extremes) = knee_and_extremes(&search, &certified);
    let fv: Vec<Vec<f64>> = certified
        .front
        .iter()
        .map(|&i| vectors[i].clone())
        .collect();
    let reference = reference_point(&fv);
    let hypervolume = hypervolume(&fv, &reference);
    ParetoReport {
        objectives: study.objectives.clone(),
        damper_floors: study.space.dampers.iter().map(|f| f + 1).collect(),
        search,
        ranks,
        crowding,
        certified,
        knee,
        extremes,
        reference,
        hypervolume,
        table_designs,
        table: table.0,
        table_runs: table.1,
    }
}
