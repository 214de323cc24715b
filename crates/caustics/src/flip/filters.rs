//! FLIP's filters, all sampled at the viewer's pixels per degree, and the separable convolution
//! that applies them.
//!
//! * The contrast sensitivity functions of the colour pipeline (FLIP paper, spatial filtering):
//!   each opponent channel's CSF is a sum of Gaussians in the spatial domain,
//!   `S(x) = a1 √(π/b1) exp(−π² x²/b1) + a2 √(π/b2) exp(−π² x²/b2)`, x in degrees, with the
//!   paper's parameters in [`CSF`]. The achromatic (Y) and red-green (Cx) filters are one Gaussian
//!   (a2 = 0) and so separable; the blue-yellow (Cz) filter is two, applied as two separable
//!   filters whose 1D weights are the square roots of the 2D ones (`misc/separatedConvolutions.pdf`
//!   of the reference implementation), summed after the second pass.
//! * The feature pipeline's edge and point detectors: the first and second derivatives of a
//!   Gaussian of standard deviation `σ = ½ w ppd` pixels, w = 0.082° (FLIP paper, feature
//!   pipeline), separated the same way.
//!
//! Borders clamp to the edge, as the reference implementation's loops do (`Min(Max(0, x + i),
//! w − 1)`). Each sum runs over the kernel from its left (top) end, as the reference's does, so
//! that the `f32` results round alike.

use std::f32::consts::PI;

/// The CSF parameters of the FLIP paper's spatial filtering, per opponent channel
/// `[Y, Cx, Cz]`: `a1, b1, a2, b2` (b in degrees²). The reference implementation's
/// `GaussianConstants` hold the same values.
pub struct CsfParameters {
    pub a1: [f32; 3],
    pub b1: [f32; 3],
    pub a2: [f32; 3],
    pub b2: [f32; 3],
}

/// The values of [`CsfParameters`] that FLIP uses.
pub const CSF: CsfParameters = CsfParameters {
    a1: [1.0, 1.0, 34.1],
    b1: [0.0047, 0.0053, 0.04],
    a2: [0.0, 0.0, 13.5],
    b2: [1.0e-5, 1.0e-5, 0.025],
};

/// The width of the feature detectors' Gaussian, `w` in degrees (FLIP paper, feature pipeline).
pub const FEATURE_WIDTH_DEGREES: f32 = 0.082;

/// The 1D weights of the colour pipeline: `y` and `cx` each sum to 1; `cz1` and `cz2` are the two
/// separated Gaussians of the blue-yellow CSF, scaled together so that the 2D filter
/// `cz1 ⊗ cz1 + cz2 ⊗ cz2` sums to 1.
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialFilters {
    pub y: Vec<f32>,
    pub cx: Vec<f32>,
    pub cz1: Vec<f32>,
    pub cz2: Vec<f32>,
}

/// The 1D weights of the feature pipeline: the Gaussian (sums to 1), its first derivative (the
/// edge detector) and its second derivative (the point detector), each derivative's positive
/// weights summing to 1 and its negative weights to −1.
#[derive(Debug, Clone, PartialEq)]
pub struct FeatureFilters {
    pub gaussian: Vec<f32>,
    pub edge: Vec<f32>,
    pub point: Vec<f32>,
}

/// The CSF kernels' radius in pixels: three standard deviations of the widest Gaussian
/// (the largest b, whose standard deviation is `√(b / 2π²)` degrees).
pub fn spatial_radius(ppd: f32) -> usize {
    let widest = CSF.b1.iter().chain(&CSF.b2).copied().fold(0.0f32, f32::max);
    (3.0 * (widest / (2.0 * (PI * PI))).sqrt() * ppd).ceil() as usize
}

/// `a √(π/b) exp(−π² x²/b)`, one term of a CSF, at `x2` = x² (degrees²).
fn csf_term(x2: f32, a: f32, b: f32) -> f32 {
    a * (PI / b).sqrt() * ((-(PI * PI)) * x2 / b).exp()
}

/// The 1D factor of a 2D term `a √(π/b) exp(−π² r²/b)` (its square root at r² = x²).
fn csf_term_separated(x2: f32, a: f32, b: f32) -> f32 {
    (a * (PI / b).sqrt()).sqrt() * ((-(PI * PI)) * x2 / b).exp()
}

/// The colour pipeline's filters at `ppd` pixels per degree.
pub fn spatial_filters(ppd: f32) -> SpatialFilters {
    let radius = spatial_radius(ppd);
    let degrees_per_pixel = 1.0 / ppd;
    let mut f = SpatialFilters { y: vec![], cx: vec![], cz1: vec![], cz2: vec![] };
    let (mut sum_y, mut sum_cx, mut sum_cz1, mut sum_cz2) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
    for i in 0..=2 * radius {
        let x = (i as f32 - radius as f32) * degrees_per_pixel;
        let x2 = x * x;
        let y = csf_term(x2, CSF.a1[0], CSF.b1[0]);
        let cx = csf_term(x2, CSF.a1[1], CSF.b1[1]);
        let cz1 = csf_term_separated(x2, CSF.a1[2], CSF.b1[2]);
        let cz2 = csf_term_separated(x2, CSF.a2[2], CSF.b2[2]);
        (sum_y, sum_cx, sum_cz1, sum_cz2) = (sum_y + y, sum_cx + cx, sum_cz1 + cz1, sum_cz2 + cz2);
        f.y.push(y);
        f.cx.push(cx);
        f.cz1.push(cz1);
        f.cz2.push(cz2);
    }
    let (scale_y, scale_cx) = (1.0 / sum_y, 1.0 / sum_cx);
    let scale_cz = 1.0 / (sum_cz1 * sum_cz1 + sum_cz2 * sum_cz2).sqrt();
    f.y.iter_mut().for_each(|v| *v *= scale_y);
    f.cx.iter_mut().for_each(|v| *v *= scale_cx);
    f.cz1.iter_mut().chain(f.cz2.iter_mut()).for_each(|v| *v *= scale_cz);
    f
}

/// The feature pipeline's filters at `ppd` pixels per degree: σ = ½ w ppd pixels, radius ⌈3σ⌉.
pub fn feature_filters(ppd: f32) -> FeatureFilters {
    let sigma = 0.5 * FEATURE_WIDTH_DEGREES * ppd;
    let radius = (3.0 * sigma).ceil() as i64;
    let mut f = FeatureFilters { gaussian: vec![], edge: vec![], point: vec![] };
    let (mut sum_g, mut edge_pos, mut edge_neg, mut point_pos, mut point_neg) =
        (0.0f32, 0.0f32, 0.0f32, 0.0f32, 0.0f32);
    for i in -radius..=radius {
        let x = i as f32;
        let g = (-(x * x) / (2.0 * sigma * sigma)).exp();
        let edge = -x * g;
        let point = (x * x / (sigma * sigma) - 1.0) * g;
        sum_g += g;
        if edge > 0.0 {
            edge_pos += edge;
        } else {
            edge_neg -= edge;
        }
        if point > 0.0 {
            point_pos += point;
        } else {
            point_neg -= point;
        }
        f.gaussian.push(g);
        f.edge.push(edge);
        f.point.push(point);
    }
    f.gaussian.iter_mut().for_each(|v| *v /= sum_g);
    f.edge.iter_mut().for_each(|v| *v /= if *v > 0.0 { edge_pos } else { edge_neg });
    f.point.iter_mut().for_each(|v| *v /= if *v > 0.0 { point_pos } else { point_neg });
    f
}

/// One channel of an image, row-major, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Plane {
    pub width: usize,
    pub height: usize,
    pub values: Vec<f32>,
}

impl Plane {
    pub fn from_fn(width: usize, height: usize, f: impl Fn(usize) -> f32) -> Plane {
        Plane { width, height, values: (0..width * height).map(f).collect() }
    }

    /// Convolved along x with `kernel` (odd length, centred), the border clamped to the edge.
    pub fn convolve_x(&self, kernel: &[f32]) -> Plane {
        let r = (kernel.len() / 2) as i64;
        let last = self.width as i64 - 1;
        Plane::from_fn(self.width, self.height, |i| {
            let (x, row) = ((i % self.width) as i64, i / self.width * self.width);
            kernel
                .iter()
                .zip(-r..)
                .fold(0.0f32, |acc, (w, dx)| acc + w * self.values[row + (x + dx).clamp(0, last) as usize])
        })
    }

    /// Convolved along y with `kernel` (odd length, centred), the border clamped to the edge.
    pub fn convolve_y(&self, kernel: &[f32]) -> Plane {
        let r = (kernel.len() / 2) as i64;
        let last = self.height as i64 - 1;
        Plane::from_fn(self.width, self.height, |i| {
            let (x, y) = (i % self.width, (i / self.width) as i64);
            kernel
                .iter()
                .zip(-r..)
                .fold(0.0f32, |acc, (w, dy)| acc + w * self.values[(y + dy).clamp(0, last) as usize * self.width + x])
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sum(v: &[f32]) -> f32 {
        v.iter().sum()
    }

    #[test]
    fn the_radii_at_67_ppd() {
        // Widest CSF Gaussian: b = 0.04 deg², σ = √(0.04 / 2π²) = 0.045 deg = 3.02 px; 3σ = 9.05 -> 10.
        assert_eq!(spatial_radius(67.0), 10);
        // Feature σ = 0.041 · 67 = 2.747 px; 3σ = 8.24 -> 9.
        assert_eq!(feature_filters(67.0).gaussian.len(), 19);
        assert_eq!(spatial_filters(67.0).y.len(), 21);
        assert_eq!(spatial_radius(30.0), 5, "3 · 0.045 · 30 = 4.05 -> 5");
    }

    #[test]
    fn the_filters_are_normalised_and_symmetric() {
        for ppd in [10.0f32, 30.0, 67.02] {
            let s = spatial_filters(ppd);
            assert!((sum(&s.y) - 1.0).abs() < 1e-5 && (sum(&s.cx) - 1.0).abs() < 1e-5);
            let cz = sum(&s.cz1).powi(2) + sum(&s.cz2).powi(2);
            assert!((cz - 1.0).abs() < 1e-5, "the 2D blue-yellow filter sums to {cz}");
            let f = feature_filters(ppd);
            assert!((sum(&f.gaussian) - 1.0).abs() < 1e-5);
            for d in [&f.edge, &f.point] {
                let pos: f32 = d.iter().filter(|v| **v > 0.0).sum();
                let neg: f32 = d.iter().filter(|v| **v < 0.0).sum();
                assert!((pos - 1.0).abs() < 1e-5 && (neg + 1.0).abs() < 1e-5, "{pos} {neg}");
            }
            let n = f.edge.len();
            // To rounding: the positive and negative weights are normalised by separate sums.
            for i in 0..n {
                assert!((f.edge[i] + f.edge[n - 1 - i]).abs() < 1e-6, "the edge detector is odd");
                assert!((f.point[i] - f.point[n - 1 - i]).abs() < 1e-6, "the point detector is even");
            }
            assert_eq!(f.edge[n / 2], 0.0);
        }
    }

    /// The edge detector is −d/dx of a Gaussian: on a rising ramp it answers negative, and the
    /// point detector (second derivative, centre negative) answers negative on a bright dot.
    #[test]
    fn the_detectors_answer_a_ramp_and_a_dot() {
        let f = feature_filters(20.0);
        let ramp = Plane::from_fn(15, 1, |i| i as f32);
        assert!(ramp.convolve_x(&f.edge).values[7] < 0.0);
        let dot = Plane::from_fn(15, 1, |i| if i == 7 { 1.0 } else { 0.0 });
        assert!(dot.convolve_x(&f.point).values[7] < 0.0);
    }

    #[test]
    fn convolution_clamps_to_the_edge_and_runs_along_its_axis() {
        let p = Plane { width: 3, height: 2, values: vec![1.0, 2.0, 3.0, 10.0, 20.0, 30.0] };
        let k = [0.25, 0.5, 0.25];
        assert_eq!(p.convolve_x(&k).values, vec![1.25, 2.0, 2.75, 12.5, 20.0, 27.5]);
        assert_eq!(p.convolve_y(&k).values, vec![3.25, 6.5, 9.75, 7.75, 15.5, 23.25]);
    }
}
