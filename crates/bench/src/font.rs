//! The font the plots measure and draw their text with: a TrueType file loaded at run time (no
//! font is committed), DejaVu Sans from Debian's `fonts-dejavu-core` unless `CAUSTICLAB_FONT`
//! names another. The SVG names the family (`sans-serif`) and lets the viewer draw it; the PNG
//! is drawn with this font; both are laid out with its metrics.

use anyhow::Result;
use std::path::PathBuf;
use std::sync::OnceLock;

/// Debian/Ubuntu `fonts-dejavu-core`.
pub const DEFAULT_FONT: &str = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
/// The family name the plots use for every text.
pub const FAMILY: &str = "sans-serif";

fn path() -> PathBuf {
    std::env::var_os("CAUSTICLAB_FONT").map(PathBuf::from).unwrap_or_else(|| PathBuf::from(DEFAULT_FONT))
}

/// Loads and registers the font once; later calls return the first outcome. Call it before a
/// sweep so that a missing font fails before hours of cells, not after.
pub fn load() -> Result<()> {
    static LOADED: OnceLock<Result<(), String>> = OnceLock::new();
    let outcome = LOADED.get_or_init(|| {
        let p = path();
        let bytes = std::fs::read(&p).map_err(|e| {
            format!(
                "the bench plots need a TrueType font and cannot read {}: {e}. Install Debian's \
                 fonts-dejavu-core (bash scripts/setup.sh does), or set CAUSTICLAB_FONT to a .ttf file",
                p.display()
            )
        })?;
        // plotters keeps fonts for the life of the process: the bytes are leaked once.
        let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
        plotters::style::register_font(FAMILY, plotters::style::FontStyle::Normal, bytes)
            .map_err(|_| format!("{}: not a TrueType or OpenType font (CAUSTICLAB_FONT)", p.display()))
    });
    outcome.clone().map_err(anyhow::Error::msg)
}
