//! Wyman & Davis 2006 Sec. 3.2.1 culls a caustic quad that stretches between two surfaces (its
//! polygon would hang in the air between them) and keeps one on a single surface. `quads.vert`
//! tests a block's centre against the light's receiver-positions map; here the same rule is
//! evaluated on the CPU against the exact geometry of the scene, from the photons the photon
//! buffer dump holds, and the power the light-space quads put into the caustic map must be
//! that of the blocks the rule keeps, validation layer on.
//!
//! The scene makes the rule matter: the glass sphere of `sphere_on_plane` raised to y = 2.5, so
//! that its photons cross the focus and spread over about 2 m of floor, falling on a comb of
//! diffuse strips (0.1 m wide, 0.3 m tall, 0.2 m apart): a block with photons on a strip's top
//! and on the floor beside it spans two surfaces; so does one with photons on a strip's wall,
//! which the light does not see. Without the culling the caustic map would hold the power of
//! every block whose four photons landed (checked to be over 10% more).

use caustics::image_io::ImageF32;
use caustics::scene::Scene;
use caustics::techniques::wyman_davis2006::settings::{QuadLighting, Space};
use caustics::techniques::Technique;
use glam::DVec3;
use std::path::PathBuf;

mod common;
use common::render_dumps;

const STRIPS: usize = 11;
const STRIP_WIDTH: f64 = 0.1;
const STRIP_HEIGHT: f64 = 0.3;
const STRIP_PITCH: f64 = 0.2;
const STRIP_LENGTH: f64 = 3.0;

fn strip_centre(k: usize) -> f64 {
    -1.0 + STRIP_PITCH * k as f64
}

/// `sphere_on_plane` with the sphere raised and the comb of strips on the floor, as a scene
/// file in the temporary folder.
fn scene() -> Scene {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let mut text = std::fs::read_to_string(root.join("sphere_on_plane.toml")).expect("shipped scene");
    assert!(text.contains("translate = [0.0, 1.0, 0.0]"), "the sphere's placement changed");
    text = text.replace("translate = [0.0, 1.0, 0.0]", "translate = [0.0, 2.5, 0.0]");
    for k in 0..STRIPS {
        text += &format!(
            "\n[[objects]]\nshape = \"box\"\nsize = [{STRIP_WIDTH}, {STRIP_HEIGHT}, {STRIP_LENGTH}]\n\
             translate = [{}, {}, 0.0]\nmaterial = \"floor\"\n",
            strip_centre(k),
            0.5 * STRIP_HEIGHT
        );
    }
    let dir = caustics::scratch::ScratchDir::new("causticlab", "culling");
    let path = dir.join("comb.toml");
    std::fs::write(&path, text).expect("write the scene");
    let mut s = Scene::load(&path).expect("the comb scene");
    s.caustics.technique = Technique::WdQuads;
    s.caustics.space = Space::Light;
    s.caustics.quad_lighting = QuadLighting::Eq4;
    s.caustics.photons = 64;
    s.caustics.fresnel = false;
    s.caustics.caustic_map_resolution = 1024;
    s.camera.width = 64;
    s.camera.height = 64;
    s
}

/// Distance from `light` along its ray through `p` to the first diffuse surface (the floor or
/// a strip), the exact counterpart of the receiver-positions map.
fn first_surface(light: DVec3, p: DVec3) -> f64 {
    let d = (p - light).normalize();
    let mut t = if d.y < 0.0 { -light.y / d.y } else { f64::INFINITY };
    for k in 0..STRIPS {
        let lo = DVec3::new(strip_centre(k) - 0.5 * STRIP_WIDTH, 0.0, -0.5 * STRIP_LENGTH);
        let hi = DVec3::new(strip_centre(k) + 0.5 * STRIP_WIDTH, STRIP_HEIGHT, 0.5 * STRIP_LENGTH);
        let (mut near, mut far) = (0.0f64, f64::INFINITY);
        for a in 0..3 {
            let (t0, t1) = ((lo[a] - light[a]) / d[a], (hi[a] - light[a]) / d[a]);
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1));
        }
        if near <= far {
            t = t.min(near);
        }
    }
    t
}

/// (power of the blocks the rule keeps, power of every block whose four photons landed), W
/// (mean of R, G, B). A block's power is the mean of its four photons' (each photon is shared
/// by four blocks; `quads.vert` weighs each by its texel's solid angle, which varies by under
/// 0.1% between neighbours here).
fn predicted(scene: &Scene, photons: &ImageF32) -> (f64, f64) {
    let light = scene.lights[0].position.as_dvec3();
    let pos = photons.layer(Some("light0.position")).expect("positions");
    let pow = photons.layer(Some("light0.power")).expect("power");
    let (np, nw, n) = (pos.channels.len(), pow.channels.len(), photons.width as usize);
    let photon = |i: usize, j: usize| {
        let k = j * n + i;
        let p = &pos.data[k * np..k * np + 4];
        let w = &pow.data[k * nw..k * nw + 3];
        (p[3] > 0.5, DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64), (w[0] + w[1] + w[2]) as f64 / 3.0)
    };
    let (mut kept, mut all) = (0.0, 0.0);
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let q = [photon(i, j), photon(i + 1, j), photon(i + 1, j + 1), photon(i, j + 1)];
            if !q.iter().all(|c| c.0) {
                continue;
            }
            let power = 0.25 * q.iter().map(|c| c.2).sum::<f64>();
            all += power;
            let centre = 0.25 * q.iter().map(|c| c.1).sum::<DVec3>();
            let span = q[2].1.distance(q[0].1).max(q[3].1.distance(q[1].1));
            let d_centre = centre.distance(light);
            // Sec. 3.2.1's test as quads.vert states it, against the exact first surface.
            if (first_surface(light, centre) - d_centre).abs() <= 0.05 * span + 0.02 * d_centre {
                kept += power;
            }
        }
    }
    (kept, all)
}

fn map_power(cmap: &ImageF32) -> f64 {
    let l = cmap.layer(Some("light0")).expect("light 0's caustic map");
    let nc = l.channels.len();
    l.data.chunks_exact(nc).map(|p| (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0).sum()
}

#[test]
fn a_quad_spanning_two_surfaces_is_culled_and_one_on_a_single_surface_is_not() {
    let scene = scene();
    let dumps = render_dumps(&scene, 1, &["photon_buffer", "caustic_map"]);
    let (kept, all) = predicted(&scene, &dumps[0].1);
    let held = map_power(&dumps[1].1);
    println!("caustic map {held:.5} W; blocks the rule keeps {kept:.5} W; every landed block {all:.5} W");
    assert!(all > 1.1 * kept, "the scene should make the culling matter: {all} vs {kept}");
    // The map's receiver positions are coarser than the exact geometry: a block whose centre is
    // within a texel of a strip's edge may go either way.
    assert!((held / kept - 1.0).abs() < 0.03, "caustic map {held} W, the rule keeps {kept} W (all {all} W)");
}
