//! FLIP's error image: each error value through the magma colour map ([`super::magma::MAGMA`]),
//! written as an 8-bit sRGB PNG, as the reference implementation shows its maps.

use super::magma::MAGMA;
use crate::image_io::write_rgb8_png;
use anyhow::Result;
use std::path::Path;

/// The magma entry of an error value in [0, 1]: `⌊255 e + ½⌋`, the nearest of the 256 entries
/// (the reference implementation's `colorMap`). Values outside [0, 1] (FLIP makes none) take the
/// end entries; NaN takes entry 0.
pub fn magma_index(error: f32) -> usize {
    (error.clamp(0.0, 1.0) * 255.0 + 0.5) as usize
}

/// The magma colour of an error value, sRGB-encoded in [0, 1].
pub fn magma(error: f32) -> [f32; 3] {
    MAGMA[magma_index(error)]
}

/// A colour in [0, 1] as 8-bit codes, `⌊255 c + ½⌋` (how the reference implementation writes its
/// PNGs, `ImageHelpers::pngSave`).
pub fn to_rgb8(colour: [f32; 3]) -> [u8; 3] {
    colour.map(|c| (255.0 * c.clamp(0.0, 1.0) + 0.5) as u8)
}

/// The error values (row-major, row 0 at the top) as magma RGB bytes.
pub fn magma_rgb8(errors: &[f32]) -> Vec<u8> {
    errors.iter().flat_map(|&e| to_rgb8(magma(e))).collect()
}

/// Writes the error values as a magma PNG (atomically, as every image causticlab writes).
pub fn write_magma_png(path: &Path, width: usize, height: usize, errors: &[f32]) -> Result<()> {
    write_rgb8_png(path, width as u32, height as u32, &magma_rgb8(errors))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Magma's published ends (matplotlib): (0.001462, 0.000466, 0.013866) and
    /// (0.987053, 0.991438, 0.749504); its middle entry 128 is (0.716387, 0.214982, 0.475290).
    #[test]
    fn the_ends_and_middle_are_magma() {
        assert_eq!(magma(0.0), [0.001462, 0.000466, 0.013866]);
        assert_eq!(magma(1.0), [0.987053, 0.991438, 0.749504]);
        assert_eq!(magma(128.0 / 255.0), [0.716387, 0.214982, 0.475290]);
        assert_eq!(to_rgb8(magma(1.0)), [252, 253, 191]);
    }

    #[test]
    fn values_round_to_the_nearest_entry() {
        assert_eq!(magma_index(0.5 / 255.0 - 1e-4), 0);
        assert_eq!(magma_index(0.5 / 255.0 + 1e-4), 1);
        assert_eq!(magma_index(254.6 / 255.0), 255);
        assert_eq!((magma_index(-0.5), magma_index(7.0), magma_index(f32::NAN)), (0, 255, 0));
    }

    /// Magma runs dark to light: the lightness (here the sum of the channels) rises entry by entry.
    #[test]
    fn the_map_rises_monotonically() {
        let sums: Vec<f32> = MAGMA.iter().map(|c| c.iter().sum()).collect();
        assert!(sums.windows(2).all(|w| w[1] > w[0]));
    }

    #[test]
    fn the_png_holds_the_magma_bytes() {
        let dir = std::env::temp_dir().join(format!("flip_magma_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("e.png");
        write_magma_png(&path, 2, 1, &[0.0, 1.0]).unwrap();
        let mut reader = png::Decoder::new(std::fs::File::open(&path).unwrap()).read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height), (2, 1));
        assert_eq!(&buf[..6], &[0, 0, 4, 252, 253, 191]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
