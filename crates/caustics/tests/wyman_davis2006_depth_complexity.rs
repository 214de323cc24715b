//! The caustic quads' depth complexity (Wyman & Davis 2006 Fig. 6): the alpha of their target
//! counts every fragment they rasterize (`shaders_glsl/wyman_davis2006/quads.frag`).
//!
//! What geometry predicts, independently of that shader: the quads are the cells of the photon
//! grid carried onto the receivers, a mesh whose shared edges Vulkan rasterizes once (a pixel
//! centre on an edge belongs to one triangle), so where the mapping from the light's grid to
//! the floor does not fold, every covered pixel gets exactly one fragment; where the refracted
//! beams cross (a caustic's fold) the mesh overlaps itself and pixels get more.

use caustics::image_io::ImageF32;
use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::techniques::wyman_davis2006::settings::{QuadDraw, Space};
use caustics::techniques::Technique;
use std::collections::BTreeMap;

mod common;
use common::{context, shipped};

/// Pixels by their fragment count (channel 3 of every layer of the quads' target) after one
/// frame of `wd-quads` as polygons on the sphere.
fn histogram(space: Space, photons: u32) -> BTreeMap<u32, usize> {
    let (ctx, sh) = context();
    let mut scene = shipped("sphere_on_plane.toml");
    scene.caustics.technique = Technique::WdQuads;
    scene.caustics.space = space;
    scene.caustics.quad_draw = QuadDraw::Polygons;
    scene.caustics.photons = photons;
    scene.caustics.caustic_map_resolution = 256;
    scene.camera.width = 96;
    scene.camera.height = 96;
    let mut r = Renderer::new(&ctx, &sh, &scene, &RendererOptions::default()).expect("renderer");
    r.frame(FrameStep::default()).expect("frame");
    let dump = if space == Space::Eye { "eye_caustic" } else { "caustic_map" };
    let img: ImageF32 = r.dump(dump).expect("dump").expect("the quads' target");
    let mut hist = BTreeMap::new();
    for c in img.layers.iter().flat_map(|l| l.data.chunks_exact(4).map(|p| p[3])) {
        assert!(c >= 0.0 && c.fract() == 0.0, "a fragment count of {c}");
        *hist.entry(c as u32).or_insert(0) += 1;
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
    println!("{space:?}, {photons}² photons: pixels by fragment count {hist:?}");
    hist
}

fn covered(hist: &BTreeMap<u32, usize>) -> usize {
    hist.iter().filter(|(&c, _)| c > 0).map(|(_, n)| n).sum()
}

#[test]
fn unfolded_quads_tile_the_floor_once() {
    // 64² photons through the sphere: most of the beam's cells land unfolded.
    for space in [Space::Eye, Space::Light] {
        let hist = histogram(space, 64);
        let (all, once) = (covered(&hist), hist.get(&1).copied().unwrap_or(0));
        assert!(all > 500, "{space:?}: only {all} pixels covered: the test would be vacuous");
        assert!(once as f64 >= 0.9 * all as f64, "{space:?}: {once} of {all} covered pixels got one fragment");
    }
}

#[test]
fn the_caustics_fold_overlaps_the_quads() {
    // Beyond the sphere's focus the beams cross: some pixels get two fragments or more, a
    // minority of those the quads cover.
    let hist = histogram(Space::Light, 256);
    let all = covered(&hist);
    let folded: usize = hist.iter().filter(|(&c, _)| c >= 2).map(|(_, n)| n).sum();
    assert!(folded > 0, "no pixel got two fragments: {hist:?}");
    assert!(folded < all / 2, "{folded} of {all} covered pixels overlap: {hist:?}");
}
