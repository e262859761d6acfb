//! Drawing a [`Figure`] into SVG with plotters, in the look of [`style`].

use super::axis::Scale;
use super::figure::{Figure, HeatMap, Kind, Legend, Marker, Panel, Series};
use super::meta::{AxisMeta, FigureMeta, HeatMapMeta, PanelMeta, SeriesMeta, range_of};
use super::style::{self, INK, font_size};
use crate::FigureError;
use plotters::coord::Shift;
use plotters::prelude::*;

/// Labelled ticks along x and y (at most).
const X_TICKS: usize = 10;
const Y_TICKS: usize = 8;

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

fn font(px: f64) -> TextStyle<'static> {
    (style::FONT, font_size(px)).into_font().color(&INK)
}

/// Draws `fig` and returns the SVG (metadata included) and the metadata.
pub fn svg(fig: &Figure) -> Result<(String, FigureMeta), FigureError> {
    if fig.panels.is_empty() {
        return Err(FigureError::NoPanels {
            title: fig.title.clone(),
        });
    }
    let (w, h) = fig.pixel_size();
    let mut out = String::new();
    let mut panels = Vec::new();
    {
        let root = SVGBackend::with_string(&mut out, (w, h)).into_drawing_area();
        root.fill(&WHITE)?;
        let body = if fig.title.is_empty() {
            root.clone()
        } else {
            root.titled(&fig.title, font(style::TITLE_PX))?
        };
        let cells = body.split_evenly((fig.rows(), fig.columns.max(1)));
        for (p, cell) in fig.panels.iter().zip(&cells) {
            panels.push(draw_panel(&root, cell, p)?);
        }
        root.present()?;
    }
    let meta = FigureMeta {
        title: fig.title.clone(),
        width: w,
        height: h,
        panels,
    };
    let end = out.rfind("</svg>").ok_or(FigureError::UnterminatedSvg)?;
    out.insert_str(end, &meta.to_svg_element());
    Ok((out, meta))
}

/// Finite (and positive on log axes) (x, y) pairs of the given columns.
fn accepted<'a>(
    xs: &'a [f64],
    ys: &'a [f64],
    sx: Scale,
    sy: Scale,
) -> impl Iterator<Item = (f64, f64)> + 'a {
    xs.iter()
        .zip(ys)
        .map(|(&x, &y)| (x, y))
        .filter(move |&(x, y)| sx.accepts(x) && sy.accepts(y))
}

fn data_range(vals: impl Iterator<Item = f64>, log: bool) -> Option<(f64, f64)> {
    let r = range_of(vals.filter(|v| v.is_finite() && (!log || *v > 0.0)));
    Some((r[0]?, r[1]?))
}

/// Stacked tops of the panel's `Area` series (each band on the previous one).
fn stacked_tops(p: &Panel) -> Result<Vec<Vec<f64>>, FigureError> {
    let mut base: Option<Vec<f64>> = None;
    let mut tops = Vec::new();
    for s in p.series.iter().filter(|s| s.kind == Kind::Area) {
        let top: Vec<f64> = match &base {
            None => s.y.clone(),
            Some(b) => {
                if b.len() != s.y.len() {
                    return Err(FigureError::BandLengths {
                        name: s.name.clone(),
                        points: s.y.len(),
                        below: b.len(),
                    });
                }
                b.iter().zip(&s.y).map(|(b, y)| b + y).collect()
            }
        };
        base = Some(top.clone());
        tops.push(top);
    }
    Ok(tops)
}

fn heat_edges(c: &[f64]) -> Vec<f64> {
    match c.len() {
        0 => vec![],
        1 => vec![c[0] - 0.5, c[0] + 0.5],
        n => {
            let mut e = Vec::with_capacity(n + 1);
            e.push(c[0] - 0.5 * (c[1] - c[0]));
            for i in 0..n - 1 {
                e.push(0.5 * (c[i] + c[i + 1]));
            }
            e.push(c[n - 1] + 0.5 * (c[n - 1] - c[n - 2]));
            e
        }
    }
}

fn check_lengths(p: &Panel) -> Result<(), FigureError> {
    for s in &p.series {
        if s.x.len() != s.y.len() {
            return Err(FigureError::SeriesLengths {
                name: s.name.clone(),
                x: s.x.len(),
                y: s.y.len(),
            });
        }
    }
    if let Some(h) = &p.heatmap
        && (h.z.len() != h.y.len() || h.z.iter().any(|r| r.len() != h.x.len()))
    {
        return Err(FigureError::HeatMapShape {
            label: h.label.clone(),
            rows: h.y.len(),
            columns: h.x.len(),
        });
    }
    Ok(())
}

/// The axis scales of a panel: fixed ranges, else fitted to the points that can be drawn
/// (both coordinates finite, and positive on a log axis).
fn scales(p: &Panel, tops: &[Vec<f64>]) -> (Scale, Scale) {
    let ok_x = |v: f64| v.is_finite() && (!p.x.log || v > 0.0);
    let ok_y = |v: f64| v.is_finite() && (!p.y.log || v > 0.0);
    let mut xs: Vec<f64> = Vec::new();
    let mut ys: Vec<f64> = Vec::new();
    let mut push = |x: &[f64], y: &[f64]| {
        for (&a, &b) in x.iter().zip(y) {
            if ok_x(a) && ok_y(b) {
                xs.push(a);
                ys.push(b);
            }
        }
    };
    let mut areas = 0;
    for s in &p.series {
        if s.kind == Kind::Area {
            push(&s.x, &tops[areas]);
            areas += 1;
        }
        push(&s.x, &s.y);
    }
    if let Some(h) = &p.heatmap {
        xs.extend(heat_edges(&h.x));
        ys.extend(heat_edges(&h.y));
    }
    let (xlo, xhi) = p.x.resolve(data_range(xs.into_iter(), p.x.log));
    let (ylo, yhi) = p.y.resolve(data_range(ys.into_iter(), p.y.log));
    (
        Scale {
            lo: xlo,
            hi: xhi,
            log: p.x.log,
            ticks: X_TICKS,
            integer: p.x.integer,
        },
        Scale {
            lo: ylo,
            hi: yhi,
            log: p.y.log,
            ticks: Y_TICKS,
            integer: p.y.integer,
        },
    )
}

/// Width of the y tick labels, px (DejaVu Sans average advance).
fn tick_label_width(s: Scale) -> u32 {
    let chars = s
        .major_ticks(s.ticks)
        .iter()
        .map(|v| s.format(*v).chars().count())
        .max()
        .unwrap_or(1);
    (chars as f64 * style::TICK_PX * style::CHAR_WIDTH).ceil() as u32
}

fn draw_panel(root: &Area, cell: &Area, p: &Panel) -> Result<PanelMeta, FigureError> {
    check_lengths(p)?;
    let tops = stacked_tops(p)?;
    let (sx, sy) = scales(p, &tops);
    let (cell, legend_strip) = if p.legend == Legend::Right {
        let (w, _) = cell.dim_in_pixel();
        let lw = legend_size(&legend_entries(p)).0 as u32 + 6;
        let (a, b) = cell.split_horizontally(w.saturating_sub(lw));
        (a, Some(b))
    } else {
        (cell.clone(), None)
    };
    let (chart_area, bar_area) = if p.heatmap.is_some() {
        let (w, _) = cell.dim_in_pixel();
        let (a, b) = cell.split_horizontally(w.saturating_sub(100));
        (a, Some(b))
    } else {
        (cell.clone(), None)
    };
    let mut builder = ChartBuilder::on(&chart_area);
    builder
        .margin(10)
        .margin_right(22)
        .x_label_area_size((style::TICK_PX + style::AXIS_LABEL_PX * 1.3 + 16.0).ceil() as u32)
        .y_label_area_size(tick_label_width(sy) + (style::AXIS_LABEL_PX * 1.3 + 16.0) as u32);
    if !p.title.is_empty() {
        builder.caption(&p.title, font(style::PANEL_TITLE_PX));
    }
    let mut chart = builder.build_cartesian_2d(sx, sy)?;
    chart
        .configure_mesh()
        .x_desc(p.x.label.as_str())
        .y_desc(p.y.label.as_str())
        .label_style(font(style::TICK_PX))
        .axis_desc_style(font(style::AXIS_LABEL_PX))
        .axis_style(INK)
        .bold_line_style(style::GRID)
        .light_line_style(style::GRID_MINOR)
        .x_labels(X_TICKS)
        .y_labels(Y_TICKS)
        .draw()?;

    let mut heat_meta = None;
    if let Some(h) = &p.heatmap {
        heat_meta = Some(draw_heatmap(&mut chart, h, bar_area.as_ref())?);
    }

    let (px, _) = chart.plotting_area().get_pixel_range();
    let width_px = (px.end - px.start).max(1) as usize;
    let mut metas = Vec::new();
    let mut area_i = 0;
    let mut base: Option<&Vec<f64>> = None;
    for (i, s) in p.series.iter().enumerate() {
        let color = s.color.unwrap_or_else(|| style::color(i));
        let pts: Vec<(f64, f64)> = accepted(&s.x, &s.y, sx, sy).collect();
        match s.kind {
            Kind::Area => {
                let top = &tops[area_i];
                area_i += 1;
                draw_band(&mut chart, &s.x, top, base, color, (sx, sy), width_px)?;
                base = Some(top);
            }
            Kind::Line => draw_line(&mut chart, &s.x, &s.y, s, color, sx, sy, width_px)?,
            Kind::Scatter => {}
        }
        if s.marker.is_some() || s.kind == Kind::Scatter {
            draw_markers(&mut chart, &pts, s, color)?;
        }
        metas.push(SeriesMeta {
            name: s.name.clone(),
            kind: match s.kind {
                Kind::Line => "line",
                Kind::Scatter => "scatter",
                Kind::Area => "area",
            }
            .into(),
            points: s.x.len(),
            drawn: pts.len(),
            x: range_of(pts.iter().map(|p| p.0)),
            y: range_of(pts.iter().map(|p| p.1)),
        });
    }
    let legend = legend_entries(p);
    let (lw, lh) = legend_size(&legend);
    let (pxr, pyr) = chart.plotting_area().get_pixel_range();
    let plot_area = [pxr.start, pyr.start, pxr.end, pyr.end];
    let legend_at = match legend_strip {
        Some(strip) => {
            let (xr, _) = strip.get_pixel_range();
            Some((xr.start, pyr.start))
        }
        None => {
            let margin = 8;
            let x0 = match p.legend {
                Legend::UpperLeft | Legend::LowerLeft => pxr.start + margin,
                _ => pxr.end - margin - lw,
            };
            let y0 = match p.legend {
                Legend::LowerLeft | Legend::LowerRight => pyr.end - margin - lh,
                _ => pyr.start + margin,
            };
            (p.legend != Legend::None).then_some((x0, y0))
        }
    };
    let mut legend_box = None;
    if let Some((x0, y0)) = legend_at
        && !legend.is_empty()
    {
        draw_legend(root, (x0, y0), &legend)?;
        legend_box = Some([x0, y0, x0 + lw, y0 + lh]);
    }
    Ok(PanelMeta {
        title: p.title.clone(),
        x: AxisMeta {
            label: p.x.label.clone(),
            log: sx.log,
            min: sx.lo,
            max: sx.hi,
            ticks: sx.major_ticks(sx.ticks),
        },
        y: AxisMeta {
            label: p.y.label.clone(),
            log: sy.log,
            min: sy.lo,
            max: sy.hi,
            ticks: sy.major_ticks(sy.ticks),
        },
        series: metas,
        heatmap: heat_meta,
        plot_area: Some(plot_area),
        legend: legend_box,
    })
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<Scale, Scale>>;

fn line_style(s: &Series, color: RGBColor) -> ShapeStyle {
    color.stroke_width(s.width)
}

/// Thins a long polyline to at most ~4 points per pixel column (first, min, max, last of
/// each column, in order): the drawn shape and the data range are unchanged.
fn thin(seg: &[(f64, f64)], sx: Scale, width_px: usize) -> Vec<(f64, f64)> {
    if seg.len() <= 4 * width_px {
        return seg.to_vec();
    }
    let col = |x: f64| {
        let t = if sx.log {
            (x.ln() - sx.lo.ln()) / (sx.hi.ln() - sx.lo.ln())
        } else {
            (x - sx.lo) / (sx.hi - sx.lo)
        };
        (t * width_px as f64).floor() as i64
    };
    let mut out = Vec::with_capacity(4 * width_px + 4);
    let mut i = 0;
    while i < seg.len() {
        let c = col(seg[i].0);
        let mut j = i;
        let (mut lo, mut hi) = (i, i);
        while j < seg.len() && col(seg[j].0) == c {
            if seg[j].1 < seg[lo].1 {
                lo = j;
            }
            if seg[j].1 > seg[hi].1 {
                hi = j;
            }
            j += 1;
        }
        let mut keep = [i, lo, hi, j - 1];
        keep.sort_unstable();
        let mut last = usize::MAX;
        for k in keep {
            if k != last {
                out.push(seg[k]);
                last = k;
            }
        }
        i = j;
    }
    out
}

#[allow(clippy::too_many_arguments)] // one call site; the arguments are the panel's state
fn draw_line(
    chart: &mut Chart,
    xs: &[f64],
    ys: &[f64],
    s: &Series,
    color: RGBColor,
    sx: Scale,
    sy: Scale,
    width_px: usize,
) -> Result<(), FigureError> {
    // Split at points the axes cannot show (NaN gaps, non-positive values on log axes).
    let mut seg: Vec<(f64, f64)> = Vec::new();
    let flush = |seg: &mut Vec<(f64, f64)>, chart: &mut Chart| -> Result<(), FigureError> {
        if seg.len() >= 2 {
            let pts = thin(seg, sx, width_px);
            if s.dotted {
                chart.draw_series(DashedLineSeries::new(
                    pts,
                    style::DOT.0,
                    style::DOT.1,
                    line_style(s, color),
                ))?;
            } else if s.dashed {
                chart.draw_series(DashedLineSeries::new(
                    pts,
                    style::DASH.0,
                    style::DASH.1,
                    line_style(s, color),
                ))?;
            } else {
                chart.draw_series(LineSeries::new(pts, line_style(s, color)))?;
            }
        }
        seg.clear();
        Ok(())
    };
    for (&x, &y) in xs.iter().zip(ys) {
        if sx.accepts(x) && sy.accepts(y) {
            seg.push((x, y));
        } else {
            flush(&mut seg, chart)?;
        }
    }
    flush(&mut seg, chart)
}

fn draw_band(
    chart: &mut Chart,
    xs: &[f64],
    top: &[f64],
    base: Option<&Vec<f64>>,
    color: RGBColor,
    (sx, sy): (Scale, Scale),
    width_px: usize,
) -> Result<(), FigureError> {
    let ok = |x: f64, y: f64| sx.accepts(x) && sy.accepts(y);
    let upper: Vec<(f64, f64)> = xs
        .iter()
        .zip(top)
        .filter(|(x, y)| ok(**x, **y))
        .map(|(x, y)| (*x, *y))
        .collect();
    let lower: Vec<(f64, f64)> = match base {
        Some(b) => xs
            .iter()
            .zip(b)
            .filter(|(x, y)| ok(**x, **y))
            .map(|(x, y)| (*x, *y))
            .collect(),
        None => xs
            .iter()
            .filter(|x| sx.accepts(**x))
            .map(|x| (*x, if sy.log { sy.lo } else { 0.0 }))
            .collect(),
    };
    let upper = thin(&upper, sx, width_px);
    let lower = thin(&lower, sx, width_px);
    let mut poly = upper.clone();
    poly.extend(lower.iter().rev());
    chart.draw_series(std::iter::once(Polygon::new(
        poly,
        color.mix(style::AREA_OPACITY).filled(),
    )))?;
    chart.draw_series(LineSeries::new(upper, color.stroke_width(1)))?;
    Ok(())
}

fn marker_style(s: &Series, color: RGBColor) -> ShapeStyle {
    let m = s.marker.unwrap_or(Marker::Circle);
    if s.hollow || m == Marker::Cross {
        color.stroke_width(2)
    } else {
        color.filled()
    }
}

fn draw_markers(
    chart: &mut Chart,
    pts: &[(f64, f64)],
    s: &Series,
    color: RGBColor,
) -> Result<(), FigureError> {
    let m = s.marker.unwrap_or(Marker::Circle);
    let st = marker_style(s, color);
    let plot = chart.plotting_area();
    let r = style::MARKER_RADIUS;
    for &c in pts {
        let at = EmptyElement::at(c);
        match m {
            Marker::Circle => plot.draw(&(at + Circle::new((0, 0), r, st)))?,
            Marker::Square => plot.draw(&(at + Rectangle::new([(-r, -r), (r, r)], st)))?,
            Marker::Triangle => plot.draw(&(at + TriangleMarker::new((0, 0), r + 1, st)))?,
            Marker::Diamond => plot.draw(
                &(at + Polygon::new(vec![(0, -r - 1), (r + 1, 0), (0, r + 1), (-r - 1, 0)], st)),
            )?,
            Marker::Cross => plot.draw(&(at + Cross::new((0, 0), r + 1, st)))?,
        }
    }
    Ok(())
}

/// The legend entries of a panel: named series not left out, with their colours.
fn legend_entries(p: &Panel) -> Vec<(&Series, RGBColor)> {
    p.series
        .iter()
        .enumerate()
        .filter(|(_, s)| s.in_legend && !s.name.is_empty())
        .map(|(i, s)| (s, s.color.unwrap_or_else(|| style::color(i))))
        .collect()
}

const LEGEND_PAD: i32 = 7;
const LEGEND_GLYPH: i32 = 26;

fn legend_row() -> i32 {
    (style::LEGEND_PX * 1.45).round() as i32
}

/// Legend box size, px.
fn legend_size(entries: &[(&Series, RGBColor)]) -> (i32, i32) {
    if entries.is_empty() {
        return (0, 0);
    }
    let text_w = entries
        .iter()
        .map(|(s, _)| s.name.chars().count())
        .max()
        .unwrap_or(0) as f64
        * style::LEGEND_PX
        * style::CHAR_WIDTH;
    (
        LEGEND_PAD * 3 + LEGEND_GLYPH + text_w.ceil() as i32,
        LEGEND_PAD * 2 + legend_row() * entries.len() as i32,
    )
}

/// Legend box with its top-left corner at `(x0, y0)` (pixel coordinates of the root).
fn draw_legend(
    root: &Area,
    (x0, y0): (i32, i32),
    entries: &[(&Series, RGBColor)],
) -> Result<(), FigureError> {
    if entries.is_empty() {
        return Ok(());
    }
    let (w, h) = legend_size(entries);
    let (pad, glyph, row) = (LEGEND_PAD, LEGEND_GLYPH, legend_row());
    root.draw(&Rectangle::new(
        [(x0, y0), (x0 + w, y0 + h)],
        WHITE.mix(0.88).filled(),
    ))?;
    root.draw(&Rectangle::new(
        [(x0, y0), (x0 + w, y0 + h)],
        style::GRID.stroke_width(1),
    ))?;
    for (k, (s, color)) in entries.iter().enumerate() {
        let cy = y0 + pad + row * k as i32 + row / 2;
        let gx = x0 + pad;
        match s.kind {
            Kind::Area => {
                root.draw(&Rectangle::new(
                    [(gx + 3, cy - 6), (gx + glyph - 3, cy + 6)],
                    color.mix(style::AREA_OPACITY).filled(),
                ))?;
            }
            Kind::Line => {
                let st = line_style(s, *color);
                if s.dotted {
                    for a in (0..glyph).step_by(6) {
                        root.draw(&PathElement::new(vec![(gx + a, cy), (gx + a + 2, cy)], st))?;
                    }
                } else if s.dashed {
                    for (a, b) in [(0, 8), (13, 21)] {
                        root.draw(&PathElement::new(vec![(gx + a, cy), (gx + b, cy)], st))?;
                    }
                } else {
                    root.draw(&PathElement::new(vec![(gx, cy), (gx + glyph, cy)], st))?;
                }
            }
            Kind::Scatter => {}
        }
        if s.marker.is_some() || s.kind == Kind::Scatter {
            let m = s.marker.unwrap_or(Marker::Circle);
            let st = marker_style(s, *color);
            let c = (gx + glyph / 2, cy);
            let r = style::MARKER_RADIUS;
            match m {
                Marker::Circle => root.draw(&Circle::new(c, r, st))?,
                Marker::Square => root.draw(&Rectangle::new(
                    [(c.0 - r, c.1 - r), (c.0 + r, c.1 + r)],
                    st,
                ))?,
                Marker::Triangle => root.draw(&TriangleMarker::new(c, r + 1, st))?,
                Marker::Diamond => root.draw(&Polygon::new(
                    vec![
                        (c.0, c.1 - r - 1),
                        (c.0 + r + 1, c.1),
                        (c.0, c.1 + r + 1),
                        (c.0 - r - 1, c.1),
                    ],
                    st,
                ))?,
                Marker::Cross => root.draw(&Cross::new(c, r + 1, st))?,
            }
        }
        root.draw(&Text::new(
            s.name.clone(),
            (gx + glyph + pad, cy),
            font(style::LEGEND_PX).pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Left,
                plotters::style::text_anchor::VPos::Center,
            )),
        ))?;
    }
    Ok(())
}

fn draw_heatmap(
    chart: &mut Chart,
    h: &HeatMap,
    bar: Option<&Area>,
) -> Result<HeatMapMeta, FigureError> {
    let finite = range_of(h.z.iter().flatten().copied().filter(|v| v.is_finite()));
    let (zlo, zhi) = h.z_range.unwrap_or(match finite {
        [Some(a), Some(b)] if b > a => (a, b),
        [Some(a), Some(_)] => (a - 0.5 * a.abs().max(1.0), a + 0.5 * a.abs().max(1.0)),
        _ => (0.0, 1.0),
    });
    let ex = heat_edges(&h.x);
    let ey = heat_edges(&h.y);
    let mut missing = 0;
    for (j, row) in h.z.iter().enumerate() {
        for (i, &z) in row.iter().enumerate() {
            if !z.is_finite() {
                missing += 1;
            }
            let c = style::colormap((z - zlo) / (zhi - zlo));
            chart.draw_series(std::iter::once(Rectangle::new(
                [(ex[i], ey[j]), (ex[i + 1], ey[j + 1])],
                c.filled(),
            )))?;
        }
    }
    if let Some(bar) = bar {
        let zs = Scale {
            lo: zlo,
            hi: zhi,
            log: false,
            ticks: Y_TICKS,
            integer: false,
        };
        let unit = Scale {
            lo: 0.0,
            hi: 1.0,
            log: false,
            ticks: 2,
            integer: false,
        };
        let mut b = ChartBuilder::on(bar)
            .margin_top(10)
            .margin_bottom((style::TICK_PX + style::AXIS_LABEL_PX * 1.3 + 26.0).ceil() as u32)
            .margin_left(4)
            .margin_right(4)
            .right_y_label_area_size(
                tick_label_width(zs) + (style::AXIS_LABEL_PX * 1.3 + 14.0) as u32,
            )
            .build_cartesian_2d(unit, zs)?;
        b.configure_mesh()
            .disable_x_mesh()
            .disable_y_mesh()
            .disable_x_axis()
            .y_desc(h.label.as_str())
            .label_style(font(style::TICK_PX))
            .axis_desc_style(font(style::AXIS_LABEL_PX))
            .axis_style(INK)
            .y_labels(Y_TICKS)
            .draw()?;
        let n = 64;
        b.draw_series((0..n).map(|k| {
            let a = zlo + (zhi - zlo) * k as f64 / n as f64;
            let c = zlo + (zhi - zlo) * (k + 1) as f64 / n as f64;
            Rectangle::new(
                [(0.0, a), (1.0, c)],
                style::colormap((k as f64 + 0.5) / n as f64).filled(),
            )
        }))?;
    }
    Ok(HeatMapMeta {
        label: h.label.clone(),
        nx: h.x.len(),
        ny: h.y.len(),
        z: finite,
        z_range: [zlo, zhi],
        missing,
    })
}
