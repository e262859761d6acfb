//! The search of a front: seeded from the sweep's designs, then generations of polls
//! around the front (a multi-objective pattern search, after Custódio et al.'s direct
//! multisearch, 2011), each a batch of designs × every record at the sweep fidelity,
//! journalled task by task.
//!
//! One generation of `batch` designs, from the front of everything evaluated so far
//! (objectives normalised to the front's ideal and nadir):
//! - **fill** (a fifth of the batch): the largest gaps between neighbouring front points
//!   (two objectives: consecutive along the front; more: each point and its nearest
//!   neighbour), each proposing the midpoint of the two designs' scaled variables;
//! - **surrogates** (one per objective, then one per largest gap, up to
//!   `SURROGATE_GAPS`): the designs minimising augmented Tchebycheff scalarisations of
//!   a cubic radial-basis surrogate of each objective over everything evaluated, aimed
//!   at each end of the front and at its largest gaps, over a fixed candidate set
//!   ([`super::surrogate`]) — the global part of the search, which can reach a basin
//!   the polls around the front do not;
//! - **ends** (up to a fifth each): each objective's best design polled along ± each
//!   scaled variable at its own step;
//! - **polls** (the rest): the front points by their exclusive hypervolume contribution,
//!   largest first, polled the same way.
//!
//! Every design carries a poll step (scaled variables; `initial_radius` for the sweep's,
//! its parent's for a polled design). A point whose polls put no design on the front
//! halves its step; a point whose polls are all evaluated already halves it before
//! polling, down to `MIN_STEP`. A poll is clipped to the box and must satisfy the
//! constraints; a proposal within 1e-4 (scaled) of a design already evaluated or
//! proposed is skipped.
//!
//! The proposals depend only on the values evaluated before them (no random numbers),
//! and every batch's runs are reduced in task order, so the search is the same whatever
//! the thread count; its runs are keyed by the bits of their slip loads in
//! `pareto.jsonl`, so a resumed search proposes the same designs and takes their runs
//! from the journal.

use super::front::{first_front, ideal_and_nadir, normalised};
use super::vector::objective_vector;
use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::eval::evaluate::{TaskJournal, run_designs_journalled, suite_ranges};
use crate::model::check::DesignCheck;
use crate::model::fidelity::Fidelity;
use crate::model::study::Study;
use crate::phases::sweep::Manifest;

/// Where a design of a front came from: every design a study evaluated at the sweep
/// fidelity is a candidate for its front.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// The sweep's sample (`s0001`…).
    Sweep,
    /// The front's search (`p0001`…).
    Search,
    /// The building file's design (`file`), where the space holds it.
    File,
    /// The refinement's evaluations (`r0001`…, in the order it made them).
    Refine,
}

impl Source {
    /// The word `pareto.csv` writes in its `source` column.
    pub fn as_str(self) -> &'static str {
        match self {
            Source::Sweep => "sweep",
            Source::Search => "search",
            Source::File => "file",
            Source::Refine => "refine",
        }
    }
}

/// One evaluated design of a front's search.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluated {
    /// `s0001`… (a sweep design), `p0001`… (the search's), `file`, or `r0001`… (the
    /// refinement's).
    pub label: String,
    /// Where it came from.
    pub source: Source,
    /// Scaled variables.
    pub z: Vec<f64>,
    /// Slip loads, N per dissipator.
    pub slip_loads_n: Vec<f64>,
    /// The objective vector at the sweep fidelity (+∞ where the design collapses).
    pub objectives: Vec<f64>,
    /// The study's objective at the sweep fidelity, and its check against the limits
    /// (a study with limits): what the refiners read, so every design the search
    /// evaluated is a start and a finalist candidate of the refinement too.
    pub scalar: Option<(f64, Option<DesignCheck>)>,
}

/// What a front's search evaluated.
#[derive(Debug, Clone)]
pub struct Search {
    /// The sweep's sampled designs, then the search's, in order.
    pub evaluated: Vec<Evaluated>,
    /// How many of them the sweep sampled.
    pub sweep_designs: usize,
    /// How many the search itself evaluated (after the sweep's; the file's and the
    /// refinement's designs, added as candidates of the front, come after these).
    pub search_designs: usize,
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
        (self.sweep_designs + self.search_designs + 2) * records
    }
}

/// The bare frame's objective vector, the file's design's, and the sweep's sampled
/// designs ([`sweep_vectors`]).
pub type SweepVectors = (Vec<f64>, Vec<f64>, Vec<Evaluated>);

/// The objective vectors of the sweep's designs (`manifest`, its complete `rows`): the
/// bare frame's, the file's, then the sampled designs as [`Evaluated`].
pub fn sweep_vectors(
    study: &Study,
    manifest: &Manifest,
    rows: &[RecordMetrics],
) -> Result<SweepVectors, OptError> {
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
                source: Source::Sweep,
                z: z.clone(),
                slip_loads_n: design.slip_loads_n.clone(),
                objectives: v,
                scalar: None,
            }),
            (None, _) => {}
        }
    }
    Ok((bare_v, file_v, out))
}

/// Searches the front of `study` from its sweep (`manifest`, complete `rows`): the
/// generations of [the module](self) until `pareto.designs` designs are evaluated (or
/// no poll is left), at the sweep fidelity, taking runs from `journal` (`pareto.jsonl`)
/// and appending the others.
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
    let before = journal.map_or(0, TaskJournal::reused);
    let mut added = 0;
    let mut ran = 0;
    // each design's poll step (scaled variables)
    let mut steps: Vec<f64> = vec![cfg.initial_radius; evaluated.len()];
    while added < cfg.designs {
        let n = cfg.batch.min(cfg.designs - added);
        let (zs, parents) = propose(study, &evaluated, &mut steps, n);
        if zs.is_empty() {
            break;
        }
        let first_new = evaluated.len();
        let loads: Vec<Vec<f64>> = zs.iter().map(|z| study.space.slip_loads(z)).collect();
        let runs = run_designs_journalled(study, &loads, &fid, journal, tick)?;
        ran += loads.len() * nr;
        for (z, (l, r)) in zs.into_iter().zip(loads.into_iter().zip(runs)) {
            added += 1;
            let objectives = objective_vector(study, &l, &r, Some(bare_rows), &ranges)?;
            let scalar = scalar_of(study, &l, &r, bare_rows)?;
            evaluated.push(Evaluated {
                label: format!("p{added:04}"),
                source: Source::Search,
                z,
                slip_loads_n: l,
                objectives,
                scalar: Some(scalar),
            });
        }
        // a point whose polls found nothing on the front halves its step; a design
        // found takes its parent's step
        let vectors: Vec<Vec<f64>> = evaluated.iter().map(|e| e.objectives.clone()).collect();
        let ranks = super::front::nondominated_ranks(&vectors);
        let mut polled: Vec<(usize, bool)> = Vec::new();
        for (k, p) in parents.iter().enumerate() {
            let child = first_new + k;
            steps.push(p.map_or(cfg.initial_radius, |i| steps[i]));
            if let Some(i) = *p {
                let hit = ranks[child] == 1 && vectors[child].iter().all(|v| v.is_finite());
                match polled.iter_mut().find(|(j, _)| *j == i) {
                    Some(e) => e.1 |= hit,
                    None => polled.push((i, hit)),
                }
            }
        }
        for (i, hit) in polled {
            if !hit {
                steps[i] *= 0.5;
            }
        }
    }
    let reused = journal.map_or(0, TaskJournal::reused) - before;
    Ok(Search {
        search_designs: evaluated.len() - sweep_designs,
        evaluated,
        sweep_designs,
        bare,
        file,
        ran: ran - reused,
        reused,
    })
}

/// The study's objective of a design (slip loads `loads_n`, N) from its `rows` (sweep
/// fidelity) and, with limits, its check: what a refiner reads of it.
pub fn scalar_of(
    study: &Study,
    loads_n: &[f64],
    rows: &[RecordMetrics],
    bare: &[RecordMetrics],
) -> Result<(f64, Option<DesignCheck>), OptError> {
    let f = study.objective_value(rows, bare, loads_n)?;
    let check = if study.checks.has_limits() {
        Some(study.check_design(rows)?)
    } else {
        None
    };
    Ok((f, check))
}

/// Gaps of the front a generation's surrogate proposals aim at (after each objective's
/// end).
const SURROGATE_GAPS: usize = 7;

/// Designs proposed by the surrogates ([`super::surrogate`]) in one generation, up to
/// `room` of them: one per objective's end, then one per largest gap (up to
/// [`SURROGATE_GAPS`]), none within the surrogate's separation of `evaluated` or
/// `proposed`. The surrogates fit the designs of lowest non-dominated rank (up to
/// [`super::surrogate::MAX_FIT`]), each objective normalised to the current front's ideal
/// and nadir; none when the fit fails (too few designs, or a singular system).
fn surrogate_proposals(
    space: &crate::model::space::DesignSpace,
    evaluated: &[Evaluated],
    front: &[usize],
    norm: &[Vec<f64>],
    gaps: &[(f64, usize, usize)],
    proposed: &[Vec<f64>],
    room: usize,
) -> Vec<Vec<f64>> {
    use super::surrogate::{CLIP, MAX_FIT, Rbf, candidates, propose, weights};
    let k = norm.first().map_or(0, Vec::len);
    if room == 0 || k == 0 {
        return Vec::new();
    }
    let (lo, hi) = ideal_and_nadir(k, front.iter().map(|&i| evaluated[i].objectives.as_slice()));
    let (finite, vectors) = finite_objectives(evaluated);
    let ranks = super::front::nondominated_ranks(&vectors);
    let mut fit: Vec<usize> = (0..finite.len()).collect();
    fit.sort_by_key(|&j| (ranks[j], j));
    fit.truncate(MAX_FIT);
    fit.sort_unstable();
    let points: Vec<Vec<f64>> = fit
        .iter()
        .map(|&j| evaluated[finite[j]].z.clone())
        .collect();
    let mut fits = Vec::with_capacity(k);
    for m in 0..k {
        let range = hi[m] - lo[m];
        let values: Vec<f64> = fit
            .iter()
            .map(|&j| {
                let v = vectors[j][m];
                let s = if range > 0.0 {
                    (v - lo[m]) / range
                } else {
                    0.0
                };
                s.min(CLIP)
            })
            .collect();
        match Rbf::fit(&points, &values) {
            Some(f) => fits.push(f),
            None => return Vec::new(),
        }
    }
    let around: Vec<&[f64]> = front.iter().map(|&i| evaluated[i].z.as_slice()).collect();
    let cands = candidates(space, &around);
    let pairs: Vec<(usize, usize)> = gaps.iter().map(|g| (g.1, g.2)).collect();
    let mut w = weights(norm, &pairs, SURROGATE_GAPS);
    w.truncate(room);
    let mut taken: Vec<Vec<f64>> = evaluated.iter().map(|e| e.z.clone()).collect();
    taken.extend(proposed.iter().cloned());
    propose(&fits, &cands, &w, &taken)
}

/// Smallest poll step, scaled (1/400 of a variable's range: 5 kN on the benchmark).
const MIN_STEP: f64 = 0.0025;

/// The next generation: a fifth of the batch fills the largest gaps of the front
/// (midpoints), then the surrogates' proposals, and the rest polls the front's ends and
/// sparsest points along ± each variable at the point's own step (halved when a poll
/// around it found nothing new). Returns the designs and, for each, the point it was
/// polled from (`None` for a fill or a surrogate's proposal).
fn propose(
    study: &Study,
    evaluated: &[Evaluated],
    steps: &mut [f64],
    n: usize,
) -> (Vec<Vec<f64>>, Vec<Option<usize>>) {
    let space = &study.space;
    let Some((front, norm)) = current_front(evaluated) else {
        return (Vec::new(), Vec::new());
    };
    let gaps = gaps(&norm);
    let mut out: Vec<Vec<f64>> = Vec::new();
    let mut parents: Vec<Option<usize>> = Vec::new();
    let novel = |z: &[f64], out: &[Vec<f64>]| {
        let far = |q: &[f64]| z.iter().zip(q).any(|(a, b)| (a - b).abs() > 1e-4);
        evaluated.iter().all(|e| far(&e.z)) && out.iter().all(|q| far(q))
    };
    let fills = n / 5;
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
            parents.push(None);
        }
    }
    // the surrogate's proposals: each objective's end, then the largest gaps
    for z in surrogate_proposals(space, evaluated, &front, &norm, &gaps, &out, n - out.len()) {
        out.push(z);
        parents.push(None);
    }
    let order = by_contribution(&norm);
    let d = space.dim();
    // each objective's end of the front first, a fifth of the batch each, then the
    // points of largest contribution
    let k = norm.first().map_or(0, Vec::len);
    let ends: Vec<usize> = (0..k)
        .map(|m| {
            (0..front.len())
                .min_by(|&a, &b| norm[a][m].total_cmp(&norm[b][m]).then(a.cmp(&b)))
                .unwrap_or(0)
        })
        .collect();
    let per_end = n.div_ceil(5);
    let mut plan: Vec<(usize, usize)> = ends.iter().map(|&e| (e, per_end)).collect();
    plan.extend(order.iter().map(|&o| (o, usize::MAX)));
    for (o, cap) in plan {
        if out.len() >= n {
            break;
        }
        if cap == 0 {
            continue;
        }
        let i = front[o];
        let base = evaluated[i].z.clone();
        loop {
            let h = steps[i];
            let mut polls = Vec::new();
            for j in 0..d {
                for sign in [1.0, -1.0] {
                    let mut z = base.clone();
                    z[j] = (z[j] + sign * h).clamp(0.0, 1.0);
                    if z[j] != base[j] && space.is_feasible(&z) {
                        polls.push(z);
                    }
                }
            }
            let fresh: Vec<Vec<f64>> = polls.into_iter().filter(|z| novel(z, &out)).collect();
            if fresh.is_empty() {
                if h * 0.5 < MIN_STEP {
                    break;
                }
                steps[i] = h * 0.5;
                continue;
            }
            for z in fresh.into_iter().take(cap) {
                if out.len() < n {
                    out.push(z);
                    parents.push(Some(i));
                }
            }
            break;
        }
    }
    (out, parents)
}

/// The points of a front (normalised objectives) by their exclusive hypervolume
/// contribution, largest first (ties by index), against the reference point 1.1 in every
/// objective (the nadir plus a tenth of the range): the points beside the largest gaps,
/// and the ends by how much the front would lose without them.
fn by_contribution(norm: &[Vec<f64>]) -> Vec<usize> {
    let k = norm.first().map_or(0, Vec::len);
    let reference = vec![1.1; k];
    let total = super::front::hypervolume(norm, &reference);
    let contribution: Vec<f64> = (0..norm.len())
        .map(|i| {
            let rest: Vec<Vec<f64>> = norm
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, p)| p.clone())
                .collect();
            total - super::front::hypervolume(&rest, &reference)
        })
        .collect();
    let mut order: Vec<usize> = (0..norm.len()).collect();
    order.sort_by(|&a, &b| contribution[b].total_cmp(&contribution[a]).then(a.cmp(&b)));
    order
}

/// The designs whose objectives are all finite (indices into `evaluated`) and their
/// objective vectors, in the same order.
fn finite_objectives(evaluated: &[Evaluated]) -> (Vec<usize>, Vec<Vec<f64>>) {
    let finite: Vec<usize> = (0..evaluated.len())
        .filter(|&i| evaluated[i].objectives.iter().all(|v| v.is_finite()))
        .collect();
    let vectors = finite
        .iter()
        .map(|&i| evaluated[i].objectives.clone())
        .collect();
    (finite, vectors)
}

/// The front of the designs evaluated so far (indices, sorted by the objectives) and its
/// normalised objectives; `None` when no design stands.
fn current_front(evaluated: &[Evaluated]) -> Option<(Vec<usize>, Vec<Vec<f64>>)> {
    let (finite, vectors) = finite_objectives(evaluated);
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
        return None;
    }
    let fv: Vec<Vec<f64>> = front
        .iter()
        .map(|&i| evaluated[i].objectives.clone())
        .collect();
    let norm = normalised(&fv);
    Some((front, norm))
}

/// Gaps between neighbours of a front (normalised objectives, in front order): two
/// objectives, consecutive points; more, each point and its nearest neighbour. Largest
/// first: (length, i, j).
fn gaps(norm: &[Vec<f64>]) -> Vec<(f64, usize, usize)> {
    let dist = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y) * (x - y))
            .sum::<f64>()
            .sqrt()
    };
    let mut gaps: Vec<(f64, usize, usize)> = Vec::new();
    if norm.first().map_or(0, Vec::len) == 2 {
        for i in 1..norm.len() {
            gaps.push((dist(&norm[i - 1], &norm[i]), i - 1, i));
        }
    } else {
        for i in 0..norm.len() {
            let nearest = (0..norm.len())
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
    gaps
}
