//! What a figure shows, as data: written into every SVG we draw (a `<metadata
//! id="slipload-figure">` element holding JSON) and read back by tests and reports.
//!
//! Tests and reports read figures back with `meta::FigureMeta::from_svg(&svg)?`: every
//! panel's axis ranges (data units) and every series' name, point count and data range.

use crate::FigureError;
use crate::names::METADATA_ID;
use serde::{Deserialize, Serialize};

/// A figure: its title and panels (row-major order).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FigureMeta {
    /// Figure title.
    pub title: String,
    /// Figure size, px.
    pub width: u32,
    /// Figure size, px.
    pub height: u32,
    /// Panels, row by row.
    pub panels: Vec<PanelMeta>,
}

/// One panel (one pair of axes).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PanelMeta {
    /// Panel title ("" when none).
    pub title: String,
    /// Horizontal axis as drawn.
    pub x: AxisMeta,
    /// Vertical axis as drawn.
    pub y: AxisMeta,
    /// Series, in drawing order (a heat map counts as none; see `heatmap`).
    pub series: Vec<SeriesMeta>,
    /// The heat map of this panel, if it is one.
    pub heatmap: Option<HeatMapMeta>,
    /// The plotting area (inside the axes), px of the figure: [left, top, right, bottom].
    #[serde(default)]
    pub plot_area: Option<[i32; 4]>,
    /// The legend box, px of the figure: [left, top, right, bottom] (`None`: no legend).
    #[serde(default)]
    pub legend: Option<[i32; 4]>,
}

/// An axis as drawn.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AxisMeta {
    /// "quantity (unit)".
    pub label: String,
    /// Logarithmic.
    pub log: bool,
    /// Shown range, data units.
    pub min: f64,
    /// Shown range, data units.
    pub max: f64,
    /// Labelled (major) ticks, data units (empty in figures drawn before they were
    /// recorded).
    #[serde(default)]
    pub ticks: Vec<f64>,
}

/// One series.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SeriesMeta {
    /// Legend name.
    pub name: String,
    /// `line`, `scatter` or `area` (a stacked band).
    pub kind: String,
    /// Points given (including those a log axis could not show).
    pub points: usize,
    /// Points drawn (finite, and positive on log axes).
    pub drawn: usize,
    /// [min, max] of the drawn x values (`null`s when none was drawn).
    pub x: [Option<f64>; 2],
    /// [min, max] of the drawn y values; for a stacked band, of the band's own values
    /// (not the stacked total).
    pub y: [Option<f64>; 2],
}

/// A heat map: values z on a grid of cell centres.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HeatMapMeta {
    /// Colour-bar label, "quantity (unit)".
    pub label: String,
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    /// [min, max] of the finite z values (`null`s when none).
    pub z: [Option<f64>; 2],
    /// Colour-bar range, data units.
    pub z_range: [f64; 2],
    /// Cells without a finite value (drawn grey).
    pub missing: usize,
}

impl FigureMeta {
    /// The metadata element to put inside `<svg>…</svg>`.
    pub fn to_svg_element(&self) -> String {
        let json = serde_json::to_string(self).expect("figure metadata is plain data");
        format!(
            "<metadata id=\"{METADATA_ID}\">{}</metadata>\n",
            xml_escape(&json)
        )
    }

    /// Reads the metadata back from an SVG this module's writer produced.
    pub fn from_svg(svg: &str) -> Result<Self, FigureError> {
        let open = format!("<metadata id=\"{METADATA_ID}\">");
        let start = svg.find(&open).ok_or(FigureError::NoMetadata)? + open.len();
        let len = svg[start..]
            .find("</metadata>")
            .ok_or(FigureError::UnterminatedMetadata)?;
        let json = xml_unescape(&svg[start..start + len]);
        Ok(serde_json::from_str(&json)?)
    }
}

/// [min, max] of `values`, `None`s when there are none.
pub fn range_of(values: impl IntoIterator<Item = f64>) -> [Option<f64>; 2] {
    let mut r: [Option<f64>; 2] = [None, None];
    for v in values {
        r[0] = Some(r[0].map_or(v, |m: f64| m.min(v)));
        r[1] = Some(r[1].map_or(v, |m: f64| m.max(v)));
    }
    r
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn xml_unescape(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&")
}
