//! Design tables: for each design (the optimum, uniform and storey-shear-proportional
//! designs of the same total slip load, the building file's slip loads, the bare frame)
//! the slip loads per floor and the responses they buy, over every record of the study
//! at the check fidelity (reference accuracy, energies on). Per-floor and response
//! statistics pool the records of all suites; the objective keeps its own definition.
//! Robustness: the objective with every slip load scaled by 0.75 and by 1.25.

use crate::base::collapse::{objective_text, reduction, reduction_text};
use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::eval::evaluate::{DesignLoads, TaskJournal, run_designs_journalled, suite_ranges};
use crate::model::fidelity::Fidelity;
use crate::model::objective::{Metric, Statistic};
use crate::model::sampler::FrictionLaw;
use crate::model::study::Study;
use crate::store::folder::StudyFolder;
use serde::{Deserialize, Serialize};
use slipload_motion::G;
use std::fmt::Write as _;

/// What a table shows where a storey has no damper (no slip load, stroke or ratio).
pub const NONE: &str = "—";

/// One row of a design table (SI unless the name says otherwise).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TableRow {
    /// Design name.
    pub design: String,
    /// Slip load per dissipator, kN.
    pub slip_load_kn: Vec<f64>,
    /// The friction law per dissipator, kN, where the design is the building file's and
    /// the file writes more than symmetric slip loads (`locked`, asymmetric bounds): it,
    /// not `slip_load_kn`, is what ran.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction_kn: Option<Vec<FrictionLaw>>,
    /// Slip load / floor weight (m_i g).
    pub ratio_to_floor_weight: Vec<f64>,
    /// Slip load / weight above the storey (Σ_{j≥i} m_j g, the storey's gravity shear).
    pub ratio_to_weight_above: Vec<f64>,
    /// Peak drift ratio per storey: mean over the records.
    pub drift_ratio_mean: Vec<f64>,
    /// Peak drift ratio per storey: 84th percentile.
    pub drift_ratio_p84: Vec<f64>,
    /// Peak drift ratio per storey: max.
    pub drift_ratio_max: Vec<f64>,
    /// The study's objective (`"collapsed"` when the design collapses on a record:
    /// [`crate::base::collapse`]).
    #[serde(with = "crate::base::collapse::objective_serde")]
    pub objective: f64,
    /// 1 − objective / objective of the bare frame (`"collapsed"`, or `"bare frame
    /// collapsed"` when only the reference collapses).
    #[serde(with = "crate::base::collapse::reduction_serde")]
    pub objective_reduction: f64,
    /// Mean over records of the peak drift ratio (max over storeys).
    pub peak_drift_ratio_mean: f64,
    /// 1 − that / the bare frame's (in words when either collapses on a record).
    #[serde(with = "crate::base::collapse::reduction_serde")]
    pub peak_drift_reduction: f64,
    /// Mean residual drift ratio (max over storeys) over the records run to their end (a
    /// run that stopped on the collapse limit has none); `"collapsed"` when every run
    /// stopped.
    #[serde(with = "crate::base::collapse::objective_serde")]
    pub residual_drift_ratio_mean: f64,
    /// Mean peak floor acceleration, m/s².
    pub peak_floor_acceleration_mean: f64,
    /// Mean peak base shear, N.
    pub base_shear_mean: f64,
    /// Damper stroke per storey, max over records, m.
    pub stroke_max: Vec<f64>,
    /// Mean E_friction / E_input.
    pub energy_ratio_mean: f64,
    /// Mean relative performance index (Filiatrault & Cherry 1988).
    pub rpi_mean: f64,
    /// Objective with every slip load × 0.75.
    #[serde(with = "crate::base::collapse::objective_serde")]
    pub objective_at_75pct: f64,
    /// Objective with every slip load × 1.25.
    #[serde(with = "crate::base::collapse::objective_serde")]
    pub objective_at_125pct: f64,
    /// Per suite, for a frame whose storeys yield or carry P-Δ (absent otherwise): the
    /// responses at each intensity level, ductility, hysteretic energy and collapses.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub by_suite: Option<Vec<SuiteStats>>,
}

impl TableRow {
    /// A CSV ratio cell of a dissipator with friction law `law`: `locked`, or the ratio
    /// of its upper bound F⁺.
    fn ratio_cell(&self, law: FrictionLaw, ratio: f64) -> String {
        match law {
            FrictionLaw::Locked => "locked".into(),
            FrictionLaw::Bounds(_) => ratio.to_string(),
        }
    }

    /// A Markdown ratio cell of dissipator `k`: `locked`, or the ratio to 3 decimals.
    fn ratio_md(&self, k: usize, ratio: f64) -> String {
        match self.friction_kn.as_ref().map(|l| l[k]) {
            Some(FrictionLaw::Locked) => "locked".into(),
            _ => format!("{ratio:.3}"),
        }
    }
}

/// One design's responses over one suite (a yielding or P-Δ frame).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SuiteStats {
    /// Suite name.
    pub suite: String,
    /// Records in the suite.
    pub records: usize,
    /// Records on which the design collapsed (the run passed the drift limit).
    pub collapses: usize,
    /// Peak drift ratio (max over storeys): mean over the records.
    pub peak_drift_ratio_mean: f64,
    /// Peak drift ratio: max over the records.
    pub peak_drift_ratio_max: f64,
    /// Residual drift ratio (max over storeys): mean over the records run to their end
    /// (`"collapsed"` when every run stopped on the collapse limit).
    #[serde(with = "crate::base::collapse::objective_serde")]
    pub residual_drift_ratio_mean: f64,
    /// Peak storey ductility (max over storeys): mean over the records (`None` when no
    /// storey yields).
    pub peak_ductility_mean: Option<f64>,
    /// Peak storey ductility: max over the records.
    pub peak_ductility_max: Option<f64>,
    /// Hysteretic (plastic) energy of the frame, J: mean over the records.
    pub hysteretic_energy_mean: Option<f64>,
    /// Friction share of the dissipated energy, E_f / (E_f + E_p): mean over the records.
    pub friction_share_mean: Option<f64>,
}

impl SuiteStats {
    fn of(suite: &str, r: &[RecordMetrics]) -> SuiteStats {
        let opt_mean = |v: Vec<Option<f64>>| -> Option<f64> {
            v.into_iter()
                .collect::<Option<Vec<f64>>>()
                .map(|v| Statistic::Mean.of(&v))
        };
        let mu: Vec<Option<f64>> = r.iter().map(RecordMetrics::peak_ductility).collect();
        let mu_max = mu
            .iter()
            .copied()
            .collect::<Option<Vec<f64>>>()
            .map(|v| Statistic::Max.of(&v));
        SuiteStats {
            suite: suite.to_string(),
            records: r.len(),
            collapses: r.iter().filter(|m| m.collapsed()).count(),
            peak_drift_ratio_mean: mean(r.iter().map(RecordMetrics::peak_drift_ratio)),
            peak_drift_ratio_max: Statistic::Max.of(&r
                .iter()
                .map(RecordMetrics::peak_drift_ratio)
                .collect::<Vec<_>>()),
            residual_drift_ratio_mean: residual_mean(r),
            peak_ductility_mean: opt_mean(mu),
            peak_ductility_max: mu_max,
            hysteretic_energy_mean: opt_mean(r.iter().map(|m| m.energy_plastic).collect()),
            // over the records that dissipated anything by friction or yielding
            friction_share_mean: {
                let shares: Option<Vec<f64>> = r
                    .iter()
                    .map(|m| {
                        let f = m.energy_friction?;
                        let total = f + m.energy_plastic.unwrap_or(0.0);
                        Some((total > 0.0).then(|| f / total))
                    })
                    .collect::<Option<Vec<Option<f64>>>>()
                    .map(|v| v.into_iter().flatten().collect());
                shares
                    .filter(|v| !v.is_empty())
                    .map(|v| Statistic::Mean.of(&v))
            },
        }
    }
}

/// A design table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DesignTable {
    /// Study name.
    pub study: String,
    /// The objective, as a label.
    pub objective: String,
    /// Method and time-step factor of the runs.
    pub fidelity: String,
    /// Floors (from 1) of the dissipators.
    pub damper_floors: Vec<usize>,
    /// Records per design.
    pub records: usize,
    /// The rows.
    pub rows: Vec<TableRow>,
}

fn stat_by_storey(
    rows: &[RecordMetrics],
    st: Statistic,
    f: impl Fn(&RecordMetrics) -> &[f64],
) -> Vec<f64> {
    let n = f(&rows[0]).len();
    (0..n)
        .map(|i| st.of(&rows.iter().map(|m| f(m)[i]).collect::<Vec<_>>()))
        .collect()
}

/// Mean residual drift ratio over the runs that reached the record's end (a run that
/// stopped on the collapse limit has no residual drift); +∞ (`collapsed`) when none did.
fn residual_mean(r: &[RecordMetrics]) -> f64 {
    let v: Vec<f64> = r
        .iter()
        .filter(|m| !m.collapsed())
        .map(RecordMetrics::residual)
        .collect();
    if v.is_empty() {
        f64::INFINITY
    } else {
        Statistic::Mean.of(&v)
    }
}

/// Peak drift ratio of runs for a reduction: +∞ when a run collapsed (its peak is where
/// it stopped, not a response to compare).
fn drift_for_reduction(r: &[RecordMetrics]) -> f64 {
    if r.iter().any(RecordMetrics::collapsed) {
        f64::INFINITY
    } else {
        mean(r.iter().map(RecordMetrics::peak_drift_ratio))
    }
}

fn mean(v: impl Iterator<Item = f64>) -> f64 {
    let v: Vec<f64> = v.collect();
    Statistic::Mean.of(&v)
}

impl DesignTable {
    /// Runs every design (slip loads, N) and its ±25 % variants at the check fidelity.
    /// The bare frame is added as the reference row if it is not among the designs.
    pub fn build<D: Clone + Into<DesignLoads>>(
        study: &Study,
        designs: &[(String, D)],
        tick: &(dyn Fn() + Sync),
    ) -> Result<DesignTable, OptError> {
        Self::build_with_runs(study, designs, tick).map(|(table, _)| table)
    }

    /// As [`DesignTable::build`], also returning the responses it ran (so figures need
    /// no extra simulations), each over every record of the study: `runs[0]` the bare
    /// frame, then for design `k` `runs[1 + 3k]` (its slip loads), `runs[2 + 3k]` (× 0.75)
    /// and `runs[3 + 3k]` (× 1.25).
    pub fn build_with_runs<D: Clone + Into<DesignLoads>>(
        study: &Study,
        designs: &[(String, D)],
        tick: &(dyn Fn() + Sync),
    ) -> Result<(DesignTable, Vec<Vec<RecordMetrics>>), OptError> {
        Self::build_journalled(study, designs, None, tick)
    }

    /// As [`DesignTable::build_with_runs`], taking finished runs from `journal` (the
    /// check fidelity's task journal) and appending the others.
    pub fn build_journalled<D: Clone + Into<DesignLoads>>(
        study: &Study,
        designs: &[(String, D)],
        journal: Option<&TaskJournal>,
        tick: &(dyn Fn() + Sync),
    ) -> Result<(DesignTable, Vec<Vec<RecordMetrics>>), OptError> {
        let fid = Fidelity::check(study);
        let m = study.space.dampers.len();
        let designs: Vec<(String, DesignLoads)> = designs
            .iter()
            .map(|(n, d)| (n.clone(), d.clone().into()))
            .collect();
        let mut all: Vec<DesignLoads> = vec![DesignLoads::from(vec![0.0; m])];
        for (_, s) in &designs {
            all.push(s.clone());
            all.push(s.scaled(0.75));
            all.push(s.scaled(1.25));
        }
        let runs = run_designs_journalled(study, &all, &fid, journal, tick)?;
        let bare = &runs[0];
        let ranges = suite_ranges(study);
        let objective = |rows: &[RecordMetrics]| study.objective.value(rows, Some(bare), &ranges);
        let f_bare = objective(bare)?;
        let pdr_bare = drift_for_reduction(bare);
        let masses: Vec<f64> = (0..study.building.floors())
            .map(|i| study.building.mass.row(i).sum())
            .collect();
        let mut rows = Vec::new();
        for (k, (name, design)) in designs.iter().enumerate() {
            let loads = &design.slip_loads_n;
            let r = &runs[1 + 3 * k];
            let f = objective(r)?;
            let pdr = mean(r.iter().map(RecordMetrics::peak_drift_ratio));
            let rpi = r
                .iter()
                .zip(bare)
                .map(|(x, b)| Metric::Rpi.value(x, Some(b)))
                .collect::<Result<Vec<_>, _>>()?;
            let er = r
                .iter()
                .map(|x| Metric::EnergyRatio.value(x, None).map(|v| 1.0 - v))
                .collect::<Result<Vec<_>, _>>()?;
            rows.push(TableRow {
                design: name.clone(),
                slip_load_kn: loads.iter().map(|v| v / 1e3).collect(),
                friction_kn: design
                    .friction_n
                    .as_ref()
                    .map(|l| l.iter().map(|x| x.scaled(1e-3)).collect()),
                ratio_to_floor_weight: study
                    .space
                    .dampers
                    .iter()
                    .zip(loads)
                    .map(|(&fl, s)| s / (masses[fl] * G))
                    .collect(),
                ratio_to_weight_above: study
                    .space
                    .dampers
                    .iter()
                    .zip(loads)
                    .map(|(&fl, s)| s / (masses[fl..].iter().sum::<f64>() * G))
                    .collect(),
                drift_ratio_mean: stat_by_storey(r, Statistic::Mean, |m| &m.drift_ratio),
                drift_ratio_p84: stat_by_storey(r, Statistic::P84, |m| &m.drift_ratio),
                drift_ratio_max: stat_by_storey(r, Statistic::Max, |m| &m.drift_ratio),
                objective: f,
                objective_reduction: reduction(f, f_bare),
                peak_drift_ratio_mean: pdr,
                peak_drift_reduction: reduction(drift_for_reduction(r), pdr_bare),
                residual_drift_ratio_mean: residual_mean(r),
                peak_floor_acceleration_mean: mean(r.iter().map(|m| m.peak_floor_acceleration)),
                base_shear_mean: mean(r.iter().map(|m| m.peak_base_shear)),
                stroke_max: stat_by_storey(r, Statistic::Max, |m| &m.stroke),
                energy_ratio_mean: Statistic::Mean.of(&er),
                rpi_mean: Statistic::Mean.of(&rpi),
                objective_at_75pct: objective(&runs[2 + 3 * k])?,
                objective_at_125pct: objective(&runs[3 + 3 * k])?,
                by_suite: study.building.is_nonlinear_frame().then(|| {
                    study
                        .suites
                        .iter()
                        .map(|su| SuiteStats::of(&su.name, &r[su.range.clone()]))
                        .collect()
                }),
            });
        }
        let table = DesignTable {
            study: study.name.clone(),
            objective: study.objective.label(),
            fidelity: format!(
                "{} at {} x the sweep time step",
                fid.method.as_str(),
                fid.dt_factor
            ),
            damper_floors: study.space.dampers.iter().map(|f| f + 1).collect(),
            records: study.records.len(),
            rows,
        };
        Ok((table, runs))
    }

    /// Writes `design-table.csv`, `design-table.md` and `design-table.json` into the study folder.
    pub fn write_files(&self, folder: &StudyFolder) -> Result<(), OptError> {
        self.write_files_as(folder, "design-table")
    }

    /// Writes `STEM.csv`, `STEM.md` and `STEM.json` into the study folder; the Markdown's
    /// title says which table it is (the front's for `pareto-table`).
    pub fn write_files_as(&self, folder: &StudyFolder, stem: &str) -> Result<(), OptError> {
        let title = match stem {
            "pareto-table" => "Design table of the front",
            _ => "Design table",
        };
        folder.write(&format!("{stem}.csv"), self.to_csv().as_bytes())?;
        folder.write(
            &format!("{stem}.md"),
            self.to_markdown_titled(title).as_bytes(),
        )?;
        folder.write(&format!("{stem}.json"), self.to_json().as_bytes())
    }

    /// CSV, full precision, one line per design.
    pub fn to_csv(&self) -> String {
        let fl = &self.damper_floors;
        let n = self.rows.first().map_or(0, |r| r.drift_ratio_mean.len());
        let mut s = String::from("design");
        let per = |s: &mut String, name: &str, idx: &mut dyn Iterator<Item = usize>| {
            for i in idx {
                let _ = write!(s, ",{name}_{i}");
            }
        };
        per(&mut s, "slip_load_kN", &mut fl.iter().copied());
        per(&mut s, "ratio_to_floor_weight", &mut fl.iter().copied());
        per(&mut s, "ratio_to_weight_above", &mut fl.iter().copied());
        per(&mut s, "drift_ratio_mean", &mut (1..=n));
        per(&mut s, "drift_ratio_p84", &mut (1..=n));
        per(&mut s, "drift_ratio_max", &mut (1..=n));
        s.push_str(",objective,objective_reduction,peak_drift_ratio_mean,peak_drift_reduction,residual_drift_ratio_mean,peak_floor_acceleration_mean_m_s2,base_shear_mean_N");
        per(&mut s, "stroke_max_m", &mut (1..=n));
        s.push_str(",energy_ratio_mean,rpi_mean,objective_at_75pct,objective_at_125pct\n");
        for r in &self.rows {
            let _ = write!(s, "{}", r.design);
            // a friction law the slip loads cannot say is written as it is, ratios too
            match &r.friction_kn {
                Some(laws) => {
                    for l in laws {
                        let _ = write!(s, ",{}", l.text(1.0));
                    }
                    for ratios in [&r.ratio_to_floor_weight, &r.ratio_to_weight_above] {
                        for (l, v) in laws.iter().zip(ratios) {
                            let _ = write!(s, ",{}", r.ratio_cell(*l, *v));
                        }
                    }
                }
                None => {
                    for v in r
                        .slip_load_kn
                        .iter()
                        .chain(&r.ratio_to_floor_weight)
                        .chain(&r.ratio_to_weight_above)
                    {
                        let _ = write!(s, ",{v}");
                    }
                }
            }
            for v in r
                .drift_ratio_mean
                .iter()
                .chain(&r.drift_ratio_p84)
                .chain(&r.drift_ratio_max)
            {
                let _ = write!(s, ",{v}");
            }
            let _ = write!(
                s,
                ",{},{},{},{},{},{},{}",
                objective_text(r.objective, None),
                reduction_text(r.objective_reduction, None),
                r.peak_drift_ratio_mean,
                reduction_text(r.peak_drift_reduction, None),
                objective_text(r.residual_drift_ratio_mean, None),
                r.peak_floor_acceleration_mean,
                r.base_shear_mean
            );
            for v in &r.stroke_max {
                let _ = write!(s, ",{v}");
            }
            let _ = writeln!(
                s,
                ",{},{},{},{}",
                r.energy_ratio_mean,
                r.rpi_mean,
                objective_text(r.objective_at_75pct, None),
                objective_text(r.objective_at_125pct, None)
            );
        }
        s
    }

    /// Pretty JSON with a final newline.
    pub fn to_json(&self) -> String {
        let mut s = serde_json::to_string_pretty(self).expect("a table serialises");
        s.push('\n');
        s
    }

    /// Markdown for people: two tables (slip loads and drifts per floor; responses).
    pub fn to_markdown(&self) -> String {
        self.to_markdown_titled("Design table")
    }

    /// [`DesignTable::to_markdown`] under the title `title` (`# TITLE: STUDY`).
    pub fn to_markdown_titled(&self, title: &str) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "# {title}: {}\n", self.study);
        let _ = writeln!(
            s,
            "Objective: {} ({} records, {}). Drift ratios in %, slip loads in kN; \"/W\" = slip load over the floor weight, \"/ΣW\" = over the weight above the storey (its gravity shear); residual drift = the largest storey drift ratio left at the end of the record (after the free vibration a suite asks for, `free_vibration_s`), mean over the records run to their end.\n",
            self.objective, self.records, self.fidelity
        );
        s.push_str("| design | floor | slip load (kN) | /W | /ΣW | drift mean (%) | drift p84 (%) | drift max (%) | stroke max (mm) |\n");
        s.push_str("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
        let storeys = self.rows.first().map_or(0, |r| r.drift_ratio_mean.len());
        for r in &self.rows {
            // every storey, those without a damper too (their damper columns "—")
            for i in 0..storeys {
                let damper = self.damper_floors.iter().position(|&f| f == i + 1);
                let (load, w, sw, stroke) = match damper {
                    Some(k) => (
                        match r.friction_kn.as_ref().map(|l| l[k]) {
                            Some(FrictionLaw::Locked) => "locked".to_string(),
                            Some(FrictionLaw::Bounds([lo, hi])) => format!("{lo:.1}..{hi:.1}"),
                            None => format!("{:.1}", r.slip_load_kn[k]),
                        },
                        r.ratio_md(k, r.ratio_to_floor_weight[k]),
                        r.ratio_md(k, r.ratio_to_weight_above[k]),
                        format!("{:.1}", 1e3 * r.stroke_max[i]),
                    ),
                    None => (
                        "no damper".to_string(),
                        NONE.to_string(),
                        NONE.to_string(),
                        NONE.to_string(),
                    ),
                };
                let _ = writeln!(
                    s,
                    "| {} | {} | {load} | {w} | {sw} | {:.3} | {:.3} | {:.3} | {stroke} |",
                    if i == 0 { r.design.as_str() } else { "" },
                    i + 1,
                    100.0 * r.drift_ratio_mean[i],
                    100.0 * r.drift_ratio_p84[i],
                    100.0 * r.drift_ratio_max[i],
                );
            }
        }
        s.push_str("\n| design | objective | reduction vs bare | peak drift mean (%) | drift reduction | residual drift (%) | floor accel. (m/s²) | base shear (MN) | E_friction/E_input | RPI | objective at 0.75× / 1.25× |\n");
        s.push_str("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
        for r in &self.rows {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {:.3} | {} | {} | {:.2} | {:.2} | {:.2} | {:.3} | {} / {} |",
                r.design,
                objective_text(r.objective, Some(5)),
                reduction_text(r.objective_reduction, Some(1)),
                100.0 * r.peak_drift_ratio_mean,
                reduction_text(r.peak_drift_reduction, Some(1)),
                objective_text(100.0 * r.residual_drift_ratio_mean, Some(4)),
                r.peak_floor_acceleration_mean,
                r.base_shear_mean / 1e6,
                r.energy_ratio_mean,
                r.rpi_mean,
                objective_text(r.objective_at_75pct, Some(5)),
                objective_text(r.objective_at_125pct, Some(5))
            );
        }
        if self.rows.iter().any(|r| r.by_suite.is_some()) {
            s.push_str("\nBy suite (the frame yields or carries P-Δ): peak drift and residual drift ratios in %, peak storey ductility = peak drift / yield drift (max over the storeys), hysteretic energy of the frame in kJ, friction share = E_friction / (E_friction + E_plastic); collapses = records on which the run passed the drift limit (the design fails them).\n\n");
            s.push_str("| design | suite | records | collapses | peak drift mean (%) | peak drift max (%) | residual drift (%) | ductility mean | ductility max | hysteretic energy (kJ) | friction share |\n");
            s.push_str("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
            let opt = |v: Option<f64>, scale: f64, digits: usize| {
                v.map_or("-".to_string(), |v| format!("{:.*}", digits, v * scale))
            };
            for r in &self.rows {
                for (k, st) in r.by_suite.iter().flatten().enumerate() {
                    let _ = writeln!(
                        s,
                        "| {} | {} | {} | {} | {:.3} | {:.3} | {} | {} | {} | {} | {} |",
                        if k == 0 { r.design.as_str() } else { "" },
                        st.suite,
                        st.records,
                        st.collapses,
                        100.0 * st.peak_drift_ratio_mean,
                        100.0 * st.peak_drift_ratio_max,
                        objective_text(100.0 * st.residual_drift_ratio_mean, Some(4)),
                        opt(st.peak_ductility_mean, 1.0, 2),
                        opt(st.peak_ductility_max, 1.0, 2),
                        opt(st.hysteretic_energy_mean, 1e-3, 1),
                        opt(st.friction_share_mean, 1.0, 3),
                    );
                }
            }
        }
        s
    }
}

/// The standard candidates around an optimum (slip loads N): the optimum, the uniform and
/// storey-shear-proportional designs with the same total, the building file's design as
/// written ([`DesignLoads::file`]: a locked or asymmetric damper stays so), and the bare
/// frame.
pub fn standard_designs(study: &Study, optimum: &[f64]) -> Vec<(String, DesignLoads)> {
    let total: f64 = optimum.iter().sum();
    let m = optimum.len();
    let shaped = |shape: crate::model::space::Shape| {
        let all = shape.on_floors(&study.building);
        let sh: Vec<f64> = study.space.dampers.iter().map(|&f| all[f]).collect();
        let sum: f64 = sh.iter().sum();
        sh.iter().map(|v| v / sum * total).collect::<Vec<f64>>()
    };
    let all: Vec<(String, DesignLoads)> = vec![
        ("optimum".to_string(), optimum.to_vec().into()),
        (
            "uniform".to_string(),
            shaped(crate::model::space::Shape::Uniform).into(),
        ),
        (
            "storey-shear".to_string(),
            shaped(crate::model::space::Shape::StoreyShear).into(),
        ),
        ("file".to_string(), DesignLoads::file(study)),
        ("bare".to_string(), vec![0.0; m].into()),
    ];
    // a profile optimum already is its profile at that total: keep the first of equals
    let same = |a: &DesignLoads, b: &DesignLoads| {
        a.friction_n == b.friction_n
            && a.slip_loads_n
                .iter()
                .zip(&b.slip_loads_n)
                .all(|(x, y)| (x - y).abs() <= 1e-9 * x.abs().max(y.abs()).max(1.0))
    };
    let mut out: Vec<(String, DesignLoads)> = Vec::new();
    for (name, loads) in all {
        if !out.iter().any(|(_, l)| same(l, &loads)) {
            out.push((name, loads));
        }
    }
    out
}
