//! `slipload accuracy` figures: the work-precision diagram (error vs CPU time) and error
//! vs Δt with the fitted orders, one panel per error measure. The data are the rows of
//! `NAME.csv` whose scene is the report drawn (the median over records when there are
//! several, else the one record).

use slipload_figures::plot::{Figure, Legend, Marker, Panel, Series, style};
use slipload_sim::accuracy::{Entry, Errors, StudyReport};
use std::path::{Path, PathBuf};

/// The three error measures: (label on the axis, accessor, accessor of the fitted order).
type Measure = (
    &'static str,
    fn(&Errors) -> f64,
    fn(&slipload_sim::accuracy::Orders) -> Option<f64>,
);

const MEASURES: [Measure; 3] = [
    ("peak drift error (-)", |e| e.peak_drift, |o| o.peak_drift),
    (
        "friction energy error (-)",
        |e| e.friction_energy,
        |o| o.friction_energy,
    ),
    (
        "roof history error (-)",
        |e| e.roof_history,
        |o| o.roof_history,
    ),
];

/// Errors below this are round-off (the `exact` reference against itself): not drawn on
/// the log axes (the observed order ignores them too, `accuracy::observed_order`).
const FLOOR: f64 = 1e-13;

/// Methods in the report's order (first appearance).
fn methods(r: &StudyReport) -> Vec<&str> {
    let mut m: Vec<&str> = Vec::new();
    for e in &r.entries {
        if !m.contains(&e.method.as_str()) {
            m.push(&e.method);
        }
    }
    m
}

/// Log-axis range for the errors, with room on top for the "failed" row.
fn error_range(r: &StudyReport, err: fn(&Errors) -> f64) -> (f64, f64, f64) {
    let (lo, hi) = r
        .entries
        .iter()
        .filter_map(|e| e.errors.as_ref().map(err))
        .filter(|v| v.is_finite() && *v > FLOOR)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    let (lo, hi) = if lo.is_finite() {
        (lo, hi)
    } else {
        (1e-6, 1e-2)
    };
    // Failed runs sit on a row 8× above the largest error; the axis ends at 20×.
    (lo / 3.0, hi * 8.0, hi * 20.0)
}

/// Estimated CPU time of a failed entry: the cost of the method's successful run with the
/// nearest Δt, scaled by the step ratio (cost ∝ steps ∝ 1/Δt). `None` when the method has
/// no successful run.
fn estimated_cpu(failed: &Entry, ok: &[&Entry], cost: fn(&Entry) -> Option<f64>) -> Option<f64> {
    let near = ok.iter().filter(|e| cost(e).is_some()).min_by(|a, b| {
        (a.dt / failed.dt)
            .ln()
            .abs()
            .total_cmp(&(b.dt / failed.dt).ln().abs())
    })?;
    Some(cost(near)? * near.dt / failed.dt)
}

/// The cost a panel draws: the peak-drift panel the time of a run asking for peaks only
/// (what a sweep pays; the time with outputs for reports without it), the energy and
/// history panels the time of the runs they measure, with energies and histories.
fn panel_cost(measure: usize) -> (&'static str, fn(&Entry) -> Option<f64>) {
    if measure == 0 {
        ("CPU time per run, peaks only (s)", |e| {
            e.cpu_seconds_peaks_only.or(e.cpu_seconds)
        })
    } else {
        ("CPU time per run, with energies and histories (s)", |e| {
            e.cpu_seconds
        })
    }
}

/// Builds both figures.
pub fn figures(r: &StudyReport) -> (Figure, Figure) {
    let methods = methods(r);
    let mut wp = Figure::new(format!("Work-precision: {}", r.scene)).size(1000, 1000);
    let mut dt = Figure::new(format!("Error vs time step: {}", r.scene)).size(1000, 1000);
    for (measure, (label, err, order)) in MEASURES.into_iter().enumerate() {
        let (ylo, fail_y, yhi) = error_range(r, err);
        let (x_label, cost) = panel_cost(measure);
        let mut pw = Panel::new(x_label, label)
            .x_log()
            .y_log()
            .y_range(ylo, yhi)
            .legend(Legend::Right);
        let mut pd = Panel::new("time step Δt (s)", label)
            .x_log()
            .y_log()
            .y_range(ylo, yhi)
            .legend(Legend::Right);
        let mut fail_cost = (Vec::new(), Vec::new());
        let mut fail_dt = (Vec::new(), Vec::new());
        for (k, m) in methods.iter().enumerate() {
            let entries: Vec<&Entry> = r.entries.iter().filter(|e| e.method == *m).collect();
            let ok: Vec<&Entry> = entries
                .iter()
                .copied()
                .filter(|e| e.errors.is_some())
                .collect();
            let x_cpu: Vec<f64> = ok.iter().map(|e| cost(e).unwrap_or(f64::NAN)).collect();
            let x_dt: Vec<f64> = ok.iter().map(|e| e.dt).collect();
            let y: Vec<f64> = ok
                .iter()
                .map(|e| e.errors.as_ref().map_or(f64::NAN, err))
                .map(|v| if v > FLOOR { v } else { f64::NAN })
                .collect();
            let marker = Marker::ALL[k % Marker::ALL.len()];
            let name = if ok.is_empty() {
                format!("{m} (every run failed)")
            } else if y.iter().all(|v| v.is_nan()) {
                format!("{m} (errors < {FLOOR:.0e})")
            } else {
                m.to_string()
            };
            // The reference against itself is round-off, below the axis: its cost (at
            // T1/400, the default step, when the report has it) is a vertical line.
            let reference = (*m == "exact" && y.iter().all(|v| v.is_nan()))
                .then(|| {
                    ok.iter()
                        .find(|e| e.dt_label == "T1/400")
                        .or(ok.first())
                        .and_then(|e| cost(e).map(|c| (c, e.dt_label.clone())))
                })
                .flatten();
            match reference {
                Some((c, at)) => pw.push(
                    Series::line(
                        format!("exact at {at} (error vs itself < {FLOOR:.0e})"),
                        vec![c, c],
                        vec![ylo, yhi],
                    )
                    .dashed()
                    .color(k),
                ),
                None => pw.push(
                    Series::line(name.clone(), x_cpu, y.clone())
                        .marker(marker)
                        .color(k),
                ),
            }
            let with_order = match r.orders.iter().find(|o| o.method == *m).and_then(order) {
                Some(p) => format!("{name} (order {p:.2})"),
                None => name,
            };
            pd.push(Series::line(with_order, x_dt, y).marker(marker).color(k));
            for f in entries.iter().filter(|e| e.errors.is_none()) {
                fail_dt.0.push(f.dt);
                fail_dt.1.push(fail_y);
                if let Some(c) = estimated_cpu(f, &ok, cost) {
                    fail_cost.0.push(c);
                    fail_cost.1.push(fail_y);
                }
            }
        }
        pw.push(
            Series::scatter("failed (cost est. ∝ 1/Δt)", fail_cost.0, fail_cost.1)
                .marker(Marker::Cross)
                .rgb(style::INK),
        );
        pd.push(
            Series::scatter("failed", fail_dt.0, fail_dt.1)
                .marker(Marker::Cross)
                .rgb(style::INK),
        );
        wp = wp.panel(pw);
        dt = dt.panel(pd);
    }
    (wp, dt)
}

/// Writes `DIR/NAME-work-precision.{svg,png}` and `DIR/NAME-error-vs-dt.{svg,png}`.
pub fn write(dir: &Path, name: &str, r: &StudyReport) -> anyhow::Result<Vec<PathBuf>> {
    let (wp, dt) = figures(r);
    let (a, b) = wp.save(&dir.join(format!("{name}-work-precision")))?;
    let (c, d) = dt.save(&dir.join(format!("{name}-error-vs-dt")))?;
    Ok(vec![a, b, c, d])
}
