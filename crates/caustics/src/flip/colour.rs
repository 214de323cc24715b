//! The colour spaces FLIP moves through: linear sRGB, CIE XYZ (D65), the opponent space YCxCz in
//! which the contrast sensitivity functions filter, CIELab with the Hunt adjustment in which the
//! HyAB distance is measured (FLIP paper, the colour pipeline).
//!
//! Everything is `f32`, in the order the reference implementation (`FLIP.h` of flip-evaluator 1.7,
//! class `color3`) computes it, so that our maps agree with its maps to rounding.

/// A colour triple: `[R, G, B]`, `[X, Y, Z]`, `[Y, Cx, Cz]` or `[L, a, b]` by context.
pub type Triple = [f32; 3];

/// D65 white in XYZ (Y = 1), the reference white of YCxCz and CIELab (`DEFAULT_ILLUMINANT` of the
/// reference implementation). Its digits are the reference's, kept as written so that they can be
/// checked against it (f32 keeps about seven of them).
#[allow(clippy::excessive_precision)]
pub const D65: Triple = [0.950_428_545, 1.0, 1.088_900_371];

/// Its reciprocal, written out as the reference implementation writes it (`INV_DEFAULT_ILLUMINANT`)
/// rather than divided here, so that the products round alike.
#[allow(clippy::excessive_precision)]
pub const D65_INVERSE: Triple = [1.052_156_925, 1.0, 0.918_357_670];

/// Luminance of linear sRGB (Rec. 709 weights): the Y whose median and maximum set HDR-FLIP's
/// exposure range.
pub fn luminance(rgb: Triple) -> f32 {
    0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]
}

/// Linear sRGB to XYZ under D65. The matrix is the one the reference implementation uses
/// (exact fractions; source it names: image-engineering.de, "How to convert between sRGB and
/// CIEXYZ").
pub fn linear_rgb_to_xyz(c: Triple) -> Triple {
    let m = [
        [10_135_552.0f32 / 24_577_794.0, 8_788_810.0 / 24_577_794.0, 4_435_075.0 / 24_577_794.0],
        [2_613_072.0 / 12_288_897.0, 8_788_810.0 / 12_288_897.0, 887_015.0 / 12_288_897.0],
        [1_425_312.0 / 73_733_382.0, 8_788_810.0 / 73_733_382.0, 70_074_185.0 / 73_733_382.0],
    ];
    m.map(|row| row[0] * c[0] + row[1] * c[1] + row[2] * c[2])
}

/// XYZ under D65 back to linear sRGB (the inverse matrix, to the reference's nine digits, kept as
/// written).
#[allow(clippy::excessive_precision)]
pub fn xyz_to_linear_rgb(c: Triple) -> Triple {
    let m = [
        [3.241_003_275f32, -1.537_398_934, -0.498_615_861],
        [-0.969_224_334, 1.875_930_071, 0.041_554_224],
        [0.055_639_423, -0.204_011_202, 1.057_148_933],
    ];
    m.map(|row| row[0] * c[0] + row[1] * c[1] + row[2] * c[2])
}

/// XYZ to YCxCz (Zhang & Wandell's opponent space, the linear part of CIELab): achromatic
/// `116 Y/Yn − 16`, red-green `500 (X/Xn − Y/Yn)`, blue-yellow `200 (Y/Yn − Z/Zn)`.
pub fn xyz_to_ycxcz(c: Triple) -> Triple {
    let [x, y, z] = [c[0] * D65_INVERSE[0], c[1] * D65_INVERSE[1], c[2] * D65_INVERSE[2]];
    [116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)]
}

/// YCxCz back to XYZ: after filtering, the colour pipeline returns through linear RGB (where it
/// clamps to the displayable [0, 1]) to CIELab.
pub fn ycxcz_to_xyz(c: Triple) -> Triple {
    let y = (c[0] + 16.0) / 116.0;
    let cx = c[1] / 500.0;
    let cz = c[2] / 200.0;
    [(y + cx) * D65[0], y * D65[1], (y - cz) * D65[2]]
}

/// XYZ to CIELab under D65: the cube root above (6/29)³, the linear segment below it.
pub fn xyz_to_lab(c: Triple) -> Triple {
    let delta = 6.0f32 / 29.0;
    let delta_cube = delta * (delta * delta);
    let slope = 1.0 / (3.0 * (delta * delta));
    let offset = 4.0f32 / 29.0;
    let f = |t: f32| if t > delta_cube { t.powf(1.0 / 3.0) } else { slope * t + offset };
    let [x, y, z] = [f(c[0] * D65_INVERSE[0]), f(c[1] * D65_INVERSE[1]), f(c[2] * D65_INVERSE[2])];
    [116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)]
}

/// The Hunt adjustment (FLIP paper, colour pipeline: chroma is perceived weaker at low lightness):
/// a and b are scaled by `0.01 L`.
pub fn hunt(lab: Triple) -> Triple {
    let l = lab[0];
    [l, 0.01 * l * lab[1], 0.01 * l * lab[2]]
}

/// HyAB (Abasi et al. 2020, as the FLIP paper adopts it for large differences): the city-block
/// distance in lightness plus the Euclidean distance in the (Hunt-adjusted) a, b plane.
pub fn hyab(p: Triple, q: Triple) -> f32 {
    let (da, db) = (p[1] - q[1], p[2] - q[2]);
    (p[0] - q[0]).abs() + (da * da + db * db).sqrt()
}

/// Linear RGB straight to Hunt-adjusted CIELab.
pub fn linear_rgb_to_hunt_lab(c: Triple) -> Triple {
    hunt(xyz_to_lab(linear_rgb_to_xyz(c)))
}

/// The largest colour difference FLIP expects, `c_max`: HyAB between pure green and pure blue
/// (Hunt-adjusted), raised to `q_c` (FLIP paper, colour pipeline: the error redistribution).
pub fn max_colour_difference(q_c: f32) -> f32 {
    hyab(linear_rgb_to_hunt_lab([0.0, 1.0, 0.0]), linear_rgb_to_hunt_lab([0.0, 0.0, 1.0])).powf(q_c)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Triple, b: Triple, tol: f32) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn white_is_the_d65_white_point_and_lab_100_0_0() {
        let xyz = linear_rgb_to_xyz([1.0, 1.0, 1.0]);
        assert!(close(xyz, D65, 1e-6), "{xyz:?}");
        assert!(close(xyz_to_lab(xyz), [100.0, 0.0, 0.0], 1e-4), "{:?}", xyz_to_lab(xyz));
        assert!(close(xyz_to_ycxcz(xyz), [100.0, 0.0, 0.0], 1e-4));
        for (a, b) in D65.iter().zip(D65_INVERSE) {
            assert!((a * b - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn the_matrices_and_ycxcz_invert_each_other() {
        for c in [[0.2f32, 0.5, 0.9], [1.0, 0.0, 0.0], [0.01, 0.02, 0.5]] {
            let back = xyz_to_linear_rgb(ycxcz_to_xyz(xyz_to_ycxcz(linear_rgb_to_xyz(c))));
            assert!(close(back, c, 1e-5), "{c:?} -> {back:?}");
        }
    }

    /// Published CIELab of the sRGB primaries (D65): red (53.24, 80.09, 67.20), blue
    /// (32.30, 79.19, −107.86), green (87.73, −86.18, 83.18).
    #[test]
    fn the_primaries_have_their_published_lab() {
        for (rgb, lab) in [
            ([1.0f32, 0.0, 0.0], [53.24f32, 80.09, 67.20]),
            ([0.0, 0.0, 1.0], [32.30, 79.19, -107.86]),
            ([0.0, 1.0, 0.0], [87.73, -86.18, 83.18]),
        ] {
            let got = xyz_to_lab(linear_rgb_to_xyz(rgb));
            assert!(close(got, lab, 0.02), "{rgb:?}: {got:?}, published {lab:?}");
        }
    }

    #[test]
    fn srgb_decoding_meets_its_segments() {
        assert_eq!(crate::image_io::srgb_decode(0.0), 0.0);
        assert!((crate::image_io::srgb_decode(1.0) - 1.0).abs() < 1e-6);
        assert!((crate::image_io::srgb_decode(0.5) - 0.214_041).abs() < 1e-5, "mid-grey 0.5 is 21.4% linear");
        assert!((crate::image_io::srgb_decode(0.04045) - 0.04045 / 12.92).abs() < 1e-9);
    }

    #[test]
    fn hyab_is_city_block_in_l_and_euclidean_in_ab() {
        assert_eq!(hyab([50.0, 3.0, 0.0], [40.0, 0.0, 4.0]), 10.0 + 5.0);
        assert_eq!(hunt([50.0, 10.0, -20.0]), [50.0, 5.0, -10.0]);
    }

    /// c_max by hand from the published Lab of green and blue above: Hunt scales a, b by L/100,
    /// HyAB = |87.73 − 32.30| + |(−75.61, 72.97) − (25.58, −34.84)| = 203.3, and 203.3^0.7 = 41.27.
    #[test]
    fn the_largest_difference_is_green_against_blue() {
        let c = max_colour_difference(0.7);
        assert!((c - 41.27).abs() < 0.05, "c_max {c}");
    }
}
