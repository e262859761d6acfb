//! The typed errors of the figures.

use std::path::PathBuf;

use crate::names::{FONT_ENV, FONT_PATHS, METADATA_ID};

/// Why a figure could not be drawn, rasterised, written or read back.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FigureError {
    /// A figure without panels.
    #[error("figure \"{title}\" has no panels")]
    NoPanels {
        /// The figure's title.
        title: String,
    },
    /// A series whose x and y columns differ in length.
    #[error("series \"{name}\" has {x} x values and {y} y values")]
    SeriesLengths {
        /// The series' legend name.
        name: String,
        /// x values given.
        x: usize,
        /// y values given.
        y: usize,
    },
    /// A stacked band whose length differs from the band below it.
    #[error("stacked band \"{name}\" has {points} points, the band below {below}")]
    BandLengths {
        /// The band's legend name.
        name: String,
        /// Its points.
        points: usize,
        /// The points of the band below.
        below: usize,
    },
    /// A heat map whose values are not one row of `x.len()` values per y.
    #[error("heat map \"{label}\" needs {rows} rows of {columns} values")]
    HeatMapShape {
        /// The colour-bar label.
        label: String,
        /// Rows expected (cells along y).
        rows: usize,
        /// Values per row expected (cells along x).
        columns: usize,
    },
    /// plotters failed while drawing the SVG.
    #[error(transparent)]
    Plotters(#[from] plotters::drawing::DrawingAreaErrorKind<std::io::Error>),
    /// plotters' SVG text lacks its closing tag.
    #[error("plotters wrote no </svg>")]
    UnterminatedSvg,
    /// Drawing the figure `stem` (the SVG) failed.
    #[error("drawing figure {}", stem.display())]
    Draw {
        /// The figure's path without extension.
        stem: PathBuf,
        /// Why.
        #[source]
        source: Box<FigureError>,
    },
    /// Rasterising the figure `stem` (the PNG) failed.
    #[error("rasterising figure {}", stem.display())]
    Rasterise {
        /// The figure's path without extension.
        stem: PathBuf,
        /// Why.
        #[source]
        source: Box<FigureError>,
    },
    /// No usable font for the PNG text.
    #[error(transparent)]
    Font(#[from] FontError),
    /// resvg could not parse the SVG drawn.
    #[error("parsing the SVG we drew")]
    SvgParse(#[source] resvg::usvg::Error),
    /// A figure size no pixmap can hold.
    #[error("figure size {width}×{height} px")]
    PixmapSize {
        /// Width, px.
        width: u32,
        /// Height, px.
        height: u32,
    },
    /// PNG encoding failed.
    #[error("encoding the PNG")]
    PngEncode(#[source] Box<dyn std::error::Error + Send + Sync>),
    /// Writing a figure or CSV file failed (the path is in the message).
    #[error(transparent)]
    Write(#[from] slipload_opt::OptError),
    /// An SVG without the figure metadata element.
    #[error("no <metadata id=\"{}\"> in the SVG", METADATA_ID)]
    NoMetadata,
    /// The figure metadata element is not closed.
    #[error("unterminated figure metadata")]
    UnterminatedMetadata,
    /// The figure metadata is not the JSON this crate writes.
    #[error(transparent)]
    MetadataJson(#[from] serde_json::Error),
}

/// Why no font for the PNG text could be loaded (cloneable: found once per process).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum FontError {
    /// The font environment variable names no file.
    #[error("{FONT_ENV}={} is not a font file", path.display())]
    NotAFile {
        /// The path it names.
        path: PathBuf,
    },
    /// DejaVu Sans is in none of the usual places.
    #[error(
        "no DejaVu Sans font for the PNG figures: looked at {}; install it \
         (Debian/Ubuntu: apt-get install fonts-dejavu-core) or set {FONT_ENV} to a .ttf file",
        FONT_PATHS.join(", ")
    )]
    NotFound,
    /// The font file could not be read.
    #[error("reading font {}: {reason}", path.display())]
    Read {
        /// The font file.
        path: PathBuf,
        /// The I/O error, as text.
        reason: String,
    },
    /// The file holds no font resvg can read.
    #[error("{} holds no font resvg can read", path.display())]
    Unreadable {
        /// The font file.
        path: PathBuf,
    },
}
