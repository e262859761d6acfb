//! What a study in plan reports: the designs of its final table (bare frame, the file's
//! slip loads, the optimum, and the optimum's storey totals split as a planar model
//! would), each checked at the finer step, with per-damper slip loads, each line's
//! share of its direction, drift profiles per line; as text, CSV, Markdown and JSON, and
//! the data of its figures ([`PlanFigureData`]).

use super::config::trim;
use super::evaluate::DesignEval;
use super::study::PlanStudy;
use crate::model::check::md_text;
use serde::Serialize;
use slipload_sim::response::csv_field;
use std::fmt::Write as _;

/// A row of the final table.
#[derive(Debug, Clone, Serialize)]
pub struct PlanRow {
    /// `bare`, `file`, `optimum`, `planar split`.
    pub design: String,
    /// What it is.
    pub description: String,
    /// Its evaluation at the check's step.
    pub eval: DesignEval,
    /// Its objective at the check's step.
    pub objective: f64,
    /// Whether it passes the limits (true without limits, unless a run collapsed).
    pub passes: bool,
    /// Each limit's demand over its limit.
    pub ratios: Vec<f64>,
}

/// Everything a study in plan found.
#[derive(Debug, Clone, Serialize)]
pub struct PlanReport {
    /// The study's name.
    pub study: String,
    /// The design variables' names.
    pub variables: Vec<String>,
    /// The limits' names, in the rows' ratio order.
    pub limits: Vec<String>,
    /// Designs the sweep evaluated.
    pub sweep_designs: usize,
    /// New designs the refinement evaluated.
    pub refine_designs: usize,
    /// Of those, taken from the journal of an earlier run.
    pub replayed: usize,
    /// Why the refinement stopped.
    pub stop: String,
    /// The optimum's scaled variables.
    pub z: Vec<f64>,
    /// The optimum's objective at the sweep's step.
    pub objective_sweep: f64,
    /// Runs per design.
    pub runs_per_design: usize,
    /// The final table, checked at the finer step.
    pub rows: Vec<PlanRow>,
    /// The step factor of the check.
    pub check_dt_factor: f64,
}

impl PlanReport {
    /// The files a study in plan writes (besides its journal and figures).
    pub const FILES: [&'static str; 9] = [
        "plan-summary.txt",
        "plan-check.md",
        "plan-optimum.json",
        "plan-designs.csv",
        "plan-dampers.csv",
        "plan-dampers.md",
        "plan-devices.csv",
        "plan-devices.md",
        "plan-profiles.csv",
    ];

    /// A row by design name.
    pub fn row(&self, design: &str) -> Option<&PlanRow> {
        self.rows.iter().find(|r| r.design == design)
    }
}

/// Each line with dampers and its share of its direction's slip load (summed over the
/// storeys) under `loads`: (line name, share), in the lines' order.
pub fn line_shares(study: &PlanStudy, loads: &[Option<f64>]) -> Vec<(String, f64)> {
    let b = &study.building;
    let mut per_line = vec![0.0; b.lines.len()];
    for (site, l) in study.dampers.iter().zip(loads) {
        per_line[site.line] += l.unwrap_or(0.0);
    }
    let dir_of = |l: usize| b.lines[l].angle.rem_euclid(std::f64::consts::PI);
    let same = |a: f64, c: f64| {
        let d = (a - c).abs();
        d < 1e-9 || (std::f64::consts::PI - d).abs() < 1e-9
    };
    let with_dampers: Vec<usize> = (0..b.lines.len())
        .filter(|&l| study.dampers.iter().any(|d| d.line == l))
        .collect();
    with_dampers
        .iter()
        .map(|&l| {
            let total: f64 = with_dampers
                .iter()
                .filter(|&&k| same(dir_of(k), dir_of(l)))
                .map(|&k| per_line[k])
                .sum();
            let share = if total > 0.0 {
                per_line[l] / total
            } else {
                0.0
            };
            (b.lines[l].name.clone(), share)
        })
        .collect()
}

/// The loads of `loads` with every direction's storey total split between the sized
/// lines of that direction in proportion to their storey stiffness (a planar model's
/// placement of the same slip load).
pub fn planar_split(study: &PlanStudy, loads: &[Option<f64>]) -> Vec<Option<f64>> {
    let b = &study.building;
    let sized: Vec<usize> = study.space.dampers.clone();
    let dir_of = |l: usize| b.lines[l].angle.rem_euclid(std::f64::consts::PI);
    let same = |a: f64, c: f64| {
        let d = (a - c).abs();
        d < 1e-9 || (std::f64::consts::PI - d).abs() < 1e-9
    };
    let mut out = loads.to_vec();
    for &k in &sized {
        let site = &study.dampers[k];
        let group: Vec<usize> = sized
            .iter()
            .copied()
            .filter(|&j| {
                let o = &study.dampers[j];
                o.storey == site.storey && same(dir_of(o.line), dir_of(site.line))
            })
            .collect();
        let total: f64 = group.iter().map(|&j| loads[j].unwrap_or(0.0)).sum();
        let stiff: f64 = group
            .iter()
            .map(|&j| b.lines[study.dampers[j].line].stiffness[site.storey])
            .sum();
        out[k] = Some(total * b.lines[site.line].stiffness[site.storey] / stiff);
    }
    out
}

fn pct(v: f64) -> String {
    format!("{:.3}", v * 100.0)
}

fn kn(v: Option<f64>) -> String {
    v.map_or_else(|| "file".into(), |f| format!("{:.1}", f / 1e3))
}

/// `plan-dampers.csv`: every damper's slip load (kN, to 0.1) and its statistic of peak
/// slip (mm) in the nominal case of the first suite, per design of the table.
pub fn dampers_csv(study: &PlanStudy, report: &PlanReport) -> String {
    let mut s = String::from("design,damper,line,storey,slip_load_kn,peak_slip_mm\n");
    for row in &report.rows {
        let cell = &row.eval.cells[0];
        for (k, site) in study.dampers.iter().enumerate() {
            let _ = writeln!(
                s,
                "{},{},{},{},{},{:.3}",
                row.design,
                csv_field(&site.name),
                csv_field(&study.building.lines[site.line].name),
                site.storey + 1,
                kn(row.eval.loads[k]),
                cell.peaks.slip.get(k).copied().unwrap_or(0.0) * 1e3
            );
        }
    }
    s
}

/// `plan-dampers.md`: the slip loads per line and storey of the optimum beside the planar
/// split (kN, to 0.1), and each line's share of its direction.
pub fn dampers_md(study: &PlanStudy, report: &PlanReport) -> String {
    let b = &study.building;
    let mut s = format!(
        "# {}: slip loads by line and storey\n\nSlip loads in kN, rounded to 0.1 kN. Shares: each line's part of the slip load along its direction, summed over the storeys.\n\n",
        md_text(&report.study)
    );
    let lines: Vec<usize> = (0..b.lines.len())
        .filter(|&l| study.dampers.iter().any(|d| d.line == l))
        .collect();
    for row in &report.rows {
        if row.design == "bare" {
            continue;
        }
        let _ = writeln!(s, "## {} — {}\n", row.design, row.description);
        let _ = write!(s, "| storey |");
        for &l in &lines {
            let _ = write!(s, " {} |", md_text(&b.lines[l].name));
        }
        let _ = write!(s, "\n|---|");
        for _ in &lines {
            let _ = write!(s, "---:|");
        }
        s.push('\n');
        for f in (0..b.storeys()).rev() {
            let _ = write!(s, "| {} |", f + 1);
            for &l in &lines {
                let v = study
                    .dampers
                    .iter()
                    .position(|d| d.line == l && d.storey == f)
                    .map_or_else(|| "—".into(), |k| kn(row.eval.loads[k]));
                let _ = write!(s, " {v} |");
            }
            s.push('\n');
        }
        let shares = line_shares(study, &row.eval.loads);
        let _ = write!(s, "| share |");
        for (_, sh) in &shares {
            let _ = write!(s, " {:.1} % |", sh * 100.0);
        }
        s.push_str("\n\n");
    }
    s
}

/// Per damper of `row`, each device demand's worst over the suites and property cases
/// (each the suite's statistic over its pairs): (stroke m, velocity m/s, travel m,
/// energy J, force N).
pub fn device_demands(row: &PlanRow) -> Vec<[f64; 5]> {
    let n = row.eval.loads.len();
    (0..n)
        .map(|k| {
            let mut out = [0.0f64; 5];
            for c in &row.eval.cells {
                let d = &c.peaks.devices;
                for (o, v) in
                    out.iter_mut()
                        .zip([&d.stroke, &d.velocity, &d.travel, &d.energy, &d.force])
                {
                    *o = o.max(v.get(k).copied().unwrap_or(0.0));
                }
            }
            out
        })
        .collect()
}

/// `plan-devices.csv`: the optimum's device table, one row per damper.
pub fn devices_csv(study: &PlanStudy, report: &PlanReport) -> String {
    let mut s = String::from(
        "damper,line,storey,slip_load_kn,stroke_mm,velocity_mm_s,travel_mm,energy_kj,peak_force_kn\n",
    );
    let Some(row) = report.row("optimum") else {
        return s;
    };
    for (site, (d, load)) in study
        .dampers
        .iter()
        .zip(device_demands(row).iter().zip(&row.eval.loads))
    {
        let _ = writeln!(
            s,
            "{},{},{},{},{:.2},{:.1},{:.1},{:.2},{:.1}",
            csv_field(&site.name),
            csv_field(&study.building.lines[site.line].name),
            site.storey + 1,
            kn(*load),
            d[0] * 1e3,
            d[1] * 1e3,
            d[2] * 1e3,
            d[3] / 1e3,
            d[4] / 1e3
        );
    }
    s
}

/// `plan-devices.md`: the optimum's device table, line by line, top storey first.
pub fn devices_md(study: &PlanStudy, report: &PlanReport) -> String {
    let stat = match study.config.objective.statistic {
        super::config::PlanStatistic::Mean => "mean",
        super::config::PlanStatistic::Max => "largest",
    };
    let mut s = format!(
        "# {}: device table of the optimum\n\nEach damper's demands at the final table's step: the {stat} over each suite's pairs (each pair its largest over its orientations), the worst suite and property case. Stroke: the larger slip either way from the start. Slip loads to 0.1 kN.\n\n| damper | slip load (kN) | stroke (mm) | peak velocity (mm/s) | cumulative travel (mm) | energy (kJ) | peak force (kN) |\n|---|---:|---:|---:|---:|---:|---:|\n",
        md_text(&report.study)
    );
    let Some(row) = report.row("optimum") else {
        return s;
    };
    let demands = device_demands(row);
    let mut order: Vec<usize> = (0..study.dampers.len()).collect();
    order.sort_by_key(|&k| {
        (
            study.dampers[k].line,
            std::cmp::Reverse(study.dampers[k].storey),
        )
    });
    for k in order {
        let d = demands[k];
        let _ = writeln!(
            s,
            "| {} | {} | {:.2} | {:.1} | {:.1} | {:.2} | {:.1} |",
            md_text(&study.dampers[k].name),
            kn(row.eval.loads[k]),
            d[0] * 1e3,
            d[1] * 1e3,
            d[2] * 1e3,
            d[3] / 1e3,
            d[4] / 1e3
        );
    }
    s
}

/// ASCE 7-16 Table 12.3-1's reading of a torsional ratio: regular up to 1.2, type 1a
/// (torsional irregularity) past 1.2, type 1b (extreme) past 1.4.
pub fn torsion_class(ratio: f64) -> &'static str {
    if ratio > 1.4 {
        "extreme (1b)"
    } else if ratio > 1.2 {
        "irregular (1a)"
    } else {
        "regular"
    }
}

/// `plan-check.md`: the optimum storey by storey against the study's limits, per suite at
/// its worst property case — the edge drift and the torsional ratio, each the suite's
/// statistic over its pairs — with the torsional class of every storey; the planar split
/// (or the file's design) beside it.
pub fn check_md(study: &PlanStudy, report: &PlanReport) -> String {
    let limits = study.config.limits.unwrap_or_default();
    let stat = match study.config.objective.statistic {
        super::config::PlanStatistic::Mean => "mean",
        super::config::PlanStatistic::Max => "largest",
    };
    let mut s = format!(
        "# {}: check of the optimum storey by storey\n\nPer suite, each storey's edge drift (the largest of the plan's four edges, percent of the storey height) and torsional irregularity ratio (the larger edge drift over the edges' mean, along x or y), each the {stat} over the suite's pairs (each pair its largest over its orientations) at the worst property case ({}). The torsional class reads ASCE 7-16 Table 12.3-1's thresholds (1.2, 1.4) on these dynamic peaks; the standard's own check uses the drifts of the equivalent lateral forces with accidental torsion, so the class here is an indicator, not that check.\n\n",
        md_text(&report.study),
        study
            .cases
            .iter()
            .map(|c| c.name.as_str())
            .collect::<Vec<_>>()
            .join("; ")
    );
    let verdict = |row: &PlanRow| {
        if study.config.limits.is_none() {
            "no limits given".to_string()
        } else if row.passes {
            "PASS (every limit met)".to_string()
        } else {
            "FAIL (a limit missed or a run collapsed)".to_string()
        }
    };
    let others = report.row("planar split").or_else(|| report.row("file"));
    for row in ["optimum"]
        .iter()
        .filter_map(|d| report.row(d))
        .chain(others)
    {
        let _ = writeln!(s, "## {} — {}\n", row.design, verdict(row));
        for (si, suite) in study.suites.iter().enumerate() {
            let cells: Vec<&super::evaluate::Cell> =
                row.eval.cells.iter().filter(|c| c.suite == si).collect();
            let n = study.building.storeys();
            let worst = |f: &dyn Fn(&super::evaluate::Cell) -> f64| {
                cells.iter().map(|c| f(c)).fold(f64::NEG_INFINITY, f64::max)
            };
            let _ = writeln!(
                s,
                "### suite {}\n\n| storey | edge drift (%) | limit (%) | demand/limit | torsional ratio | limit | class |\n|---|---:|---:|---:|---:|---:|---|",
                md_text(&suite.name)
            );
            for f in (0..n).rev() {
                let edge = worst(&|c| c.peaks.edge_drift.get(f).copied().unwrap_or(f64::NAN));
                let tor = worst(&|c| c.peaks.torsion.get(f).copied().unwrap_or(f64::NAN));
                let (el, er) = match limits.edge_drift_ratio {
                    Some(l) => (format!("{:.3}", l * 100.0), format!("{:.3}", edge / l)),
                    None => ("—".into(), "—".into()),
                };
                let tl = limits
                    .torsional_ratio
                    .map_or_else(|| "—".to_string(), |l| format!("{l}"));
                // (a plan without `plan_size` has no edges and no torsional ratio)
                let shown = |v: f64, text: String| if v.is_finite() { text } else { "—".into() };
                let _ = writeln!(
                    s,
                    "| {} | {} | {el} | {er} | {} | {tl} | {} |",
                    f + 1,
                    shown(edge, format!("{:.3}", edge * 100.0)),
                    shown(tor, format!("{tor:.3}")),
                    shown(tor, torsion_class(tor).to_string())
                );
            }
            s.push('\n');
        }
    }
    s
}

/// `plan-profiles.csv`: per design, suite and case, every line's and the edges' drift
/// ratio per storey (percent; m where the building gives no storey heights) and the
/// torsional ratio.
pub fn profiles_csv(study: &PlanStudy, report: &PlanReport) -> String {
    let b = &study.building;
    let n = b.storeys();
    let mut s = String::from("design,suite,case,measure,storey,value\n");
    for row in &report.rows {
        for c in &row.eval.cells {
            let suite = &study.suites[c.suite].name;
            let case = &study.cases[c.case].name;
            for (l, line) in b.lines.iter().enumerate() {
                for f in 0..n {
                    let _ = writeln!(
                        s,
                        "{},{},{},drift_pct line {},{},{}",
                        row.design,
                        csv_field(suite),
                        case,
                        csv_field(&line.name),
                        f + 1,
                        pct(c.peaks.line_drift[l * n + f])
                    );
                }
            }
            for (f, v) in c.peaks.edge_drift.iter().enumerate() {
                let _ = writeln!(
                    s,
                    "{},{},{},drift_pct edges,{},{}",
                    row.design,
                    csv_field(suite),
                    case,
                    f + 1,
                    pct(*v)
                );
            }
            for (f, v) in c.peaks.torsion.iter().enumerate() {
                let _ = writeln!(
                    s,
                    "{},{},{},torsional_ratio,{},{:.4}",
                    row.design,
                    csv_field(suite),
                    case,
                    f + 1,
                    v
                );
            }
        }
    }
    s
}

/// `plan-summary.txt`, also what `slipload optimize` prints for a study in plan.
pub fn summary(study: &PlanStudy, report: &PlanReport) -> String {
    let mut s = String::new();
    let metric = study.config.objective.metric;
    let stat = match study.config.objective.statistic {
        super::config::PlanStatistic::Mean => "mean",
        super::config::PlanStatistic::Max => "largest",
    };
    let _ = writeln!(
        s,
        "study in plan {}: {} storeys, {} lines, {} dampers ({} sized by {} variable(s), placement `{}`)",
        report.study,
        study.building.storeys(),
        study.building.lines.len(),
        study.dampers.len(),
        study.space.dampers.len(),
        study.space.dim(),
        study.config.space.placement.as_str()
    );
    for su in &study.suites {
        let _ = writeln!(
            s,
            "  suite {}: {} pairs x scale {} at {} orientation(s) ({} deg; the second component at +90 deg), each pair's largest response over them",
            su.name,
            su.pairs.len(),
            match &su.code {
                None => trim(su.factor),
                Some(c) => format!(
                    "{:.4} (scaled to a code spectrum, {}: the pairs' mean maximum-direction spectrum at or above 90 % of the {} target over [{:.3}, {:.3}] s, met at {:.3} s)",
                    c.factor,
                    c.target_text(),
                    c.hazard.as_str(),
                    c.range_s[0],
                    c.range_s[1],
                    c.controlling_period_s
                ),
            },
            su.angles_deg.len(),
            su.angles_deg
                .iter()
                .map(|a| trim(*a))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    let _ = writeln!(
        s,
        "  property cases: {}",
        study
            .cases
            .iter()
            .map(|c| c.name.as_str())
            .collect::<Vec<_>>()
            .join("; ")
    );
    let reads = match study
        .config
        .property_bounds
        .as_ref()
        .map(|b| b.objective_reads)
    {
        Some(crate::model::check::BoundReading::Nominal) => " of nominal properties",
        _ => "",
    };
    if let Some(b) = &study.config.property_bounds {
        let (lo, hi) = b.slip_load.bounds();
        let brace = b.brace_stiffness.as_ref().map_or_else(
            || "as given".to_string(),
            |k| {
                let (kl, kh) = k.bounds();
                format!("x {} and x {}", trim(kl), trim(kh))
            },
        );
        let _ = writeln!(
            s,
            "  property bounds: slip loads x {} (lower) and x {} (upper), brace stiffnesses {brace}; the limits read every case, the objective {}",
            trim(lo),
            trim(hi),
            match b.objective_reads {
                crate::model::check::BoundReading::Nominal => "the nominal properties",
                crate::model::check::BoundReading::Worst => "every case",
            }
        );
    }
    let _ = writeln!(
        s,
        "objective: the {stat} over each suite's pairs of the {}, at the worst suite and case{reads}; {} runs per design ({} {})",
        match metric {
            super::config::PlanMetric::EdgeDriftRatio => "largest edge drift ratio",
            super::config::PlanMetric::LineDriftRatio => "largest line drift ratio",
            super::config::PlanMetric::Rotation => "largest floor rotation (rad)",
            super::config::PlanMetric::TorsionalRatio => "largest torsional irregularity ratio",
            super::config::PlanMetric::TotalSlipLoad => "total slip load",
        },
        report.runs_per_design,
        study.method.as_str(),
        study.config.fidelity.dt_s.map_or_else(
            || "at its default step".to_string(),
            |d| format!("at dt = {d} s")
        )
    );
    let _ = writeln!(
        s,
        "search: {} sweep designs, {} refinement designs, stopped by {}",
        report.sweep_designs, report.refine_designs, report.stop
    );
    let at_search = if report.objective_sweep.is_finite() {
        format!(
            "the optimum's objective at the search's step: {}",
            objective_text(metric, report.objective_sweep)
        )
    } else {
        // the search keeps the design nearest to passing when none passes
        let worst = report
            .row("optimum")
            .map_or(f64::NAN, |r| r.ratios.iter().copied().fold(0.0, f64::max));
        format!(
            "no design of the search passes the limits: the optimum is the one nearest to passing, its largest demand over limit {worst:.3} here"
        )
    };
    let _ = writeln!(
        s,
        "final table at dt x {} ({at_search}):",
        trim(report.check_dt_factor),
    );
    for row in &report.rows {
        let nominal = &row.eval.cells[0];
        let torsion = nominal.torsional;
        let _ = writeln!(
            s,
            "  {:<13} objective {:<12} edge drift {} %, torsional ratio {:.3}, total slip load {:.1} kN{}{}",
            row.design,
            objective_text(metric, row.objective),
            pct(nominal.edge),
            torsion,
            row.eval.loads.iter().map(|l| l.unwrap_or(0.0)).sum::<f64>() / 1e3,
            if study.config.limits.is_some() {
                if row.passes {
                    ", passes"
                } else {
                    ", FAILS a limit"
                }
            } else {
                ""
            },
            if row.eval.collapsed() > 0 {
                format!(", {} runs collapsed", row.eval.collapsed())
            } else {
                String::new()
            }
        );
    }
    let _ = writeln!(
        s,
        "  (edge drift and torsional ratio: the nominal case of suite {}; the objective reads every suite and case{reads})",
        study.suites[0].name
    );
    if let Some(opt) = report.row("optimum") {
        let shares = line_shares(study, &opt.eval.loads);
        let planar = report
            .row("planar split")
            .or_else(|| report.row("file"))
            .map(|r| (r.design.clone(), line_shares(study, &r.eval.loads)));
        let _ = write!(
            s,
            "placement of the optimum's slip load (share of its direction):"
        );
        for (k, (name, sh)) in shares.iter().enumerate() {
            let _ = write!(s, " {name} {:.1} %", sh * 100.0);
            if let Some((label, p)) = &planar {
                let _ = write!(s, " ({label} {:.1} %)", p[k].1 * 100.0);
            }
            if k + 1 < shares.len() {
                s.push(',');
            }
        }
        s.push('\n');
        let _ = writeln!(s, "optimum slip loads by variable:");
        let [lo, hi] = study.config.space.slip_load_kn;
        let what = match study.config.space.placement {
            super::config::Placement::Lines => "first-storey slip load",
            super::config::Placement::Directions => "first-storey total",
            super::config::Placement::Free => "slip load",
        };
        for (j, name) in report.variables.iter().enumerate() {
            let _ = writeln!(
                s,
                "  {name}: {what} {:.1} kN (z = {:.4})",
                lo + (hi - lo) * report.z[j],
                report.z[j]
            );
        }
    }
    s
}

fn objective_text(metric: super::config::PlanMetric, v: f64) -> String {
    if !v.is_finite() {
        return "inf".into();
    }
    match metric {
        super::config::PlanMetric::EdgeDriftRatio | super::config::PlanMetric::LineDriftRatio => {
            format!("{} %", pct(v))
        }
        super::config::PlanMetric::Rotation => format!("{v:.4e} rad"),
        super::config::PlanMetric::TorsionalRatio => format!("{v:.4}"),
        super::config::PlanMetric::TotalSlipLoad => format!("{:.1} kN", v / 1e3),
    }
}

/// One line of the plan view: its ends in plan (m), its name.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanLine {
    /// Name.
    pub name: String,
    /// [x, y] of its two ends, m.
    pub ends: [[f64; 2]; 2],
}

/// The data of a study in plan's figures.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanFigureData {
    /// The study's name.
    pub study: String,
    /// Plan size [Lx, Ly], m, when given.
    pub plan_size: Option<[f64; 2]>,
    /// The lines in plan.
    pub lines: Vec<PlanLine>,
    /// Each floor's centre of mass, m.
    pub centres: Vec<[f64; 2]>,
    /// Storeys.
    pub storeys: usize,
    /// Per design drawn (name, per line per storey slip load N (0: none), per line per
    /// storey drift ratio, per storey edge drift ratio).
    pub designs: Vec<PlanFigureDesign>,
    /// Whether drifts are ratios (storey heights given) or metres.
    pub ratios: bool,
}

/// One design of the plan figures.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanFigureDesign {
    /// Its name in the table.
    pub name: String,
    /// Slip load per line and storey, N (0 where none), `[line][storey]`.
    pub slip_loads: Vec<Vec<f64>>,
    /// Drift (ratio) per line and storey, `[line][storey]`, the first suite's nominal case.
    pub drifts: Vec<Vec<f64>>,
    /// Largest edge drift (ratio) per storey, the same cell.
    pub edge: Vec<f64>,
}

/// The figures' data of `report`: the optimum and the planar split (or the file's
/// design), the first suite's nominal case.
pub fn figure_data(study: &PlanStudy, report: &PlanReport) -> PlanFigureData {
    let b = &study.building;
    let n = b.storeys();
    let extent = b.plan_size;
    let lines = b
        .lines
        .iter()
        .map(|line| {
            let (c, s) = line.direction();
            let [px, py] = line.point;
            let ends = match extent {
                Some([lx, ly]) => clip(px, py, c, s, lx, ly).unwrap_or([[px, py], [px, py]]),
                None => [
                    [px - 10.0 * c, py - 10.0 * s],
                    [px + 10.0 * c, py + 10.0 * s],
                ],
            };
            PlanLine {
                name: line.name.clone(),
                ends,
            }
        })
        .collect();
    let designs = ["optimum", "planar split", "file"]
        .iter()
        .filter_map(|d| report.row(d))
        .take(2)
        .map(|row| {
            let cell = &row.eval.cells[0];
            let mut slip = vec![vec![0.0; n]; b.lines.len()];
            for (site, l) in study.dampers.iter().zip(&row.eval.loads) {
                slip[site.line][site.storey] = l.unwrap_or(0.0);
            }
            PlanFigureDesign {
                name: row.design.clone(),
                slip_loads: slip,
                drifts: (0..b.lines.len())
                    .map(|l| cell.peaks.line_drift[l * n..(l + 1) * n].to_vec())
                    .collect(),
                edge: cell.peaks.edge_drift.clone(),
            }
        })
        .collect();
    PlanFigureData {
        study: report.study.clone(),
        plan_size: extent,
        lines,
        centres: b.floors.iter().map(|f| f.centre).collect(),
        storeys: n,
        designs,
        ratios: b.storey_heights.is_some(),
    }
}

/// The segment of the line through (px, py) along (c, s) inside [0, lx] × [0, ly].
fn clip(px: f64, py: f64, c: f64, s: f64, lx: f64, ly: f64) -> Option<[[f64; 2]; 2]> {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    for (p, d, hi) in [(px, c, lx), (py, s, ly)] {
        if d.abs() < 1e-12 {
            if p < -1e-9 || p > hi + 1e-9 {
                return None;
            }
        } else {
            let (a, b) = ((0.0 - p) / d, (hi - p) / d);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
    }
    (t0 <= t1).then_some([[px + t0 * c, py + t0 * s], [px + t1 * c, py + t1 * s]])
}
