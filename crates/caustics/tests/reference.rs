//! Integration tests of the exact CPU photon reference and of the image comparison.

use caustics::compare::{compare, compare_files, Region};
use caustics::image_io::{write_exr, ImageF32, Layer};
use caustics::reference::{trace_reference, ReferenceOptions, ReferenceResult};
use caustics::scene::{ReceiverMapSpec, Scene};
use std::f64::consts::PI;
use std::path::Path;

fn sphere_scene() -> Scene {
    Scene::load(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/sphere_on_plane.toml")))
        .expect("load sphere_on_plane")
}

fn with_receiver(mut scene: Scene, half: f32, resolution: u32) -> Scene {
    scene.receiver_map =
        Some(ReceiverMapSpec { plane_y: 0.0, x_range: [-half, half], z_range: [-half, half], resolution });
    scene
}

fn opts(photons: u64, seed: u64, fresnel: bool, threads: usize) -> ReferenceOptions {
    ReferenceOptions { photons, seed, fresnel, max_bounces: 8, outside_reflection: true, threads, smooth_normals: true }
}

fn layer<'a>(img: &'a ImageF32, name: Option<&str>) -> &'a Layer {
    img.layer(name).unwrap_or_else(|| panic!("layer {name:?} missing"))
}

/// Mean RGB of a layer's texel.
fn mean3(img: &ImageF32, name: Option<&str>, i: usize, j: usize) -> f64 {
    let l = layer(img, name);
    (0..3).map(|c| l.sample(img.width, i as u32, j as u32, c) as f64).sum::<f64>() / 3.0
}

const I: f64 = 100.0; // W/sr, from the scene file
const R: f64 = 0.5;
const D: f64 = 5.0;

fn omega_sphere() -> f64 {
    2.0 * PI * (1.0 - (1.0 - (R / D) * (R / D)).sqrt())
}

fn sum3(a: [f64; 3]) -> f64 {
    a.iter().sum()
}

#[test]
fn power_is_conserved_without_fresnel() {
    // The receiver covers the whole 40 x 40 floor: rays entering the sphere near grazing
    // leave it deviated by up to ~90 degrees and land several metres away (about 0.15 %
    // of the flux falls outside [-3, 3]^2).
    let scene = with_receiver(sphere_scene(), 20.0, 64);
    let n = 200_000;
    let r = trace_reference(&scene, &opts(n, 11, false, 0)).unwrap();
    assert_eq!(r.photons_traced, n);
    let expect = I * omega_sphere();
    for c in 0..3 {
        let e = r.emitted_flux[c];
        assert!((e - expect).abs() / expect < 1e-6, "emitted {e} vs I*Omega {expect}");
        // Every photon's power is accounted for exactly once.
        let books = r.caustic_flux[c] + r.lost_tir[c] + r.lost_other[c] + r.missed_flux[c];
        assert!((books - e).abs() / e < 1e-9, "bookkeeping {books} vs {e}");
        // All transmitted light lands inside the widened receiver: only TIR (and the
        // rim of the cone that misses the tessellated sphere, < 0.1%) is missing.
        let landed = r.caustic_flux[c] + r.lost_tir[c];
        assert!((landed - e).abs() / e < 1e-3, "caustic+tir {landed} vs emitted {e}");
        let c_expect = expect - r.lost_tir[c];
        assert!((r.caustic_flux[c] - c_expect).abs() / c_expect < 0.02);
        assert!(r.lost_tir[c] < 0.05 * e, "TIR loss implausibly large: {}", r.lost_tir[c]);
    }
    // The `caustic` layer integrates to the caustic flux (E * texel area).
    let img = &r.image;
    let area = (40.0 * 40.0) / (64.0 * 64.0);
    let l = layer(img, Some("caustic"));
    let total: f64 = l.data.iter().map(|&v| v as f64).sum::<f64>() * area;
    assert!((total - sum3(r.caustic_flux)).abs() / sum3(r.caustic_flux) < 1e-5);
}

#[test]
fn caustic_is_rotationally_symmetric_under_overhead_light() {
    // The icosphere is only mirror-symmetric about x and z (not 4-fold), so its facets
    // make the 90-degree rotations differ by ~2.5 % at this texel size; noise adds ~1 %.
    let n = 16usize;
    let scene = with_receiver(sphere_scene(), 1.0, n as u32);
    let r = trace_reference(&scene, &opts(600_000, 5, false, 0)).unwrap();
    let img = &r.image;
    let c = |i: usize, j: usize| mean3(img, Some("caustic"), i, j);
    let total: f64 = (0..n).flat_map(|j| (0..n).map(move |i| (i, j))).map(|(i, j)| c(i, j)).sum();
    assert!(total > 0.0);
    // 90°, 180° and 270° rotations and a mirror about x in texel space.
    type Map = fn(usize, usize, usize) -> (usize, usize);
    let maps: [Map; 4] = [
        |i, j, n| (j, n - 1 - i),
        |i, j, n| (n - 1 - i, n - 1 - j),
        |i, j, n| (n - 1 - j, i),
        |i, j, n| (n - 1 - i, j),
    ];
    for (k, m) in maps.iter().enumerate() {
        let mut diff = 0.0;
        for j in 0..n {
            for i in 0..n {
                let (ri, rj) = m(i, j, n);
                diff += (c(i, j) - c(ri, rj)).abs();
            }
        }
        println!("symmetry {k}: {}", diff / total);
        assert!(diff / total < 0.05, "transform {k}: relative difference {}", diff / total);
    }
    // And the caustic is centred: its centroid lies under the sphere centre.
    let (mut cx, mut cz) = (0.0, 0.0);
    for j in 0..n {
        for i in 0..n {
            cx += c(i, j) * (i as f64 + 0.5 - n as f64 / 2.0);
            cz += c(i, j) * (j as f64 + 0.5 - n as f64 / 2.0);
        }
    }
    assert!((cx / total).abs() < 0.1 && (cz / total).abs() < 0.1, "centroid {cx} {cz}");
}

fn images_bit_equal(a: &ReferenceResult, b: &ReferenceResult) -> bool {
    a.image.layers.len() == b.image.layers.len()
        && a.image.layers.iter().zip(&b.image.layers).all(|(x, y)| {
            x.channels == y.channels
                && x.data.len() == y.data.len()
                && x.data.iter().zip(&y.data).all(|(p, q)| p.to_bits() == q.to_bits())
        })
}

#[test]
fn deterministic_for_any_thread_count_and_seed_dependent() {
    let scene = with_receiver(sphere_scene(), 1.0, 32);
    // 150k photons = 3 chunks, so threads really interleave.
    let a = trace_reference(&scene, &opts(150_000, 3, true, 1)).unwrap();
    let b = trace_reference(&scene, &opts(150_000, 3, true, 2)).unwrap();
    let c = trace_reference(&scene, &opts(150_000, 3, true, 3)).unwrap();
    let d = trace_reference(&scene, &opts(150_000, 4, true, 2)).unwrap();
    assert!(images_bit_equal(&a, &b), "threads=1 vs threads=2 differ");
    assert!(images_bit_equal(&a, &c), "threads=1 vs threads=3 differ");
    assert_eq!(a.caustic_flux.map(f64::to_bits), b.caustic_flux.map(f64::to_bits));
    assert!(!images_bit_equal(&a, &d), "different seeds gave the same image");
    assert_ne!(a.caustic_flux, d.caustic_flux);
}

/// With Fresnel on, `outside_reflection = false` drops the photons the sphere reflects off its
/// outside: the full reference's caustic flux is the flux without them plus that of the photons
/// whose one specular interaction is that reflection (`max_bounces = 1`), within 0.5% (each run
/// draws its own photons: about four standard deviations of the three estimates at 200k photons;
/// measured 0.08%), and that share is the few per cent glass reflects.
#[test]
fn leaving_out_the_outside_reflection_drops_exactly_the_reflected_photons() {
    let scene = with_receiver(sphere_scene(), 3.0, 32);
    let full = trace_reference(&scene, &opts(200_000, 9, true, 0)).unwrap();
    let without =
        trace_reference(&scene, &ReferenceOptions { outside_reflection: false, ..opts(200_000, 9, true, 0) }).unwrap();
    let reflected = trace_reference(&scene, &ReferenceOptions { max_bounces: 1, ..opts(200_000, 9, true, 0) }).unwrap();
    for c in 0..3 {
        let (f, w, r) = (full.caustic_flux[c], without.caustic_flux[c], reflected.caustic_flux[c]);
        assert!((f - w - r).abs() < 5e-3 * f, "channel {c}: {f} W against {w} + {r} W");
    }
    let share = sum3(reflected.caustic_flux) / sum3(full.caustic_flux);
    println!("outside reflection: {share:.4} of the caustic flux");
    assert!(share > 0.02 && share < 0.1, "outside reflection {share} of the caustic flux");
}

#[test]
fn fresnel_transmits_less_than_the_image_space_model() {
    let scene = with_receiver(sphere_scene(), 3.0, 32);
    let plain = trace_reference(&scene, &opts(200_000, 9, false, 0)).unwrap();
    let fres = trace_reference(&scene, &opts(200_000, 9, true, 0)).unwrap();
    let ratio = sum3(fres.caustic_flux) / sum3(plain.caustic_flux);
    println!("fresnel/plain caustic flux ratio {ratio}");
    assert!(ratio > 0.85 && ratio < 0.97, "ratio {ratio}");
    assert_eq!(fres.lost_tir, [0.0; 3], "with Fresnel, TIR reflects instead of losing");
    // Two interfaces at >= 4 % each: transmission below 0.96^2 on average.
    assert!(ratio < 0.96 * 0.96 + 0.01);
}

#[test]
fn direct_light_is_exact_and_shadowed_under_the_sphere() {
    let n = 64usize;
    let half = 2.0;
    let scene = with_receiver(sphere_scene(), half as f32, n as u32);
    let r = trace_reference(&scene, &opts(200_000, 2, false, 0)).unwrap();
    let img = &r.image;
    assert_eq!((img.width, img.height), (n as u32, n as u32));
    let main = layer(img, None);
    assert_eq!(main.channels, ["R", "G", "B", "E0"]);
    let texel = 2.0 * half / n as f64;
    let centre = |k: usize| -half + (k as f64 + 0.5) * texel;
    let mut unshadowed_checked = 0;
    for j in 0..n {
        for i in 0..n {
            let (x, z) = (centre(i), centre(j));
            // Point light 100 W/sr at height 6: E0 = I h / r^3.
            let r2 = x * x + z * z + 36.0;
            let e0 = I * 6.0 / (r2 * r2.sqrt());
            let got_e0 = main.sample(n as u32, i as u32, j as u32, 3) as f64;
            assert!((got_e0 - e0).abs() / e0 < 1e-5, "E0 at ({i},{j}) {got_e0} vs {e0}");
            // Outside the shadow cone (sphere silhouette radius ~0.6 on the floor) and no
            // caustic photon there: exactly 1.
            let far = (x * x + z * z).sqrt() > 1.0;
            if far && mean3(img, Some("caustic"), i, j) == 0.0 {
                for c in 0..3 {
                    assert_eq!(main.sample(n as u32, i as u32, j as u32, c), 1.0, "({i},{j})");
                }
                unshadowed_checked += 1;
            }
            // Direct irradiance is E0 outside the shadow, zero under the sphere.
            let direct = mean3(img, Some("irradiance"), i, j) - mean3(img, Some("caustic"), i, j);
            if far {
                assert!((direct - e0).abs() / e0 < 1e-4, "direct at ({i},{j})");
            }
            if (x * x + z * z).sqrt() < 0.4 {
                assert!(direct.abs() < 1e-6 * e0, "direct light under the sphere at ({i},{j})");
            }
        }
    }
    assert!(unshadowed_checked > 100, "only {unshadowed_checked} caustic-free texels");
    // The focused caustic under the sphere is much brighter than the unshadowed floor.
    let mid = n / 2;
    assert!(mean3(img, None, mid, mid) > 3.0, "no focused caustic: {}", mean3(img, None, mid, mid));
}

#[test]
fn scene_without_receiver_is_an_input_error() {
    let mut scene = sphere_scene();
    scene.receiver_map = None;
    let err = trace_reference(&scene, &opts(1000, 1, false, 1)).unwrap_err();
    assert!(err.downcast_ref::<caustics::InputError>().is_some());
    assert!(err.to_string().contains("receiver_map"), "{err}");
}

/// A synthetic receiver image: `v` per texel (all channels), E0 = 2, caustic layer = (v-1)*E0.
fn synthetic(n: u32, f: impl Fn(u32, u32) -> f32) -> ImageF32 {
    let mut main = Vec::new();
    let mut cau = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let v = f(i, j);
            main.extend_from_slice(&[v, v, v, 2.0]);
            let c = ((v - 1.0) * 2.0).max(0.0);
            cau.extend_from_slice(&[c, c, c]);
        }
    }
    ImageF32 {
        width: n,
        height: n,
        layers: vec![
            Layer::new(None, &["R", "G", "B", "E0"], main),
            Layer::new(Some("caustic"), &["R", "G", "B"], cau),
        ],
    }
}

fn blob(cx: f32, cy: f32) -> impl Fn(u32, u32) -> f32 {
    move |i, j| {
        let d2 = (i as f32 - cx).powi(2) + (j as f32 - cy).powi(2);
        1.0 + 4.0 * (-d2 / 8.0).exp()
    }
}

#[test]
fn compare_identical_images() {
    let a = synthetic(32, blob(16.0, 12.0));
    let (cmp, err) = compare(&a, &a.clone()).unwrap();
    assert!(cmp.region_texels > 0);
    assert_eq!(cmp.rel_rmse, 0.0);
    assert_eq!(cmp.rel_rmse_scaled, 0.0);
    assert!((cmp.best_scale - 1.0).abs() < 1e-12);
    assert_eq!(cmp.peak_ratio, 1.0);
    assert_eq!(cmp.peak_offset_texels, 0.0);
    assert!((cmp.caustic_flux_ratio - 1.0).abs() < 1e-12);
    let l = layer(&err, None);
    assert_eq!(l.channels, ["A", "B", "diff", "in_region"]);
    assert!(l.data.chunks(4).all(|p| p[2] == 0.0));
    let in_region = l.data.chunks(4).filter(|p| p[3] == 1.0).count();
    assert_eq!(in_region, cmp.region_texels);
    let text = cmp.to_string();
    assert!(text.contains("relative RMSE") && text.lines().count() == 8, "{text}");
    assert_eq!(cmp.non_finite_texels, 0);
    assert!(cmp.within(0.0, 0.0));
}

#[test]
fn a_texel_that_is_not_finite_is_counted_and_fails_within() {
    let b = synthetic(32, blob(16.0, 12.0));
    // Far from the blob, where both maps read 1 and the texel would be outside the region.
    for bad in [f32::NAN, f32::INFINITY] {
        let mut a = b.clone();
        let nc = a.layers[0].channels.len();
        a.layers[0].data[nc * (31 * 32 + 31)] = bad;
        let (cmp, err) = compare(&a, &b).unwrap();
        assert_eq!(cmp.non_finite_texels, 1, "{bad}");
        assert!(!cmp.rel_rmse.is_finite(), "{bad}: {cmp}");
        assert!(!cmp.within(f64::MAX, f64::MAX), "{bad}: {cmp}");
        let texel = &layer(&err, None).data[4 * (31 * 32 + 31)..][..4];
        assert_eq!(texel[3], 1.0, "{bad}: the texel is in the region: {texel:?}");
    }
    // NaN in the reference is counted too.
    let mut nan_b = b.clone();
    nan_b.layers[0].data[0] = f32::NAN;
    let (cmp, _) = compare(&b, &nan_b).unwrap();
    assert_eq!(cmp.non_finite_texels, 1);
    assert!(!cmp.within(f64::MAX, f64::MAX));
}

#[test]
fn compare_scaled_and_shifted() {
    let b = synthetic(32, blob(16.0, 12.0));
    // Twice the excess over 1.
    let a = synthetic(32, |i, j| 1.0 + 2.0 * (blob(16.0, 12.0)(i, j) - 1.0));
    let (cmp, _) = compare(&a, &b).unwrap();
    assert!(cmp.rel_rmse > 0.1, "{}", cmp.rel_rmse);
    // Not exactly 0 (the scale acts on v, not v-1), but far below the unscaled error.
    assert!(cmp.rel_rmse_scaled < 0.5 * cmp.rel_rmse, "{cmp}");
    assert!(cmp.best_scale < 1.0);
    assert!((cmp.peak_ratio - 9.0 / 5.0).abs() < 1e-5);
    assert!((cmp.caustic_flux_ratio - 2.0).abs() < 1e-5, "{}", cmp.caustic_flux_ratio);

    // A pure scale of v: scaled error exactly recovers it.
    let c = synthetic(32, |i, j| 1.5 * blob(16.0, 12.0)(i, j));
    let (cmp, _) = compare(&c, &b).unwrap();
    assert!(cmp.rel_rmse > 0.3);
    assert!(cmp.rel_rmse_scaled < 1e-6, "{cmp}");
    assert!((cmp.best_scale - 1.0 / 1.5).abs() < 1e-6);

    // A peak moved by (3, 4) texels.
    let s = synthetic(32, blob(19.0, 16.0));
    let (cmp, _) = compare(&s, &b).unwrap();
    assert!((cmp.peak_offset_texels - 5.0).abs() < 1e-12, "{}", cmp.peak_offset_texels);
    assert!((cmp.peak_ratio - 1.0).abs() < 1e-6);
}

#[test]
fn compare_errors_name_the_file_and_channel() {
    let dir = caustics::scratch::ScratchDir::new("causticlab", "compare");
    let pa = dir.join("small_a.exr");
    let pb = dir.join("big_b.exr");
    write_exr(&pa, &synthetic(16, blob(8.0, 8.0))).unwrap();
    write_exr(&pb, &synthetic(32, blob(8.0, 8.0))).unwrap();
    let err = compare_files(&pa, &pb, Region::Caustic).unwrap_err();
    assert!(err.downcast_ref::<caustics::InputError>().is_some(), "{err:#}");
    let msg = format!("{err:#}");
    assert!(msg.contains("small_a.exr") && msg.contains("big_b.exr"), "{msg}");

    // Missing `G` in the main layer of one file.
    let mut bad = synthetic(16, blob(8.0, 8.0));
    bad.layers[0] = Layer::new(None, &["R", "B", "E0"], vec![1.0; 16 * 16 * 3]);
    let pc = dir.join("no_green.exr");
    write_exr(&pc, &bad).unwrap();
    let err = compare_files(&pa, &pc, Region::Caustic).unwrap_err();
    let msg = format!("{err:#}");
    assert!(msg.contains("no_green.exr") && msg.contains("`G`"), "{msg}");
    // Round trip through files gives the same result as in memory.
    let (cmp, _) = compare_files(&pa, &pa, Region::Caustic).unwrap();
    assert_eq!(cmp.rel_rmse, 0.0);
}

/// `cargo test --release -p caustics --test reference -- --ignored --nocapture`
#[test]
#[ignore]
fn throughput_sphere_on_plane() {
    let scene = sphere_scene();
    let photons = 4_000_000;
    for fresnel in [false, true] {
        let t = std::time::Instant::now();
        let r = trace_reference(&scene, &opts(photons, 1, fresnel, 0)).unwrap();
        let s = t.elapsed().as_secs_f64();
        println!(
            "fresnel={fresnel}: {} photons in {s:.2} s = {:.3} Mphotons/s ({} threads); caustic flux {:?}",
            r.photons_traced,
            r.photons_traced as f64 / s / 1e6,
            std::thread::available_parallelism().map_or(1, |n| n.get()),
            r.caustic_flux
        );
    }
}

/// A refracted ray through a true sphere never meets total internal reflection (it leaves at
/// the angle it entered). Interpolated vertex normals stand for that sphere; the facets of the
/// 20480-triangle icosphere do not, and lose some photons to TIR.
#[test]
fn smooth_normals_behave_like_the_sphere_the_mesh_stands_for() {
    let scene = with_receiver(sphere_scene(), 3.0, 32);
    let smooth = trace_reference(&scene, &opts(400_000, 3, false, 0)).unwrap();
    let facets =
        trace_reference(&scene, &ReferenceOptions { smooth_normals: false, ..opts(400_000, 3, false, 0) }).unwrap();
    let emitted = sum3(smooth.emitted_flux);
    assert!(sum3(smooth.lost_tir) < 1e-3 * emitted, "smooth: {} W of {emitted} W lost to TIR", sum3(smooth.lost_tir));
    assert!(sum3(facets.lost_tir) > 2.0 * sum3(smooth.lost_tir), "facets lose more to TIR than the smooth surface");
}
