//! Evaluating designs of a study in plan: every pair of every suite at each of its
//! orientations in every property case, in parallel, reduced per pair to the largest over
//! its orientations and per suite to the study's statistic over its pairs
//! ([`DesignEval`]); then the objective and the limits' ratios a refiner reads.
//!
//! Each run is independent and the reductions run in a fixed order, so a design's values
//! do not depend on the threads.

use super::config::{PlanMetric, PlanStatistic};
use super::study::PlanStudy;
use crate::base::error::OptError;
use crate::phases::refine::LimitValues;
use rayon::prelude::*;
use serde::Serialize;
use slipload_sim::floorplan::{FloorPlan, FloorPlanScene, GroundComponent};
use slipload_sim::scene::OutputsConfig;
use std::sync::Arc;

/// The peaks of one run (one pair at one orientation in one case), or of a pair (the
/// largest over its orientations), or a suite's statistic of them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Peaks {
    /// Peak drift ratio of every line at every storey, line after line (drift in m
    /// where the building gives no storey heights).
    pub line_drift: Vec<f64>,
    /// Per storey, the largest peak drift ratio of the plan's four edges (empty without
    /// `plan_size`).
    pub edge_drift: Vec<f64>,
    /// Per storey, the larger torsional irregularity ratio of x and y (empty without
    /// `plan_size`).
    pub torsion: Vec<f64>,
    /// Per floor, the peak rotation, rad.
    pub rotation: Vec<f64>,
    /// Per damper, the peak slip, m.
    pub slip: Vec<f64>,
    /// Per storey, the largest residual drift ratio of any line.
    pub residual: Vec<f64>,
    /// Runs that collapsed (a yielding line past its collapse drift).
    pub collapsed: usize,
    /// Per damper, the demands of a device (empty unless the runs asked for them,
    /// [`Step::demands`]).
    pub devices: Devices,
}

/// Per damper, what a device must take (each entry one damper, in the plan's order).
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Devices {
    /// The larger slip either way from the start, m: the stroke.
    pub stroke: Vec<f64>,
    /// Peak slip velocity, m/s.
    pub velocity: Vec<f64>,
    /// Cumulative slip travel, m.
    pub travel: Vec<f64>,
    /// Energy dissipated, J.
    pub energy: Vec<f64>,
    /// Peak friction force, N.
    pub force: Vec<f64>,
}

impl Devices {
    fn fields(&self) -> [&Vec<f64>; 5] {
        [
            &self.stroke,
            &self.velocity,
            &self.travel,
            &self.energy,
            &self.force,
        ]
    }
    fn fields_mut(&mut self) -> [&mut Vec<f64>; 5] {
        [
            &mut self.stroke,
            &mut self.velocity,
            &mut self.travel,
            &mut self.energy,
            &mut self.force,
        ]
    }
}

fn max_of(v: &[f64]) -> f64 {
    v.iter().copied().fold(0.0, f64::max)
}

impl Peaks {
    /// The largest edge drift ratio over the storeys.
    pub fn edge(&self) -> f64 {
        max_of(&self.edge_drift)
    }
    /// The largest line drift ratio.
    pub fn line(&self) -> f64 {
        max_of(&self.line_drift)
    }
    /// The largest torsional ratio (1 for a plan that does not twist).
    pub fn torsional(&self) -> f64 {
        self.torsion.iter().copied().fold(1.0, f64::max)
    }
    /// The largest floor rotation, rad.
    pub fn rot(&self) -> f64 {
        max_of(&self.rotation)
    }

    /// Entry by entry largest of `runs` (one pair's orientations).
    fn envelope(runs: &[Peaks]) -> Peaks {
        let mut out = runs[0].clone();
        for r in &runs[1..] {
            let up = |a: &mut Vec<f64>, b: &[f64]| {
                for (x, y) in a.iter_mut().zip(b) {
                    *x = x.max(*y);
                }
            };
            up(&mut out.line_drift, &r.line_drift);
            up(&mut out.edge_drift, &r.edge_drift);
            up(&mut out.torsion, &r.torsion);
            up(&mut out.rotation, &r.rotation);
            up(&mut out.slip, &r.slip);
            up(&mut out.residual, &r.residual);
            out.collapsed += r.collapsed;
            for (a, b) in out.devices.fields_mut().into_iter().zip(r.devices.fields()) {
                up(a, b);
            }
        }
        out
    }

    /// Entry by entry statistic of `pairs` (each already enveloped).
    fn statistic(pairs: &[Peaks], stat: PlanStatistic) -> Peaks {
        let n = pairs.len() as f64;
        let reduce = |get: &dyn Fn(&Peaks) -> &Vec<f64>| -> Vec<f64> {
            let len = get(&pairs[0]).len();
            (0..len)
                .map(|i| {
                    let vals = pairs.iter().map(|p| get(p)[i]);
                    match stat {
                        PlanStatistic::Mean => vals.sum::<f64>() / n,
                        PlanStatistic::Max => vals.fold(f64::NEG_INFINITY, f64::max),
                    }
                })
                .collect()
        };
        Peaks {
            line_drift: reduce(&|p| &p.line_drift),
            edge_drift: reduce(&|p| &p.edge_drift),
            torsion: reduce(&|p| &p.torsion),
            rotation: reduce(&|p| &p.rotation),
            slip: reduce(&|p| &p.slip),
            residual: reduce(&|p| &p.residual),
            collapsed: pairs.iter().map(|p| p.collapsed).sum(),
            devices: Devices {
                stroke: reduce(&|p| &p.devices.stroke),
                velocity: reduce(&|p| &p.devices.velocity),
                travel: reduce(&|p| &p.devices.travel),
                energy: reduce(&|p| &p.devices.energy),
                force: reduce(&|p| &p.devices.force),
            },
        }
    }
}

/// A suite's statistic in one property case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Cell {
    /// The suite (index).
    pub suite: usize,
    /// The property case (index).
    pub case: usize,
    /// The statistic of the pairs' peaks.
    pub peaks: Peaks,
    /// The statistic of the scalar measures over the pairs (each pair's largest over its
    /// storeys first): what the objective and limits read.
    pub edge: f64,
    /// Likewise, the largest line drift ratio.
    pub line: f64,
    /// Likewise, the torsional ratio.
    pub torsional: f64,
    /// Likewise, the floor rotation, rad.
    pub rotation: f64,
}

/// One design evaluated.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignEval {
    /// Slip load of every damper, N (`None`: the file's bounds kept).
    pub loads: Vec<Option<f64>>,
    /// Per suite and case, suite after suite.
    pub cells: Vec<Cell>,
}

impl DesignEval {
    /// Runs that collapsed.
    pub fn collapsed(&self) -> usize {
        self.cells.iter().map(|c| c.peaks.collapsed).sum()
    }

    /// The value of `metric` in `cell`.
    fn value(study: &PlanStudy, cell: &Cell, loads: &[Option<f64>], metric: PlanMetric) -> f64 {
        match metric {
            PlanMetric::EdgeDriftRatio => cell.edge,
            PlanMetric::LineDriftRatio => cell.line,
            PlanMetric::Rotation => cell.rotation,
            PlanMetric::TorsionalRatio => cell.torsional,
            PlanMetric::TotalSlipLoad => study
                .space
                .dampers
                .iter()
                .map(|&k| loads[k].unwrap_or(0.0))
                .sum(),
        }
    }

    /// The objective: the worst value of the cells whose case the objective reads (+∞
    /// when a run collapsed).
    pub fn objective(&self, study: &PlanStudy) -> f64 {
        if self.collapsed() > 0 {
            return f64::INFINITY;
        }
        let metric = study.config.objective.metric;
        self.cells
            .iter()
            .filter(|c| study.cases[c.case].objective)
            .map(|c| Self::value(study, c, &self.loads, metric))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Each limit's demand over its limit, per suite (the worst case), in the order
    /// (suite, edge drift, torsion); empty without limits.
    pub fn ratios(&self, study: &PlanStudy) -> Vec<f64> {
        let Some(l) = &study.config.limits else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for s in 0..study.suites.len() {
            let worst = |f: &dyn Fn(&Cell) -> f64| {
                self.cells
                    .iter()
                    .filter(|c| c.suite == s)
                    .map(f)
                    .fold(f64::NEG_INFINITY, f64::max)
            };
            if let Some(v) = l.edge_drift_ratio {
                out.push(worst(&|c| c.edge) / v);
            }
            if let Some(v) = l.torsional_ratio {
                out.push(worst(&|c| c.torsional) / v);
            }
        }
        out
    }

    /// The names of [`DesignEval::ratios`], in their order.
    pub fn ratio_names(study: &PlanStudy) -> Vec<String> {
        let Some(l) = &study.config.limits else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for s in &study.suites {
            if let Some(v) = l.edge_drift_ratio {
                out.push(format!("{}: edge drift ratio <= {}", s.name, v));
            }
            if let Some(v) = l.torsional_ratio {
                out.push(format!("{}: torsional ratio <= {v}", s.name));
            }
        }
        out
    }

    /// Whether every limit passes and nothing collapsed.
    pub fn passes(&self, study: &PlanStudy) -> bool {
        self.collapsed() == 0 && self.ratios(study).iter().all(|r| *r <= 1.0)
    }

    /// What the refiners minimise, and the limit values the model refiner reads: the
    /// objective where the design passes, +∞ otherwise.
    pub fn point_value(&self, study: &PlanStudy) -> (f64, Option<LimitValues>) {
        let objective = self.objective(study);
        if study.config.limits.is_none() {
            return (objective, None);
        }
        let ratios = self.ratios(study);
        let f = if self.passes(study) {
            objective
        } else {
            f64::INFINITY
        };
        (f, Some(LimitValues::new(objective, ratios)))
    }
}

/// How finely the runs step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// Multiplies the study's step (1 for the sweep and refinement; the check's factor
    /// for the final table).
    pub factor: f64,
    /// Whether the runs record each damper's demands (the final table's; the search
    /// does not pay for them).
    pub demands: bool,
}

impl Step {
    /// The search's runs: the study's step, no per-damper demands.
    pub const SEARCH: Step = Step {
        factor: 1.0,
        demands: false,
    };
}

/// One run's task: design, case, suite, pair, orientation.
struct Task {
    design: usize,
    case: usize,
    suite: usize,
    pair: usize,
    angle: usize,
}

/// Evaluates designs given by their slip loads (every damper's, N), in one parallel
/// batch of runs.
pub fn evaluate_loads(
    study: &PlanStudy,
    designs: &[Vec<Option<f64>>],
    step: Step,
) -> Result<Vec<DesignEval>, OptError> {
    // each design's building in each case, built once
    let buildings: Vec<Vec<Arc<FloorPlan>>> = designs
        .iter()
        .map(|loads| {
            (0..study.cases.len())
                .map(|c| Arc::new(study.with_slip_loads(c, loads)))
                .collect()
        })
        .collect();
    let mut tasks = Vec::new();
    for design in 0..designs.len() {
        for case in 0..study.cases.len() {
            for (suite, s) in study.suites.iter().enumerate() {
                for pair in 0..s.pairs.len() {
                    for angle in 0..s.angles_deg.len() {
                        tasks.push(Task {
                            design,
                            case,
                            suite,
                            pair,
                            angle,
                        });
                    }
                }
            }
        }
    }
    let runs: Vec<Result<Peaks, OptError>> = tasks
        .par_iter()
        .map(|t| run_one(study, &buildings[t.design][t.case], t, step))
        .collect();
    let mut runs = runs.into_iter();
    let mut out = Vec::with_capacity(designs.len());
    for loads in designs {
        let mut cells = Vec::new();
        for case in 0..study.cases.len() {
            for (suite, s) in study.suites.iter().enumerate() {
                let mut pairs = Vec::with_capacity(s.pairs.len());
                for _ in 0..s.pairs.len() {
                    let orient: Vec<Peaks> = (0..s.angles_deg.len())
                        .map(|_| runs.next().expect("one run per task"))
                        .collect::<Result<_, _>>()?;
                    pairs.push(Peaks::envelope(&orient));
                }
                let stat = study.config.objective.statistic;
                let scalar = |f: &dyn Fn(&Peaks) -> f64| {
                    let vals = pairs.iter().map(f);
                    match stat {
                        PlanStatistic::Mean => vals.sum::<f64>() / pairs.len() as f64,
                        PlanStatistic::Max => vals.fold(f64::NEG_INFINITY, f64::max),
                    }
                };
                cells.push(Cell {
                    suite,
                    case,
                    edge: scalar(&Peaks::edge),
                    line: scalar(&Peaks::line),
                    torsional: scalar(&Peaks::torsional),
                    rotation: scalar(&Peaks::rot),
                    peaks: Peaks::statistic(&pairs, stat),
                });
            }
        }
        // suite after suite, then case (the order the tables read)
        cells.sort_by_key(|c| (c.suite, c.case));
        out.push(DesignEval {
            loads: loads.clone(),
            cells,
        });
    }
    Ok(out)
}

/// One run: the pair's first component at the orientation, the second at +90°.
fn run_one(
    study: &PlanStudy,
    building: &Arc<FloorPlan>,
    t: &Task,
    step: Step,
) -> Result<Peaks, OptError> {
    let s = &study.suites[t.suite];
    let p = &s.pairs[t.pair];
    let theta = s.angles_deg[t.angle];
    let ground = vec![
        GroundComponent {
            record: p.first.clone(),
            angle: theta.to_radians(),
        },
        GroundComponent {
            record: p.second.clone(),
            angle: (theta + 90.0).to_radians(),
        },
    ];
    let duration = s
        .duration_s
        .unwrap_or_else(|| p.first.duration().max(p.second.duration()));
    let outputs = OutputsConfig {
        energies: false,
        dampers: step.demands,
        ..OutputsConfig::default()
    };
    let mut scene = FloorPlanScene::new(building.clone(), ground, duration, study.method, outputs);
    scene.name = format!("{} at {theta} deg", p.name);
    let dt = study.config.fidelity.dt_s.unwrap_or(scene.method.dt) * step.factor;
    scene.override_with(None, Some(dt), None, false)?;
    let outcome = slipload_sim::floorplan::simulate(&scene)?;
    Ok(peaks_of(&outcome.response, building))
}

/// The study's peaks of one run's response.
fn peaks_of(r: &slipload_sim::Response, b: &FloorPlan) -> Peaks {
    let n = b.storeys();
    let lines = b.lines.len() * n;
    let drift = r.peak_drift_ratio.as_ref().unwrap_or(&r.peak_drift);
    let line_drift = drift[..lines.min(drift.len())].to_vec();
    let edge_drift: Vec<f64> = if b.plan_size.is_some() && drift.len() >= lines + 4 * n {
        (0..n)
            .map(|f| max_of(&drift[lines + 4 * f..lines + 4 * f + 4]))
            .collect()
    } else {
        Vec::new()
    };
    let torsion = r
        .in_plan
        .as_ref()
        .and_then(|p| p.torsional_irregularity.as_ref())
        .map(|t| t.iter().map(|[x, y]| x.max(*y)).collect())
        .unwrap_or_default();
    let rotation = (0..n)
        .map(|f| r.peak_displacement.get(3 * f + 2).copied().unwrap_or(0.0))
        .collect();
    let heights = b.storey_heights.as_ref();
    let residual = (0..n)
        .map(|f| {
            (0..b.lines.len())
                .map(|l| {
                    let d = r
                        .residual_drift
                        .get(l * n + f)
                        .copied()
                        .unwrap_or(0.0)
                        .abs();
                    heights.map_or(d, |h| d / h[f])
                })
                .fold(0.0, f64::max)
        })
        .collect();
    Peaks {
        line_drift,
        edge_drift,
        torsion,
        rotation,
        slip: r.peak_slip.clone(),
        residual,
        collapsed: usize::from(r.collapse.is_some()),
        devices: r
            .dampers
            .as_ref()
            .map_or_else(Devices::default, |d| Devices {
                stroke: d
                    .iter()
                    .map(|x| x.slip_max_pos_m.max(x.slip_max_neg_m))
                    .collect(),
                velocity: d.iter().map(|x| x.peak_slip_velocity_m_s).collect(),
                travel: d.iter().map(|x| x.cumulative_travel_m).collect(),
                energy: d.iter().map(|x| x.energy_j).collect(),
                force: d.iter().map(|x| x.peak_force_n).collect(),
            }),
    }
}
