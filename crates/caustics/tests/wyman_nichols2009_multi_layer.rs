//! Adaptive caustic maps through several refractors (Wyman & Nichols 2009 Sec. 3.1.1 applied to
//! the photons of Sec. 3.2, Fig. 13), validation layer on, on `scenes/stacked_spheres.toml`,
//! where every photon that reaches the lower glass sphere has crossed the upper one:
//! - with geometry buffers as fine as the photon grid, max-traversal's photons are the deferred
//!   dense photon buffer's (`photon_refraction = deferred`, which follows photons through every
//!   object): the same texels, landing points within 1e-4 m and power within 1e-4 relative, on
//!   both paths; and many of them land elsewhere than the forward photon buffer's, which
//!   refracts through the first sphere only (so the layers are what the test sees);
//! - each sphere's own buffers are in the `adaptive_geometry` dump;
//! - max-error's receiver map is close to the exact CPU reference (which traces the real
//!   spheres): relative RMSE under 0.3, peak within 10%, where the single-layer forward photon
//!   buffer's peak is under half the reference's.

use caustics::compare::compare;
use caustics::image_io::ImageF32;
use caustics::reference::{trace_reference, ReferenceOptions};
use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::wyman_nichols2009::adaptive::AdaptivePhoton;
use caustics::techniques::PhotonRefraction;
use std::collections::BTreeMap;
use std::path::PathBuf;
use vkcore::{Context, ShaderCompiler};

mod common;
use common::context;

/// The stacked spheres with `technique` at `photons`² and a caustic map of 4 × photons (the
/// default `gbuffer_scale`, 0.25, then gives geometry buffers as fine as the photon grid).
fn scene(technique: &str, photons: u32, refraction: PhotonRefraction) -> Scene {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/stacked_spheres.toml");
    let mut s = Scene::load(&p).expect("shipped scene");
    s.caustics.technique = technique.parse().expect("a known name");
    s.caustics.photons = photons;
    s.caustics.photon_refraction = refraction;
    s.caustics.caustic_map_resolution = 4 * photons;
    s.camera.width = 64;
    s.camera.height = 64;
    s
}

/// The render's dumps and, for `adaptive`, its output photons.
fn run(
    ctx: &Context,
    sh: &ShaderCompiler,
    s: &Scene,
    dumps: &[&str],
) -> (BTreeMap<String, ImageF32>, Vec<AdaptivePhoton>) {
    let mut r = Renderer::new(ctx, sh, s, &RendererOptions::default()).expect("renderer");
    r.frame(FrameStep::default()).expect("frame");
    let names: Vec<String> = dumps.iter().map(|d| d.to_string()).collect();
    let out = r.dumps(&names).expect("dumps").into_iter().map(|(d, img)| (d.name.to_string(), img)).collect();
    let photons =
        r.caustics().and_then(|c| c.adaptive()).map(|a| a.read_photons(ctx).expect("photons")).unwrap_or_default();
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
    (out, photons)
}

fn layer<'a>(img: &'a ImageF32, name: &str) -> &'a [f32] {
    &img.layer(Some(name)).unwrap_or_else(|| panic!("no layer {name}")).data
}

/// A photon buffer's valid photons: texel -> (landing point, power).
fn valid_photons(pb: &ImageF32) -> BTreeMap<(u32, u32), ([f32; 3], [f32; 3])> {
    let (pos, pow) = (layer(pb, "light0.position"), layer(pb, "light0.power"));
    (0..pb.width * pb.height)
        .filter(|&i| pos[i as usize * 4 + 3] > 0.5)
        .map(|i| {
            let (p, w) = (&pos[i as usize * 4..][..3], &pow[i as usize * 3..][..3]);
            ((i % pb.width, i / pb.width), ([p[0], p[1], p[2]], [w[0], w[1], w[2]]))
        })
        .collect()
}

#[test]
fn max_traversal_photons_cross_every_refractor_as_deferred_photons_do() {
    let (ctx, sh) = context();
    let n = 256;
    let mut s = scene("wd-points", n, PhotonRefraction::Deferred);
    s.receiver_map = None;
    let deferred = valid_photons(&run(&ctx, &sh, &s, &["photon_buffer"]).0["photon_buffer"]);
    s.caustics.photon_refraction = PhotonRefraction::Forward;
    let forward = valid_photons(&run(&ctx, &sh, &s, &["photon_buffer"]).0["photon_buffer"]);
    // The layers matter: many photons land elsewhere when the lower sphere refracts them.
    let moved = deferred
        .iter()
        .filter(|(t, (p, _))| forward.get(t).is_none_or(|(q, _)| (0..3).any(|i| (p[i] - q[i]).abs() > 1e-2)))
        .count();
    assert!(moved > 1000, "{moved} of {} photons moved by the lower sphere: a vacuous test", deferred.len());
    for path in ["compute", "xfb"] {
        let mut a = scene("adaptive", n, PhotonRefraction::Forward);
        a.receiver_map = None;
        a.caustics.path = path.parse().expect("a known name");
        let (dumps, photons) = run(&ctx, &sh, &a, &["adaptive_geometry"]);
        // Each sphere's own buffers: the lower one seen whole, though it lies in the upper
        // one's shadow in the buffers of both.
        let g = &dumps["adaptive_geometry"];
        let covered = |l: &str| layer(g, l).chunks_exact(4).filter(|t| t[3] > 0.5).count();
        let (all, upper, lower) = (
            covered("light0.front.normal"),
            covered("light0.refractor0.front.normal"),
            covered("light0.refractor1.front.normal"),
        );
        assert!(upper > 100 && lower > 100, "{path}: refractor buffers cover {upper} and {lower} texels");
        assert_eq!(all, upper, "{path}: all objects' buffers cover {all} texels, the upper sphere's {upper}");
        let mut got = BTreeMap::new();
        for ph in &photons {
            let [x, y, _] = ph.cell();
            assert!(got.insert((x, y), ph).is_none(), "{path}: photon ({x}, {y}) twice");
        }
        let only_adaptive: Vec<_> = got.keys().filter(|t| !deferred.contains_key(t)).take(8).collect();
        let only_deferred: Vec<_> = deferred.keys().filter(|t| !got.contains_key(t)).take(8).collect();
        assert!(
            only_adaptive.is_empty() && only_deferred.is_empty(),
            "{path}: {} adaptive vs {} deferred photons; only adaptive: {only_adaptive:?}; only deferred: \
             {only_deferred:?}",
            got.len(),
            deferred.len()
        );
        for (t, (pos, power)) in &deferred {
            let ph = got[t];
            let dp = (0..3).map(|i| (ph.position[i] - pos[i]).abs()).fold(0.0f32, f32::max);
            let dw = (0..3).map(|i| (ph.power[i] - power[i]).abs() / power[i].max(1e-30)).fold(0.0f32, f32::max);
            assert!(
                dp < 1e-4 && dw < 1e-4,
                "{path}: photon {t:?} at {:?} {:?}, deferred {pos:?} {power:?}",
                ph.position,
                ph.power
            );
        }
    }
}

#[test]
fn max_error_through_two_refractors_approaches_the_reference() {
    let (ctx, sh) = context();
    let reference_scene = scene("none", 256, PhotonRefraction::Forward);
    // Fresnel on, as in tests/wyman_nichols2009_deferred_photons.rs: the image-space model refracts at all four
    // interfaces with Fresnel transmittance.
    let opts = ReferenceOptions { photons: 2_000_000, fresnel: true, ..Default::default() };
    let reference = trace_reference(&reference_scene, &opts).expect("reference").image;
    // 1024² equivalent photons: max-error tests convergence from the 512² level on. Geometry
    // buffers at the paper's quarter of the 512² caustic map.
    let mut adaptive = scene("adaptive", 1024, PhotonRefraction::Forward);
    adaptive.caustics.metric = "max-error".parse().expect("a known name");
    adaptive.caustics.caustic_map_resolution = 512;
    let mut forward = scene("wd-points", 256, PhotonRefraction::Forward);
    forward.caustics.caustic_map_resolution = 512;
    let mut errors = vec![];
    for s in [&forward, &adaptive] {
        let (out, _) = run(&ctx, &sh, s, &["receiver"]);
        let (c, _) = compare(&out["receiver"], &reference).expect("compare");
        println!("stacked_spheres {}: {c:?}", s.caustics.technique);
        errors.push(c);
    }
    let (forward, adaptive) = (&errors[0], &errors[1]);
    assert!(
        forward.peak_ratio < 0.5,
        "forward photons: peak ratio {} (the test scene lost its point)",
        forward.peak_ratio
    );
    assert!(adaptive.rel_rmse < 0.3, "adaptive: relative RMSE {}", adaptive.rel_rmse);
    assert!((0.9..=1.1).contains(&adaptive.peak_ratio), "adaptive: peak ratio {}", adaptive.peak_ratio);
}

/// More specular objects than the layered trace holds: a clear error naming the limit, not a
/// silently single-layer render.
#[test]
fn more_refractors_than_the_trace_follows_are_refused() {
    let (ctx, sh) = context();
    let mut s = scene("adaptive", 256, PhotonRefraction::Forward);
    let sphere = s.objects.iter().find(|o| o.name == "upper sphere").expect("the upper sphere").clone();
    for i in 0..3 {
        let mut o = sphere.clone();
        o.name = format!("extra sphere {i}");
        s.objects.push(o);
    }
    let err = Renderer::new(&ctx, &sh, &s, &RendererOptions::default()).err().expect("refused").to_string();
    assert!(err.contains("5 specular objects") && err.contains("at most 4"), "{err}");
}
