//! The data of the study figures (`optimize`, `sweep`, `merge`); drawing them, and the
//! CSV written beside each, is the caller's:
//! - objective map over the slip loads of two dissipators, the others held at the
//!   optimum (new simulations at the sweep fidelity, run by the sweep's parallel
//!   evaluation code; opt-in);
//! - the refiners' convergence: best objective so far vs simulations, per refiner whose
//!   journal (`refine-METHOD.jsonl`) is in the folder;
//! - peak drift-ratio profiles over the storeys of the ranked designs (mean and 84th
//!   percentile over the suite);
//! - per-record peak drift ratio of the best design vs the bare frame.
//!
//! The drift profiles and the per-record scatter are drawn per suite where a study has
//! several (a design earthquake and MCE_R are never averaged together), each under the
//! suite's name ([`SuiteFigures::stem`]), with the drift limits the suite states.

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::eval::evaluate::{TaskJournal, run_designs_journalled, suite_ranges};
use crate::model::check::{Checks, LimitMetric};
use crate::model::config::MAX_DESIGNS;
use crate::model::fidelity::Fidelity;
use crate::model::objective::Statistic;
use crate::model::space::SpaceConfig;
use crate::model::study::{Study, SuiteInfo};
use crate::phases::refine::Point;
use crate::phases::sweep::Manifest;
use crate::phases::table::DesignTable;
pub use crate::store::folder::PER_SUITE_STEMS;
use std::path::{Path, PathBuf};

/// The objective over a grid of two dissipators' slip loads.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectiveMap {
    /// The two floors (from 1) whose slip loads vary.
    pub floors: [usize; 2],
    /// Grid values of the first floor's slip load, kN (ascending).
    pub loads_a_kn: Vec<f64>,
    /// Grid values of the second floor's slip load, kN (ascending).
    pub loads_b_kn: Vec<f64>,
    /// Objective at (a\[i\], b\[j\]): `objective[i * loads_b_kn.len() + j]`.
    pub objective: Vec<f64>,
    /// The optimum's slip loads on the two floors, kN (the marker on the map).
    pub optimum_kn: [f64; 2],
    /// The objective, as a label (the colour bar's).
    pub label: String,
}

/// An objective map asked for: `grid` × `grid` designs over the slip loads of two floors.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MapRequest {
    /// The two floors (from 1) whose slip loads vary.
    pub floors: [usize; 2],
    /// Grid points per axis.
    pub grid: usize,
}

impl MapRequest {
    /// The dissipator indices of the map's two floors, checked before any simulation:
    /// two different floors that have dissipators, a grid of at least 2 and at most
    /// [`MAX_DESIGNS`] designs (unless large runs are allowed).
    pub fn dampers(&self, study: &Study) -> Result<[usize; 2], OptError> {
        let (floors, grid) = (self.floors, self.grid);
        if floors[0] == floors[1] {
            return Err(OptError::Argument(format!(
                "--map-floors: give two different floors (got {0},{0})",
                floors[0]
            )));
        }
        if grid < 2 {
            return Err(OptError::Argument(format!(
                "--map-grid must be at least 2 (got {grid})"
            )));
        }
        let damper = |f: usize| -> Result<usize, OptError> {
            study
                .space
                .dampers
                .iter()
                .position(|&d| d + 1 == f)
                .ok_or_else(|| {
                    OptError::Argument(format!(
                        "--map-floors: floor {f} has no dissipator (floors with one: {})",
                        study
                            .space
                            .dampers
                            .iter()
                            .map(|d| (d + 1).to_string())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ))
                })
        };
        let dampers = [damper(floors[0])?, damper(floors[1])?];
        let designs = (grid as f64).powi(2);
        if designs > MAX_DESIGNS && !slipload_sim::limits::allow_large() {
            return Err(OptError::Argument(format!(
                "--map-grid {grid}: {designs:.3e} designs exceed the limit of {MAX_DESIGNS:.0e} that no real study needs; {}",
                slipload_sim::limits::OVERRIDE_HINT
            )));
        }
        Ok(dampers)
    }
}

/// Bounds (N) of dissipator `k`'s slip load for the map: the study's bounds for a free
/// space; for a profile space, 0 to twice the optimum (at least 1 kN).
fn map_bounds(study: &Study, k: usize, optimum: f64) -> (f64, f64) {
    match &study.config.space {
        SpaceConfig::Free { lower_kn, upper_kn } => (lower_kn[k] * 1e3, upper_kn[k] * 1e3),
        SpaceConfig::Profile { .. } => (0.0, (2.0 * optimum).max(1e3)),
    }
}

/// Runs the objective map `request`: its designs over the bounds of the dissipators on
/// its floors, every other slip load at `optimum` (N per dissipator), each over every
/// record at the sweep fidelity. `bare` holds the bare frame's responses at that
/// fidelity (the sweep's first design). With a `journal` its runs are taken from it
/// when there and appended when not (keyed by fidelity, slip loads and record, so they
/// sit beside the check's runs without mixing), so a resumed `optimize --map` reruns
/// nothing.
pub fn objective_map(
    study: &Study,
    optimum: &[f64],
    bare: &[RecordMetrics],
    request: &MapRequest,
    journal: Option<&TaskJournal>,
    tick: &(dyn Fn() + Sync),
) -> Result<ObjectiveMap, OptError> {
    let [ka, kb] = request.dampers(study)?;
    let grid = request.grid;
    let axis = |k: usize| -> Vec<f64> {
        let (lo, hi) = map_bounds(study, k, optimum[k]);
        (0..grid)
            .map(|i| lo + (hi - lo) * i as f64 / (grid - 1) as f64)
            .collect()
    };
    let (xa, xb) = (axis(ka), axis(kb));
    let mut designs = Vec::with_capacity(grid * grid);
    for &a in &xa {
        for &b in &xb {
            let mut d = optimum.to_vec();
            d[ka] = a;
            d[kb] = b;
            designs.push(d);
        }
    }
    let ranges = suite_ranges(study);
    let objective = run_designs_journalled(study, &designs, &Fidelity::sweep(study), journal, tick)
        .and_then(|runs| {
            runs.iter()
                .map(|rows| study.objective.value(rows, Some(bare), &ranges))
                .collect::<Result<Vec<f64>, OptError>>()
        })
        .map_err(|e| e.context("objective map simulations"))?;
    Ok(ObjectiveMap {
        floors: request.floors,
        loads_a_kn: xa.iter().map(|v| v / 1e3).collect(),
        loads_b_kn: xb.iter().map(|v| v / 1e3).collect(),
        objective,
        optimum_kn: [optimum[ka] / 1e3, optimum[kb] / 1e3],
        label: study.objective.label(),
    })
}

/// One refiner's path: best objective so far vs simulations.
#[derive(Debug, Clone, PartialEq)]
pub struct Convergence {
    /// Refiner name (from the journal's file name).
    pub refiner: String,
    /// (simulations so far, objective of this evaluation, best so far); the first point
    /// is the end of the sweep (its best design).
    pub points: Vec<(usize, f64, f64)>,
}

/// The refiners' paths from every `refine-METHOD.jsonl` journal in `dir`. Each refine
/// evaluation simulates every record (`records`); the count starts after the sweep's
/// `sweep_tasks` simulations, at the sweep's best objective `best_sweep`.
pub fn convergence(
    dir: &Path,
    sweep_tasks: usize,
    records: usize,
    best_sweep: f64,
) -> Result<Vec<Convergence>, OptError> {
    let listing = std::fs::read_dir(dir).map_err(|source| OptError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut names: Vec<(String, PathBuf)> = listing
        .filter_map(Result::ok)
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            let method = name.strip_prefix("refine-")?.strip_suffix(".jsonl")?;
            Some((method.to_string(), e.path()))
        })
        .collect();
    names.sort();
    let mut out = Vec::new();
    for (refiner, path) in names {
        let points = crate::store::journal::read_entries::<Point>(&path)?;
        if points.is_empty() {
            continue;
        }
        let mut best = best_sweep;
        let mut path_pts = vec![(sweep_tasks, best_sweep, best_sweep)];
        for (k, p) in points.iter().enumerate() {
            best = best.min(p.f);
            path_pts.push((sweep_tasks + (k + 1) * records, p.f, best));
        }
        out.push(Convergence {
            refiner,
            points: path_pts,
        });
    }
    Ok(out)
}

/// Peak drift-ratio profile of one design over the storeys.
#[derive(Debug, Clone, PartialEq)]
pub struct DriftProfile {
    /// Design name.
    pub design: String,
    /// Mean over the records, per storey (bottom first).
    pub mean: Vec<f64>,
    /// 84th percentile over the records, per storey.
    pub p84: Vec<f64>,
}

/// Profiles of designs from their per-record responses (`runs[d][r]`), over the runs
/// `picked` (indices into each design's responses).
pub fn drift_profiles(
    names: &[String],
    runs: &[&[RecordMetrics]],
    picked: &[usize],
) -> Vec<DriftProfile> {
    names
        .iter()
        .zip(runs)
        .map(|(name, rows)| {
            let rows: Vec<&RecordMetrics> = picked.iter().filter_map(|&i| rows.get(i)).collect();
            let n = rows.first().map_or(0, |m| m.drift_ratio.len());
            let stat = |st: Statistic| -> Vec<f64> {
                (0..n)
                    .map(|i| {
                        st.of(&rows
                            .iter()
                            .map(|m| m.drift_ratio.get(i).copied().unwrap_or(f64::NAN))
                            .collect::<Vec<_>>())
                    })
                    .collect()
            };
            DriftProfile {
                design: name.clone(),
                mean: stat(Statistic::Mean),
                p84: stat(Statistic::P84),
            }
        })
        .collect()
}

/// Peak drift ratio (max over storeys) per record: a design vs the bare frame.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordScatter {
    /// The design compared with the bare frame.
    pub design: String,
    /// Record names.
    pub records: Vec<String>,
    /// The suite of each record.
    pub suites: Vec<String>,
    /// The bare frame's peak drift ratio per record.
    pub bare: Vec<f64>,
    /// The design's peak drift ratio per record.
    pub design_values: Vec<f64>,
}

impl RecordScatter {
    /// From the per-record responses of the bare frame and the design, the runs `picked`
    /// (indices into `records`, `bare` and `rows`), each of the suite `suite`.
    pub fn new(
        design: &str,
        suite: &str,
        picked: &[usize],
        records: &[String],
        bare: &[RecordMetrics],
        rows: &[RecordMetrics],
    ) -> RecordScatter {
        let drift =
            |m: &[RecordMetrics], i: usize| m.get(i).map_or(f64::NAN, |r| r.peak_drift_ratio());
        RecordScatter {
            design: design.to_string(),
            records: picked
                .iter()
                .map(|&i| records.get(i).cloned().unwrap_or_default())
                .collect(),
            suites: vec![suite.to_string(); picked.len()],
            bare: picked.iter().map(|&i| drift(bare, i)).collect(),
            design_values: picked.iter().map(|&i| drift(rows, i)).collect(),
        }
    }
}

/// A drift limit a suite states (`suites[i].limits`), drawn on its drift profiles.
#[derive(Debug, Clone, PartialEq)]
pub struct DriftLimit {
    /// What the limit bounds: `mean`, `p84`, … of the suite's peak drift ratios (a
    /// criterion) or `per record` (a record's unacceptable response).
    pub applies_to: String,
    /// The limit, as a drift ratio (dimensionless).
    pub ratio: f64,
}

/// The peak drift ratio limits of one suite: its criteria on `peak_drift_ratio`, then its
/// per-record limits of an unacceptable response, in the order the study states them.
pub fn drift_limits(checks: &Checks, suite: usize) -> Vec<DriftLimit> {
    let Some(Some(limits)) = checks.limits.get(suite) else {
        return Vec::new();
    };
    let criteria = limits
        .criteria
        .iter()
        .filter(|c| c.metric == LimitMetric::PeakDriftRatio)
        .map(|c| DriftLimit {
            applies_to: c.statistic.as_str().to_string(),
            ratio: c.max,
        });
    let records = limits
        .unacceptable
        .record_limits
        .iter()
        .filter(|l| l.metric == LimitMetric::PeakDriftRatio)
        .map(|l| DriftLimit {
            applies_to: "per record".to_string(),
            ratio: l.max,
        });
    criteria.chain(records).collect()
}

/// The drift profiles and the per-record scatter of one suite (of the whole study where
/// it has one suite).
#[derive(Debug, Clone, PartialEq)]
pub struct SuiteFigures {
    /// The suite's name.
    pub suite: String,
    /// What its figures' file names add to the stem (`-LABEL`, the suite's name made a
    /// plain file name); empty for a study of one suite, whose figures keep the plain
    /// names.
    pub suffix: String,
    /// Drift profiles of the ranked designs, best first.
    pub profiles: Vec<DriftProfile>,
    /// The best design vs the bare frame, per record.
    pub scatter: Option<RecordScatter>,
    /// The peak drift ratio limits the suite states.
    pub limits: Vec<DriftLimit>,
}

impl SuiteFigures {
    /// The file stem of the figure `base` (`drift-profiles`, `records-scatter`) of this
    /// suite: `base` itself for a study of one suite, else `base-LABEL`.
    pub fn stem(&self, base: &str) -> String {
        format!("{base}{}", self.suffix)
    }
}

/// The file-name suffix of each suite's figures: none for one suite; else `-LABEL`, the
/// suite's name with every character other than an ASCII letter, digit, `.`, `_` or `-`
/// replaced by `_` (a name that would repeat an earlier suite's takes `-K`, its
/// position from 1).
pub fn suite_suffixes(names: &[String]) -> Vec<String> {
    if names.len() <= 1 {
        return vec![String::new(); names.len()];
    }
    let mut out: Vec<String> = Vec::with_capacity(names.len());
    for (k, name) in names.iter().enumerate() {
        let mut label: String = name
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        if label.is_empty() || label.chars().all(|c| c == '.') {
            label = format!("suite{}", k + 1);
        }
        let mut suffix = format!("-{label}");
        if out.contains(&suffix) {
            suffix = format!("-{label}-{}", k + 1);
        }
        out.push(suffix);
    }
    out
}

/// The runs (indices into a run list of `runs` entries over `records` records, case
/// after case) of each suite: those whose record lies in the suite's range; for a study
/// of one suite, every run.
fn suite_runs(suites: &[SuiteInfo], runs: usize, records: usize) -> Vec<Vec<usize>> {
    if suites.len() <= 1 {
        return vec![(0..runs).collect()];
    }
    suites
        .iter()
        .map(|s| {
            (0..runs)
                .filter(|i| records > 0 && s.range.contains(&(i % records)))
                .collect()
        })
        .collect()
}

/// The per-suite figures of designs `names` (their responses `runs`, each over the run
/// list `run_names`, whose records `records` repeat case after case), the best design
/// `best` (its name and responses) against the bare frame's responses `bare`.
#[allow(clippy::too_many_arguments)] // two callers; each argument is one of the study's lists
fn per_suite(
    suites: &[SuiteInfo],
    checks: &Checks,
    run_names: &[String],
    records: usize,
    names: &[String],
    runs: &[&[RecordMetrics]],
    best: Option<(&str, &[RecordMetrics])>,
    bare: &[RecordMetrics],
) -> Vec<SuiteFigures> {
    let picked = suite_runs(suites, run_names.len(), records);
    let suite_names: Vec<String> = if suites.is_empty() {
        vec![String::new()]
    } else {
        suites.iter().map(|s| s.name.clone()).collect()
    };
    let suffixes = suite_suffixes(&suite_names);
    suite_names
        .iter()
        .zip(suffixes)
        .zip(&picked)
        .enumerate()
        .map(|(k, ((suite, suffix), picked))| SuiteFigures {
            suite: suite.clone(),
            suffix,
            profiles: drift_profiles(names, runs, picked),
            scatter: best.map(|(design, rows)| {
                RecordScatter::new(design, suite, picked, run_names, bare, rows)
            }),
            limits: drift_limits(checks, k),
        })
        .collect()
}

/// The figure data of one study run.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureData {
    /// The objective map, when asked for.
    pub map: Option<ObjectiveMap>,
    /// The refiners' paths (none for a sweep).
    pub convergence: Vec<Convergence>,
    /// The drift profiles and the per-record scatter, per suite (one entry, under the
    /// plain names, for a study of one suite).
    pub suites: Vec<SuiteFigures>,
    /// Method and time step of the profiles and the scatter, for the titles.
    pub fidelity: String,
    /// The suites scaled to a code spectrum: each scaled mean spectrum against its target,
    /// by the rule the suite was scaled by ([`crate::model::study::CodeScaling::clause`]).
    pub spectra: Vec<(String, crate::model::study::CodeScaling)>,
}

impl FigureData {
    /// A sweep's figure data from its manifest and responses alone (no new simulations),
    /// so a single run and `merge` of its shards draw the same bytes: drift profiles of
    /// the three best designs, the building file's design and the bare frame; the best
    /// design vs the bare frame per record; per suite where there are several.
    pub fn of_sweep(m: &Manifest, rows: &[RecordMetrics]) -> Result<FigureData, OptError> {
        let nr = m.records.len();
        let obj = m.objectives(rows)?;
        let mut order: Vec<usize> = (0..obj.len()).collect();
        order.sort_by(|&a, &b| obj[a].0.total_cmp(&obj[b].0).then(a.cmp(&b)));
        // design 0 is the bare frame (the manifest puts it first)
        let is_file = |d: usize| m.designs[d].label == "file";
        let mut picked: Vec<usize> = order
            .iter()
            .copied()
            .filter(|&d| d != 0 && !is_file(d))
            .take(3)
            .collect();
        picked.extend(order.iter().copied().filter(|&d| is_file(d)));
        picked.push(0);
        picked.sort_by(|&a, &b| obj[a].0.total_cmp(&obj[b].0).then(a.cmp(&b)));
        let names: Vec<String> = picked.iter().map(|&d| m.designs[d].label.clone()).collect();
        let runs: Vec<&[RecordMetrics]> = picked
            .iter()
            .map(|&d| &rows[d * nr..(d + 1) * nr])
            .collect();
        let best = order.iter().copied().find(|&d| d != 0);
        // the study's records: the suites' ranges end at the last
        let records = m.suites.iter().map(|s| s.range.end).max().unwrap_or(nr);
        Ok(FigureData {
            map: None,
            convergence: Vec::new(),
            suites: per_suite(
                &m.suites,
                &m.checks,
                &m.records,
                records,
                &names,
                &runs,
                best.map(|d| (m.designs[d].label.as_str(), &rows[d * nr..(d + 1) * nr])),
                &rows[..nr],
            ),
            fidelity: format!("{} (sweep fidelity)", m.method.as_str()),
            spectra: Vec::new(),
        }
        .with_spectra(&m.suites))
    }

    /// The figure data with the code scaling of `suites` (those scaled to a code spectrum).
    pub fn with_spectra(mut self, suites: &[SuiteInfo]) -> FigureData {
        self.spectra = suites
            .iter()
            .filter_map(|s| s.code_scaling.clone().map(|c| (s.name.clone(), c)))
            .collect();
        self
    }

    /// The stems of the per-suite figures this data draws ([`SuiteFigures::stem`]), for
    /// the folder to claim before they are written.
    pub fn suite_stems(&self) -> Vec<String> {
        self.suites
            .iter()
            .filter(|s| !s.suffix.is_empty())
            .flat_map(|s| PER_SUITE_STEMS.map(|b| s.stem(b)))
            .collect()
    }

    /// An optimisation's figure data: the drift profiles of the design table's designs
    /// ranked by their objective, the first design (the optimum) vs the bare frame per
    /// record, both from the table's runs (`runs` as [`DesignTable::build_with_runs`]
    /// returns them) and per suite of `study`, with the refiners' paths and the objective
    /// map given.
    pub fn of_design_table(
        study: &Study,
        designs: &[(String, crate::eval::evaluate::DesignLoads)],
        table: &DesignTable,
        runs: &[Vec<RecordMetrics>],
        convergence: Vec<Convergence>,
        map: Option<ObjectiveMap>,
    ) -> FigureData {
        let records: Vec<String> = study.records.iter().map(|r| r.name().to_string()).collect();
        // the designs ranked by the objective (design-table fidelity)
        let mut order: Vec<usize> = (0..designs.len()).collect();
        order.sort_by(|&a, &b| {
            table.rows[a]
                .objective
                .total_cmp(&table.rows[b].objective)
                .then(a.cmp(&b))
        });
        let names: Vec<String> = order.iter().map(|&k| designs[k].0.clone()).collect();
        let rows: Vec<&[RecordMetrics]> =
            order.iter().map(|&k| runs[1 + 3 * k].as_slice()).collect();
        let best = designs
            .first()
            .zip(runs.get(1))
            .map(|((name, _), rows)| (name.as_str(), rows.as_slice()));
        let bare: &[RecordMetrics] = runs.first().map_or(&[], Vec::as_slice);
        FigureData {
            map,
            convergence,
            suites: per_suite(
                &study.suites,
                &study.checks,
                &records,
                records.len(),
                &names,
                &rows,
                best,
                bare,
            ),
            fidelity: table.fidelity.clone(),
            spectra: Vec::new(),
        }
    }
}
