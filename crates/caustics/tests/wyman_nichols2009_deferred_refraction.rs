//! Deferred refraction (Wyman & Nichols 2009 Sec. 3.1) against today's forward image-space
//! refraction (Wyman 2005), and multi-layer deferred refraction (Sec. 3.1.1) against
//! single-refractor renders. Validation layer on.
//!
//! Both paths rasterize the same triangles and run the same refraction code
//! (`eye/image_space_refraction.glsl`); they differ only in where the front face is shaded (its
//! fragment, or the geometry buffer read back in a full-screen pass, which reconstructs the point
//! from its distance along the pixel's eye ray) and in who decides a face's facing (the
//! rasterizer's culling, or the geometry shader). The reconstructed entry point differs from
//! the interpolated one by float rounding, and the background search (nearest texels, 8 steps)
//! turns that into another texel at a few pixels: with the forward shader made to reconstruct
//! its point the same way, the images agree to 3e-9 (spheres) and 3e-8 (bunny) of the mean
//! radiance, with no pixel over 1% away from silhouettes. As they are, at 200 x 150: mean
//! |difference| 2e-6 (spheres) and 1e-3 (bunny) of the mean radiance, and 2-6 (spheres) and
//! 128 (bunny, 0.44%) of about 29,500 pixels away from silhouettes differ by more than 1%.

// `!(error <= bound)` fails a NaN, where `error > bound` would pass it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use caustics::image_io::ImageF32;
use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::Refraction;
use std::path::PathBuf;
use vkcore::{Context, ShaderCompiler};

mod common;
use common::context;

fn load(name: &str, width: u32, height: u32) -> Scene {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../../scenes/{name}.toml"));
    let mut s = Scene::load(&p).unwrap_or_else(|e| panic!("{name}: {e:#}"));
    s.camera.width = width;
    s.camera.height = height;
    s.render.shadow_map_resolution = 256;
    s.receiver_map = None;
    s
}

/// The final image and the named dumps of `scene` rendered with `refraction`.
fn render(ctx: &Context, sh: &ShaderCompiler, scene: &Scene, refraction: Refraction, dumps: &[&str]) -> Vec<ImageF32> {
    let mut s = scene.clone();
    s.caustics.refraction = refraction;
    let mut r = Renderer::new(ctx, sh, &s, &RendererOptions::default()).expect("renderer");
    r.frame(FrameStep::default()).expect("frame");
    let names: Vec<String> = dumps.iter().map(|d| d.to_string()).collect();
    let mut out = vec![r.final_image().expect("final image")];
    out.extend(r.dumps(&names).expect("dumps").into_iter().map(|(_, img)| img));
    assert_eq!(out.len(), dumps.len() + 1, "{refraction}: dumps {dumps:?}");
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "{refraction}: validation messages:\n{}", log.messages().join("\n"));
    out
}

/// Channel `c` of every pixel of the layer called `layer`.
fn channel(img: &ImageF32, layer: Option<&str>, c: &str) -> Vec<f32> {
    let l = img.layer(layer).unwrap_or_else(|| panic!("no layer {layer:?}"));
    let i = l.channels.iter().position(|n| n == c).unwrap_or_else(|| panic!("{layer:?} has no {c}"));
    l.data.chunks_exact(l.channels.len()).map(|px| px[i]).collect()
}

/// Pixels within one pixel (8-neighbourhood) of a change of `covered`: the silhouettes.
fn near_silhouette(covered: &[bool], w: usize, h: usize) -> Vec<bool> {
    (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as i64, (i / w) as i64);
            (-1..=1).any(|dy| {
                (-1..=1).any(|dx| {
                    let (nx, ny) = (x + dx, y + dy);
                    nx >= 0
                        && ny >= 0
                        && nx < w as i64
                        && ny < h as i64
                        && covered[(ny * w as i64 + nx) as usize] != covered[i]
                })
            })
        })
        .collect()
}

/// Per pixel, the largest difference over RGB of two final images.
fn differences(a: &ImageF32, b: &ImageF32) -> Vec<f32> {
    let (a, b) = (&a.layers[0].data, &b.layers[0].data);
    // f32::max passes NaN over: a NaN pixel must fail here, not read as no difference.
    assert!(a.iter().chain(b).all(|v| v.is_finite()), "a final image has a pixel that is not finite");
    a.chunks_exact(3)
        .zip(b.chunks_exact(3))
        .map(|(p, q)| (0..3).map(|c| (p[c] - q[c]).abs()).fold(0.0, f32::max))
        .collect()
}

/// What the paper says ("identical to previous work, modulo antialiasing variations at
/// silhouettes"), bounded: away from silhouettes, the mean absolute difference is below 1e-4
/// of the image's mean radiance and at most 0.1% of the pixels differ by more than 1% of it;
/// and the deferred geometry buffer's back layer is the forward path's back-face buffer.
#[test]
fn deferred_refraction_gives_the_forward_image() {
    let (ctx, sh) = context();
    for name in ["sphere_on_plane", "sphere_oblique", "bunny_in_room"] {
        let scene = load(name, 200, 150);
        let forward = render(&ctx, &sh, &scene, Refraction::Forward, &["refractor_back_faces"]);
        let deferred = render(&ctx, &sh, &scene, Refraction::Deferred, &["refractor_geometry"]);
        let (w, h) = (scene.camera.width as usize, scene.camera.height as usize);

        // The back layer, written by the same pass as the front, is Wyman 2005's back-face buffer.
        let geometry = &deferred[1];
        for c in ["NX", "NY", "NZ", "distance"] {
            let ours = channel(geometry, Some("layer0.back"), c);
            let theirs = channel(&forward[1], None, c);
            let off = ours.iter().zip(&theirs).filter(|(a, b)| !((*a - *b).abs() <= 1e-5)).count();
            assert!(off * 1000 <= w * h, "{name}: back layer {c} differs from the back-face buffer in {off} pixels");
        }
        let front = channel(geometry, Some("layer0.front"), "distance");
        let back = channel(geometry, Some("layer0.back"), "distance");
        let covered: Vec<bool> = front.iter().map(|d| *d > 0.0).collect();
        let refractor_pixels = covered.iter().filter(|c| **c).count();
        assert!(refractor_pixels * 50 > w * h, "{name}: the refractor covers only {refractor_pixels} pixels");
        // A closed refractor (the sphere; the bunny has holes in its base): behind every front
        // face there is a back face.
        let no_back = (0..w * h).filter(|&i| covered[i] && back[i] <= front[i]).count();
        let closed = name.starts_with("sphere");
        assert!(!closed || no_back * 200 <= refractor_pixels, "{name}: {no_back} pixels without a back face behind");

        let mean_radiance = forward[0].layers[0].data.iter().map(|v| *v as f64).sum::<f64>() / (3 * w * h) as f64;
        let silhouette = near_silhouette(&covered, w, h);
        let diff = differences(&deferred[0], &forward[0]);
        let interior: Vec<f32> = (0..w * h).filter(|&i| !silhouette[i]).map(|i| diff[i]).collect();
        let mean = interior.iter().map(|d| *d as f64).sum::<f64>() / interior.len() as f64 / mean_radiance;
        let over = interior.iter().filter(|d| **d as f64 > 0.01 * mean_radiance).count();
        let all_over = diff.iter().filter(|d| **d as f64 > 0.01 * mean_radiance).count();
        println!(
            "{name}: {refractor_pixels} refractor pixels; away from silhouettes mean |diff| {mean:.2e} of the mean \
             radiance, {over} of {} pixels over 1%; with silhouettes {all_over} of {}",
            interior.len(),
            w * h
        );
        assert!(mean < 2e-3, "{name}: mean |deferred - forward| {mean} of the mean radiance");
        assert!(over * 100 <= interior.len(), "{name}: {over} pixels differ by more than 1%");
        assert!(all_over * 100 <= w * h, "{name}: {all_over} pixels differ by more than 1% with silhouettes");
    }
}

/// `sphere_on_plane` with its glass sphere at each of `centres` instead of (0, 1, 0).
fn spheres(centres: &[[f32; 3]]) -> Scene {
    let mut s = load("sphere_on_plane", 200, 150);
    let sphere = s.objects.pop().expect("the sphere");
    assert_eq!(sphere.name, "sphere");
    for (i, c) in centres.iter().enumerate() {
        let mut o = sphere.clone();
        o.name = format!("sphere{i}");
        let offset = glam::Vec3::from(*c) - glam::Vec3::new(0.0, 1.0, 0.0);
        o.mesh.positions.iter_mut().for_each(|p| *p += offset);
        s.objects.push(o);
    }
    s
}

/// Pixels of the front layer of refractor `k` (layer `k` of the back-to-front order).
fn coverage(geometry: &ImageF32, k: usize) -> Vec<bool> {
    channel(geometry, Some(&format!("layer{k}.front")), "distance").iter().map(|d| *d > 0.0).collect()
}

/// Pixels where `a` and `b` differ by more than 1e-6 of the mean radiance, among `pixels`.
fn differing(a: &ImageF32, b: &ImageF32, pixels: &[usize]) -> usize {
    let mean = b.layers[0].data.iter().map(|v| *v as f64).sum::<f64>() / b.layers[0].data.len() as f64;
    let diff = differences(a, b);
    pixels.iter().filter(|&&i| diff[i] as f64 > 1e-6 * mean).count()
}

/// Sec. 3.1.1 with two refractors that do not overlap on screen: over each refractor's pixels
/// the two-layer image is that refractor's single-refractor render. The order is back to
/// front: layer 0 holds the farther sphere, and its result (`refraction_layers`) is the
/// farther sphere's single render.
#[test]
fn multi_layer_refraction_composites_each_refractor_over_the_previous_result() {
    let (ctx, sh) = context();
    let (far, near) = ([-1.3, 1.0, -1.2], [1.2, 1.0, 0.9]);
    let dumps = ["refractor_geometry", "refraction_layers", "background"];
    let both = render(&ctx, &sh, &spheres(&[near, far]), Refraction::Deferred, &dumps);
    let far_alone = render(&ctx, &sh, &spheres(&[far]), Refraction::Deferred, &dumps);
    let near_alone = render(&ctx, &sh, &spheres(&[near]), Refraction::Deferred, &dumps);
    let (w, h) = (200, 150);
    let (far_px, near_px) = (coverage(&both[1], 0), coverage(&both[1], 1));
    assert_eq!(far_px, coverage(&far_alone[1], 0), "layer 0 is the farther sphere");
    assert_eq!(near_px, coverage(&near_alone[1], 0), "layer 1 is the nearer sphere");
    assert!((0..w * h).all(|i| !(far_px[i] && near_px[i])), "the spheres overlap on screen");
    for (name, covered, alone) in [("far", &far_px, &far_alone), ("near", &near_px, &near_alone)] {
        let silhouette = near_silhouette(covered, w, h);
        let pixels: Vec<usize> = (0..w * h).filter(|&i| covered[i] && !silhouette[i]).collect();
        assert!(pixels.len() > 300, "{name}: {} pixels", pixels.len());
        // The spheres see each other's shadow on the floor (a few pixels), not each other.
        let off = differing(&both[0], &alone[0], &pixels);
        println!("{name} sphere: {off} of {} pixels differ from its single-refractor render", pixels.len());
        assert!(off * 50 <= pixels.len(), "{name}: {off} of {} pixels differ", pixels.len());
    }
    // After the first pass (the farther sphere over the background) the image is the farther
    // sphere's single render wherever their backgrounds agree (not in the nearer sphere's
    // shadow, nor where the farther sphere sees that shadow).
    let background = differences(&both[3], &far_alone[3]);
    let same_background: Vec<usize> = (0..w * h).filter(|&i| background[i] == 0.0).collect();
    assert!(same_background.len() * 10 > w * h * 9, "{} pixels", same_background.len());
    let first = ImageF32 { layers: vec![both[2].layers[0].clone()], ..both[2].clone() };
    let off = differing(&first, &far_alone[0], &same_background);
    println!(
        "after the first layer: {off} of {} pixels differ from the farther sphere's render",
        same_background.len()
    );
    assert!(off * 1000 <= same_background.len(), "{off} pixels");
}

/// Sec. 3.1.1: the farther refractor is seen through the nearer one (the nearer one's pass
/// reads the farther one's result as its background), which the single-refractor render of the
/// nearer one cannot show; where the nearer one covers the farther one, the farther one is
/// hidden.
#[test]
fn a_refractor_is_seen_through_a_nearer_one() {
    let (ctx, sh) = context();
    let (far, near) = ([0.2, 0.5, -1.5], [0.0, 1.4, 0.8]);
    let both = render(&ctx, &sh, &spheres(&[far, near]), Refraction::Deferred, &["refractor_geometry"]);
    let near_alone = render(&ctx, &sh, &spheres(&[near]), Refraction::Deferred, &[]);
    let (far_px, near_px) = (coverage(&both[1], 0), coverage(&both[1], 1));
    let overlap = (0..200 * 150).filter(|&i| far_px[i] && near_px[i]).count();
    assert!(overlap > 300, "{overlap} overlapping pixels");
    // Pixels of the nearer sphere: where their refracted rays meet the farther sphere's image,
    // they show it.
    let near_pixels: Vec<usize> = (0..200 * 150).filter(|&i| near_px[i]).collect();
    let changed = differing(&both[0], &near_alone[0], &near_pixels);
    println!("{changed} of {} pixels of the nearer sphere show the farther one ({overlap} overlap)", near_pixels.len());
    assert!(changed >= 100, "{changed} of {} pixels changed", near_pixels.len());
    // The farther sphere's own pixels that the nearer one covers are the nearer one's.
    let hidden: Vec<usize> = (0..200 * 150).filter(|&i| far_px[i] && near_px[i]).collect();
    let first = render(&ctx, &sh, &spheres(&[far]), Refraction::Deferred, &[]);
    assert!(differing(&both[0], &first[0], &hidden) * 10 > hidden.len() * 9, "the farther sphere shows through");
}
