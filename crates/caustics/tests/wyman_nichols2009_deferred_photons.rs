//! Deferred caustic maps (Wyman & Nichols 2009 Sec. 3.2, Fig. 10; `photon_refraction =
//! deferred`), validation layer on:
//! - with one specular object the deferred photon buffer is the forward one: on
//!   `sphere_on_plane` (fitted photon view) and the bunny room (the papers' 90-degree view) the
//!   same texels hold a photon (none may differ: the geometry buffers' front layer covers the
//!   texels the forward pass rasterizes, `tests/wyman_nichols2009_adaptive.rs`), their landing points agree within
//!   1e-4 m and their power within 1e-4 relative, the back faces are the forward back-face pass's
//!   image, and the caustic maps of `wd-points` and `hcm` (compute traversal) agree within 1e-3
//!   relative L1;
//! - through several refractors (Sec. 3.1.1 applied to photons, Fig. 13): on
//!   `scenes/stacked_spheres.toml`, where every photon that reaches the lower sphere has crossed
//!   the upper one, the receiver map of deferred photons is much closer to the exact CPU
//!   reference (which traces the real spheres) than the forward photon buffer's, which refracts a
//!   photon through the first sphere only: at least halves the relative RMSE, puts the peak
//!   within 10% of the reference's, and the per-refractor buffers are dumped.

use caustics::compare::compare;
use caustics::image_io::ImageF32;
use caustics::reference::{trace_reference, ReferenceOptions};
use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::{PhotonRefraction, PhotonView};
use std::collections::BTreeMap;
use std::path::PathBuf;
use vkcore::{Context, ShaderCompiler};

mod common;
use common::context;

fn scene(name: &str, technique: &str, photons: u32, photon_refraction: PhotonRefraction) -> Scene {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../../scenes/{name}.toml"));
    let mut s = Scene::load(&p).expect("shipped scene");
    s.caustics.technique = technique.parse().expect("a known name");
    s.caustics.photons = photons;
    s.caustics.photon_refraction = photon_refraction;
    s.caustics.caustic_map_resolution = 512;
    if technique == "hcm" {
        s.caustics.path = "compute".parse().expect("a known name");
    }
    if name == "bunny_in_room" {
        s.caustics.photon_view = PhotonView::FixedFov;
    }
    s.camera.width = 64;
    s.camera.height = 64;
    s
}

fn run(ctx: &Context, sh: &ShaderCompiler, s: &Scene, dumps: &[&str]) -> BTreeMap<String, ImageF32> {
    let mut r = Renderer::new(ctx, sh, s, &RendererOptions::default()).expect("renderer");
    r.frame(FrameStep::default()).expect("frame");
    let names: Vec<String> = dumps.iter().map(|d| d.to_string()).collect();
    let out: BTreeMap<String, ImageF32> =
        r.dumps(&names).expect("dumps").into_iter().map(|(d, img)| (d.name.to_string(), img)).collect();
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
    out
}

fn layer<'a>(img: &'a ImageF32, name: &str) -> &'a [f32] {
    &img.layer(Some(name)).unwrap_or_else(|| panic!("no layer {name}")).data
}

/// Relative L1 distance of two images' first layers.
fn relative_l1(a: &ImageF32, b: &ImageF32) -> f64 {
    let (a, b) = (&a.layers[0].data, &b.layers[0].data);
    let diff: f64 = a.iter().zip(b).map(|(x, y)| (*x as f64 - *y as f64).abs()).sum();
    diff / b.iter().map(|y| y.abs() as f64).sum::<f64>().max(1e-30)
}

#[test]
fn deferred_photon_buffer_is_the_forward_one() {
    let (ctx, sh) = context();
    for name in ["sphere_on_plane", "bunny_in_room"] {
        let dumps = ["photon_buffer", "photon_back_faces", "caustic_map"];
        let forward = run(&ctx, &sh, &scene(name, "wd-points", 128, PhotonRefraction::Forward), &dumps);
        let deferred = run(&ctx, &sh, &scene(name, "wd-points", 128, PhotonRefraction::Deferred), &dumps);
        let (f, d) = (&forward["photon_buffer"], &deferred["photon_buffer"]);
        let (fp, dp) = (layer(f, "light0.position"), layer(d, "light0.position"));
        let (fw, dw) = (layer(f, "light0.power"), layer(d, "light0.power"));
        let (mut valid, mut worst_position, mut worst_power) = (0, 0.0f32, 0.0f32);
        for i in 0..(f.width * f.height) as usize {
            let (a, b) = (&fp[i * 4..i * 4 + 4], &dp[i * 4..i * 4 + 4]);
            assert_eq!(a[3] > 0.5, b[3] > 0.5, "{name}: texel {i}: forward valid {}, deferred valid {}", a[3], b[3]);
            // Power is kept for lost photons too: every traced texel has some.
            let (pa, pb) = (&fw[i * 3..i * 3 + 3], &dw[i * 3..i * 3 + 3]);
            assert_eq!(pa[0] > 0.0, pb[0] > 0.0, "{name}: texel {i}: traced forward {pa:?}, deferred {pb:?}");
            for c in 0..3 {
                worst_power = worst_power.max((pa[c] - pb[c]).abs() / pa[c].abs().max(1e-12));
            }
            if a[3] > 0.5 {
                valid += 1;
                worst_position = worst_position.max((0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f32::max));
            }
        }
        println!("{name}: {valid} valid photons, positions within {worst_position:.2e} m, power {worst_power:.2e}");
        assert!(valid > 200, "{name}: {valid} valid photons: a vacuous test");
        assert!(worst_position < 1e-4, "{name}: landing points differ by up to {worst_position} m");
        assert!(worst_power < 1e-4, "{name}: power differs by up to {worst_power} (relative)");
        let back = relative_l1(&deferred["photon_back_faces"], &forward["photon_back_faces"]);
        assert!(back < 1e-6, "{name}: back faces differ: relative L1 {back}");
        for technique in ["wd-points", "hcm"] {
            let maps: Vec<ImageF32> = [PhotonRefraction::Forward, PhotonRefraction::Deferred]
                .map(|r| run(&ctx, &sh, &scene(name, technique, 128, r), &["caustic_map"]).remove("caustic_map"))
                .into_iter()
                .map(|m| m.expect("a caustic map"))
                .collect();
            let l1 = relative_l1(&maps[1], &maps[0]);
            println!("{name} {technique}: caustic maps differ by {l1:.2e} (relative L1)");
            assert!(maps[0].layers[0].data.iter().any(|&v| v > 0.0), "{name} {technique}: an empty caustic map");
            assert!(l1 < 1e-3, "{name} {technique}: deferred and forward caustic maps differ by {l1} (relative L1)");
        }
    }
}

#[test]
fn photons_through_two_refractors_approach_the_reference() {
    let (ctx, sh) = context();
    let reference_scene = scene("stacked_spheres", "none", 256, PhotonRefraction::Forward);
    // Fresnel on: without it the reference stops refracting after two interfaces, as the
    // image-space model of one refractor does.
    let opts = ReferenceOptions { photons: 2_000_000, fresnel: true, ..Default::default() };
    let reference = trace_reference(&reference_scene, &opts).expect("reference").image;
    let mut errors = vec![];
    for r in [PhotonRefraction::Forward, PhotonRefraction::Deferred] {
        let s = scene("stacked_spheres", "wd-points", 256, r);
        let mut dumps = vec!["receiver"];
        if r == PhotonRefraction::Deferred {
            dumps.push("photon_geometry_buffers");
        }
        let out = run(&ctx, &sh, &s, &dumps);
        let (c, _) = compare(&out["receiver"], &reference).expect("compare");
        println!("stacked_spheres {r}: {c:?}");
        if r == PhotonRefraction::Deferred {
            let g = &out["photon_geometry_buffers"];
            // Each sphere's own buffers: the lower one is seen whole, though hidden behind the
            // upper one in the buffers of both.
            let covered = |l: &str| layer(g, l).chunks_exact(4).filter(|t| t[3] > 0.5).count();
            let (all, upper, lower) = (
                covered("light0.front.normal"),
                covered("light0.refractor0.front.normal"),
                covered("light0.refractor1.front.normal"),
            );
            assert!(upper > 100 && lower > 100, "refractor buffers cover {upper} and {lower} texels");
            assert_eq!(all, upper, "the lower sphere lies in the upper one's shadow: {all} vs {upper} texels");
        }
        errors.push(c);
    }
    let (forward, deferred) = (&errors[0], &errors[1]);
    assert!(
        deferred.rel_rmse < 0.5 * forward.rel_rmse,
        "deferred photons' relative RMSE {} is not under half the forward one's {}",
        deferred.rel_rmse,
        forward.rel_rmse
    );
    assert!(deferred.rel_rmse < 0.3, "deferred photons: relative RMSE {}", deferred.rel_rmse);
    assert!((0.9..=1.1).contains(&deferred.peak_ratio), "deferred photons: peak ratio {}", deferred.peak_ratio);
    assert!(
        forward.peak_ratio < 0.5,
        "forward photons: peak ratio {} (the test scene lost its point)",
        forward.peak_ratio
    );
}
