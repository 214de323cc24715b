//! Wyman & Dachsbacher's multiple splat sizes as an `hcm` splat option (`splat = interpolated`,
//! Wyman 2008 Fig. 7's third column), validation layer on: what it needs of the other settings,
//! the four layers it splats (radius 2^i times `splat_radius` in layer i), and what it is for,
//! less undersampling noise than constant splats where photons are sparse. Its power and error
//! at the conformance suite's settings are the registry row `hcm-interpolated`'s
//! (`conformance_wyman2008`).

use caustics::compare::compare;
use caustics::image_io::ImageF32;
use caustics::reference::{trace_reference, ReferenceOptions};
use caustics::scene::Scene;
use caustics::techniques::wyman2008::SplatMode;

mod common;
use common::{render_dumps, shipped};

fn scene(technique: &str, splat: SplatMode, photons: u32) -> Scene {
    let mut s = shipped("sphere_on_plane.toml");
    s.caustics.technique = technique.parse().expect("a known name");
    s.caustics.splat = splat;
    s.caustics.photons = photons;
    s.caustics.fresnel = false;
    s.camera.width = 64;
    s.camera.height = 64;
    s
}

/// Interpolated splats are hcm's, on the point splat; each refusal names the key and why.
#[test]
fn interpolated_splats_belong_to_hcms_point_splat() {
    let refused: [(&str, &str, &[&str]); 4] = [
        ("adaptive", "", &["caustics.splat", "interpolated", "hcm", "adaptive"]),
        ("wd-points", "", &["caustics.splat", "interpolated", "wd-points"]),
        ("hcm", "compute", &["caustics.splat", "compute"]),
        ("hcm", "beam-area", &["caustics.varying_radius", "beam-area"]),
    ];
    for (technique, tweak, needles) in refused {
        let mut s = scene(technique, SplatMode::Interpolated, 64);
        match tweak {
            "compute" => s.caustics.splat_path = "compute".parse().expect("a known name"),
            "beam-area" => s.caustics.varying_radius = "beam-area".parse().expect("a known name"),
            _ => {}
        }
        let err = s.caustics.validate_combination("scene.toml", "caustics.").expect_err(technique).to_string();
        for n in needles {
            assert!(err.contains(n), "{technique} {tweak}: `{err}` does not name {n}");
        }
    }
    let s = scene("hcm", SplatMode::Interpolated, 64);
    s.caustics.validate_combination("scene.toml", "caustics.").expect("hcm with interpolated splats");
    assert_eq!(s.caustics.caustic_levels(), 4);
}

/// Texels of `layer` with any photon (channel `photons`: photons per texel).
fn covered(cmap: &ImageF32, layer: &str) -> usize {
    let l = cmap.layers.iter().find(|l| l.name.as_deref() == Some(layer)).unwrap_or_else(|| panic!("no {layer}"));
    let a = l.channels.iter().position(|c| c == "photons").expect("a photons channel");
    l.data.chunks_exact(l.channels.len()).filter(|t| t[a] > 0.0).count()
}

/// Layer i holds the splats at radius 1.5 * 2^i: each wider radius covers more texels, up to
/// four times as many where the photons are sparse (a splat's disc grows fourfold; measured at
/// 64² photons: 11.6k, 30.1k, 69.2k and 136.6k of the 512² texels).
#[test]
fn each_layer_holds_the_splats_at_twice_the_last_ones_radius() {
    let dumps = render_dumps(&scene("hcm", SplatMode::Interpolated, 64), 1, &["caustic_map"]);
    let cmap = &dumps[0].1;
    let counts: Vec<usize> = (0..4).map(|i| covered(cmap, &format!("light0_level{i}"))).collect();
    println!("texels covered per layer: {counts:?}");
    for w in counts.windows(2) {
        assert!(w[1] as f64 > 1.5 * w[0] as f64, "a layer's splats are not wider than the last one's: {counts:?}");
    }
}

/// With sparse photons (64² on the glass sphere: the floor around the focus gets one photon
/// every few texels) constant splats leave a pattern of dots that interpolated splats fill from
/// their wider layers: the error against the exact reference falls, the flux stays. Measured on
/// lavapipe: relative RMSE 0.214 constant, 0.116 interpolated (flux ratio 0.986 and 1.034).
#[test]
fn interpolated_splats_fill_where_constant_splats_leave_dots() {
    let reference_scene = scene("hcm", SplatMode::Fixed, 64);
    let opts = ReferenceOptions { photons: 1_000_000, fresnel: false, ..Default::default() };
    let reference = trace_reference(&reference_scene, &opts).expect("reference").image;
    let error = |splat: SplatMode| {
        let dumps = render_dumps(&scene("hcm", splat, 64), 1, &["receiver"]);
        let (c, _) = compare(&dumps[0].1, &reference).expect("compare");
        println!("{splat}: {c}");
        c
    };
    let (fixed, interpolated) = (error(SplatMode::Fixed), error(SplatMode::Interpolated));
    assert!(
        interpolated.rel_rmse < 0.75 * fixed.rel_rmse,
        "interpolated {} against constant {}",
        interpolated.rel_rmse,
        fixed.rel_rmse
    );
    assert!((interpolated.caustic_flux_ratio - 1.0).abs() < 0.1, "flux ratio {}", interpolated.caustic_flux_ratio);
}
