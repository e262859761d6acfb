//! The figure as data: a [`Figure`] of [`Panel`]s holding [`Series`] and [`HeatMap`]s,
//! with their builders. Drawing it is [`super::render`]'s; saving it, [`Figure::save`].

use super::axis::Axis;
use super::style;
use plotters::style::RGBColor;

/// A figure: a title and panels laid out on a grid, row by row.
#[derive(Debug, Clone)]
pub struct Figure {
    /// Title above all panels ("" for none).
    pub title: String,
    /// Panels in row-major order.
    pub panels: Vec<Panel>,
    /// Panels per row (default 1).
    pub columns: usize,
    /// Size in px; `None` = [`style::SIZE`] for one panel, else
    /// [`style::GRID_WIDTH`] × ([`style::ROW_HEIGHT`] per row + title).
    pub size: Option<(u32, u32)>,
}

/// Where a panel's legend goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Legend {
    /// Inside, top right (default).
    #[default]
    UpperRight,
    /// Inside, top left.
    UpperLeft,
    /// Inside, bottom right.
    LowerRight,
    /// Inside, bottom left.
    LowerLeft,
    /// Outside, right of the axes, top-aligned (the axes give up the width it needs):
    /// for time histories, which fill their axes.
    Right,
    /// No legend.
    None,
}

/// One pair of axes with its series (or one heat map).
#[derive(Debug, Clone)]
pub struct Panel {
    /// Title above the panel ("" for none).
    pub title: String,
    /// Horizontal axis.
    pub x: Axis,
    /// Vertical axis.
    pub y: Axis,
    /// Series, drawn in order (stacked areas stack in order, on the first one's x).
    pub series: Vec<Series>,
    /// A heat map drawn under the series, with a colour bar on the right.
    pub heatmap: Option<HeatMap>,
    /// Legend placement.
    pub legend: Legend,
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Polyline (gaps at non-finite points), optional markers.
    Line,
    /// Markers only.
    Scatter,
    /// A band stacked on the previous `Area` series of the panel (filled, translucent).
    Area,
}

/// Marker shapes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    /// ●
    Circle,
    /// ■
    Square,
    /// ▲
    Triangle,
    /// ◆
    Diamond,
    /// ✕ (use it for failed runs)
    Cross,
}

impl Marker {
    /// Shapes in the order series get them.
    pub const ALL: [Marker; 4] = [
        Marker::Circle,
        Marker::Square,
        Marker::Triangle,
        Marker::Diamond,
    ];
}

/// One data series.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend name.
    pub name: String,
    /// x values, data units.
    pub x: Vec<f64>,
    /// y values, data units (same length as `x`).
    pub y: Vec<f64>,
    /// How it is drawn.
    pub kind: Kind,
    /// Colour; `None` = palette colour of the series' index in its panel.
    pub color: Option<RGBColor>,
    /// Dashed line (reference lines: thresholds, targets).
    pub dashed: bool,
    /// Dotted line (a second kind of reference line: limits, a fraction of a target);
    /// takes precedence over `dashed`.
    pub dotted: bool,
    /// Markers at the points (always for `Scatter`; default circle).
    pub marker: Option<Marker>,
    /// Hollow markers.
    pub hollow: bool,
    /// Line width, px (default [`style::LINE_WIDTH`]).
    pub width: u32,
    /// Listed in the legend (default true).
    pub in_legend: bool,
}

/// A heat map: `z[j][i]` at cell centres (`x[i]`, `y[j]`); non-finite z drawn grey.
#[derive(Debug, Clone)]
pub struct HeatMap {
    /// Cell centres along x, increasing.
    pub x: Vec<f64>,
    /// Cell centres along y, increasing.
    pub y: Vec<f64>,
    /// Values, one row per y.
    pub z: Vec<Vec<f64>>,
    /// Colour-bar label, "quantity (unit)".
    pub label: String,
    /// Colour-bar range; `None` = the finite z range.
    pub z_range: Option<(f64, f64)>,
}

impl Panel {
    /// A panel with linear axes labelled `x_label` and `y_label` ("quantity (unit)").
    pub fn new(x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Self {
            title: String::new(),
            x: Axis::new(x_label),
            y: Axis::new(y_label),
            series: Vec::new(),
            heatmap: None,
            legend: Legend::default(),
        }
    }

    /// Sets the panel title.
    pub fn title(mut self, t: impl Into<String>) -> Self {
        self.title = t.into();
        self
    }

    /// Logarithmic x axis.
    pub fn x_log(mut self) -> Self {
        self.x.log = true;
        self
    }

    /// Logarithmic y axis.
    pub fn y_log(mut self) -> Self {
        self.y.log = true;
        self
    }

    /// Fixed x range.
    pub fn x_range(mut self, lo: f64, hi: f64) -> Self {
        self.x.range = Some((lo, hi));
        self
    }

    /// Fixed y range.
    pub fn y_range(mut self, lo: f64, hi: f64) -> Self {
        self.y.range = Some((lo, hi));
        self
    }

    /// A fitted x range that includes zero.
    pub fn x_from_zero(mut self) -> Self {
        self.x.include_zero = true;
        self
    }

    /// A fitted y range that includes zero.
    pub fn y_from_zero(mut self) -> Self {
        self.y.include_zero = true;
        self
    }

    /// Whole-number ticks on y (storeys, counts).
    pub fn y_integer(mut self) -> Self {
        self.y.integer = true;
        self
    }

    /// Whole-number ticks on x.
    pub fn x_integer(mut self) -> Self {
        self.x.integer = true;
        self
    }

    /// Legend placement.
    pub fn legend(mut self, l: Legend) -> Self {
        self.legend = l;
        self
    }

    /// Adds a series.
    pub fn series(mut self, s: Series) -> Self {
        self.series.push(s);
        self
    }

    /// Adds a series (in place).
    pub fn push(&mut self, s: Series) {
        self.series.push(s);
    }

    /// Sets the heat map.
    pub fn heatmap(mut self, h: HeatMap) -> Self {
        self.heatmap = Some(h);
        self
    }
}

impl Series {
    fn new(name: impl Into<String>, x: Vec<f64>, y: Vec<f64>, kind: Kind) -> Self {
        Self {
            name: name.into(),
            x,
            y,
            kind,
            color: None,
            dashed: false,
            dotted: false,
            marker: None,
            hollow: false,
            width: style::LINE_WIDTH,
            in_legend: true,
        }
    }

    /// A line through (x, y).
    pub fn line(name: impl Into<String>, x: Vec<f64>, y: Vec<f64>) -> Self {
        Self::new(name, x, y, Kind::Line)
    }

    /// Markers at (x, y).
    pub fn scatter(name: impl Into<String>, x: Vec<f64>, y: Vec<f64>) -> Self {
        let mut s = Self::new(name, x, y, Kind::Scatter);
        s.marker = Some(Marker::Circle);
        s
    }

    /// A stacked band of height y over x (stacks on the panel's previous band).
    pub fn area(name: impl Into<String>, x: Vec<f64>, y: Vec<f64>) -> Self {
        Self::new(name, x, y, Kind::Area)
    }

    /// A dashed horizontal reference line at `y` from `x0` to `x1`.
    pub fn hline(name: impl Into<String>, y: f64, x0: f64, x1: f64) -> Self {
        let mut s = Self::new(name, vec![x0, x1], vec![y, y], Kind::Line);
        s.dashed = true;
        s.width = style::REF_WIDTH;
        s
    }

    /// Palette colour `i`.
    pub fn color(mut self, i: usize) -> Self {
        self.color = Some(style::color(i));
        self
    }

    /// An explicit colour.
    pub fn rgb(mut self, c: RGBColor) -> Self {
        self.color = Some(c);
        self
    }

    /// Dashed line.
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }

    /// Dotted line.
    pub fn dotted(mut self) -> Self {
        self.dotted = true;
        self
    }

    /// Markers of shape `m` at the points.
    pub fn marker(mut self, m: Marker) -> Self {
        self.marker = Some(m);
        self
    }

    /// Hollow markers.
    pub fn hollow(mut self) -> Self {
        self.hollow = true;
        self
    }

    /// Line width, px.
    pub fn width(mut self, w: u32) -> Self {
        self.width = w.max(1);
        self
    }

    /// Leaves the series out of the legend.
    pub fn no_legend(mut self) -> Self {
        self.in_legend = false;
        self
    }
}
