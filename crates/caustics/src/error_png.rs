//! The error image of [`crate::compare`] as a picture: where a technique's receiver map is too
//! bright or too dark against the reference, so that a technique's characteristic error (the
//! blur of a gather where photons are dense, the noise of points where they are sparse, a quad
//! that burns) can be seen, not only summed into one RMSE.
//!
//! Diverging colours over the reference: red where `A > B`, blue where `A < B`, full saturation
//! at `|A − B| = scale`; texels outside the compared region are the reference in dim grey, so
//! the error sits on the caustic's shape. `scale` defaults to half the reference's peak over the
//! region (at least 0.5 of E/E0), so a 50%-of-peak error is as strong as a colour gets.

use crate::image_io::{write_rgb8_png, ImageF32};
use anyhow::{ensure, Result};
use std::path::Path;

/// The scale [`write_error_png`] saturates at, from the error image's `B` and `in_region`.
pub fn default_scale(err: &ImageF32) -> f32 {
    let peak = channels(err).map(|[_, b, _, r]| if r > 0.5 { b } else { 0.0 }).fold(0.0f32, f32::max);
    (0.5 * peak).max(0.5)
}

fn channels(err: &ImageF32) -> impl Iterator<Item = [f32; 4]> + '_ {
    let data = err.layers.first().map(|l| l.data.as_slice()).unwrap_or(&[]);
    data.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]])
}

/// The RGB bytes of the picture (row 0 = top, as the EXR).
pub fn error_rgb8(err: &ImageF32, scale: f32) -> Vec<u8> {
    let peak = 2.0 * scale;
    channels(err)
        .flat_map(|[_, b, diff, region]| {
            if region < 0.5 {
                let g = (b / peak).clamp(0.0, 1.0) * 0.35;
                let v = (g * 255.0).round() as u8;
                return [v, v, v];
            }
            let t = (diff / scale).clamp(-1.0, 1.0);
            let (strong, weak) = (255.0, 255.0 * (1.0 - t.abs()));
            let (r, g, bl) = if t >= 0.0 { (strong, weak, weak) } else { (weak, weak, strong) };
            [r as u8, g as u8, bl as u8]
        })
        .collect()
}

/// Writes the error image of [`crate::compare`] (`A, B, diff, in_region`) as a false-colour PNG.
pub fn write_error_png(path: &Path, err: &ImageF32, scale: f32) -> Result<()> {
    ensure!(
        err.layers.first().is_some_and(|l| l.channels == ["A", "B", "diff", "in_region"]),
        "{}: not an error image of `causticlab compare`",
        path.display()
    );
    ensure!(scale.is_finite() && scale > 0.0, "error-image scale {scale} must be positive");
    write_rgb8_png(path, err.width, err.height, &error_rgb8(err, scale))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::Layer;

    fn image(texels: &[[f32; 4]]) -> ImageF32 {
        let data = texels.iter().flatten().copied().collect();
        ImageF32 {
            width: texels.len() as u32,
            height: 1,
            layers: vec![Layer::new(None, &["A", "B", "diff", "in_region"], data)],
        }
    }

    #[test]
    fn too_bright_is_red_too_dark_is_blue_and_outside_is_grey() {
        let err = image(&[[3.0, 1.0, 2.0, 1.0], [0.0, 2.0, -2.0, 1.0], [1.0, 1.0, 0.0, 1.0], [4.0, 4.0, 0.0, 0.0]]);
        let px = error_rgb8(&err, 2.0);
        assert_eq!(&px[0..3], &[255, 0, 0], "A − B = +scale saturates red");
        assert_eq!(&px[3..6], &[0, 0, 255], "A − B = −scale saturates blue");
        assert_eq!(&px[6..9], &[255, 255, 255], "no error is white");
        assert!(px[9] == px[10] && px[10] == px[11] && px[9] > 0 && px[9] < 100, "outside: dim grey {:?}", &px[9..12]);
    }

    #[test]
    fn the_default_scale_is_half_the_reference_peak_in_the_region() {
        let err = image(&[[0.0, 8.0, 0.0, 1.0], [0.0, 100.0, 0.0, 0.0]]);
        assert_eq!(default_scale(&err), 4.0);
        assert_eq!(default_scale(&image(&[[0.0, 0.2, 0.0, 1.0]])), 0.5);
    }
}
