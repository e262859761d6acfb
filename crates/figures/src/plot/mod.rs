//! Figures: one look for every plot slipload draws, written as `NAME.svg` and `NAME.png`.
//!
//! A figure is described as data ([`Figure`] → [`Panel`]s → [`Series`] or a [`HeatMap`]),
//! then [`Figure::save`] draws it with plotters into an SVG, rasterises that SVG with
//! resvg into a PNG that looks the same (text in DejaVu Sans read from the system at run
//! time, see [`raster`]), and writes both atomically. Every SVG carries a
//! `<metadata id="slipload-figure">` element ([`meta::FigureMeta`]) with each panel's
//! axis ranges and each series' name, point count and data range, so tests and reports
//! can read a figure back without parsing pixels.
//!
//! Adding a figure: build the panels from the data the command already has (axis labels
//! "quantity (unit)", converted to the units shown), call `save(dir.join("name"))`, and
//! write the data to a CSV beside it when no CSV there has it already.

pub mod axis;
mod figure;
pub mod meta;
pub mod raster;
mod render;
pub mod style;

pub use axis::Axis;
pub use figure::{Figure, HeatMap, Kind, Legend, Marker, Panel, Series};
pub use meta::FigureMeta;
pub use plotters::style::RGBColor;

use crate::FigureError;
use std::path::{Path, PathBuf};

impl Figure {
    /// An empty figure titled `title`.
    pub fn new(title: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            panels: Vec::new(),
            columns: 1,
            size: None,
        }
    }

    /// Adds a panel.
    pub fn panel(mut self, p: Panel) -> Self {
        self.panels.push(p);
        self
    }

    /// Panels per row.
    pub fn columns(mut self, n: usize) -> Self {
        self.columns = n.max(1);
        self
    }

    /// Size in px.
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.size = Some((width, height));
        self
    }

    /// Rows of the panel grid.
    pub fn rows(&self) -> usize {
        self.panels.len().div_ceil(self.columns.max(1)).max(1)
    }

    /// The size the figure is drawn at, px.
    pub fn pixel_size(&self) -> (u32, u32) {
        self.size.unwrap_or_else(|| {
            if self.panels.len() <= 1 {
                style::SIZE
            } else {
                let title = if self.title.is_empty() {
                    0
                } else {
                    style::TITLE_HEIGHT
                };
                (
                    style::GRID_WIDTH,
                    self.rows() as u32 * style::ROW_HEIGHT + title,
                )
            }
        })
    }

    /// The SVG text (with its metadata element) and the metadata.
    pub fn to_svg(&self) -> Result<(String, FigureMeta), FigureError> {
        render::svg(self)
    }

    /// Writes `STEM.svg` and `STEM.png` (a trailing `.svg`/`.png` on `stem` is ignored).
    /// Both are rendered before either is written, and each is written atomically, so a
    /// failure leaves no partial file. Returns the paths written (SVG, PNG).
    pub fn save(&self, stem: &Path) -> Result<(PathBuf, PathBuf), FigureError> {
        let stem = strip_image_extension(stem);
        let (svg, _) = self.to_svg().map_err(|e| FigureError::Draw {
            stem: stem.clone(),
            source: Box::new(e),
        })?;
        let png = raster::svg_to_png(&svg).map_err(|e| FigureError::Rasterise {
            stem: stem.clone(),
            source: Box::new(e),
        })?;
        let svg_path = with_suffix(&stem, "svg");
        let png_path = with_suffix(&stem, "png");
        slipload_opt::base::output::write_atomic(&svg_path, svg.as_bytes())?;
        slipload_opt::base::output::write_atomic(&png_path, &png)?;
        Ok((svg_path, png_path))
    }
}

/// `stem` without a trailing `.svg` or `.png`.
pub fn strip_image_extension(stem: &Path) -> PathBuf {
    match stem.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("svg") || e.eq_ignore_ascii_case("png") => {
            stem.with_extension("")
        }
        _ => stem.to_path_buf(),
    }
}

/// `stem` + `.ext`, appended (a stem like `x-0.40g` keeps its dot).
pub fn with_suffix(stem: &Path, ext: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_os_string();
    s.push(".");
    s.push(ext);
    PathBuf::from(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn demo_dir() -> PathBuf {
        let d = std::env::temp_dir().join(format!("slipload-plot-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    /// Every series kind, log axes, a legend, a heat map: drawn, rasterised, read back.
    #[test]
    fn every_kind_draws_and_reads_back() {
        let t: Vec<f64> = (0..=2000).map(|i| i as f64 * 0.01).collect();
        let y: Vec<f64> = t.iter().map(|t| (t * 3.0).sin() * 12.0).collect();
        let mut with_gap = y.clone();
        with_gap[700] = f64::NAN;
        let lines = Panel::new("time (s)", "displacement (mm)")
            .title("lines")
            .series(Series::line("floor 1", t.clone(), with_gap))
            .series(Series::hline("±μN/k′", 10.0, 0.0, 20.0).rgb(style::INK))
            .series(
                Series::hline("", -10.0, 0.0, 20.0)
                    .rgb(style::INK)
                    .no_legend(),
            );
        let e1: Vec<f64> = t.iter().map(|t| t * 2.0).collect();
        let e2: Vec<f64> = t.iter().map(|t| 1.0 + t.sin()).collect();
        let areas = Panel::new("time (s)", "energy (kJ)")
            .title("stacked")
            .y_from_zero()
            .legend(Legend::UpperLeft)
            .series(Series::area("friction", t.clone(), e1))
            .series(Series::area("kinetic + strain", t.clone(), e2));
        let cost = vec![1e-3, 3e-3, 1e-2, 4e-2];
        let err = vec![1e-2, 2e-4, 3e-6, 1e-8];
        let log = Panel::new("CPU time (s)", "error (-)")
            .x_log()
            .y_log()
            .title("log-log")
            .legend(Legend::LowerLeft)
            .series(Series::line("newmark", cost.clone(), err.clone()).marker(Marker::Circle))
            .series(
                Series::scatter("failed", vec![2e-3], vec![5e-1])
                    .marker(Marker::Cross)
                    .rgb(style::INK),
            );
        let heat = Panel::new("slip load 1 (kN)", "slip load 2 (kN)")
            .title("heat map")
            .legend(Legend::None)
            .heatmap(HeatMap {
                x: vec![0.0, 50.0, 100.0, 150.0],
                y: vec![0.0, 100.0, 200.0],
                z: vec![
                    vec![1.0, 0.8, 0.7, 0.75],
                    vec![0.9, 0.6, f64::NAN, 0.7],
                    vec![0.95, 0.7, 0.65, 0.8],
                ],
                label: "mean drift ratio (%)".into(),
                z_range: None,
            })
            .series(Series::scatter("optimum", vec![100.0], vec![100.0]).rgb(RGBColor(255, 0, 0)));
        let fig = Figure::new("Every kind of panel")
            .columns(2)
            .panel(lines)
            .panel(areas)
            .panel(log)
            .panel(heat);
        let dir = demo_dir();
        let (svg_path, png_path) = fig.save(&dir.join("demo.svg")).unwrap();
        assert_eq!(svg_path, dir.join("demo.svg"));
        let png = std::fs::read(&png_path).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        let meta = FigureMeta::from_svg(&std::fs::read_to_string(&svg_path).unwrap()).unwrap();
        assert_eq!(meta.panels.len(), 4);
        let p0 = &meta.panels[0];
        assert_eq!(p0.series.len(), 3);
        assert_eq!(p0.series[0].points, 2001);
        assert_eq!(p0.series[0].drawn, 2000, "the NaN is a gap");
        assert_eq!(p0.series[0].x, [Some(0.0), Some(20.0)]);
        assert!(p0.y.min <= -12.0 && p0.y.max >= 12.0);
        let p1 = &meta.panels[1];
        assert_eq!(p1.y.min, 0.0);
        // The axis holds the stacked total (40 + 1 + sin 20), the band its own values.
        assert!(p1.y.max >= 40.0 + 1.0 + 20f64.sin());
        let band_max = t.iter().map(|t| 1.0 + t.sin()).fold(f64::MIN, f64::max);
        assert_eq!(p1.series[1].y[1], Some(band_max));
        let p2 = &meta.panels[2];
        assert!(p2.x.log && p2.y.log);
        assert!(p2.y.min < 1e-8 && p2.y.max > 0.5);
        let h = meta.panels[3].heatmap.as_ref().unwrap();
        assert_eq!((h.nx, h.ny, h.missing), (4, 3, 1));
        assert_eq!(h.z, [Some(0.6), Some(1.0)]);
        if std::env::var_os("SLIPLOAD_KEEP_PLOTS").is_none() {
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }

    #[test]
    fn mismatched_lengths_are_an_error() {
        let fig = Figure::new("bad").panel(Panel::new("x (m)", "y (m)").series(Series::line(
            "s",
            vec![1.0, 2.0],
            vec![1.0],
        )));
        let e = fig.to_svg().unwrap_err();
        assert!(
            format!("{e:#}").contains("2 x values and 1 y values"),
            "{e:#}"
        );
    }
}
