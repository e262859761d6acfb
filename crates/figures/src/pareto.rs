//! The front figure of a study with `objectives` (`pareto-front.{svg,png,csv}`): two
//! objectives, one panel with every evaluated design and the front through them; three
//! or four, the pairwise panels (every design's projection, the front's designs
//! highlighted). The bare frame, the building file's design, each objective's optimum
//! on the front and the knee are marked.

use crate::FigureError;
use slipload_opt::model::objectives::{ParetoMetric, ParetoObjective};
use slipload_opt::phases::pareto::ParetoReport;
use std::fmt::Write as _;
use std::path::Path;

/// An objective's value as plotted, and its axis label: drift ratios in %, base shear in
/// MN, damper size in kN, the rest as they are.
fn scaled(o: &ParetoObjective) -> (f64, String) {
    let (k, unit) = match o.metric {
        ParetoMetric::PeakDriftRatio | ParetoMetric::ResidualDriftRatio => (100.0, "%"),
        ParetoMetric::PeakFloorAcceleration => (1.0, "m/s²"),
        ParetoMetric::BaseShear => (1e-6, "MN"),
        ParetoMetric::DamperSize => (1e-3, "kN"),
        _ => (1.0, "-"),
    };
    (k, format!("{} ({unit})", o.label()))
}

/// `pareto-front.csv`: every evaluated design's objectives (sweep fidelity), and the
/// marked designs (`bare`, `file`) after them, with a role column (`front`, `knee`,
/// `min-METRIC`, `evaluated`, `bare`, `file`).
pub fn front_csv(p: &ParetoReport) -> String {
    let mut s = String::from("label");
    for o in &p.objectives {
        let _ = write!(s, ",{}", o.column());
    }
    s.push_str(",role\n");
    let front = &p.certified.front;
    for (i, e) in p.search.evaluated.iter().enumerate() {
        let pos = front.iter().position(|&f| f == i);
        let role = match pos {
            Some(q) if q == p.knee => "knee".to_string(),
            Some(q) => match p.extremes.iter().position(|&x| x == q) {
                Some(m) => format!("min-{}", p.objectives[m].metric.as_str()),
                None => "front".to_string(),
            },
            None => "evaluated".to_string(),
        };
        let _ = write!(s, "{}", e.label);
        for v in &e.objectives {
            let _ = write!(s, ",{v}");
        }
        let _ = writeln!(s, ",{role}");
    }
    for (name, v) in [("bare", &p.search.bare), ("file", &p.search.file)] {
        let _ = write!(s, "{name}");
        for x in v {
            let _ = write!(s, ",{x}");
        }
        let _ = writeln!(s, ",{name}");
    }
    s
}

/// Writes `pareto-front.{svg,png,csv}` into `dir`; returns the stem written.
pub fn write_front(p: &ParetoReport, dir: &Path) -> Result<Vec<String>, FigureError> {
    use crate::plot::{Figure, Legend, Marker, Panel, Series, style};
    let k = p.objectives.len();
    let pairs: Vec<(usize, usize)> = (0..k)
        .flat_map(|a| (a + 1..k).map(move |b| (a, b)))
        .collect();
    let ev = &p.search.evaluated;
    let front = &p.certified.front;
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    let mut fig = Figure::new(format!(
        "Pareto front: {} designs evaluated, {} on the front",
        ev.len(),
        front.len()
    ));
    if pairs.len() > 1 {
        fig = fig.columns(if pairs.len() > 4 { 3 } else { 2 });
    }
    for (n, &(a, b)) in pairs.iter().enumerate() {
        let (ka, la) = scaled(&p.objectives[a]);
        let (kb, lb) = scaled(&p.objectives[b]);
        let xy = |idx: &mut dyn Iterator<Item = &Vec<f64>>| -> (Vec<f64>, Vec<f64>) {
            idx.filter(|v| finite(v))
                .map(|v| (v[a] * ka, v[b] * kb))
                .unzip()
        };
        let (ex, ey) = xy(&mut ev.iter().map(|e| &e.objectives));
        let (fx, fy) = xy(&mut front.iter().map(|&i| &ev[i].objectives));
        let front_series = if k == 2 {
            Series::line("front", fx, fy).marker(Marker::Circle)
        } else {
            Series::scatter("front (all objectives)", fx, fy)
        };
        let mut panel = Panel::new(la, lb)
            .legend(if n == 0 {
                Legend::LowerRight
            } else {
                Legend::None
            })
            .series(Series::scatter("evaluated", ex, ey).color(7).hollow())
            .series(front_series.color(0));
        let (ox, oy) = xy(&mut p.extremes.iter().map(|&q| &ev[front[q]].objectives));
        panel = panel.series(
            Series::scatter("objective optima", ox, oy)
                .marker(Marker::Square)
                .color(2),
        );
        if let Some(&i) = front.get(p.knee) {
            let (x, y) = xy(&mut std::iter::once(&ev[i].objectives));
            panel = panel.series(
                Series::scatter("knee", x, y)
                    .marker(Marker::Diamond)
                    .rgb(style::INK),
            );
        }
        for (name, v, m, c) in [
            (
                "building file's design",
                &p.search.file,
                Marker::Triangle,
                3,
            ),
            ("bare frame", &p.search.bare, Marker::Cross, 1),
        ] {
            if finite(v) {
                panel = panel.series(
                    Series::scatter(name, vec![v[a] * ka], vec![v[b] * kb])
                        .marker(m)
                        .color(c),
                );
            }
        }
        fig = fig.panel(panel);
    }
    slipload_opt::base::output::write_atomic(
        &dir.join("pareto-front.csv"),
        front_csv(p).as_bytes(),
    )?;
    fig.save(&dir.join("pareto-front"))?;
    Ok(vec!["pareto-front".to_string()])
}
