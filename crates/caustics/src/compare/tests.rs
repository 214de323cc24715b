//! The error figures every quality table prints, each held against a value worked out by hand
//! from the module's definitions (not from the code), with a twin on each side of every
//! threshold.

use super::*;

/// A `w`×`h` receiver map with relative irradiance `v` per texel (R, G, B equal) and `E0`.
fn map(w: u32, h: u32, v: &[f32], e0: Option<&[f32]>) -> ImageF32 {
    let n = (w * h) as usize;
    assert_eq!(v.len(), n);
    // Channels out of the usual order: each is found by its name.
    let mut data = vec![];
    let channels: &[&str] = if e0.is_some() { &["E0", "B", "G", "R"] } else { &["B", "G", "R"] };
    for t in 0..n {
        if let Some(e) = e0 {
            data.push(e[t]);
        }
        data.extend_from_slice(&[v[t], v[t], v[t]]);
    }
    ImageF32 { width: w, height: h, layers: vec![Layer::new(None, channels, data)] }
}

fn with_caustic(mut img: ImageF32, c: &[f32]) -> ImageF32 {
    let data = c.iter().flat_map(|&x| [x, x, x]).collect();
    img.layers.push(Layer::new(Some("caustic"), &["R", "G", "B"], data));
    img
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

#[test]
fn a_map_against_itself_has_no_error() {
    let a = map(3, 1, &[1.0, 2.0, 0.5], Some(&[1.0, 1.0, 1.0]));
    let (c, _) = compare(&a, &a).unwrap();
    assert_eq!(
        c,
        Comparison {
            region_texels: 2,
            rel_rmse: 0.0,
            rel_rmse_scaled: 0.0,
            best_scale: 1.0,
            peak_ratio: 1.0,
            peak_offset_texels: 0.0,
            caustic_flux_ratio: 1.0,
            non_finite_texels: 0,
        }
    );
}

#[test]
fn the_mean_of_r_g_b_is_the_texels_value() {
    // R, G, B = 3, 0, 0 reads 1: outside the region; 6, 0, 0 reads 2.
    let img = |r: f32| ImageF32 {
        width: 1,
        height: 1,
        layers: vec![Layer::new(None, &["G", "R", "B", "E0"], vec![0.0, r, 0.0, 1.0])],
    };
    assert_eq!(compare(&img(3.0), &img(3.0)).unwrap().0.region_texels, 0);
    let (c, e) = compare(&img(6.0), &img(3.0)).unwrap();
    assert_eq!(c.region_texels, 1);
    assert_eq!(e.layers[0].data, [2.0, 1.0, 1.0, 1.0]);
}

#[test]
fn the_region_is_where_either_map_differs_from_1_by_more_than_the_threshold() {
    // Texel by texel: at the threshold (out), just beyond it above and below (in), only the
    // reference beyond it (in), and beyond it but unlit in one map (out).
    let a = map(5, 1, &[1.05, 1.0502, 0.9498, 1.0, 1.5], Some(&[1.0, 1.0, 1.0, 1.0, 0.0]));
    let b = map(5, 1, &[1.0, 1.0, 1.0, 0.9, 1.5], Some(&[1.0, 1.0, 1.0, 1.0, 1.0]));
    let (c, e) = compare(&a, &b).unwrap();
    let in_region: Vec<f32> = e.layers[0].data.chunks(4).map(|p| p[3]).collect();
    assert_eq!(in_region, [0.0, 1.0, 1.0, 1.0, 0.0]);
    assert_eq!(c.region_texels, 3);
    assert_eq!(e.layers[0].channels, ["A", "B", "diff", "in_region"]);
    let diff: Vec<f32> = e.layers[0].data.chunks(4).map(|p| p[2]).collect();
    assert!((diff[3] - 0.1).abs() < 1e-6 && (diff[1] - 0.0502).abs() < 1e-6, "{diff:?}");
    // Over every lit texel instead (Trendall & Stewart Sec. 5.2): all but the unlit one.
    let (lit, _) = compare_labelled(&a, "a", &b, "b", Region::Lit).unwrap();
    assert_eq!(lit.region_texels, 4);
    // Without E0 every texel is lit (the flux then comes from `caustic` layers).
    let plain = with_caustic(map(2, 1, &[1.0, 1.0], None), &[1.0, 1.0]);
    let (lit, _) = compare_labelled(&plain, "a", &plain, "b", Region::Lit).unwrap();
    assert_eq!(lit.region_texels, 2);
}

#[test]
fn rmse_best_scale_and_peak_follow_their_definitions() {
    // a = 2, 3 and b = 2, 2 in the region; the texel reading 1 in both is outside it.
    // rel RMSE = sqrt(((2-2)² + (3-2)²) / (2² + 2²)) = sqrt(1/8);
    // best scale s = Σab / Σa² = (4 + 6) / (4 + 9) = 10/13;
    // Σ(s·a - b)² = (20/13 - 2)² + (30/13 - 2)² = (36 + 16) / 169 = 4/13, over Σb² = 8: sqrt(1/26).
    let a = map(3, 1, &[2.0, 3.0, 1.0], Some(&[1.0, 1.0, 1.0]));
    let b = map(3, 1, &[2.0, 2.0, 1.0], Some(&[1.0, 1.0, 1.0]));
    let (c, _) = compare(&a, &b).unwrap();
    assert_eq!(c.region_texels, 2);
    assert!(close(c.rel_rmse, (1.0f64 / 8.0).sqrt()), "{}", c.rel_rmse);
    assert!(close(c.best_scale, 10.0 / 13.0), "{}", c.best_scale);
    assert!(close(c.rel_rmse_scaled, (1.0f64 / 26.0).sqrt()), "{}", c.rel_rmse_scaled);
    // Peaks: a's 3 at x = 1, b's first 2 at x = 0 (the first of equals): ratio 1.5, one texel.
    assert!(close(c.peak_ratio, 1.5) && close(c.peak_offset_texels, 1.0), "{c:?}");
    // Caustic flux from E0: Σ max(v - 1, 0)·E0 = 1 + 2 against 1 + 1.
    assert!(close(c.caustic_flux_ratio, 1.5), "{}", c.caustic_flux_ratio);
}

#[test]
fn the_peak_offset_is_the_distance_between_the_two_maxima_in_texels() {
    // 4 wide, 3 high: a's peak at (x 3, y 2), b's at (x 0, y 1): sqrt(3² + 1²) (offsets that
    // differ in x and y, so that a sum for a difference or for a square shows).
    let mut va = [1.0f32; 12];
    let mut vb = [1.0f32; 12];
    va[2 * 4 + 3] = 4.0;
    va[0] = 3.0;
    vb[4] = 2.0;
    vb[2 * 4 + 3] = 1.5;
    let lit = [1.0f32; 12];
    let (c, _) = compare(&map(4, 3, &va, Some(&lit)), &map(4, 3, &vb, Some(&lit))).unwrap();
    assert!(close(c.peak_offset_texels, 10f64.sqrt()), "{}", c.peak_offset_texels);
    assert!(close(c.peak_ratio, 2.0), "{}", c.peak_ratio);
}

#[test]
fn the_caustic_flux_is_read_from_caustic_layers_when_both_have_one() {
    let a = with_caustic(map(2, 1, &[1.0, 1.0], None), &[3.0, 1.0]);
    let b = with_caustic(map(2, 1, &[1.0, 1.0], None), &[1.0, 1.0]);
    let (c, _) = compare(&a, &b).unwrap();
    assert!(close(c.caustic_flux_ratio, 2.0), "{}", c.caustic_flux_ratio);
    // Only one of them has a layer: the flux is the E0-weighted excess, which needs E0.
    let e = compare(&a, &map(2, 1, &[1.0, 1.0], None)).unwrap_err();
    assert!(format!("{e:#}").contains("no channel `E0`"), "{e:#}");
    // The excess ignores texels below 1 and weighs each by its E0: 0.5·2 against 1·1.
    let a = map(3, 1, &[1.5, 0.2, 1.0], Some(&[2.0, 5.0, 1.0]));
    let b = map(3, 1, &[2.0, 1.0, 1.0], Some(&[1.0, 1.0, 1.0]));
    assert!(close(compare(&a, &b).unwrap().0.caustic_flux_ratio, 1.0));
}

#[test]
fn zero_references_give_ratios_of_one_or_infinity_not_nan() {
    assert_eq!(ratio(0.0, 0.0), 1.0);
    assert_eq!(ratio(2.0, 0.0), f64::INFINITY);
    assert_eq!(ratio(3.0, 2.0), 1.5);
    // A reference of zeros where the technique has light: every error infinite, none NaN.
    let a = map(2, 1, &[2.0, 2.0], Some(&[1.0, 1.0]));
    let b = map(2, 1, &[0.0, 0.0], Some(&[1.0, 1.0]));
    let (c, _) = compare(&a, &b).unwrap();
    assert_eq!((c.rel_rmse, c.peak_ratio, c.caustic_flux_ratio), (f64::INFINITY, f64::INFINITY, f64::INFINITY));
    // Both zero: no error.
    let (c, _) = compare(&b, &b).unwrap();
    assert_eq!((c.rel_rmse, c.best_scale, c.peak_ratio, c.caustic_flux_ratio), (0.0, 1.0, 1.0, 1.0));
}

#[test]
fn a_technique_of_zeros_keeps_the_scale_at_one() {
    // Σa² = 0: no scale can help; the best scale reads 1, the scaled error equals the plain one.
    let a = map(2, 1, &[0.0, 0.0], Some(&[1.0, 1.0]));
    let b = map(2, 1, &[2.0, 1.0], Some(&[1.0, 1.0]));
    let (c, _) = compare(&a, &b).unwrap();
    assert_eq!(c.best_scale, 1.0);
    assert!(close(c.rel_rmse, 1.0) && close(c.rel_rmse_scaled, 1.0), "{c:?}");
}

#[test]
fn a_texel_that_is_not_finite_poisons_the_errors_and_fails_within() {
    let a = map(3, 1, &[f32::NAN, 2.0, 1.0], Some(&[1.0, 1.0, 1.0]));
    let b = map(3, 1, &[1.0, 2.0, 1.0], Some(&[1.0, 1.0, f32::INFINITY]));
    let (c, e) = compare(&a, &b).unwrap();
    // The NaN texel is in the region (it reads NaN, not "close to 1"); the infinite E0 counts.
    assert_eq!((c.non_finite_texels, c.region_texels), (2, 2));
    assert!(c.rel_rmse.is_nan(), "{c:?}");
    assert_eq!(e.layers[0].data[3], 1.0);
    // The peaks skip it: 2 against 2.
    assert_eq!((c.peak_ratio, c.peak_offset_texels), (1.0, 0.0));
    assert!(!c.within(1e9, 1e9));
}

#[test]
fn within_holds_at_its_bounds_and_fails_beyond_them() {
    let c = Comparison {
        region_texels: 10,
        rel_rmse: 0.25,
        rel_rmse_scaled: 0.2,
        best_scale: 1.0,
        peak_ratio: 1.0,
        peak_offset_texels: 0.0,
        caustic_flux_ratio: 0.75,
        non_finite_texels: 0,
    };
    assert!(c.within(0.25, 0.25));
    assert!(!c.within(0.2499, 0.25));
    assert!(!c.within(0.25, 0.2499));
    assert!(Comparison { caustic_flux_ratio: 1.25, ..c.clone() }.within(0.25, 0.25));
    assert!(!Comparison { caustic_flux_ratio: 1.2501, ..c.clone() }.within(0.25, 0.25));
    assert!(!Comparison { non_finite_texels: 1, ..c.clone() }.within(1.0, 1.0));
    assert!(!Comparison { rel_rmse: f64::NAN, ..c.clone() }.within(1.0, 1.0));
}

#[test]
fn the_printed_table_names_every_figure_with_its_value() {
    let c = Comparison {
        region_texels: 7502,
        rel_rmse: 0.0072,
        rel_rmse_scaled: 0.0071,
        best_scale: 1.0001,
        peak_ratio: 0.997,
        peak_offset_texels: 1.0,
        caustic_flux_ratio: 0.9999,
        non_finite_texels: 3,
    };
    let s = c.to_string();
    let rows: Vec<(String, String)> = s
        .lines()
        .map(|l| {
            let (k, v) = l.split_once("  ").unwrap_or_else(|| panic!("{l:?}: no value"));
            (k.trim().to_string(), v.trim().to_string())
        })
        .collect();
    let want = [
        ("region texels", "7502"),
        ("relative RMSE", "0.007200"),
        ("relative RMSE (scaled)", "0.007100"),
        ("best scale", "1.000100"),
        ("peak ratio", "0.997000"),
        ("peak offset (texels)", "1.000"),
        ("caustic flux ratio", "0.999900"),
        ("non-finite texels", "3"),
    ];
    let want: Vec<(String, String)> = want.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
    assert_eq!(rows, want);
    // The values line up in one column.
    let ends: Vec<usize> = s.lines().map(str::len).collect();
    assert!(ends.iter().all(|&e| e == ends[0]), "{s}");
}

#[test]
fn maps_that_cannot_be_compared_are_named() {
    let a = map(2, 1, &[1.0, 1.0], None);
    let e = compare_labelled(&a, "a.exr", &map(1, 2, &[1.0, 1.0], None), "b.exr", Region::Caustic).unwrap_err();
    assert!(format!("{e}").contains("size mismatch: a.exr is 2x1 but b.exr is 1x2"), "{e}");
    let no_blue = ImageF32 { width: 1, height: 1, layers: vec![Layer::new(None, &["R", "G"], vec![1.0, 1.0])] };
    let e = compare_labelled(&no_blue, "a.exr", &map(1, 1, &[1.0], None), "b.exr", Region::Caustic).unwrap_err();
    assert!(format!("{e}").contains("a.exr: the main layer has no channel `B`"), "{e}");
    let short = ImageF32 { width: 2, height: 1, layers: vec![Layer::new(None, &["R", "G", "B"], vec![1.0; 3])] };
    let e = compare_labelled(&a, "a.exr", &short, "b.exr", Region::Caustic).unwrap_err();
    assert!(format!("{e}").contains("b.exr: the main layer has the wrong number of values"), "{e}");
    let no_main = ImageF32 { width: 1, height: 1, layers: vec![] };
    let e = compare_labelled(&no_main, "a.exr", &no_main, "b.exr", Region::Caustic).unwrap_err();
    assert!(format!("{e}").contains("a.exr: no main layer"), "{e}");
}
