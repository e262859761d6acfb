//! The figures of a study in plan ([`write_plan`]): `plan-view` — each storey's plan with
//! its lines, each line drawn as thick as the slip load its dampers carry there (the
//! optimum's; the legend gives the slip load and the line's drift), the centre of mass
//! marked — and `line-drift-profiles` — every line's drift per storey and the largest
//! at the plan's edges, the optimum solid beside the planar split (or the file's design)
//! dashed. Each with its data as CSV.

use crate::error::FigureError;
use crate::plot::{Figure, Legend, Marker, Panel, Series, style};
use slipload_opt::plan::PlanFigureData;
use slipload_sim::response::csv_field;
use std::fmt::Write as _;
use std::path::Path;

/// Thickest line drawn, px (the largest slip load of the figure).
const MAX_WIDTH: f64 = 12.0;

/// Writes `plan-view` and `line-drift-profiles` (`.svg`, `.png`, `.csv`) into `dir`;
/// returns the stems written.
pub fn write_plan(data: &PlanFigureData, dir: &Path) -> Result<Vec<String>, FigureError> {
    let mut names = Vec::new();
    let Some(opt) = data.designs.first() else {
        return Ok(names);
    };
    let unit = if data.ratios { "%" } else { "mm" };
    let scale = if data.ratios { 100.0 } else { 1e3 };
    let largest = opt.slip_loads.iter().flatten().copied().fold(0.0, f64::max);
    // plan view: one panel per storey, top storey first
    let mut fig = Figure::new(format!(
        "{}: plan view per storey, line width ~ slip load of the {}",
        data.study, opt.name
    ))
    .columns(data.storeys.clamp(1, 2));
    let mut csv = String::from("storey,line,x0_m,y0_m,x1_m,y1_m,slip_load_kn,drift\n");
    for f in (0..data.storeys).rev() {
        let drifts: Vec<String> = data
            .lines
            .iter()
            .enumerate()
            .map(|(l, line)| format!("{} {:.2}", line.name, opt.drifts[l][f] * scale))
            .collect();
        let mut panel = Panel::new("x (m)", "y (m)")
            .title(format!(
                "storey {}: drift ({unit}) {}",
                f + 1,
                drifts.join(", ")
            ))
            .legend(Legend::None);
        if let Some([lx, ly]) = data.plan_size {
            let pad = 0.08 * lx.max(ly);
            panel = panel.x_range(-pad, lx + pad).y_range(-pad, ly + pad);
            panel.push(
                Series::line(
                    "plan",
                    vec![0.0, lx, lx, 0.0, 0.0],
                    vec![0.0, 0.0, ly, ly, 0.0],
                )
                .rgb(style::GRID)
                .width(1)
                .no_legend(),
            );
        }
        for (l, line) in data.lines.iter().enumerate() {
            let load = opt.slip_loads[l][f];
            let width = if largest > 0.0 && load > 0.0 {
                (1.0 + (MAX_WIDTH - 1.0) * load / largest).round() as u32
            } else {
                1
            };
            let [[x0, y0], [x1, y1]] = line.ends;
            let drift = opt.drifts[l][f] * scale;
            panel.push(
                Series::line(
                    format!("{}: {:.0} kN, {drift:.2} {unit}", line.name, load / 1e3),
                    vec![x0, x1],
                    vec![y0, y1],
                )
                .color(l)
                .width(width),
            );
            let _ = writeln!(
                csv,
                "{},{},{x0},{y0},{x1},{y1},{:.1},{drift:.4}",
                f + 1,
                csv_field(&line.name),
                load / 1e3
            );
        }
        let [cx, cy] = data.centres[f];
        panel.push(
            Series::scatter("centre of mass", vec![cx], vec![cy])
                .marker(Marker::Diamond)
                .rgb(style::INK),
        );
        fig = fig.panel(panel);
    }
    slipload_opt::base::output::write_atomic(&dir.join("plan-view.csv"), csv.as_bytes())?;
    fig.save(&dir.join("plan-view"))?;
    names.push("plan-view".to_string());

    // drift profiles by line
    let storeys: Vec<f64> = (1..=data.storeys).map(|s| s as f64).collect();
    let mut panel = Panel::new(format!("peak drift ({unit})"), "storey")
        .x_from_zero()
        .y_integer()
        .legend(Legend::Right);
    let mut csv = String::from("design,measure,storey,drift\n");
    for (d, design) in data.designs.iter().enumerate() {
        for (l, line) in data.lines.iter().enumerate() {
            let x: Vec<f64> = design.drifts[l].iter().map(|v| v * scale).collect();
            for (s, v) in x.iter().enumerate() {
                let _ = writeln!(
                    csv,
                    "{},line {},{},{v:.4}",
                    csv_field(&design.name),
                    csv_field(&line.name),
                    s + 1
                );
            }
            let mut series = Series::line(
                format!("{} ({})", line.name, design.name),
                x,
                storeys.clone(),
            )
            .color(l)
            .marker(Marker::ALL[l % Marker::ALL.len()]);
            if d > 0 {
                series = series.dashed().hollow();
            }
            panel.push(series);
        }
        if !design.edge.is_empty() {
            let x: Vec<f64> = design.edge.iter().map(|v| v * scale).collect();
            for (s, v) in x.iter().enumerate() {
                let _ = writeln!(csv, "{},edges,{},{v:.4}", csv_field(&design.name), s + 1);
            }
            let mut series = Series::line(format!("edges ({})", design.name), x, storeys.clone())
                .rgb(style::INK);
            if d > 0 {
                series = series.dashed();
            }
            panel.push(series);
        }
    }
    let fig = Figure::new(format!(
        "{}: drift per storey by line (first suite, nominal case)",
        data.study
    ))
    .panel(panel);
    slipload_opt::base::output::write_atomic(&dir.join("line-drift-profiles.csv"), csv.as_bytes())?;
    fig.save(&dir.join("line-drift-profiles"))?;
    names.push("line-drift-profiles".to_string());
    Ok(names)
}
