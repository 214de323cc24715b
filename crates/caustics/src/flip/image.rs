//! The images FLIP compares: linear RGB, every value finite and non-negative, checked once when
//! the image is made so that the metric itself has nothing left to refuse.

use super::colour::Triple;
use crate::error::InputError;
use crate::image_io::{read_exr, srgb_decode, ImageF32};
use std::path::Path;

/// A linear-RGB image (the EXRs the renderer writes): `width * height` pixels, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Rgb {
    width: usize,
    height: usize,
    pixels: Vec<Triple>,
}

impl Rgb {
    /// From interleaved `R, G, B` values. An empty image, a length that is not `3 * width *
    /// height`, and a NaN, infinite or negative value are input errors naming the first bad pixel.
    pub fn new(width: usize, height: usize, interleaved: &[f32]) -> Result<Rgb, InputError> {
        if width == 0 || height == 0 {
            return Err(crate::input_error!("FLIP: the image is {width}x{height}: it has no pixels"));
        }
        let expected = width.checked_mul(height).and_then(|n| n.checked_mul(3));
        if expected != Some(interleaved.len()) {
            return Err(crate::input_error!(
                "FLIP: {} values for a {width}x{height} RGB image (3 a pixel)",
                interleaved.len()
            ));
        }
        if let Some(i) = interleaved.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
            let (p, c) = (i / 3, ["R", "G", "B"][i % 3]);
            return Err(crate::input_error!(
                "FLIP: pixel ({}, {}) has {c} = {}: linear RGB must be finite and non-negative",
                p % width,
                p / width,
                interleaved[i]
            ));
        }
        let pixels = interleaved.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        Ok(Rgb { width, height, pixels })
    }

    /// From 8-bit sRGB-encoded codes (`R, G, B` bytes, a PNG's pixels): each code `k` is `k / 255`
    /// decoded by the sRGB transfer function to linear, as the reference implementation reads an
    /// LDR image.
    pub fn from_srgb8(width: usize, height: usize, bytes: &[u8]) -> Result<Rgb, InputError> {
        let linear: Vec<f32> = bytes.iter().map(|&b| srgb_decode(b as f32 / 255.0)).collect();
        Rgb::new(width, height, &linear)
    }

    /// The `R`, `G`, `B` channels of an EXR image's main (unnamed) layer, e.g. a render's
    /// `final.exr` or the E/E0 of a `receiver.exr`.
    pub fn from_exr(image: &ImageF32) -> Result<Rgb, InputError> {
        let layer = image.layer(None).ok_or_else(|| InputError::new("FLIP: the EXR image has no main layer"))?;
        let index = |name: &str| {
            layer.channels.iter().position(|c| c == name).ok_or_else(|| {
                crate::input_error!("FLIP: the EXR's main layer has channels {:?}, not R, G and B", layer.channels)
            })
        };
        let rgb = [index("R")?, index("G")?, index("B")?];
        let n = layer.channels.len();
        let values: Vec<f32> = layer.data.chunks_exact(n).flat_map(|px| rgb.map(|c| px[c])).collect();
        Rgb::new(image.width as usize, image.height as usize, &values)
    }

    /// [`Rgb::from_exr`] of the EXR file at `path`.
    pub fn read_exr(path: &Path) -> anyhow::Result<Rgb> {
        let image = read_exr(path)?;
        Rgb::from_exr(&image).map_err(|e| crate::input_error!("{}: {e}", path.display()).into())
    }

    pub fn width(&self) -> usize {
        self.width
    }

    pub fn height(&self) -> usize {
        self.height
    }

    /// The pixels, row-major.
    pub fn pixels(&self) -> &[Triple] {
        &self.pixels
    }
}
