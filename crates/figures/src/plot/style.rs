//! The one look every figure shares: sizes, fonts, palette, line widths, grid.
//!
//! Change a constant here and every figure of every command follows.

use plotters::style::RGBColor;

/// Default figure size, px (width, height) of a single-panel figure.
pub const SIZE: (u32, u32) = (900, 560);
/// Width of a multi-panel figure, px.
pub const GRID_WIDTH: u32 = 1000;
/// Height of one row of panels in a multi-panel figure, px.
pub const ROW_HEIGHT: u32 = 300;
/// Extra height for the figure title, px.
pub const TITLE_HEIGHT: u32 = 40;

/// Font family written into the SVG (a CSS list: DejaVu Sans is what the PNG uses).
pub const FONT: &str = "DejaVu Sans, Verdana, sans-serif";
/// Figure title size, SVG px.
pub const TITLE_PX: f64 = 19.0;
/// Panel title size, SVG px.
pub const PANEL_TITLE_PX: f64 = 15.0;
/// Axis description ("quantity (unit)") size, SVG px.
pub const AXIS_LABEL_PX: f64 = 14.0;
/// Tick label size, SVG px.
pub const TICK_PX: f64 = 12.5;
/// Legend text size, SVG px.
pub const LEGEND_PX: f64 = 12.5;

/// plotters writes `font-size = size / 1.24` into SVG; this turns SVG px into its size.
pub fn font_size(svg_px: f64) -> f64 {
    svg_px * 1.24
}

/// Average advance of one character of DejaVu Sans at 1 px size (for legend boxes).
pub const CHAR_WIDTH: f64 = 0.60;

/// Data line width, px.
pub const LINE_WIDTH: u32 = 2;
/// Reference-line (threshold, target) width, px (dashed).
pub const REF_WIDTH: u32 = 2;
/// Marker radius, px.
pub const MARKER_RADIUS: i32 = 4;
/// Dash and gap of dashed lines, px.
pub const DASH: (u32, u32) = (7, 5);
/// Dot and gap of dotted lines, px.
pub const DOT: (u32, u32) = (2, 4);
/// Opacity of stacked-area fills.
pub const AREA_OPACITY: f64 = 0.55;

/// Text and axis colour.
pub const INK: RGBColor = RGBColor(30, 30, 30);
/// Major grid lines.
pub const GRID: RGBColor = RGBColor(215, 215, 215);
/// Minor grid lines (log-axis subdivisions).
pub const GRID_MINOR: RGBColor = RGBColor(238, 238, 238);
/// Heat-map cells without a value (failed or missing runs).
pub const MISSING: RGBColor = RGBColor(190, 190, 190);

/// Series colours in order (Okabe–Ito, safe for colour-blind readers; yellow last).
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(0, 0, 0),       // black
    RGBColor(240, 228, 66),  // yellow
];

/// Colour `i` of the palette (wraps around).
pub fn color(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// Viridis sampled at nine equally spaced points (perceptually uniform colour map).
const VIRIDIS: [(u8, u8, u8); 9] = [
    (68, 1, 84),
    (71, 44, 122),
    (59, 81, 139),
    (44, 113, 142),
    (33, 144, 141),
    (39, 173, 129),
    (92, 200, 99),
    (170, 220, 50),
    (253, 231, 37),
];

/// The heat-map colour of `t` ∈ [0, 1] (clamped; NaN gives [`MISSING`]).
pub fn colormap(t: f64) -> RGBColor {
    if !t.is_finite() {
        return MISSING;
    }
    let t = t.clamp(0.0, 1.0) * (VIRIDIS.len() - 1) as f64;
    let i = (t.floor() as usize).min(VIRIDIS.len() - 2);
    let f = t - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    let mix = |p: u8, q: u8| (f64::from(p) + f * (f64::from(q) - f64::from(p))).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}
