//! SVG → PNG with resvg, so the PNG is the SVG pixel for pixel (same layout, same text).
//!
//! Text needs a font file: DejaVu Sans, looked for at run time in the usual system
//! folders (Debian/Ubuntu package `fonts-dejavu-core`), or the file named by the
//! environment variable `SLIPLOAD_FONT`. No font is embedded in the program.

use crate::names::{FONT_ENV, FONT_PATHS};
use crate::{FigureError, FontError};
use resvg::{tiny_skia, usvg};
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

/// The fonts for PNG text (found once per process).
fn fonts() -> Result<Arc<usvg::fontdb::Database>, FontError> {
    static FONTS: OnceLock<Result<Arc<usvg::fontdb::Database>, FontError>> = OnceLock::new();
    FONTS.get_or_init(load_fonts).clone()
}

/// Fails with the message `save` would give when no font can be found: commands call it
/// before any work or output, so a missing font costs nothing and leaves no files.
pub fn check_fonts() -> Result<(), FontError> {
    fonts().map(|_| ())
}

fn font_files() -> Result<Vec<PathBuf>, FontError> {
    if let Some(p) = std::env::var_os(FONT_ENV) {
        let p = PathBuf::from(p);
        if !p.is_file() {
            return Err(FontError::NotAFile { path: p });
        }
        return Ok(vec![p]);
    }
    let regular = FONT_PATHS
        .iter()
        .map(Path::new)
        .find(|p| p.is_file())
        .ok_or(FontError::NotFound)?;
    let mut files = vec![regular.to_path_buf()];
    let bold = regular.with_file_name("DejaVuSans-Bold.ttf");
    if bold.is_file() {
        files.push(bold);
    }
    Ok(files)
}

fn load_fonts() -> Result<Arc<usvg::fontdb::Database>, FontError> {
    let mut db = usvg::fontdb::Database::new();
    for f in font_files()? {
        let bytes = std::fs::read(&f).map_err(|e| FontError::Read {
            path: f.clone(),
            reason: e.to_string(),
        })?;
        let before = db.len();
        db.load_font_data(bytes);
        if db.len() <= before {
            return Err(FontError::Unreadable { path: f });
        }
    }
    let family = db
        .faces()
        .next()
        .and_then(|f| f.families.first().map(|(name, _)| name.clone()))
        .expect("one face was loaded above");
    db.set_sans_serif_family(family.clone());
    db.set_serif_family(family.clone());
    db.set_monospace_family(family);
    Ok(Arc::new(db))
}

/// Renders `svg` to PNG bytes at its own size (white background).
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, FigureError> {
    let fontdb = fonts()?;
    let family = fontdb
        .faces()
        .next()
        .and_then(|f| f.families.first().map(|(name, _)| name.clone()))
        .expect("the font database holds a face");
    let opt = usvg::Options {
        font_family: family,
        fontdb,
        ..Default::default()
    };
    let tree = usvg::Tree::from_str(svg, &opt).map_err(FigureError::SvgParse)?;
    let size = tree.size().to_int_size();
    let mut pixmap =
        tiny_skia::Pixmap::new(size.width(), size.height()).ok_or(FigureError::PixmapSize {
            width: size.width(),
            height: size.height(),
        })?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    pixmap
        .encode_png()
        .map_err(|e| FigureError::PngEncode(Box::new(e)))
}
