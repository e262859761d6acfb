//! Helpers of the figure tests: read a figure's SVG back (through the metadata
//! `slipload_figures::plot` writes), check its PNG, read the CSV beside it.
#![allow(clippy::unwrap_used)] // in tests a failed unwrap is a failed test
#![allow(dead_code)] // each figure test uses its own subset

pub use slipload_figures::plot::meta;

use meta::{FigureMeta, PanelMeta, SeriesMeta};
use std::path::Path;

/// Reads `STEM.svg` back and checks `STEM.png` is a PNG of the figure's size.
pub fn figure(stem: &Path) -> FigureMeta {
    let svg_path = stem.with_extension("svg");
    let svg = std::fs::read_to_string(&svg_path)
        .unwrap_or_else(|e| panic!("{}: {e}", svg_path.display()));
    assert!(svg.starts_with("<svg"), "{} is an SVG", svg_path.display());
    assert!(svg.contains("<text"), "{} has text", svg_path.display());
    let m = FigureMeta::from_svg(&svg).unwrap();
    let png_path = stem.with_extension("png");
    let png = std::fs::read(&png_path).unwrap_or_else(|e| panic!("{}: {e}", png_path.display()));
    assert_eq!(
        &png[..8],
        b"\x89PNG\r\n\x1a\n",
        "{} signature",
        png_path.display()
    );
    // IHDR: width and height, big-endian, right after the 8-byte signature and the
    // chunk length and type.
    let w = u32::from_be_bytes(png[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(png[20..24].try_into().unwrap());
    assert_eq!((w, h), (m.width, m.height), "{} size", png_path.display());
    // A rendered figure compresses to far more than a blank page would.
    assert!(png.len() > 5_000, "{} has content", png_path.display());
    // No temporary files left beside the figure.
    let dir = stem.parent().unwrap();
    for e in std::fs::read_dir(dir).unwrap() {
        let name = e.unwrap().file_name().to_string_lossy().into_owned();
        assert!(
            !name.ends_with(".tmp"),
            "temporary {name} left in {}",
            dir.display()
        );
    }
    m
}

/// A CSV with a header: (columns, rows).
pub struct Csv {
    /// Header names.
    pub columns: Vec<String>,
    /// Rows of numbers (empty cells are NaN).
    pub rows: Vec<Vec<f64>>,
}

impl Csv {
    /// Reads `path`.
    pub fn read(path: &Path) -> Self {
        let text =
            std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut lines = text.lines();
        let columns: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
        let rows = lines
            .filter(|l| !l.is_empty())
            .map(|l| {
                l.split(',')
                    .map(|c| c.trim().parse().unwrap_or(f64::NAN))
                    .collect()
            })
            .collect();
        Self { columns, rows }
    }

    /// Column `name`.
    pub fn col(&self, name: &str) -> Vec<f64> {
        let j = self
            .columns
            .iter()
            .position(|c| c == name)
            .unwrap_or_else(|| panic!("no column {name} in {:?}", self.columns));
        self.rows.iter().map(|r| r[j]).collect()
    }

    /// Whether column `name` exists.
    pub fn has(&self, name: &str) -> bool {
        self.columns.iter().any(|c| c == name)
    }
}

/// (min, max) of the finite values.
pub fn range(v: &[f64]) -> (f64, f64) {
    v.iter()
        .filter(|x| x.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(*x), b.max(*x))
        })
}

/// The series' drawn y range equals `(lo, hi)` within `tol` (absolute).
pub fn assert_y(s: &SeriesMeta, (lo, hi): (f64, f64), tol: f64) {
    let (a, b) = (s.y[0].unwrap(), s.y[1].unwrap());
    assert!(
        (a - lo).abs() <= tol && (b - hi).abs() <= tol,
        "series {:?}: y [{a}, {b}] vs CSV [{lo}, {hi}] (tol {tol})",
        s.name
    );
}

/// The series' drawn x range equals `(lo, hi)` within `tol` (absolute).
pub fn assert_x(s: &SeriesMeta, (lo, hi): (f64, f64), tol: f64) {
    let (a, b) = (s.x[0].unwrap(), s.x[1].unwrap());
    assert!(
        (a - lo).abs() <= tol && (b - hi).abs() <= tol,
        "series {:?}: x [{a}, {b}] vs CSV [{lo}, {hi}] (tol {tol})",
        s.name
    );
}

/// Every series' data lie inside the panel's axes.
pub fn assert_inside(p: &PanelMeta) {
    for s in &p.series {
        if let ([Some(x0), Some(x1)], [Some(y0), Some(y1)]) = (s.x, s.y) {
            assert!(
                x0 >= p.x.min && x1 <= p.x.max && y0 >= p.y.min && y1 <= p.y.max,
                "series {:?} [{x0}, {x1}]×[{y0}, {y1}] outside the axes [{}, {}]×[{}, {}] of {:?}",
                s.name,
                p.x.min,
                p.x.max,
                p.y.min,
                p.y.max,
                p.title
            );
        }
    }
}
