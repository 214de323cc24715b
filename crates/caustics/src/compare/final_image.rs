//! `compare` on two final images (`final.exr`: the eye's linear radiance, no `E0`): what a
//! receiver map's figures would be but over every pixel, of the mean of `R, G, B`. There is no
//! "region" (no E/E0 = 1 to differ from) and no caustic flux (no `E0`); the error image is the
//! receiver map's (`A`, `B`, `diff`, `in_region` = 1 everywhere), so `error_png` draws it.

use crate::error::InputError;
use crate::image_io::{ImageF32, Layer};
use std::fmt;

/// Figures of a final image against the reference.
#[derive(Clone, Debug, PartialEq)]
pub struct FinalComparison {
    pub pixels: usize,
    /// `sqrt(Σ(a − b)² / Σ b²)` over every pixel (mean RGB).
    pub rel_rmse: f64,
    /// Pixels not finite in either image.
    pub non_finite_pixels: usize,
}

impl fmt::Display for FinalComparison {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "{:<26}{:>14}", "pixels", self.pixels)?;
        writeln!(f, "{:<26}{:>14.6}", "relative RMSE (radiance)", self.rel_rmse)?;
        writeln!(f, "{:<26}{:>14}", "non-finite pixels", self.non_finite_pixels)
    }
}

/// The |A − B| at which the error PNG of two final images saturates by default: half the
/// reference's 99th-percentile radiance (1 for a black reference). Not half its peak, as for
/// receiver maps: a final image's peak is a few pixels of the focus, far above the rest.
pub fn default_error_scale(err: &ImageF32) -> f32 {
    let mut b: Vec<f32> = err
        .layers
        .first()
        .map(|l| l.data.chunks_exact(4).map(|p| p[1]).filter(|v| v.is_finite()).collect())
        .unwrap_or_default();
    if b.is_empty() {
        return 1.0;
    }
    let k = (b.len() - 1) * 99 / 100;
    let (_, q, _) = b.select_nth_unstable_by(k, f32::total_cmp);
    if *q > 0.0 {
        0.5 * *q
    } else {
        1.0
    }
}

/// Mean of `R, G, B` of the main layer per pixel.
fn radiance(img: &ImageF32, label: &str) -> Result<Vec<f64>, InputError> {
    let main = img.layer(None).ok_or_else(|| crate::input_error!("{label}: no main layer (channels R, G, B)"))?;
    let find = |c: &str| {
        main.channels.iter().position(|x| x == c).ok_or_else(|| crate::input_error!("{label}: no channel `{c}`"))
    };
    let idx = [find("R")?, find("G")?, find("B")?];
    let n = main.channels.len();
    if main.data.len() != img.width as usize * img.height as usize * n {
        return Err(crate::input_error!("{label}: the main layer has the wrong number of values"));
    }
    Ok(main.data.chunks_exact(n).map(|p| idx.iter().map(|&c| p[c] as f64).sum::<f64>() / 3.0).collect())
}

/// Compares the final image `a` against the reference `b` (the caller has checked the sizes).
pub fn compare_final(
    a: &ImageF32,
    la: &str,
    b: &ImageF32,
    lb: &str,
) -> Result<(FinalComparison, ImageF32), InputError> {
    let (va, vb) = (radiance(a, la)?, radiance(b, lb)?);
    let (mut sdd, mut sbb, mut non_finite) = (0.0, 0.0, 0usize);
    let mut data = Vec::with_capacity(va.len() * 4);
    for (&x, &y) in va.iter().zip(&vb) {
        if !(x.is_finite() && y.is_finite()) {
            non_finite += 1;
        }
        sdd += (x - y) * (x - y);
        sbb += y * y;
        data.extend_from_slice(&[x as f32, y as f32, (x - y) as f32, 1.0]);
    }
    let rel_rmse = if sbb > 0.0 {
        (sdd / sbb).sqrt()
    } else if sdd == 0.0 {
        0.0
    } else {
        f64::INFINITY
    };
    let err = ImageF32 {
        width: a.width,
        height: a.height,
        layers: vec![Layer::new(None, &["A", "B", "diff", "in_region"], data)],
    };
    Ok((FinalComparison { pixels: va.len(), rel_rmse, non_finite_pixels: non_finite }, err))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn img(values: &[f32]) -> ImageF32 {
        let data = values.iter().flat_map(|&v| [v, v, v]).collect();
        ImageF32 { width: values.len() as u32, height: 1, layers: vec![Layer::new(None, &["R", "G", "B"], data)] }
    }

    /// A: 1, 2, 3 against B: 1, 1, 1: Σ(a − b)² = 0 + 1 + 4, Σb² = 3, rel. RMSE √(5/3).
    #[test]
    fn the_relative_rmse_is_over_every_pixel() {
        let (c, e) = compare_final(&img(&[1.0, 2.0, 3.0]), "a", &img(&[1.0; 3]), "b").unwrap();
        assert_eq!((c.pixels, c.non_finite_pixels), (3, 0));
        assert!((c.rel_rmse - (5.0f64 / 3.0).sqrt()).abs() < 1e-12, "{}", c.rel_rmse);
        assert_eq!(e.layers[0].data, [1.0, 1.0, 0.0, 1.0, 2.0, 1.0, 1.0, 1.0, 3.0, 1.0, 2.0, 1.0]);
        let (same, _) = compare_final(&img(&[0.0, 2.0]), "a", &img(&[0.0, 2.0]), "b").unwrap();
        assert_eq!(same.rel_rmse, 0.0);
        let (nan, _) = compare_final(&img(&[f32::NAN, 2.0]), "a", &img(&[1.0, 2.0]), "b").unwrap();
        assert_eq!(nan.non_finite_pixels, 1);
        assert!(nan.rel_rmse.is_nan());
    }

    /// 100 pixels of B, 1 to 100: the 99th percentile is the element of rank 98, 99; one focus
    /// pixel of 1000 in place of 100 does not move it.
    #[test]
    fn the_error_scale_is_half_the_references_99th_percentile() {
        let mut b: Vec<f32> = (1..=100).map(|v| v as f32).collect();
        let (_, e) = compare_final(&img(&b), "a", &img(&b), "b").unwrap();
        assert_eq!(default_error_scale(&e), 49.5);
        b[99] = 1000.0;
        let (_, e) = compare_final(&img(&b), "a", &img(&b), "b").unwrap();
        assert_eq!(default_error_scale(&e), 49.5);
        let (_, black) = compare_final(&img(&[0.0; 4]), "a", &img(&[0.0; 4]), "b").unwrap();
        assert_eq!(default_error_scale(&black), 1.0);
    }
}
