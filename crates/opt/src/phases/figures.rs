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

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::eval::evaluate::{TaskJournal, run_designs_journalled, suite_ranges};
use crate::model::config::MAX_DESIGNS;
use crate::model::fidelity::Fidelity;
use crate::model::objective::Statistic;
use crate::model::space::SpaceConfig;
use crate::model::study::Study;
use crate::phases::refine::Point;
use crate::phases::sweep::Manifest;
use crate::phases::table::DesignTable;
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

/// Profiles of designs from their per-record responses (`runs[d][r]`).
pub fn drift_profiles(names: &[String], runs: &[&[RecordMetrics]]) -> Vec<DriftProfile> {
    names
        .iter()
        .zip(runs)
        .map(|(name, rows)| {
            let n = rows.first().map_or(0, |m| m.drift_ratio.len());
            let stat = |st: Statistic| -> Vec<f64> {
                (0..n)
                    .map(|i| st.of(&rows.iter().map(|m| m.drift_ratio[i]).collect::<Vec<_>>()))
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
    /// The bare frame's peak drift ratio per record.
    pub bare: Vec<f64>,
    /// The design's peak drift ratio per record.
    pub design_values: Vec<f64>,
}

impl RecordScatter {
    /// From the per-record responses of the bare frame and the design.
    pub fn new(
        design: &str,
        records: &[String],
        bare: &[RecordMetrics],
        rows: &[RecordMetrics],
    ) -> RecordScatter {
        RecordScatter {
            design: design.to_string(),
            records: records.to_vec(),
            bare: bare.iter().map(RecordMetrics::peak_drift_ratio).collect(),
            design_values: rows.iter().map(RecordMetrics::peak_drift_ratio).collect(),
        }
    }
}

/// The figure data of one study run.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureData {
    /// The objective map, when asked for.
    pub map: Option<ObjectiveMap>,
    /// The refiners' paths (none for a sweep).
    pub convergence: Vec<Convergence>,
    /// Drift profiles of the ranked designs, best first.
    pub profiles: Vec<DriftProfile>,
    /// The best design vs the bare frame, per record.
    pub scatter: Option<RecordScatter>,
    /// Method and time step of the profiles and the scatter, for the titles.
    pub fidelity: String,
    /// The suites scaled to a code spectrum: each scaled mean spectrum against its target
    /// (ASCE 7-16 §16.2.3).
    pub spectra: Vec<(String, crate::model::study::CodeScaling)>,
}

impl FigureData {
    /// A sweep's figure data from its manifest and responses alone (no new simulations),
    /// so a single run and `merge` of its shards draw the same bytes: drift profiles of
    /// the three best designs, the building file's design and the bare frame; the best
    /// design vs the bare frame per record.
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
        Ok(FigureData {
            map: None,
            convergence: Vec::new(),
            profiles: drift_profiles(&names, &runs),
            scatter: best.map(|d| {
                RecordScatter::new(
                    &m.designs[d].label,
                    &m.records,
                    &rows[..nr],
                    &rows[d * nr..(d + 1) * nr],
                )
            }),
            fidelity: format!("{} (sweep fidelity)", m.method.as_str()),
            spectra: Vec::new(),
        }
        .with_spectra(&m.suites))
    }

    /// The figure data with the code scaling of `suites` (those scaled to a code spectrum).
    pub fn with_spectra(mut self, suites: &[crate::model::study::SuiteInfo]) -> FigureData {
        self.spectra = suites
            .iter()
            .filter_map(|s| s.code_scaling.clone().map(|c| (s.name.clone(), c)))
            .collect();
        self
    }

    /// An optimisation's figure data: the drift profiles of the design table's designs
    /// ranked by their objective, the first design (the optimum) vs the bare frame per
    /// record, both from the table's runs (`runs` as [`DesignTable::build_with_runs`]
    /// returns them), with the refiners' paths and the objective map given.
    pub fn of_design_table(
        records: &[String],
        designs: &[(String, crate::eval::evaluate::DesignLoads)],
        table: &DesignTable,
        runs: &[Vec<RecordMetrics>],
        convergence: Vec<Convergence>,
        map: Option<ObjectiveMap>,
    ) -> FigureData {
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
        FigureData {
            map,
            convergence,
            profiles: drift_profiles(&names, &rows),
            scatter: designs
                .first()
                .map(|(name, _)| RecordScatter::new(name, records, &runs[0], &runs[1])),
            fidelity: table.fidelity.clone(),
            spectra: Vec::new(),
        }
    }
}
