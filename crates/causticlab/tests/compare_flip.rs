//! `causticlab compare`'s HDR-FLIP (issue 51) on final images and receiver maps, its JSON keys and
//! FLIP error image, its refusals; `causticlab reference --final`'s refusals and one validated
//! run at level 0.

mod common;
use caustics::flip::{self, Exposures, Rgb};
use caustics::image_io::{read_exr, read_png_rgba, write_exr, ImageF32, Layer};
use common::{causticlab, scene, scratch};

const W: u32 = 40;
const H: u32 = 24;

/// A `W`×`H` final image (R, G, B radiance): a grey floor of 0.3 and a disc as bright as `peak`
/// of radius 4 centred at (`cx`, 12).
fn final_image(cx: f32, peak: f32) -> ImageF32 {
    let data = (0..H)
        .flat_map(|y| (0..W).map(move |x| (x, y)))
        .flat_map(|(x, y)| {
            let inside = (x as f32 + 0.5 - cx).hypot(y as f32 + 0.5 - 12.0) < 4.0;
            let v = if inside { peak } else { 0.3 };
            [v, v * 0.9, v * 0.8]
        })
        .collect();
    ImageF32 { width: W, height: H, layers: vec![Layer::new(None, &["R", "G", "B"], data)] }
}

fn json(run: &common::Run) -> serde_json::Value {
    assert_eq!(run.code, Some(0), "{}", run.describe());
    serde_json::from_str(&run.stdout).unwrap_or_else(|e| panic!("not JSON ({e}):\n{}", run.describe()))
}

#[test]
fn compare_reports_hdr_flip_of_final_images_and_writes_the_flip_png_beside_the_error_png() {
    let dir = scratch("compare-flip-final");
    let (a, b) = (dir.join("a.exr"), dir.join("b.exr"));
    // A's disc moved and brighter: FLIP is not symmetric, the exposures are B's.
    write_exr(&a, &final_image(22.0, 20.0)).unwrap();
    write_exr(&b, &final_image(18.0, 8.0)).unwrap();
    let (sa, sb) = (a.display().to_string(), b.display().to_string());

    let itself = json(&causticlab(&["compare", "--json", &sb, &sb]));
    assert_eq!(itself["kind"], "final-image");
    assert_eq!(itself["flip"]["mean"], 0.0);
    assert_eq!(itself["rel_rmse"], 0.0);

    let png = dir.join("err.png");
    let run = causticlab(&["compare", "--json", &sa, &sb, "--error-image", &png.display().to_string()]);
    let v = json(&run);
    for key in ["a", "b", "kind", "pixels", "rel_rmse", "non_finite_pixels", "flip"] {
        assert!(!v[key].is_null(), "no `{key}` in {v}");
    }
    for key in
        ["kind", "mean", "ppd", "width", "height", "start_exposure", "stop_exposure", "exposure_count", "exposures"]
    {
        assert!(!v["flip"][key].is_null(), "no `flip.{key}` in {v}");
    }
    // The figures are the library's HDR-FLIP of the same images, B the reference.
    let expected =
        flip::hdr(&Rgb::read_exr(&b).unwrap(), &Rgb::read_exr(&a).unwrap(), flip::default_ppd(), Exposures::Auto)
            .unwrap();
    assert!(expected.mean() > 0.01, "the moved disc is hardly an error: {}", expected.mean());
    assert_eq!(v["flip"]["mean"].as_f64(), Some(expected.mean()));
    assert_eq!(v["flip"]["ppd"].as_f64(), Some(flip::default_ppd()));
    assert_eq!((v["flip"]["width"].as_u64(), v["flip"]["height"].as_u64()), (Some(W as u64), Some(H as u64)));
    assert_eq!(v["flip"]["exposure_count"].as_u64(), Some(expected.exposure_count as u64));
    assert_eq!(v["flip"]["start_exposure"].as_f64(), Some(expected.start_exposure));
    assert_eq!(v["pixels"].as_u64(), Some((W * H) as u64));

    // The FLIP PNG beside the error PNG: the map through magma, the picture's size.
    let flip_png = dir.join("err.flip.png");
    assert!(run.stderr.contains(&flip_png.display().to_string()), "{}", run.describe());
    let (w, h, rgba) = read_png_rgba(&flip_png).expect("a decodable FLIP PNG");
    assert_eq!((w, h), (W, H));
    let pixel = |x: u32, y: u32| -> [u8; 3] {
        let i = 4 * (y * W + x) as usize;
        [0, 1, 2].map(|c| (caustics::image_io::srgb_encode(rgba[i + c]) * 255.0).round() as u8)
    };
    let at = |x: usize, y: usize| flip::colormap::to_rgb8(flip::colormap::magma(expected.map.at(x, y)));
    for (x, y) in [(0, 0), (14, 12), (20, 12), (26, 12), (39, 23)] {
        assert_eq!(pixel(x, y), at(x as usize, y as usize), "pixel ({x}, {y})");
    }
    assert_ne!(pixel(14, 12), pixel(0, 0), "the disc's old place is as dark as the untouched floor");
    assert!(png.is_file(), "the error PNG");

    // The human output says the mean with its pixels per degree and size.
    let run = causticlab(&["compare", &sa, &sb]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    let line = format!(
        "HDR-FLIP (final image): mean FLIP {:.6} over {W}x{H} pixels at 67.02 pixels per degree",
        expected.mean()
    );
    assert!(run.stdout.contains(&line), "no `{line}`\n{}", run.describe());
}

/// A 2×2 receiver map (E/E0 in R, G, B and E0).
fn receiver(values: [f32; 4]) -> ImageF32 {
    let data = values.iter().flat_map(|&v| [v, v, v, 1.0]).collect();
    ImageF32 { width: 2, height: 2, layers: vec![Layer::new(None, &["R", "G", "B", "E0"], data)] }
}

#[test]
fn compare_reports_hdr_flip_of_receiver_maps_and_writes_the_flip_exr() {
    let dir = scratch("compare-flip-receiver");
    let (a, b) = (dir.join("a.exr"), dir.join("b.exr"));
    write_exr(&a, &receiver([1.0, 3.0, 1.0, 0.5])).unwrap();
    write_exr(&b, &receiver([1.0, 1.5, 1.0, 0.5])).unwrap();
    let exr = dir.join("err.exr");
    let v = json(&causticlab(&[
        "compare",
        "--json",
        &a.display().to_string(),
        &b.display().to_string(),
        "--error-image",
        &exr.display().to_string(),
    ]));
    assert_eq!(v["kind"], "receiver-map");
    assert_eq!(v["flip"]["kind"], "receiver-map");
    assert_eq!((v["flip"]["width"].as_u64(), v["flip"]["height"].as_u64()), (Some(2), Some(2)));
    assert!(v["flip"]["mean"].as_f64().is_some_and(|m| m > 0.0), "{v}");
    // The receiver map's figures are all still there.
    for key in [
        "region",
        "region_texels",
        "rel_rmse",
        "rel_rmse_scaled",
        "best_scale",
        "peak_ratio",
        "peak_offset_texels",
        "caustic_flux_ratio",
        "non_finite_texels",
    ] {
        assert!(!v[key].is_null(), "no `{key}` in {v}");
    }
    let flip_exr = read_exr(&dir.join("err.flip.exr")).expect("the FLIP EXR beside the error EXR");
    assert_eq!(flip_exr.layers[0].channels, ["FLIP", "exposure"]);
    let mean = flip_exr.layers[0].data.chunks(2).map(|p| p[0] as f64).sum::<f64>() / 4.0;
    assert!((mean - v["flip"]["mean"].as_f64().unwrap()).abs() < 1e-6, "{mean} against {v}");
}

#[test]
fn compare_refuses_a_receiver_map_against_a_final_image_and_images_of_two_sizes() {
    let dir = scratch("compare-flip-refusals");
    let (map, fin) = (dir.join("receiver.exr"), dir.join("final.exr"));
    write_exr(&map, &receiver([1.0; 4])).unwrap();
    write_exr(&fin, &final_image(20.0, 8.0)).unwrap();
    let (m, f) = (map.display().to_string(), fin.display().to_string());
    let other = dir.join("other.exr");
    let mut small = final_image(20.0, 8.0);
    small.height = 12;
    small.layers[0].data.truncate((W * 12 * 3) as usize);
    write_exr(&other, &small).unwrap();
    let o = other.display().to_string();
    for (args, needles) in [
        ([&m, &f], vec![m.as_str(), f.as_str(), "receiver map", "final image"]),
        ([&f, &o], vec![f.as_str(), o.as_str(), "size mismatch", "40x24", "40x12"]),
    ] {
        let run = causticlab(&["compare", args[0], args[1]]);
        assert_eq!(run.code, Some(2), "{}", run.describe());
        for n in needles {
            assert!(run.stderr.contains(n), "no `{n}`\n{}", run.describe());
        }
        assert!(!run.stderr.contains("panicked"), "{}", run.describe());
    }
}

#[test]
fn reference_final_refuses_the_cpu_references_flags_and_pool_scenes() {
    let dir = scratch("reference-final-refusals");
    let out = dir.join("out").display().to_string();
    let s = scene("sphere_on_plane");
    for (args, needle) in [
        (vec!["--final", "--photons", "1000"], "--photons"),
        (vec!["--final", "--threads", "2"], "--threads"),
        (vec!["--level", "1"], "--final"),
        // Beside --photons, which --final refuses, clap lets --level through: causticlab refuses it.
        (vec!["--level", "1", "--photons", "5"], "--level"),
        (vec!["--final", "--level", "9"], "--level"),
    ] {
        let mut full = vec!["reference", "--scene", &s, "--out", &out];
        full.extend(args.iter().copied());
        let run = causticlab(&full);
        assert_eq!(run.code, Some(2), "{args:?}\n{}", run.describe());
        assert!(run.stderr.contains(needle), "{args:?}: no `{needle}`\n{}", run.describe());
    }
    let pool = scene("pool_overhead");
    let run = causticlab(&["reference", "--final", "--scene", &pool, "--out", &out]);
    assert_eq!(run.code, Some(2), "{}", run.describe());
    assert!(run.stderr.contains("pool scene") && run.stderr.contains(&pool), "{}", run.describe());
}

/// Level 0 on lavapipe takes a few seconds: the files, the record and no validation message.
#[test]
fn reference_final_writes_the_final_image_and_its_record_validated() {
    let dir = scratch("reference-final");
    let out = dir.join("ref");
    let s = scene("sphere_on_plane");
    let run = causticlab(&[
        "--validate",
        "reference",
        "--final",
        "--level",
        "0",
        "--scene",
        &s,
        "--out",
        &out.display().to_string(),
    ]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    let img = read_exr(&out.join("final.exr")).expect("final.exr");
    assert_eq!((img.width, img.height), (512, 512));
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("reference.json")).expect("reference.json")).unwrap();
    assert_eq!(record["refinement"]["caustic_map_resolution"], 256);
    assert_eq!(record["photons_per_light"], 1024 * 1024);
    assert!(out.join("final.png").is_file());
    // The reference against itself through compare: no error.
    let f = out.join("final.exr").display().to_string();
    assert_eq!(json(&causticlab(&["compare", "--json", &f, &f]))["flip"]["mean"], 0.0);
}
