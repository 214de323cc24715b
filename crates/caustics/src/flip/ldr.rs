//! LDR-FLIP (Andersson et al. 2020): the per-pixel difference between two images in [0, 1]
//! linear RGB, as a viewer flipping between them perceives it at `ppd` pixels per degree.
//!
//! * Colour pipeline: both images to YCxCz, each channel filtered by its contrast sensitivity
//!   function ([`super::filters`]), back to linear RGB clamped to [0, 1], to CIELab with the
//!   Hunt adjustment; the HyAB distance raised to `q_c` = 0.7 and redistributed so that the
//!   fraction `p_c` = 0.4 of its largest value `c_max` ([`super::colour::max_colour_difference`])
//!   maps to `p_t` = 0.95 and `c_max` to 1: `ΔE_c`.
//! * Feature pipeline: the achromatic channel normalised to [0, 1] (`(Y + 16) / 116`), its edges
//!   (gradient magnitude of the first-derivative filters) and points (magnitude of the
//!   second-derivative filters); `ΔE_f = (max(|Δedge|, |Δpoint|) / √2)^q_f`, `q_f` = 0.5.
//! * The two combine as `ΔE = ΔE_c^(1 − ΔE_f)`: a feature difference raises a colour difference.
//!
//! The constants are those of the paper and of the reference implementation (`FLIPConstants` in
//! `FLIP.h`, flip-evaluator 1.7): [`Q_C`], [`P_C`], [`P_T`], [`Q_F`].

use super::colour::{self, Triple};
use super::filters::{feature_filters, spatial_filters, Plane};

/// Exponent of the colour difference, `q_c` (FLIP paper, colour pipeline).
pub const Q_C: f32 = 0.7;
/// Fraction of `c_max` below which colour differences are spread over [0, `p_t`], `p_c`.
pub const P_C: f32 = 0.4;
/// The error a colour difference of `p_c c_max` maps to, `p_t`.
pub const P_T: f32 = 0.95;
/// Exponent of the feature difference, `q_f` (FLIP paper, feature pipeline).
pub const Q_F: f32 = 0.5;

/// LDR-FLIP of two images of `width` x `height` pixels (linear RGB, values already in [0, 1]:
/// the caller clamps), at `ppd` pixels per degree. Row-major, row 0 at the top.
pub fn flip_ldr(width: usize, height: usize, reference: &[Triple], test: &[Triple], ppd: f32) -> Vec<f32> {
    let to_ycxcz = |img: &[Triple]| -> Vec<Triple> {
        img.iter().map(|&c| colour::xyz_to_ycxcz(colour::linear_rgb_to_xyz(c))).collect()
    };
    let (reference, test) = (to_ycxcz(reference), to_ycxcz(test));
    let colour_difference = colour_pipeline(width, height, &reference, &test, ppd);
    let feature_difference = feature_pipeline(width, height, &reference, &test, ppd);
    colour_difference.iter().zip(&feature_difference).map(|(c, f)| c.powf(1.0 - f)).collect()
}

/// One image's three YCxCz channels, filtered by their CSFs, as linear RGB clamped to [0, 1]
/// and then as Hunt-adjusted CIELab.
fn filtered_hunt_lab(width: usize, height: usize, image: &[Triple], ppd: f32) -> Vec<Triple> {
    let f = spatial_filters(ppd);
    let channel = |c: usize| Plane::from_fn(width, height, |i| image[i][c]);
    let separable = |p: &Plane, k: &[f32]| p.convolve_x(k).convolve_y(k).values;
    let (y, cx, cz) = (channel(0), channel(1), channel(2));
    let (y, cx) = (separable(&y, &f.y), separable(&cx, &f.cx));
    let (cz1, cz2) = (separable(&cz, &f.cz1), separable(&cz, &f.cz2));
    (0..width * height)
        .map(|i| {
            let rgb = colour::xyz_to_linear_rgb(colour::ycxcz_to_xyz([y[i], cx[i], cz1[i] + cz2[i]]));
            colour::linear_rgb_to_hunt_lab(rgb.map(|v| v.clamp(0.0, 1.0)))
        })
        .collect()
}

/// `ΔE_c` per pixel, in [0, 1].
fn colour_pipeline(width: usize, height: usize, reference: &[Triple], test: &[Triple], ppd: f32) -> Vec<f32> {
    let c_max = colour::max_colour_difference(Q_C);
    let knee = P_C * c_max;
    let reference = filtered_hunt_lab(width, height, reference, ppd);
    let test = filtered_hunt_lab(width, height, test, ppd);
    reference
        .iter()
        .zip(&test)
        .map(|(&r, &t)| {
            let d = colour::hyab(r, t).powf(Q_C);
            if d < knee {
                d * (P_T / knee)
            } else {
                P_T + ((d - knee) / (c_max - knee)) * (1.0 - P_T)
            }
        })
        .collect()
}

/// An image's edge and point magnitudes (the first- and second-derivative responses of its
/// normalised achromatic channel, in x and y).
fn features(width: usize, height: usize, image: &[Triple], ppd: f32) -> (Vec<f32>, Vec<f32>) {
    let f = feature_filters(ppd);
    let (scale, offset) = (1.0f32 / 116.0, 16.0f32 / 116.0);
    let grey = Plane::from_fn(width, height, |i| image[i][0] * scale + offset);
    // Separated: d/dx is the derivative along x times the Gaussian along y, and so on.
    let (dx, ddx, smooth_x) = (grey.convolve_x(&f.edge), grey.convolve_x(&f.point), grey.convolve_x(&f.gaussian));
    let (dx, ddx) = (dx.convolve_y(&f.gaussian).values, ddx.convolve_y(&f.gaussian).values);
    let (dy, ddy) = (smooth_x.convolve_y(&f.edge).values, smooth_x.convolve_y(&f.point).values);
    let magnitude = |a: &[f32], b: &[f32]| a.iter().zip(b).map(|(a, b)| (a * a + b * b).sqrt()).collect::<Vec<_>>();
    (magnitude(&dx, &dy), magnitude(&ddx, &ddy))
}

/// `ΔE_f` per pixel, in [0, 1].
fn feature_pipeline(width: usize, height: usize, reference: &[Triple], test: &[Triple], ppd: f32) -> Vec<f32> {
    let (edge_r, point_r) = features(width, height, reference, ppd);
    let (edge_t, point_t) = features(width, height, test, ppd);
    let normalisation = 1.0 / 2.0f32.sqrt();
    (0..width * height)
        .map(|i| {
            let edge = (edge_r[i] - edge_t[i]).abs();
            let point = (point_r[i] - point_t[i]).abs();
            (normalisation * edge.max(point)).powf(Q_F)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn uniform(n: usize, c: Triple) -> Vec<Triple> {
        vec![c; n]
    }

    #[test]
    fn identical_images_have_no_error() {
        let img: Vec<Triple> = (0..64).map(|i| [i as f32 / 64.0, 0.3, 1.0 - i as f32 / 64.0]).collect();
        assert!(flip_ldr(8, 8, &img, &img, 67.0).iter().all(|&e| e == 0.0));
    }

    /// Flat fields have no features, so ΔE = ΔE_c: green against blue is the largest colour
    /// difference, 1; black against white is HyAB 100 (L alone), 100^0.7 = 25.1 against
    /// p_c c_max = 16.5, so 0.95 + (25.1 − 16.5) / (41.27 − 16.5) · 0.05 = 0.967.
    #[test]
    fn flat_fields_give_the_redistributed_colour_difference() {
        let n = 36;
        let e = flip_ldr(6, 6, &uniform(n, [0.0, 1.0, 0.0]), &uniform(n, [0.0, 0.0, 1.0]), 67.0);
        assert!(e.iter().all(|&v| (v - 1.0).abs() < 1e-4), "{:?}", &e[..3]);
        let e = flip_ldr(6, 6, &uniform(n, [0.0; 3]), &uniform(n, [1.0; 3]), 67.0);
        assert!(e.iter().all(|&v| (v - 0.967).abs() < 2e-3), "{:?}", &e[..3]);
    }

    /// A small colour difference stays on the lower segment: ΔE_c = d · p_t / (p_c c_max).
    #[test]
    fn a_small_difference_lies_on_the_lower_segment() {
        let n = 25;
        let (a, b) = ([0.5f32, 0.5, 0.5], [0.52f32, 0.5, 0.5]);
        let e = flip_ldr(5, 5, &uniform(n, a), &uniform(n, b), 67.0)[12];
        let la = colour::linear_rgb_to_hunt_lab(a);
        let lb = colour::linear_rgb_to_hunt_lab(b);
        let expected = colour::hyab(la, lb).powf(Q_C) * P_T / (P_C * colour::max_colour_difference(Q_C));
        assert!(expected < P_T && (e - expected).abs() < 1e-4, "{e} against {expected}");
    }

    /// A single bright pixel on grey is a point: its feature difference raises the error above the
    /// colour difference alone, and the error is largest at the pixel.
    #[test]
    fn a_firefly_is_a_feature() {
        let (w, h) = (15, 15);
        let grey = uniform(w * h, [0.2; 3]);
        let mut firefly = grey.clone();
        firefly[7 * w + 7] = [1.0; 3];
        let e = flip_ldr(w, h, &grey, &firefly, 67.0);
        let centre = e[7 * w + 7];
        assert!(e.iter().all(|&v| v <= centre) && centre > 0.2, "centre {centre}");
        let reference: Vec<Triple> = grey.iter().map(|&c| colour::xyz_to_ycxcz(colour::linear_rgb_to_xyz(c))).collect();
        let test: Vec<Triple> = firefly.iter().map(|&c| colour::xyz_to_ycxcz(colour::linear_rgb_to_xyz(c))).collect();
        let colour_only = colour_pipeline(w, h, &reference, &test, 67.0)[7 * w + 7];
        assert!(centre > colour_only, "{centre} against the colour difference alone {colour_only}");
    }
}
