//! Converging photons (Wyman 2008 Sec. 3.2) against a CPU model of the traversal, validation
//! layer on. The CPU model reads the photon buffer the GPU rendered, projects every valid photon
//! into the caustic map in f64, builds the quadtree over the padded buffer, and traverses it
//! from the 16² level as the paper does: a node tested for convergence whose photons (two or
//! more) all land in one caustic-map texel becomes one cluster; other nodes go on to their
//! children, down to single photons. Every photon is covered by exactly one entry of the final
//! list; the test checks, photon by photon, that the GPU's entry is the CPU's on both traversal
//! paths and both clustering modes. Where a photon lies within 1e-3 texel of a texel edge, float
//! rounding may decide either way: the nodes holding one are left out, and must be few.

use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::uniforms::caustic_uniforms;
use caustics::techniques::wyman2008::{levels, TOP_SIDE};
use glam::{DMat4, DVec4, Mat4};
use std::collections::HashMap;
use std::path::PathBuf;

mod common;
use common::context;

/// A texel edge closer than this (texels) makes a photon's texel uncertain.
const EDGE: f64 = 1e-3;

struct Photon {
    /// The caustic-map texels the GPU may put it in (more than one within EDGE of a texel edge),
    /// those on the map only: none off the map or behind the light.
    texels: Vec<(i64, i64)>,
    /// One texel (or none) for sure.
    exact: bool,
}

/// Valid photons of the light's photon buffer, by photon-buffer texel.
fn photons(scene: &Scene, position: &[f32], n: u32) -> HashMap<(u32, u32), Photon> {
    let u = caustic_uniforms(scene, &scene.caustics).expect("uniforms");
    let light = &u.lights[0];
    let vp = Mat4::from_cols_array(&light.caustic_view_proj).as_dmat4();
    let m = light.caustic_plane[1] as f64;
    let mut out = HashMap::new();
    for y in 0..n {
        for x in 0..n {
            let p = &position[(y * n + x) as usize * 4..][..4];
            if p[3] < 0.5 {
                continue;
            }
            out.insert((x, y), project(vp, m, [p[0] as f64, p[1] as f64, p[2] as f64]));
        }
    }
    out
}

fn project(vp: DMat4, m: f64, p: [f64; 3]) -> Photon {
    let clip = vp * DVec4::new(p[0], p[1], p[2], 1.0);
    if clip.w <= 0.0 {
        return Photon { texels: vec![], exact: true };
    }
    let t = [(clip.x / clip.w * 0.5 + 0.5) * m, (clip.y / clip.w * 0.5 + 0.5) * m];
    // Per axis, the texel and, near an edge, the one across it.
    let options = |v: f64| -> Vec<i64> {
        let mut o = vec![v.floor() as i64];
        if (v - v.round()).abs() < EDGE {
            o.push(if v.round() > v { v.floor() as i64 + 1 } else { v.floor() as i64 - 1 });
        }
        o
    };
    let (xs, ys) = (options(t[0]), options(t[1]));
    let exact = xs.len() == 1 && ys.len() == 1;
    let on_map = |i: i64| (0..m as i64).contains(&i);
    let texels = xs.iter().flat_map(|&x| ys.iter().map(move |&y| (x, y))).filter(|&(x, y)| on_map(x) && on_map(y));
    Photon { texels: texels.collect(), exact }
}

/// Whether the photons may all land in one texel, and whether they surely do.
fn convergence(members: &[&Photon]) -> (bool, bool) {
    let mut common: Vec<(i64, i64)> = members[0].texels.clone();
    for p in &members[1..] {
        common.retain(|t| p.texels.contains(t));
    }
    let sure = !common.is_empty() && members.iter().all(|p| p.exact);
    (!common.is_empty(), sure)
}

/// The entry covering each photon after the CPU traversal: (x, y, level, final); None for a
/// photon under a node whose convergence float rounding decides.
fn cpu_traversal(
    photons: &HashMap<(u32, u32), Photon>,
    n: u32,
    tested: &dyn Fn(u32) -> bool,
) -> HashMap<(u32, u32), Option<[u32; 4]>> {
    let (_, top) = levels(n);
    let mut cover = HashMap::new();
    let mut stack: Vec<(u32, u32, u32)> = (0..TOP_SIDE * TOP_SIDE).map(|i| (i % TOP_SIDE, i / TOP_SIDE, top)).collect();
    while let Some((x, y, k)) = stack.pop() {
        let side = 1u32 << k;
        let members: Vec<(u32, u32)> = (y * side..(y + 1) * side)
            .flat_map(|py| (x * side..(x + 1) * side).map(move |px| (px, py)))
            .filter(|t| photons.contains_key(t))
            .collect();
        if members.is_empty() {
            continue;
        }
        if k == 0 {
            cover.insert((x, y), Some([x, y, 0, 0]));
            continue;
        }
        if tested(k) && members.len() >= 2 {
            let (may, sure) = convergence(&members.iter().map(|t| &photons[t]).collect::<Vec<_>>());
            if may && !sure {
                for t in &members {
                    cover.insert(*t, None);
                }
                continue;
            }
            if sure {
                for t in &members {
                    cover.insert(*t, Some([x, y, k, 1]));
                }
                continue;
            }
        }
        stack.extend((0..4).map(|c| (2 * x + (c & 1), 2 * y + (c >> 1), k - 1)));
    }
    cover
}

#[test]
fn clusters_are_exactly_the_nodes_whose_photons_converge_on_both_paths() {
    let (ctx, sh) = context();
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/sphere_on_plane.toml");
    // 200² pads to 256²: the padding is part of the quadtree; a 128² map makes photons converge.
    let n = 200;
    for cluster in ["last", "all"] {
        let mut clusters_seen = 0;
        for path in ["xfb", "compute"] {
            let mut s = Scene::load(&p).expect("shipped scene");
            s.caustics.technique = "hcm".parse().expect("a known name");
            s.caustics.photons = n;
            s.caustics.caustic_map_resolution = 128;
            s.caustics.cluster = cluster.parse().expect("a known name");
            s.caustics.path = path.parse().expect("a known name");
            s.camera.width = 64;
            s.camera.height = 64;
            s.receiver_map = None;
            let mut r = Renderer::new(&ctx, &sh, &s, &RendererOptions::default()).expect("renderer");
            r.frame(FrameStep::default()).expect("frame");
            let entries = r.caustics().and_then(|c| c.hierarchy()).expect("hcm").final_entries(&ctx).expect("entries");
            let pb = r.dump("photon_buffer").expect("dump").expect("a photon buffer");
            let pos = pb.layer(Some("light0.position")).expect("position layer");
            let photons = photons(&s, &pos.data, n);
            let tested = |k: u32| cluster == "all" || k == 1;
            let want = cpu_traversal(&photons, n, &tested);
            // The GPU's entry for each photon, and every photon covered once.
            let mut got: HashMap<(u32, u32), [u32; 4]> = HashMap::new();
            for e in &entries {
                let side = 1u32 << e[2];
                let mut covered = 0;
                for py in e[1] * side..(e[1] + 1) * side {
                    for px in e[0] * side..(e[0] + 1) * side {
                        if photons.contains_key(&(px, py)) {
                            assert!(got.insert((px, py), *e).is_none(), "{cluster} {path}: photon ({px}, {py}) twice");
                            covered += 1;
                        }
                    }
                }
                // A photon covers itself, a cluster two photons or more.
                let least = if e[3] == 1 { 2 } else { 1 };
                assert!(covered >= least, "{cluster} {path}: entry {e:?} covers {covered} photons");
            }
            assert_eq!(got.len(), photons.len(), "{cluster} {path}: photons missing from the final list");
            let uncertain = want.values().filter(|w| w.is_none()).count();
            assert!(uncertain * 100 < photons.len(), "{cluster} {path}: {uncertain} photons undecided");
            let wrong: Vec<_> =
                want.iter().filter_map(|(t, w)| w.filter(|w| got[t] != *w).map(|w| (*t, w, got[t]))).take(5).collect();
            assert!(wrong.is_empty(), "{cluster} {path}: (photon, CPU entry, GPU entry) {wrong:?}");
            clusters_seen += entries.iter().filter(|e| e[3] == 1).count();
            if cluster == "all" {
                // Clusters above level 1: the test reaches the coarser levels.
                assert!(entries.iter().any(|e| e[2] >= 2), "{path}: no cluster above level 1: a vacuous test");
            }
        }
        assert!(clusters_seen > 100, "{cluster}: {clusters_seen} clusters: a vacuous test");
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}
