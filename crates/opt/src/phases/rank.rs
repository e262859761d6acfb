//! Ranking candidate designs over each suite of a study, and how stable the ranking is:
//! the records of each suite are resampled with replacement (a seeded bootstrap) and the
//! share of resamples in which each design keeps its rank, and in which the whole order
//! is unchanged, is reported.

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::eval::evaluate::{DesignLoads, run_designs};
use crate::model::fidelity::Fidelity;
use crate::model::sampler::{FrictionLaw, SplitMix};
use crate::model::study::Study;
use crate::store::folder::StudyFolder;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// A named candidate (file format of `--designs`: a JSON array of these).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NamedDesign {
    /// Name.
    pub name: String,
    /// Slip load per dissipator, bottom to top, kN.
    pub slip_loads_kn: Vec<f64>,
    /// The friction law per dissipator, kN (`"locked"` or `{"bounds": [F⁻, F⁺]}`), where
    /// symmetric slip loads cannot say it (the building file's design in
    /// `candidates.json`): then it, not `slip_loads_kn`, is what runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction_kn: Option<Vec<FrictionLaw>>,
}

/// Ranks of the designs on one suite (or on all suites together).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SuiteRanking {
    /// Suite name (`all` for the study's objective over every suite).
    pub suite: String,
    /// Objective per design (`"collapsed"` for a design that collapses on a record of
    /// the suite: [`crate::base::collapse`]).
    #[serde(with = "crate::base::collapse::objectives_serde")]
    pub objective: Vec<f64>,
    /// Rank per design, 1 = best.
    pub rank: Vec<usize>,
    /// Share of bootstrap resamples in which each design keeps its rank.
    pub rank_kept: Vec<f64>,
    /// Share of resamples with the same order of every design.
    pub order_kept: f64,
}

/// The ranking of a set of designs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Ranking {
    /// The study's name.
    #[serde(default)]
    pub study: String,
    /// The study's objective, as a label.
    #[serde(default)]
    pub objective: String,
    /// Design names.
    pub designs: Vec<String>,
    /// Bootstrap resamples per suite.
    pub bootstrap: usize,
    /// Per suite, then `all`.
    pub suites: Vec<SuiteRanking>,
}

fn ranks(obj: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..obj.len()).collect();
    order.sort_by(|&a, &b| obj[a].total_cmp(&obj[b]).then(a.cmp(&b)));
    let mut r = vec![0; obj.len()];
    for (i, &d) in order.iter().enumerate() {
        r[d] = i + 1;
    }
    r
}

/// Reads candidate designs from `path` (`[{"name", "slip_loads_kn"}, …]`, as `optimize`
/// writes `candidates.json`) and checks them against `study` ([`to_newtons`]). A study,
/// scene or building given instead is named as such; an empty list is refused.
pub fn load_designs(study: &Study, path: &std::path::Path) -> Result<Vec<NamedDesign>, OptError> {
    let shown = path.display();
    let text = slipload_motion::limits::read_input_text(
        path,
        "designs",
        slipload_motion::limits::MAX_CONFIG_BYTES,
    )
    .map_err(|e| OptError::from(e).context(format!("reading {shown}")))?;
    let designs: Vec<NamedDesign> = match serde_json::from_str(&text) {
        Ok(d) => d,
        Err(e) => {
            return Err(match slipload_sim::FileKind::of_json(&text) {
                // a study, scene or building given as the candidates: say what it is
                Some(kind) if kind != slipload_sim::FileKind::Designs => {
                    OptError::Argument(format!(
                        "{shown} is {}, not a list of candidate designs ([{{\"name\", \"slip_loads_kn\"}}, …], as optimize writes in candidates.json): {}",
                        kind.article(),
                        kind.advice(path)
                    ))
                }
                _ => OptError::Argument(format!(
                    "{shown}: expected [{{\"name\", \"slip_loads_kn\"}}, …]: {e}"
                )),
            });
        }
    };
    if designs.is_empty() {
        return Err(OptError::Argument(format!("{shown}: no designs")));
    }
    to_newtons(study, &designs).map_err(|e| e.context(format!("checking {shown}")))?;
    Ok(designs)
}

/// Checks candidate designs against the study's space (count, finite, ≥ 0; a friction
/// law with F⁻ ≤ 0 ≤ F⁺) and that their names are unique (the tables and the ranking name
/// each design once); N out, friction laws carried.
pub fn to_newtons(study: &Study, designs: &[NamedDesign]) -> Result<Vec<DesignLoads>, OptError> {
    let m = study.space.dampers.len();
    // the building's own bound on a slip load, as the study's space holds its bounds to
    let weight = study.building.mass.sum() * slipload_motion::G;
    let max_slip_kn = slipload_sim::building::MAX_SLIP_LOAD_PER_WEIGHT * weight / 1e3;
    let mut seen = std::collections::HashMap::new();
    for (i, d) in designs.iter().enumerate() {
        if let Some(problem) = crate::model::config::label_problem(&d.name) {
            return Err(OptError::Argument(format!(
                "designs[{i}].name: {:?} {problem} (a design name labels rows of the CSV and Markdown tables)",
                d.name
            )));
        }
        if let Some(first) = seen.insert(d.name.as_str(), i) {
            return Err(OptError::Argument(format!(
                "designs[{i}]: the name {:?} is already the name of designs[{first}]; give each candidate its own name",
                d.name
            )));
        }
    }
    designs
        .iter()
        .enumerate()
        .map(|(i, d)| {
            if d.slip_loads_kn.len() != m {
                return Err(OptError::Missing(format!(
                    "designs[{i}] ({}): {} slip loads, expected {m} (one per dissipator)",
                    d.name,
                    d.slip_loads_kn.len()
                )));
            }
            if d.slip_loads_kn
                .iter()
                .any(|v| !(v.is_finite() && *v >= 0.0))
            {
                return Err(OptError::Missing(format!(
                    "designs[{i}] ({}): slip loads must be finite and >= 0",
                    d.name
                )));
            }
            if let Some(j) = d.slip_loads_kn.iter().position(|&v| v > max_slip_kn) {
                return Err(OptError::Missing(format!(
                    "designs[{i}] ({}): slip_loads_kn[{j}] = {:e} kN is more than {:e} × the building's weight ({:.4e} kN): write the dissipator \"locked\" (friction_kn) instead, else check the units",
                    d.name,
                    d.slip_loads_kn[j],
                    slipload_sim::building::MAX_SLIP_LOAD_PER_WEIGHT,
                    weight / 1e3
                )));
            }
            if let Some(laws) = &d.friction_kn {
                if laws.len() != m {
                    return Err(OptError::Missing(format!(
                        "designs[{i}] ({}): friction_kn has {} laws, expected {m} (one per dissipator)",
                        d.name,
                        laws.len()
                    )));
                }
                let bad = laws.iter().any(|l| match *l {
                    FrictionLaw::Bounds([lo, hi]) => {
                        !(lo.is_finite() && hi.is_finite() && lo <= 0.0 && hi >= 0.0)
                    }
                    FrictionLaw::Locked => false,
                });
                if bad {
                    return Err(OptError::Missing(format!(
                        "designs[{i}] ({}): friction_kn bounds must be finite with lower <= 0 <= upper",
                        d.name
                    )));
                }
                let too_large = laws.iter().position(|l| match *l {
                    FrictionLaw::Bounds([lo, hi]) => -lo > max_slip_kn || hi > max_slip_kn,
                    FrictionLaw::Locked => false,
                });
                if let Some(j) = too_large {
                    return Err(OptError::Missing(format!(
                        "designs[{i}] ({}): friction_kn[{j}] bounds more than {:e} × the building's weight ({:.4e} kN): write \"locked\" instead, else check the units",
                        d.name,
                        slipload_sim::building::MAX_SLIP_LOAD_PER_WEIGHT,
                        weight / 1e3
                    )));
                }
            }
            Ok(DesignLoads {
                slip_loads_n: d.slip_loads_kn.iter().map(|v| v * 1e3).collect(),
                friction_n: d
                    .friction_kn
                    .as_ref()
                    .map(|l| l.iter().map(|x| x.scaled(1e3)).collect()),
            })
        })
        .collect()
}

/// Runs every design over every record and ranks them per suite and overall.
pub fn rank(
    study: &Study,
    designs: &[NamedDesign],
    bootstrap: usize,
    seed: u64,
    tick: &(dyn Fn() + Sync),
) -> Result<Ranking, OptError> {
    if bootstrap == 0 {
        return Err(OptError::Argument(
            "the bootstrap needs at least 1 resample (the share of resamples keeping a rank is undefined for 0)".into(),
        ));
    }
    let loads = to_newtons(study, designs)?;
    let mut all = vec![DesignLoads::from(vec![0.0; study.space.dampers.len()])];
    all.extend(loads);
    let runs = run_designs(study, &all, &Fidelity::sweep(study), tick)?;
    let bare = &runs[0];
    let runs = &runs[1..];
    let mut rng = SplitMix::new(seed);
    let mut out = Vec::new();
    // the records of `idx` at every property case, case after case: the objective reads
    // the study's case (the nominal, or the worst of the cases)
    let n = study.records.len();
    let cases = study.checks.cases().len();
    let value = |idx: &[usize], ranges: &[std::ops::Range<usize>]| -> Result<Vec<f64>, OptError> {
        let at = |r: &[RecordMetrics]| -> Vec<RecordMetrics> {
            (0..cases)
                .flat_map(|c| idx.iter().map(move |&i| c * n + i))
                .map(|k| r[k].clone())
                .collect()
        };
        let b = at(bare);
        runs.iter()
            .zip(&all[1..])
            .map(|(r, d)| {
                study.checks.objective(
                    &study.objective,
                    &at(r),
                    Some(&b),
                    ranges,
                    idx.len(),
                    &d.slip_loads_n,
                )
            })
            .collect()
    };
    let mut groups: Vec<(String, Vec<std::ops::Range<usize>>)> = study
        .suites
        .iter()
        .map(|s| (s.name.clone(), vec![s.range.clone()]))
        .collect();
    if study.suites.len() > 1 {
        groups.push((
            "all".into(),
            study.suites.iter().map(|s| s.range.clone()).collect(),
        ));
    }
    for (name, ranges) in groups {
        // the records of the group, laid out suite after suite
        let idx: Vec<usize> = ranges.iter().flat_map(|r| r.clone()).collect();
        let mut local = Vec::new();
        let mut at = 0;
        for r in &ranges {
            local.push(at..at + r.len());
            at += r.len();
        }
        let obj = value(&idx, &local)?;
        let rk = ranks(&obj);
        let mut kept = vec![0usize; designs.len()];
        let mut order_kept = 0usize;
        for _ in 0..bootstrap {
            // resample within each suite
            let sample: Vec<usize> = ranges
                .iter()
                .flat_map(|r| {
                    let n = r.len();
                    (0..n).map(|_| r.start + rng.below(n)).collect::<Vec<_>>()
                })
                .collect();
            let rb = ranks(&value(&sample, &local)?);
            for (k, (a, b)) in rb.iter().zip(&rk).enumerate() {
                if a == b {
                    kept[k] += 1;
                }
            }
            if rb == rk {
                order_kept += 1;
            }
        }
        // bootstrap >= 1 (checked above)
        let share = |c: usize| c as f64 / bootstrap as f64;
        out.push(SuiteRanking {
            suite: name,
            objective: obj,
            rank: rk,
            rank_kept: kept.into_iter().map(share).collect(),
            order_kept: share(order_kept),
        });
    }
    Ok(Ranking {
        study: study.name.clone(),
        objective: study.objective.label(),
        designs: designs.iter().map(|d| d.name.clone()).collect(),
        bootstrap,
        suites: out,
    })
}

impl Ranking {
    /// CSV: suite, design, objective, rank, share of resamples keeping that rank.
    pub fn to_csv(&self) -> String {
        let mut s = String::from("suite,design,objective,rank,rank_kept,order_kept\n");
        for su in &self.suites {
            for (k, d) in self.designs.iter().enumerate() {
                let _ = writeln!(
                    s,
                    "{},{d},{},{},{},{}",
                    su.suite,
                    crate::base::collapse::objective_text(su.objective[k], None),
                    su.rank[k],
                    su.rank_kept[k],
                    su.order_kept
                );
            }
        }
        s
    }

    /// Markdown: a header naming the study and its objective, then one table per suite,
    /// designs by rank.
    pub fn to_markdown(&self) -> String {
        let mut s = format!(
            "# Ranking of {} designs: {}\n\nObjective: {} (lower is better); rank 1 is the best design of a suite.\n\n",
            self.designs.len(),
            self.study,
            self.objective
        );
        for su in &self.suites {
            let _ = writeln!(
                s,
                "## {}\n\nWhole order kept in {:.0} % of {} bootstrap resamples of the records.\n\n| rank | design | objective | rank kept |\n|---:|---|---:|---:|",
                su.suite,
                100.0 * su.order_kept,
                self.bootstrap
            );
            let mut order: Vec<usize> = (0..self.designs.len()).collect();
            order.sort_by_key(|&k| su.rank[k]);
            for k in order {
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {:.0} % |",
                    su.rank[k],
                    self.designs[k],
                    crate::base::collapse::objective_text(su.objective[k], Some(6)),
                    100.0 * su.rank_kept[k]
                );
            }
            s.push('\n');
        }
        s
    }
}

impl Ranking {
    /// The files [`Ranking::write_files`] writes.
    pub const FILES: [&str; 3] = ["rank.csv", "rank.md", "rank.json"];

    /// Writes `rank.csv`, `rank.md` and `rank.json` (pretty, with a final newline) into
    /// `out`.
    pub fn write_files(&self, folder: &StudyFolder) -> Result<(), OptError> {
        folder.write("rank.csv", self.to_csv().as_bytes())?;
        folder.write("rank.md", self.to_markdown().as_bytes())?;
        let mut json = serde_json::to_string_pretty(self).map_err(|source| OptError::Json {
            path: folder.path("rank.json"),
            source,
        })?;
        json.push('\n');
        folder.write("rank.json", json.as_bytes())
    }
}
