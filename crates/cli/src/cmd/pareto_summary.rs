//! The trade-off in words and numbers after `slipload optimize`: for a study with
//! `objectives`, its front (the first objective's optimum and what it costs against the
//! building file's design, the knee and where it sits, the other optima, the floors on a
//! bound, whether the front held at reference accuracy); for a one-objective study, the
//! front of drift against floor acceleration over the sweep's designs, which costs no
//! simulation (and changes no file).

use super::study_text::{kn, loads_text, on_bound_text};
use slipload_opt::model::objectives::{ParetoMetric, ParetoObjective};
use slipload_opt::phases::pareto::{ParetoReport, first_front, knee};
use slipload_opt::phases::table::TableRow;
use slipload_opt::pipeline::StudyReport;
use slipload_opt::{RecordMetrics, Study};

/// A drift ratio as the summary prints it: in percent of the storey height, to the
/// thousandth of a percent (what five decimals of the ratio were).
fn drift(v: f64) -> String {
    format!("{:.3} %", 100.0 * v)
}

/// One objective's value as the summary prints it, with its unit (a drift in percent).
fn value(o: &ParetoObjective, v: f64) -> String {
    if !v.is_finite() {
        return "collapsed".into();
    }
    match o.metric {
        ParetoMetric::PeakFloorAcceleration => format!("{v:.2} m/s²"),
        ParetoMetric::BaseShear => format!("{:.2} MN", v / 1e6),
        ParetoMetric::DamperSize => format!("{:.1} kN", v / 1e3),
        ParetoMetric::PeakDriftRatio | ParetoMetric::ResidualDriftRatio => drift(v),
        _ => format!("{v:.4}"),
    }
}

/// `a` against `b` as a signed percentage (`+32.1 %`).
fn change(a: f64, b: f64) -> String {
    if b != 0.0 && a.is_finite() && b.is_finite() {
        format!("{:+.1} %", (a / b - 1.0) * 100.0)
    } else {
        "—".into()
    }
}

/// A design's objectives, `label value, …`.
fn values(objectives: &[ParetoObjective], v: &[f64]) -> String {
    objectives
        .iter()
        .zip(v)
        .map(|(o, x)| format!("{} {}", o.label(), value(o, *x)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// What a table row costs against the building file's row: drift, base shear and floor
/// acceleration (means over the records of each run's peak, reference accuracy).
fn costs(row: &TableRow, file: &TableRow) -> String {
    format!(
        "mean peak drift ratio {} ({} against the file's {}), base shear {:.2} MN ({} against {:.2}), floor acceleration {:.2} m/s² ({} against {:.2})",
        drift(row.peak_drift_ratio_mean),
        change(row.peak_drift_ratio_mean, file.peak_drift_ratio_mean),
        drift(file.peak_drift_ratio_mean),
        row.base_shear_mean / 1e6,
        change(row.base_shear_mean, file.base_shear_mean),
        file.base_shear_mean / 1e6,
        row.peak_floor_acceleration_mean,
        change(
            row.peak_floor_acceleration_mean,
            file.peak_floor_acceleration_mean
        ),
        file.peak_floor_acceleration_mean,
    )
}

/// The lines of a searched, checked front.
pub fn front_lines(study: &Study, report: &StudyReport, p: &ParetoReport) -> Vec<String> {
    let mut out = Vec::new();
    let ev = &p.search.evaluated;
    let front = &p.certified.front;
    let nr = report.sweep.manifest.records.len();
    let names: Vec<String> = p.objectives.iter().map(ParetoObjective::label).collect();
    let searched = p.search.search_designs;
    let others = ev.len() - p.search.sweep_designs - searched;
    out.push(format!(
        "front of {}: {} non-dominated designs of {} evaluated ({} simulations at the sweep fidelity: sweep {}, search {}; {} run now){}",
        names.join(" vs "),
        front.len(),
        ev.len(),
        p.search.simulations(nr),
        (p.search.sweep_designs + 2) * nr,
        searched * nr,
        report.work.pareto.map_or(0, |w| w[0].run),
        if others > 0 {
            format!("; {others} more candidates from the building file and the refinement")
        } else {
            String::new()
        }
    ));
    if front.is_empty() {
        out.push("  every design collapsed on some record: no front".into());
        return out;
    }
    let row = |name: &str| p.table.rows.iter().find(|r| r.design == name);
    let file = row("file");
    let first = &p.objectives[0];
    let best = front[p.extremes[0]];
    let best_name = format!("min-{}", first.metric.as_str());
    out.push(format!(
        "  {} optimum {} ({} kN): {}",
        first.label(),
        ev[best].label,
        kn(&ev[best].slip_loads_n),
        values(&p.objectives, &ev[best].objectives)
    ));
    if let (Some(r), Some(f)) = (row(&best_name), file) {
        out.push(format!(
            "    what it costs against the building file's design ({} kN), {}: {}",
            kn(&study.file_slip_loads()),
            p.table.fidelity,
            costs(r, f)
        ));
    }
    let k = front[p.knee];
    let along: Vec<String> = p
        .objectives
        .iter()
        .zip(ev[k].objectives.iter().zip(&ev[best].objectives))
        .map(|(o, (a, b))| format!("{} {}", o.metric.as_str(), change(*a, *b)))
        .collect();
    out.push(format!(
        "  knee {} ({} kN), {} of {} along the front by {} (the point of least sum of the objectives normalised to the front's range): {}; against the {} optimum: {}",
        ev[k].label,
        kn(&ev[k].slip_loads_n),
        p.knee + 1,
        front.len(),
        first.label(),
        values(&p.objectives, &ev[k].objectives),
        first.metric.as_str(),
        along.join(", ")
    ));
    if let (Some(r), Some(f)) = (row("knee"), file) {
        out.push(format!(
            "    against the building file's design: {}",
            costs(r, f)
        ));
    }
    for (o, &pos) in p.objectives.iter().zip(&p.extremes).skip(1) {
        let i = front[pos];
        out.push(format!(
            "  {} optimum {} ({} kN): {}",
            o.label(),
            ev[i].label,
            kn(&ev[i].slip_loads_n),
            values(&p.objectives, &ev[i].objectives)
        ));
    }
    let first_optimum = format!("the {} optimum", first.metric.as_str());
    let bounds: Vec<String> = [(first_optimum.as_str(), best), ("the knee", k)]
        .into_iter()
        .map(|(what, i)| {
            let on = study.space.on_bounds(&ev[i].z);
            if on.is_empty() {
                format!("{what}: none")
            } else {
                format!("{what}: {}", on_bound_text(study, &ev[i].slip_loads_n, &on))
            }
        })
        .collect();
    out.push(format!(
        "  on a bound of the design space — {}",
        bounds.join("; ")
    ));
    out.extend(optimum_on_front(report, p));
    out.extend(file_outside_the_space(p));
    let c = &p.certified;
    let (worst, largest) =
        c.moved.iter().enumerate().fold(
            (0, 0.0),
            |acc, (i, &m)| if m > acc.1 { (i, m) } else { acc },
        );
    let dominated: Vec<String> = front
        .iter()
        .zip(c.check_ranks.iter().zip(&c.dominated_by))
        .filter(|(_, (r, _))| **r > 1)
        .map(|(&i, (_, by))| format!("{} (within {:.2} %)", ev[i].label, by * 100.0))
        .collect();
    out.push(format!(
        "  front at reference accuracy ({}): {}; largest change of an objective {:.2} % ({})",
        p.table.fidelity,
        if dominated.is_empty() {
            "held, no design became dominated".to_string()
        } else {
            format!(
                "{} of {} designs dominated now (within: the improvement in every objective that would make it non-dominated again): {}",
                dominated.len(),
                front.len(),
                dominated.join(", ")
            )
        },
        largest * 100.0,
        ev[front[worst]].label
    ));
    out
}

/// Where the study's optimum (the refinement's, which minimises the study's objective)
/// stands among the front's candidates at the sweep fidelity: on the front, or
/// dominated by a design named with why it is not the optimum. `None` when the optimum
/// is not among them (it always is: every design the study evaluated is a candidate).
fn optimum_on_front(report: &StudyReport, p: &ParetoReport) -> Option<String> {
    let ev = &p.search.evaluated;
    let i = ev.iter().position(|e| e.z == report.refine.optimum.z)?;
    let o = &ev[i];
    let head = format!(
        "  the study's optimum ({} kN, minimising {}) is {}",
        kn(&o.slip_loads_n),
        report.objective,
        o.label
    );
    if p.ranks[i] == 1 {
        return Some(format!(
            "{head}, on the front at the sweep fidelity: {}",
            values(&p.objectives, &o.objectives)
        ));
    }
    let by = p
        .certified
        .front
        .iter()
        .copied()
        .find(|&j| slipload_opt::phases::pareto::dominates(&ev[j].objectives, &o.objectives))?;
    Some(format!(
        "{head}, dominated at the sweep fidelity by {} ({} against {}): the optimum is the least of the study's objective over every design the study evaluated{}, and the front's objectives do not measure it alike",
        ev[by].label,
        values(&p.objectives, &ev[by].objectives),
        values(&p.objectives, &o.objectives),
        if report.code_check.is_some() {
            " that meets the limits at the check fidelity"
        } else {
            ""
        }
    ))
}

/// The building file's design, when the space cannot hold it (so it is no candidate of
/// the front) and it dominates front designs at the sweep fidelity: said, with how many.
fn file_outside_the_space(p: &ParetoReport) -> Option<String> {
    use slipload_opt::phases::pareto::search::Source;
    let ev = &p.search.evaluated;
    let file = &p.search.file;
    if ev.iter().any(|e| e.source == Source::File) || file.is_empty() {
        return None;
    }
    let beaten = p
        .certified
        .front
        .iter()
        .filter(|&&i| slipload_opt::phases::pareto::dominates(file, &ev[i].objectives))
        .count();
    (beaten > 0).then(|| {
        format!(
            "  the building file's design ({}) is outside the design space, so no candidate of the front, and dominates {beaten} of its {} designs: widen the space to hold it",
            values(&p.objectives, file),
            p.certified.front.len()
        )
    })
}

/// For a one-objective study: the front of (mean peak drift ratio, mean peak floor
/// acceleration) over the sweep's sampled designs, from the responses the sweep already
/// has, and its knee. `None` when the sweep's rows are missing or no design stands.
pub fn sweep_trade_off(study: &Study, report: &StudyReport) -> Option<String> {
    let rows = report.sweep.rows.as_ref()?;
    let m = &report.sweep.manifest;
    let nr = m.records.len();
    let mean = |v: Vec<f64>| v.iter().sum::<f64>() / v.len() as f64;
    let mut labels = Vec::new();
    let mut loads = Vec::new();
    let mut points = Vec::new();
    // the nominal properties: the first runs of each design
    let records = m.record_count();
    for (d, design) in m.designs.iter().enumerate() {
        let rec = &rows[d * nr..d * nr + records];
        if design.z.is_none() || rec.iter().any(RecordMetrics::collapsed) {
            continue;
        }
        points.push(vec![
            mean(rec.iter().map(RecordMetrics::peak_drift_ratio).collect()),
            mean(rec.iter().map(|r| r.peak_floor_acceleration).collect()),
        ]);
        labels.push(design.label.as_str());
        loads.push(design.slip_loads_n.as_slice());
    }
    let mut front = first_front(&points);
    front.sort_by(|&a, &b| points[a][0].total_cmp(&points[b][0]).then(a.cmp(&b)));
    let fv: Vec<Vec<f64>> = front.iter().map(|&i| points[i].clone()).collect();
    let k = front[knee(&fv)?];
    let say = |i: usize| {
        format!(
            "{} ({}: drift {}, floor acceleration {:.2} m/s²)",
            labels[i],
            loads_text(study, loads[i]),
            drift(points[i][0]),
            points[i][1]
        )
    };
    Some(format!(
        "trade-off in the sweep's {} designs (no extra simulation; name `objectives` in the study for a searched front checked at reference accuracy): {} non-dominated in mean peak drift ratio vs mean peak floor acceleration, from {} to {}; knee {}",
        points.len(),
        front.len(),
        say(front[0]),
        say(front[front.len() - 1]),
        say(k)
    ))
}
