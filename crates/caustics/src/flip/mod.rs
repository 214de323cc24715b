//! FLIP, the perceptual difference between a test image and a reference as a viewer flipping
//! between them sees it, per pixel, in [0, 1]:
//!
//! * LDR-FLIP, Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström & Fairchild, "FLIP: A
//!   Difference Evaluator for Alternating Images", HPG 2020 (Proc. ACM Comput. Graph. Interact.
//!   Tech. 3(2)): [`ldr()`], its colour and feature pipelines in [`mod@ldr`], [`colour`] and
//!   [`filters`];
//! * HDR-FLIP, Andersson, Nilsson, Shirley & Akenine-Möller, "Visualizing Errors in Rendered High
//!   Dynamic Range Images", Eurographics 2021 short papers: [`hdr()`], the exposure range and tone
//!   mapper in [`mod@hdr`];
//! * the magma colour map of its error images: [`colormap`].
//!
//! The papers' text is not in `../shared/papers`; the constants and the order of operations follow
//! NVIDIA's reference implementation, flip-evaluator 1.7 (`src/cpp/FLIP.h`, BSD-3-Clause), which
//! `tests/flip_reference.rs` holds these maps to (`docs/flip.md`: the fixtures, the tolerances).
//!
//! **Pixels per degree.** FLIP filters at the resolution of the viewer's eye: how many pixels one
//! degree of visual angle covers. Every map carries the `ppd` it was computed at. The default,
//! [`default_ppd`], is the reference implementation's: a 3840-pixel-wide display 0.7 m wide seen
//! from 0.7 m, 67.02 pixels per degree.
//!
//! **Input.** Images are linear RGB ([`Rgb`], e.g. [`Rgb::read_exr`] of a render). LDR-FLIP
//! compares values in [0, 1]: [`ldr()`] clamps to [0, 1], as the reference implementation does after
//! it decodes its sRGB input; an 8-bit sRGB image (a PNG) decodes to the same linear values with
//! [`Rgb::from_srgb8`]. HDR-FLIP takes any non-negative linear values.

pub mod colormap;
pub mod colour;
pub mod filters;
pub mod hdr;
mod image;
pub mod ldr;
mod magma;

pub use image::Rgb;
pub use magma::MAGMA;

use crate::error::InputError;
use crate::image_io::{write_exr_with, ImageF32, Layer};
use std::fmt;
use std::path::Path;

/// The largest `ppd` accepted: its widest filter is then about 2,500 pixels across.
pub const MAX_PPD: f64 = 10_000.0;

/// The most exposures HDR-FLIP evaluates (the full range of `f32`, 2^−149 to 2^128, is fewer
/// than 280 stops; an automatic range is at most about 150).
pub const MAX_EXPOSURES: usize = 256;

/// Pixels per degree of a display `display_width_px` pixels and `display_width_m` metres wide
/// seen from `distance_m` metres: `distance · (pixels / width) · π / 180`, in `f32` as the
/// reference implementation computes it (`calculatePPD`).
pub fn pixels_per_degree(distance_m: f64, display_width_px: f64, display_width_m: f64) -> f64 {
    let per_metre = display_width_px as f32 / display_width_m as f32;
    (distance_m as f32 * per_metre * (std::f32::consts::PI / 180.0)) as f64
}

/// The reference implementation's default viewing: 0.7 m from a 0.7 m wide, 3840-pixel display.
pub fn default_ppd() -> f64 {
    pixels_per_degree(0.7, 3840.0, 0.7)
}

/// A FLIP error map: one value in [0, 1] per pixel, row-major, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct FlipMap {
    pub width: usize,
    pub height: usize,
    pub values: Vec<f32>,
    /// The mean over every pixel (summed in f64).
    pub mean: f64,
    /// The pixels per degree the map was computed at.
    pub ppd: f64,
}

impl FlipMap {
    fn new(width: usize, height: usize, values: Vec<f32>, ppd: f64) -> FlipMap {
        let mean = values.iter().map(|&v| v as f64).sum::<f64>() / values.len() as f64;
        FlipMap { width, height, values, mean, ppd }
    }

    /// The error at pixel `(x, y)`.
    pub fn at(&self, x: usize, y: usize) -> f32 {
        self.values[y * self.width + x]
    }

    /// The map through magma as RGB bytes ([`colormap::magma_rgb8`]).
    pub fn magma_rgb8(&self) -> Vec<u8> {
        colormap::magma_rgb8(&self.values)
    }

    /// Writes the map through magma as an 8-bit PNG.
    pub fn write_magma_png(&self, path: &Path) -> anyhow::Result<()> {
        colormap::write_magma_png(path, self.width, self.height, &self.values)
    }

    /// Writes the map as an EXR of one channel, `FLIP`, with its mean and pixels per degree in
    /// the header (`flip:mean`, `flip:ppd`).
    pub fn write_exr(&self, path: &Path) -> anyhow::Result<()> {
        write_exr_with(path, &self.exr(&[]), &self.header())
    }

    /// The map as an image, beside `extra` per-pixel channels (name, values).
    fn exr(&self, extra: &[(&str, &[f32])]) -> ImageF32 {
        let mut names = vec!["FLIP"];
        names.extend(extra.iter().map(|(n, _)| *n));
        let data = (0..self.values.len())
            .flat_map(|i| std::iter::once(self.values[i]).chain(extra.iter().map(move |(_, v)| v[i])))
            .collect();
        ImageF32 { width: self.width as u32, height: self.height as u32, layers: vec![Layer::new(None, &names, data)] }
    }

    fn header(&self) -> Vec<(&'static str, String)> {
        vec![("flip:mean", format!("{}", self.mean)), ("flip:ppd", format!("{}", self.ppd))]
    }
}

impl fmt::Display for FlipMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "mean FLIP {:.6} over {}x{} pixels at {:.2} pixels per degree",
            self.mean, self.width, self.height, self.ppd
        )
    }
}

/// How HDR-FLIP's exposure range is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Exposures {
    /// From the reference's luminances, as the HDR-FLIP paper does ([`hdr::auto_exposures`]).
    Auto,
    /// Given, in stops (`start <= stop`).
    Given { start: f64, stop: f64 },
}

/// HDR-FLIP's result: the error map (the largest LDR-FLIP error over the exposures), the exposure
/// range it used, and per pixel the exposure that gave that error (`i / (count − 1)`).
#[derive(Debug, Clone, PartialEq)]
pub struct HdrFlip {
    pub map: FlipMap,
    pub start_exposure: f64,
    pub stop_exposure: f64,
    pub exposure_count: usize,
    pub exposure_map: Vec<f32>,
    /// Whether the range was found ([`Exposures::Auto`]) or given.
    pub exposures: Exposures,
}

impl HdrFlip {
    pub fn mean(&self) -> f64 {
        self.map.mean
    }

    pub fn ppd(&self) -> f64 {
        self.map.ppd
    }

    /// Writes the error map and the exposure map as an EXR (channels `FLIP` and `exposure`), its
    /// mean, pixels per degree and exposures in the header (`flip:start_exposure`, ...).
    pub fn write_exr(&self, path: &Path) -> anyhow::Result<()> {
        let mut header = self.map.header();
        header.push(("flip:start_exposure", format!("{}", self.start_exposure)));
        header.push(("flip:stop_exposure", format!("{}", self.stop_exposure)));
        header.push(("flip:exposure_count", format!("{}", self.exposure_count)));
        write_exr_with(path, &self.map.exr(&[("exposure", &self.exposure_map)]), &header)
    }
}

impl fmt::Display for HdrFlip {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let how = if self.exposures == Exposures::Auto { "found from the reference" } else { "given" };
        write!(
            f,
            "HDR-FLIP: {}; {} exposures from {:.4} to {:.4} stops ({how})",
            self.map, self.exposure_count, self.start_exposure, self.stop_exposure
        )
    }
}

fn check_pair(reference: &Rgb, test: &Rgb, ppd: f64) -> Result<(), InputError> {
    if (reference.width(), reference.height()) != (test.width(), test.height()) {
        return Err(crate::input_error!(
            "FLIP: the reference is {}x{} and the test image {}x{}: they must be the same size",
            reference.width(),
            reference.height(),
            test.width(),
            test.height()
        ));
    }
    if !(ppd > 0.0 && ppd <= MAX_PPD) {
        return Err(crate::input_error!("FLIP: {ppd} pixels per degree: it must be positive and at most {MAX_PPD}"));
    }
    Ok(())
}

/// LDR-FLIP of `test` against `reference` at `ppd` pixels per degree; values above 1 are clamped
/// to 1 (see the module docs). Different sizes and a `ppd` that is not in (0, [`MAX_PPD`]] are
/// input errors.
pub fn ldr(reference: &Rgb, test: &Rgb, ppd: f64) -> Result<FlipMap, InputError> {
    check_pair(reference, test, ppd)?;
    let clamp = |img: &Rgb| -> Vec<colour::Triple> { img.pixels().iter().map(|c| c.map(|v| v.min(1.0))).collect() };
    let (w, h) = (reference.width(), reference.height());
    let values = ldr::flip_ldr(w, h, &clamp(reference), &clamp(test), ppd as f32);
    Ok(FlipMap::new(w, h, values, ppd))
}

/// HDR-FLIP of `test` against `reference` at `ppd` pixels per degree over `exposures`. Besides
/// [`ldr()`]'s input errors: a given range that is not finite (in f32), starts after it stops or
/// spans more than [`MAX_EXPOSURES`] exposures, and an automatic range of a black reference or
/// of one so dim that its range is not finite.
pub fn hdr(reference: &Rgb, test: &Rgb, ppd: f64, exposures: Exposures) -> Result<HdrFlip, InputError> {
    check_pair(reference, test, ppd)?;
    let (start, stop) = match exposures {
        Exposures::Auto => hdr::auto_exposures(reference.pixels())?,
        Exposures::Given { start, stop } => {
            if !(start.is_finite() && stop.is_finite() && start <= stop) {
                return Err(crate::input_error!(
                    "HDR-FLIP: exposures from {start} to {stop}: they must be finite, the start at most the stop"
                ));
            }
            (start as f32, stop as f32)
        }
    };
    if !(start.is_finite() && stop.is_finite()) {
        return Err(crate::input_error!(
            "HDR-FLIP: exposures from {start} to {stop} stops do not fit in f32 (a reference too dim to set them, \
             or given ones too large)"
        ));
    }
    let count = hdr::exposure_count(start, stop);
    if count > MAX_EXPOSURES {
        return Err(crate::input_error!(
            "HDR-FLIP: exposures from {start} to {stop} stops would be {count}, more than {MAX_EXPOSURES}"
        ));
    }
    let (w, h) = (reference.width(), reference.height());
    let (values, exposure_map) =
        hdr::flip_hdr(w, h, reference.pixels(), test.pixels(), ppd as f32, (start, stop, count));
    Ok(HdrFlip {
        map: FlipMap::new(w, h, values, ppd),
        start_exposure: start as f64,
        stop_exposure: stop as f64,
        exposure_count: count,
        exposure_map,
        exposures,
    })
}

#[cfg(test)]
mod tests;
