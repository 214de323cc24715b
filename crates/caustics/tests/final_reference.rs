//! The reference final image (`caustics::final_reference`, `causticlab reference --final`) on
//! `sphere_on_plane` at 96² pixels and a small base (a 64² caustic map, 128² photons at level 0),
//! validation layer on:
//! - it converges: each level changes the image by less than the level before did (HDR-FLIP of
//!   level L against L + 1), and the last change is smaller than shah's FLIP against it;
//! - `compare`'s report on final images: an image against itself is 0, the image moved by two
//!   pixels (its caustic with it) is further from it; the FLIP map is the image's size, at the
//!   default pixels per degree;
//! - frames are traced with the seeds in turn and averaged.
//!
//! The full-size check (levels 0-3, 512², shah, wd-points and hcm) is
//! `scripts/final_reference.sh` (docs/flip.md).

// `!(x < y)` fails a NaN, where `x >= y` would pass it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use caustics::compare::{report, Region};
use caustics::final_reference::{render_final, Base, Refinement};
use caustics::image_io::{ImageF32, Layer};
use caustics::render::{self, RenderRequest};
use caustics::scene::Scene;

mod common;
use common::{context, shipped};

const BASE: Base = Base { caustic_map_resolution: 64, photons: 128 };

fn scene() -> Scene {
    let mut s = shipped("sphere_on_plane.toml");
    s.camera.width = 96;
    s.camera.height = 96;
    s
}

fn flip(a: &ImageF32, b: &ImageF32) -> f64 {
    let r = report(a, "a", b, "b", Region::Caustic).expect("compare");
    r.flip.expect("FLIP").mean()
}

/// The image moved right by `dx` pixels (the left column repeated).
fn shifted(img: &ImageF32, dx: usize) -> ImageF32 {
    let (w, l) = (img.width as usize, &img.layers[0]);
    let n = l.channels.len();
    let data =
        l.data.chunks_exact(w * n).flat_map(|row| (0..w).flat_map(move |x| &row[x.saturating_sub(dx) * n..][..n]));
    let channels: Vec<&str> = l.channels.iter().map(String::as_str).collect();
    ImageF32 { layers: vec![Layer::new(None, &channels, data.copied().collect())], ..img.clone() }
}

#[test]
fn the_reference_final_image_converges_below_a_techniques_flip() {
    let (ctx, sh) = context();
    let s = scene();
    let levels: Vec<ImageF32> = (0..3)
        .map(|l| {
            let r = Refinement::at(l, BASE).expect("a level");
            render_final(&ctx, &sh, &s, &r, 1, |_| {}).expect("the reference final image")
        })
        .collect();
    let mut shah = s.clone();
    shah.caustics.technique = "shah".parse().expect("a known name");
    shah.caustics.photons = 128;
    shah.caustics.caustic_map_resolution = 256;
    let req = RenderRequest { frames: 1, ..Default::default() };
    let shah = render::render(&ctx, &sh, &shah, &req).expect("shah").final_image;
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));

    let (step0, step1) = (flip(&levels[0], &levels[1]), flip(&levels[1], &levels[2]));
    let technique = flip(&shah, &levels[2]);
    println!("HDR-FLIP: L0 vs L1 {step0:.5}, L1 vs L2 {step1:.5}, shah vs L2 {technique:.5}");
    assert!(step1 > 0.0, "two levels render the same image: the refinement changes nothing");
    assert!(step1 < step0, "refining changed the image more at L1 -> L2 ({step1}) than at L0 -> L1 ({step0})");
    assert!(
        step1 < technique,
        "the last refinement ({step1}) changes the image by more than shah's FLIP ({technique})"
    );

    let reference = &levels[2];
    let itself = report(reference, "a", reference, "b", Region::Caustic).expect("compare");
    let f = itself.flip.expect("FLIP");
    assert_eq!(f.mean(), 0.0);
    assert_eq!((f.map.width, f.map.height, f.ppd()), (96, 96, caustics::flip::default_ppd()));
    let moved = flip(&shifted(reference, 2), reference);
    assert!(moved > 0.0, "the image moved by two pixels reads as the reference");
}

/// Frames are traced with seeds `seed`, `seed + 1`, ... and averaged: two frames give the mean of
/// the two one-frame renders with those seeds, which differ.
#[test]
fn the_frames_are_the_seeds_in_turn_averaged() {
    let (ctx, sh) = context();
    let s = scene();
    let two = Refinement { frames: 2, ..Refinement::at(0, BASE).expect("a level") };
    let averaged = render_final(&ctx, &sh, &s, &two, 7, |_| {}).expect("two frames");
    let one = |frame| {
        let req = RenderRequest { frames: 1, ..Default::default() };
        render::render(&ctx, &sh, &two.scene(&s, 7, frame).expect("settings"), &req).expect("a frame").final_image
    };
    let (a, b) = (one(0), one(1));
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
    assert!(a.layers[0].data != b.layers[0].data, "seeds 7 and 8 traced the same photons");
    let worst = averaged.layers[0]
        .data
        .iter()
        .zip(a.layers[0].data.iter().zip(&b.layers[0].data))
        .map(|(m, (x, y))| (m - 0.5 * (x + y)).abs() / (1.0 + m.abs()))
        .fold(0.0f32, f32::max);
    assert!(worst < 1e-6, "the two-frame image is not the mean of its frames: {worst}");
}
