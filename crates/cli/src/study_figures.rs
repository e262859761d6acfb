//! The data of the study figures (`optimize`, `sweep`), each with the CSV written beside
//! its figure:
//! - objective map over the slip loads of two dissipators, the others held at the
//!   optimum (new simulations at the sweep fidelity, run by the sweep's parallel
//!   evaluation code; opt-in);
//! - the refiners' convergence: best objective so far vs simulations, per refiner whose
//!   journal (`refine-METHOD.jsonl`) is in the folder;
//! - peak drift-ratio profiles over the storeys of the ranked designs (mean and 84th
//!   percentile over the suite);
//! - per-record peak drift ratio of the optimum vs the bare frame.

use anyhow::{Context, bail};
use slipload_opt::evaluate::Fidelity;
use slipload_opt::optimize::objectives;
use slipload_opt::refine::Point;
use slipload_opt::space::SpaceConfig;
use slipload_opt::sweep::Manifest;
use slipload_opt::{RecordMetrics, Statistic, Study};
use std::fmt::Write as _;
use std::path::Path;

/// The objective over a grid of two dissipators' slip loads.
#[derive(Debug, Clone)]
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

impl ObjectiveMap {
    /// `slip_load_kN_A,slip_load_kN_B,objective`, one line per grid point.
    pub fn to_csv(&self) -> String {
        let [a, b] = self.floors;
        let mut s = format!("slip_load_kN_{a},slip_load_kN_{b},objective\n");
        let nb = self.loads_b_kn.len();
        for (i, x) in self.loads_a_kn.iter().enumerate() {
            for (j, y) in self.loads_b_kn.iter().enumerate() {
                let _ = writeln!(s, "{x},{y},{}", self.objective[i * nb + j]);
            }
        }
        s
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

/// The dissipator indices of the map's two floors (from 1), checked before any
/// simulation: two different floors that have dissipators, and a grid of at least 2.
pub fn map_dampers(study: &Study, floors: [usize; 2], grid: usize) -> anyhow::Result<[usize; 2]> {
    if floors[0] == floors[1] {
        bail!(
            "--map-floors: give two different floors (got {0},{0})",
            floors[0]
        );
    }
    if grid < 2 {
        bail!("--map-grid must be at least 2 (got {grid})");
    }
    let damper = |f: usize| -> anyhow::Result<usize> {
        study
            .space
            .dampers
            .iter()
            .position(|&d| d + 1 == f)
            .with_context(|| {
                format!(
                    "--map-floors: floor {f} has no dissipator (floors with one: {})",
                    study
                        .space
                        .dampers
                        .iter()
                        .map(|d| (d + 1).to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            })
    };
    Ok([damper(floors[0])?, damper(floors[1])?])
}

/// Runs the objective map: `grid` × `grid` designs over the bounds of the dissipators on
/// `floors` (from 1), every other slip load at `optimum` (N per dissipator), each over
/// every record at the sweep fidelity. `bare` holds the bare frame's responses at that
/// fidelity (the sweep's first design).
pub fn objective_map(
    study: &Study,
    optimum: &[f64],
    bare: &[RecordMetrics],
    floors: [usize; 2],
    grid: usize,
    tick: &(dyn Fn() + Sync),
) -> anyhow::Result<ObjectiveMap> {
    let [ka, kb] = map_dampers(study, floors, grid)?;
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
    let objective = objectives(study, &designs, bare, &Fidelity::sweep(study), tick)
        .context("objective map simulations")?;
    Ok(ObjectiveMap {
        floors,
        loads_a_kn: xa.iter().map(|v| v / 1e3).collect(),
        loads_b_kn: xb.iter().map(|v| v / 1e3).collect(),
        objective,
        optimum_kn: [optimum[ka] / 1e3, optimum[kb] / 1e3],
        label: study.objective.label(),
    })
}

/// One refiner's path: best objective so far vs simulations.
#[derive(Debug, Clone)]
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
) -> anyhow::Result<Vec<Convergence>> {
    let mut names: Vec<(String, std::path::PathBuf)> = std::fs::read_dir(dir)
        .with_context(|| format!("reading {}", dir.display()))?
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
        let points = slipload_opt::journal::read_entries::<Point>(&path)
            .with_context(|| format!("reading refine journal {}", path.display()))?;
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

/// `refiner,simulations,objective,best_so_far`.
pub fn convergence_csv(paths: &[Convergence]) -> String {
    let mut s = String::from("refiner,simulations,objective,best_so_far\n");
    for c in paths {
        for (n, f, b) in &c.points {
            let _ = writeln!(s, "{},{n},{f},{b}", csv_field(&c.refiner));
        }
    }
    s
}

/// Peak drift-ratio profile of one design over the storeys.
#[derive(Debug, Clone)]
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

/// `design,storey,drift_ratio_mean,drift_ratio_p84`.
pub fn drift_profiles_csv(profiles: &[DriftProfile]) -> String {
    let mut s = String::from("design,storey,drift_ratio_mean,drift_ratio_p84\n");
    for p in profiles {
        for (i, (m, q)) in p.mean.iter().zip(&p.p84).enumerate() {
            let _ = writeln!(s, "{},{},{m},{q}", csv_field(&p.design), i + 1);
        }
    }
    s
}

/// Peak drift ratio (max over storeys) per record: a design vs the bare frame.
#[derive(Debug, Clone)]
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

    /// `record,bare_peak_drift_ratio,DESIGN_peak_drift_ratio`.
    pub fn to_csv(&self) -> String {
        let mut s = format!(
            "record,bare_peak_drift_ratio,{}_peak_drift_ratio\n",
            self.design
        );
        for ((r, b), d) in self.records.iter().zip(&self.bare).zip(&self.design_values) {
            let _ = writeln!(s, "{},{b},{d}", csv_field(r));
        }
        s
    }
}

/// A CSV field, quoted when it holds a comma, a quote or a line break.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The figures of one study run, written by [`StudyFigures::write`].
#[derive(Debug, Clone)]
pub struct StudyFigures {
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
}

impl StudyFigures {
    /// Writes every figure present (`NAME.svg`, `NAME.png`, in the shared plot style)
    /// with its data (`NAME.csv`) into `dir`; returns the names written.
    pub fn write(&self, dir: &Path) -> anyhow::Result<Vec<String>> {
        use crate::plot::{Figure, HeatMap, Legend, Marker, Panel, Series, style};
        let mut names = Vec::new();
        let mut put = |stem: &str, csv: String, fig: Figure| -> anyhow::Result<()> {
            slipload_opt::output::write_atomic(&dir.join(format!("{stem}.csv")), csv.as_bytes())?;
            fig.save(&dir.join(stem))?;
            names.push(stem.to_string());
            Ok(())
        };
        if let Some(m) = &self.map {
            let [a, b] = m.floors;
            let nb = m.loads_b_kn.len();
            let z: Vec<Vec<f64>> = (0..nb)
                .map(|j| {
                    (0..m.loads_a_kn.len())
                        .map(|i| m.objective[i * nb + j])
                        .collect()
                })
                .collect();
            let fig = Figure::new(format!("Objective map: {}", m.label)).panel(
                Panel::new(
                    format!("slip load, floor {a} (kN)"),
                    format!("slip load, floor {b} (kN)"),
                )
                .title("other floors at the optimum")
                .legend(Legend::UpperRight)
                .heatmap(HeatMap {
                    x: m.loads_a_kn.clone(),
                    y: m.loads_b_kn.clone(),
                    z,
                    label: format!("{} (-)", m.label),
                    z_range: None,
                })
                .series(
                    Series::scatter("optimum", vec![m.optimum_kn[0]], vec![m.optimum_kn[1]])
                        .marker(Marker::Diamond)
                        .rgb(style::INK),
                ),
            );
            put("objective-map", m.to_csv(), fig)?;
        }
        if !self.convergence.is_empty() {
            let mut panel = Panel::new("simulations (-)", "best objective so far (-)")
                .legend(Legend::UpperRight);
            for (k, c) in self.convergence.iter().enumerate() {
                let x = c.points.iter().map(|p| p.0 as f64).collect();
                let y = c.points.iter().map(|p| p.2).collect();
                panel = panel.series(
                    Series::line(c.refiner.clone(), x, y)
                        .color(k)
                        .marker(Marker::ALL[k % Marker::ALL.len()]),
                );
            }
            let fig = Figure::new("Refiner convergence").panel(panel);
            put("convergence", convergence_csv(&self.convergence), fig)?;
        }
        if !self.profiles.is_empty() {
            let storeys = self
                .profiles
                .iter()
                .map(|p| p.mean.len())
                .max()
                .unwrap_or(1);
            let mut panel = Panel::new("peak drift ratio (%)", "storey (-)")
                .title(format!(
                    "solid: mean, dashed: 84th percentile; {}",
                    self.fidelity
                ))
                .x_from_zero()
                .y_range(0.5, storeys as f64 + 0.5)
                .y_integer()
                .legend(Legend::UpperRight);
            for (k, p) in self.profiles.iter().enumerate() {
                let storeys: Vec<f64> = (1..=p.mean.len()).map(|i| i as f64).collect();
                let pct = |v: &[f64]| v.iter().map(|x| 100.0 * x).collect::<Vec<_>>();
                panel = panel
                    .series(
                        Series::line(p.design.clone(), pct(&p.mean), storeys.clone())
                            .color(k)
                            .marker(Marker::Circle),
                    )
                    .series(
                        Series::line(format!("{} p84", p.design), pct(&p.p84), storeys)
                            .color(k)
                            .dashed()
                            .no_legend(),
                    );
            }
            let fig = Figure::new("Peak drift-ratio profiles of the ranked designs").panel(panel);
            put("drift-profiles", drift_profiles_csv(&self.profiles), fig)?;
        }
        if let Some(sc) = &self.scatter {
            let x: Vec<f64> = sc.bare.iter().map(|v| 100.0 * v).collect();
            let y: Vec<f64> = sc.design_values.iter().map(|v| 100.0 * v).collect();
            let top = x.iter().chain(&y).copied().fold(0.0, f64::max);
            let fig = Figure::new(format!("Per record: {} vs bare frame", sc.design)).panel(
                Panel::new(
                    "bare frame: peak drift ratio (%)",
                    format!("{}: peak drift ratio (%)", sc.design),
                )
                .title(self.fidelity.clone())
                .x_from_zero()
                .y_from_zero()
                .legend(Legend::UpperLeft)
                .series(Series::scatter("records", x, y).color(0))
                .series(
                    Series::line("1:1", vec![0.0, top], vec![0.0, top])
                        .dashed()
                        .rgb(style::INK),
                ),
            );
            put("records-scatter", sc.to_csv(), fig)?;
        }
        Ok(names)
    }
}

/// A sweep's figures from its manifest and responses alone (no new simulations), so a
/// single run and `merge` of its shards draw the same bytes: drift profiles of the three
/// best designs, the building file's design and the bare frame; the best design vs the
/// bare frame per record.
pub fn sweep_figures(m: &Manifest, rows: &[RecordMetrics]) -> anyhow::Result<StudyFigures> {
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
    Ok(StudyFigures {
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
    })
}
