//! The search of a front: seeded from the sweep's designs, then generations that fill the
//! largest gaps of the current front and push its sparsest points outward, each a batch
//! of designs × every record at the sweep fidelity, journalled task by task.
//!
//! One generation of `batch` designs, from the front of everything evaluated so far
//! (objectives normalised to the front's ideal and nadir):
//! - **fill** (half the batch): the largest gaps between neighbouring front points (two
//!   objectives: consecutive along the front; more: each point and its nearest
//!   neighbour), each proposing the midpoint of the two designs' scaled variables;
//! - **push** (the rest): the front points of largest crowding distance (the ends
//!   first), each moved by a random step in the scaled variables of radius
//!   `initial_radius · 0.75^generation` (at least 0.005), clipped to the box and
//!   shortened until the constraints hold.
//!
//! A proposal within 1e-4 (scaled) of a design already evaluated or proposed is skipped.
//! The proposals depend only on the values evaluated before them and the seed, and every
//! batch's runs are reduced in task order, so the search is the same whatever the thread
//! count; its runs are keyed by the bits of their slip loads in `pareto.jsonl`, so a
//! resumed search proposes the same designs and takes their runs from the journal.

use super::front::{crowding_distance, first_front, normalised};
use super::objectives::objective_vector;
use crate::error::OptError;
use crate::evaluate::{TaskJournal, run_designs_journalled, suite_ranges};
use crate::fidelity::Fidelity;
use crate::metrics::RecordMetrics;
use crate::sampler::SplitMix;
use crate::study::Study;
use crate::sweep::Manifest;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Settings of the front's search (the study's `pareto` object).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParetoConfig {
    /// Designs the search adds to the sweep's (default 100; each runs every record).
    #[serde(default = "default_designs")]
    pub designs: usize,
    /// Designs per generation (default 10).
    #[serde(default = "default_batch")]
    pub batch: usize,
    /// Seed of the push steps (default 1).
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Radius of the first generation's push steps, in variables scaled to [0, 1]
    /// (default 0.1).
    #[serde(default = "default_radius")]
    pub initial_radius: f64,
}

fn default_designs() -> usize {
    100
}
fn default_batch() -> usize {
    10
}
fn default_seed() -> u64 {
    1
}
fn default_radius() -> f64 {
    0.1
}

impl Default for ParetoConfig {
    fn default() -> Self {
        ParetoConfig {
            designs: default_designs(),
            batch: default_batch(),
            seed: default_seed(),
            initial_radius: default_radius(),
        }
    }
}

/// Most designs a front's search may add (liftable with `--allow-large`).
pub const MAX_SEARCH_DESIGNS: usize = 100_000;

impl ParetoConfig {
    /// Checks the settings as written.
    pub fn validate(&self, path: &Path) -> Result<(), OptError> {
        if self.batch == 0 {
            return Err(OptError::invalid(
                path,
                "pareto.batch",
                "must be at least 1",
            ));
        }
        if self.designs > MAX_SEARCH_DESIGNS && !slipload_sim::limits::allow_large() {
            return Err(OptError::invalid(
                path,
                "pareto.designs",
                format!(
                    "{} designs is more than {MAX_SEARCH_DESIGNS} (a front needs hundreds; --allow-large lifts the limit)",
                    self.designs
                ),
            ));
        }
        let r = self.initial_radius;
        if !(r.is_finite() && r > 0.0 && r <= 1.0) {
            return Err(OptError::invalid(
                path,
                "pareto.initial_radius",
                format!("must be in (0, 1], got {r}"),
            ));
        }
        Ok(())
    }
}

/// One evaluated design of a front's search.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluated {
    /// `s0001`… (a sweep design) or `p0001`… (the search's).
    pub label: String,
    /// Scaled variables.
    pub z: Vec<f64>,
    /// Slip loads, N per dissipator.
    pub slip_loads_n: Vec<f64>,
    /// The objective vector at the sweep fidelity (+∞ where the design collapses).
    pub objectives: Vec<f64>,
}

/// What a front's search evaluated.
#[derive(Debug, Clone)]
pub struct Search {
    /// The sweep's sampled designs, then the search's, in order.
    pub evaluated: Vec<Evaluated>,
    /// How many of them the sweep sampled.
    pub sweep_designs: usize,
    /// The bare frame's objective vector (sweep fidelity).
    pub bare: Vec<f64>,
    /// The building file's design's (sweep fidelity).
    pub file: Vec<f64>,
    /// Simulations of the search run now.
    pub ran: usize,
    /// Simulations of the search taken from `pareto.jsonl`.
    pub reused: usize,
}

impl Search {
    /// Simulations at the sweep fidelity behind the front: the sweep's and the search's.
    pub fn simulations(&self, records: usize) -> usize {
        (self.evaluated.len() + 2) * records
    }
}

/// The objective vectors of the sweep's designs (`manifest`, its complete `rows`): the
/// bare frame's, the file's, then the sampled designs as [`Evaluated`].
pub fn sweep_vectors(
    study: &Study,
    manifest: &Manifest,
    rows: &[RecordMetrics],
) -> Result<(Vec<f64>, Vec<f64>, Vec<Evaluated>), OptError> {
    let nr = manifest.records.len();
    let ranges = suite_ranges(study);
    let bare = &rows[..nr];
    let mut bare_v = Vec::new();
    let mut file_v = Vec::new();
    let mut out = Vec::new();
    for (d, design) in manifest.designs.iter().enumerate() {
        let rec = &rows[d * nr..(d + 1) * nr];
        let v = objective_vector(study, &design.slip_loads_n, rec, Some(bare), &ranges)?;
        match (&design.z, d) {
            (_, 0) => bare_v = v,
            (_, 1) => file_v = v,
            (Some(z), _) => out.push(Evaluated {
                label: design.label.clone(),
                z: z.clone(),
                slip_loads_n: design.slip_loads_n.clone(),
                objectives: v,
            }),
            (None, _) => {}
        }
    }
    Ok((bare_v, file_v, out))
}

/// Searches the front of `study` from its sweep (`manifest`, complete `rows`): the
/// generations of [the module](self), at the sweep fidelity, taking runs from `journal`
/// (`pareto.jsonl`) and appending the others.
pub fn search(
    study: &Study,
    manifest: &Manifest,
    rows: &[RecordMetrics],
    journal: Option<&TaskJournal>,
    tick: &(dyn Fn() + Sync),
) -> Result<Search, OptError> {
    let cfg = study.config.pareto.unwrap_or_default();
    let nr = manifest.records.len();
    let (bare, file, mut evaluated) = sweep_vectors(study, manifest, rows)?;
    let sweep_designs = evaluated.len();
    let fid = Fidelity::sweep(study);
    let ranges = suite_ranges(study);
    let bare_rows = &rows[..nr];
    let mut rng = SplitMix::new(cfg.seed);
    let before = journal.map_or(0, TaskJournal::reused);
    let mut added = 0;
    let mut generation = 0;
    let mut ran = 0;
    while added < cfg.designs {
        let n = cfg.batch.min(cfg.designs - added);
        let radius = (cfg.initial_radius * 0.75f64.powi(generation)).max(0.005);
        let zs = propose(study, &evaluated, n, radius, &mut rng);
        if zs.is_empty() {
            break;
        }
        let loads: Vec<Vec<f64>> = zs.iter().map(|z| study.space.slip_loads(z)).collect();
        let runs = run_designs_journalled(study, &loads, &fid, journal, tick)?;
        ran += loads.len() * nr;
        for (z, (l, r)) in zs.into_iter().zip(loads.into_iter().zip(runs)) {
            added += 1;
            let objectives = objective_vector(study, &l, &r, Some(bare_rows), &ranges)?;
            evaluated.push(Evaluated {
                label: format!("p{added:04}"),
                z,
                slip_loads_n: l,
                objectives,
            });
        }
        generation += 1;
    }
    let reused = journal.map_or(0, TaskJournal::reused) - before;
    Ok(Search {
        evaluated,
        sweep_designs,
        bare,
        file,
        ran: ran - reused,
        reused,
    })
}

/// The next generation's designs (scaled variables): fills, then pushes.
fn propose(
    study: &Study,
    evaluated: &[Evaluated],
    n: usize,
    radius: f64,
    rng: &mut SplitMix,
) -> Vec<Vec<f64>> {
    let space = &study.space;
    let finite: Vec<usize> = (0..evaluated.len())
        .filter(|&i| evaluated[i].objectives.iter().all(|v| v.is_finite()))
        .collect();
    let vectors: Vec<Vec<f64>> = finite
        .iter()
        .map(|&i| evaluated[i].objectives.clone())
        .collect();
    let mut front: Vec<usize> = first_front(&vectors)
        .into_iter()
        .map(|k| finite[k])
        .collect();
    front.sort_by(|&a, &b| {
        let (x, y) = (&evaluated[a].objectives, &evaluated[b].objectives);
        x.iter()
            .zip(y)
            .map(|(p, q)| p.total_cmp(q))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
            .then(a.cmp(&b))
    });
    if front.is_empty() {
        return Vec::new();
    }
    let fv: Vec<Vec<f64>> = front
        .iter()
        .map(|&i| evaluated[i].objectives.clone())
        .collect();
    let norm = normalised(&fv);
    let dist = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y) * (x - y))
            .sum::<f64>()
            .sqrt()
    };
    // gaps between neighbours on the front: (length, i, j) in front order
    let mut gaps: Vec<(f64, usize, usize)> = Vec::new();
    if fv[0].len() == 2 {
        for i in 1..front.len() {
            gaps.push((dist(&norm[i - 1], &norm[i]), i - 1, i));
        }
    } else {
        for i in 0..front.len() {
            let nearest = (0..front.len())
                .filter(|&j| j != i)
                .min_by(|&a, &b| dist(&norm[i], &norm[a]).total_cmp(&dist(&norm[i], &norm[b])));
            if let Some(j) = nearest {
                let (a, b) = (i.min(j), i.max(j));
                if !gaps.iter().any(|g| g.1 == a && g.2 == b) {
                    gaps.push((dist(&norm[a], &norm[b]), a, b));
                }
            }
        }
    }
    gaps.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));

    let mut out: Vec<Vec<f64>> = Vec::new();
    let novel = |z: &[f64], out: &[Vec<f64>]| {
        let far = |q: &[f64]| z.iter().zip(q).any(|(a, b)| (a - b).abs() > 1e-4);
        evaluated.iter().all(|e| far(&e.z)) && out.iter().all(|q| far(q))
    };
    let fills = n / 2;
    for &(_, a, b) in &gaps {
        if out.len() >= fills {
            break;
        }
        let z: Vec<f64> = evaluated[front[a]]
            .z
            .iter()
            .zip(&evaluated[front[b]].z)
            .map(|(x, y)| 0.5 * (x + y))
            .collect();
        if space.is_feasible(&z) && novel(&z, &out) {
            out.push(z);
        }
    }
    // pushes: the sparsest front points first (the ends have infinite crowding)
    let crowd = crowding_distance(&norm);
    let mut order: Vec<usize> = (0..front.len()).collect();
    order.sort_by(|&a, &b| crowd[b].total_cmp(&crowd[a]).then(a.cmp(&b)));
    let d = space.dim();
    let mut attempts = 0;
    let mut k = 0;
    while out.len() < n && attempts < 50 * n {
        attempts += 1;
        let base = &evaluated[front[order[k % order.len()]]].z;
        k += 1;
        let step: Vec<f64> = (0..d)
            .map(|_| radius * (2.0 * rng.uniform() - 1.0))
            .collect();
        let mut scale = 1.0;
        let mut found = None;
        for _ in 0..6 {
            let z: Vec<f64> = base
                .iter()
                .zip(&step)
                .map(|(b, s)| (b + scale * s).clamp(0.0, 1.0))
                .collect();
            if space.is_feasible(&z) {
                found = Some(z);
                break;
            }
            scale *= 0.5;
        }
        if let Some(z) = found
            && novel(&z, &out)
        {
            out.push(z);
        }
    }
    out
}
