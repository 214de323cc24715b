//! The public API: what it refuses (and that it refuses rather than panics), the viewing default,
//! the clamping of LDR input. The maps themselves are held to the reference implementation in
//! `tests/flip_reference.rs`.

use super::*;
use crate::image_io::{ImageF32, Layer};

fn grey(w: usize, h: usize, v: f32) -> Rgb {
    Rgb::new(w, h, &vec![v; w * h * 3]).unwrap()
}

#[test]
fn the_default_viewing_is_67_pixels_per_degree() {
    // 0.7 m · 3840 px / 0.7 m · π / 180 = 3840 π / 180 = 67.0206.
    assert!((default_ppd() - 67.0206).abs() < 1e-4, "{}", default_ppd());
    assert!((pixels_per_degree(1.4, 3840.0, 0.7) - 2.0 * default_ppd()).abs() < 1e-3);
}

#[test]
fn images_of_different_sizes_are_refused() {
    let err = ldr(&grey(4, 4, 0.5), &grey(4, 5, 0.5), 67.0).unwrap_err();
    assert!(err.0.contains("4x4") && err.0.contains("4x5"), "{err}");
    assert!(hdr(&grey(4, 4, 0.5), &grey(5, 4, 0.5), 67.0, Exposures::Auto).is_err());
}

#[test]
fn empty_and_misshapen_images_are_refused() {
    let err = Rgb::new(0, 4, &[]).unwrap_err();
    assert!(err.0.contains("0x4") && err.0.contains("no pixels"), "{err}");
    let err = Rgb::new(2, 2, &[0.0; 11]).unwrap_err();
    assert!(err.0.contains("11 values") && err.0.contains("2x2"), "{err}");
    assert!(Rgb::new(usize::MAX, 2, &[]).is_err(), "an overflowing size is refused, not a panic");
}

#[test]
fn nan_infinite_and_negative_values_are_refused_naming_the_pixel() {
    for (bad, shown) in [(f32::NAN, "NaN"), (f32::INFINITY, "inf"), (-0.25, "-0.25")] {
        let mut v = vec![0.5f32; 3 * 3 * 3];
        v[3 * (2 * 3 + 1) + 2] = bad; // pixel (1, 2), channel B
        let err = Rgb::new(3, 3, &v).unwrap_err();
        assert!(err.0.contains("(1, 2)") && err.0.contains(&format!("B = {shown}")), "{err}");
    }
}

#[test]
fn pixels_per_degree_must_be_positive_and_finite() {
    let img = grey(4, 4, 0.5);
    for ppd in [0.0, -67.0, f64::NAN, f64::INFINITY, MAX_PPD * 2.0] {
        let err = ldr(&img, &img, ppd).unwrap_err();
        assert!(err.0.contains("pixels per degree"), "{ppd}: {err}");
        assert!(hdr(&img, &img, ppd, Exposures::Auto).is_err());
    }
}

#[test]
fn given_exposures_must_be_finite_ordered_and_few() {
    let img = grey(4, 4, 0.5);
    for (start, stop) in [(2.0, 1.0), (f64::NAN, 1.0), (0.0, f64::INFINITY)] {
        let err = hdr(&img, &img, 67.0, Exposures::Given { start, stop }).unwrap_err();
        assert!(err.0.contains("exposures from"), "{err}");
    }
    let err = hdr(&img, &img, 67.0, Exposures::Given { start: 0.0, stop: 1e300 }).unwrap_err();
    assert!(err.0.contains("do not fit in f32"), "{err}");
    let dim = grey(4, 4, 1e-40);
    let err = hdr(&dim, &img, 67.0, Exposures::Auto).unwrap_err();
    assert!(err.0.contains("too dim"), "{err}");
    let err = hdr(&img, &img, 67.0, Exposures::Given { start: -200.0, stop: 200.0 }).unwrap_err();
    assert!(err.0.contains("400") && err.0.contains("more than 256"), "{err}");
}

#[test]
fn a_black_reference_has_no_automatic_exposures_but_given_ones_work() {
    let (black, lit) = (grey(4, 4, 0.0), grey(4, 4, 1.0));
    let err = hdr(&black, &lit, 67.0, Exposures::Auto).unwrap_err();
    assert!(err.0.contains("black"), "{err}");
    let r = hdr(&black, &lit, 67.0, Exposures::Given { start: 0.0, stop: 0.0 }).unwrap();
    assert_eq!((r.exposure_count, r.start_exposure, r.stop_exposure), (2, 0.0, 0.0));
    assert!(r.mean() > 0.5, "black against 1.0 (0.67 after the tone curve at exposure 0): {}", r.mean());
}

#[test]
fn ldr_clamps_values_above_one() {
    let e = ldr(&grey(6, 6, 1.0), &grey(6, 6, 3.0), 67.0).unwrap();
    assert!(e.values.iter().all(|&v| v == 0.0) && e.mean == 0.0);
    let e = ldr(&grey(6, 6, 0.2), &grey(6, 6, 3.0), 67.0).unwrap();
    assert!(e.mean > 0.5, "{e}");
}

#[test]
fn identical_images_have_zero_error_and_say_their_viewing() {
    let img =
        Rgb::new(3, 2, &[0.0, 1.0, 2.0, 4.0, 8.0, 16.0, 0.1, 0.2, 0.3, 30.0, 20.0, 10.0, 5.0, 5.0, 5.0, 0.0, 0.0, 9.0])
            .unwrap();
    let r = hdr(&img, &img, 40.0, Exposures::Auto).unwrap();
    assert!(r.map.values.iter().all(|&v| v == 0.0) && r.mean() == 0.0 && r.ppd() == 40.0);
    let text = r.to_string();
    assert!(text.contains("40.00 pixels per degree") && text.contains("found from the reference"), "{text}");
    assert_eq!(r.map.magma_rgb8()[..3], colormap::to_rgb8(MAGMA[0]));
}

#[test]
fn srgb_bytes_decode_to_linear() {
    let img = Rgb::from_srgb8(2, 1, &[0, 0, 0, 255, 255, 255]).unwrap();
    assert_eq!(img.pixels()[0], [0.0; 3]);
    assert!(img.pixels()[1].iter().all(|v| (v - 1.0).abs() < 1e-6));
    assert!(Rgb::from_srgb8(2, 2, &[0; 6]).is_err());
}

#[test]
fn an_exr_needs_r_g_and_b_in_its_main_layer() {
    let exr = |channels: &[&str]| ImageF32 {
        width: 1,
        height: 1,
        layers: vec![Layer::new(None, channels, (0..channels.len()).map(|i| i as f32).collect())],
    };
    let img = Rgb::from_exr(&exr(&["B", "E0", "G", "R"])).unwrap();
    assert_eq!(img.pixels()[0], [3.0, 2.0, 0.0], "R, G, B picked by name");
    let err = Rgb::from_exr(&exr(&["X", "Y", "Z"])).unwrap_err();
    assert!(err.0.contains("not R, G and B"), "{err}");
}

#[test]
fn the_maps_are_written_with_their_viewing() {
    let dir = std::env::temp_dir().join(format!("flip_exr_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let reference = Rgb::new(2, 1, &[1.0, 1.0, 1.0, 4.0, 4.0, 4.0]).unwrap();
    let test = Rgb::new(2, 1, &[1.0, 1.0, 1.0, 0.5, 4.0, 4.0]).unwrap();
    let r = hdr(&reference, &test, 30.0, Exposures::Given { start: -2.0, stop: 1.0 }).unwrap();
    let path = dir.join("flip.exr");
    r.write_exr(&path).unwrap();
    let back = crate::image_io::read_exr(&path).unwrap();
    let layer = back.layer(None).unwrap();
    assert_eq!(layer.channels, ["FLIP", "exposure"]);
    assert_eq!(layer.data, vec![r.map.values[0], r.exposure_map[0], r.map.values[1], r.exposure_map[1]]);
    let header = crate::image_io::exr_text_attributes(&path).unwrap();
    assert_eq!(header["flip:ppd"], "30");
    assert_eq!(header["flip:exposure_count"], "3");
    assert_eq!(header["flip:mean"].parse::<f64>().unwrap(), r.mean());
    r.map.write_exr(&dir.join("ldr.exr")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}
