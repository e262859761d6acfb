//! The names the figures and their errors share: where the PNG text font is looked for,
//! and the id of the metadata element every SVG carries.

/// Environment variable naming a TrueType font file to use instead of DejaVu Sans.
pub const FONT_ENV: &str = "SLIPLOAD_FONT";

/// Where DejaVu Sans is looked for (Debian/Ubuntu, Fedora, Arch, Alpine, macOS Homebrew).
pub const FONT_PATHS: [&str; 6] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf",
    "/usr/local/share/fonts/DejaVuSans.ttf",
    "/opt/homebrew/share/fonts/DejaVuSans.ttf",
];

/// The id of the metadata element.
pub const METADATA_ID: &str = "slipload-figure";
