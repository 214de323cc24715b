//! Adaptive caustic maps (Wyman & Nichols 2009 Sec. 3.2-3.2.1), validation layer on:
//! - the light-space geometry buffers hold what the dense photon buffer's passes see: with
//!   buffers as fine as the photon grid, the front layer covers exactly the photon buffer's
//!   texels, and the back layer is the dense back-face pass's image; the coverage pyramid is the
//!   max (any) and min (all) of its level 0, computed on the CPU;
//! - with the maximal traversal metric at level L, the adaptive photons are the dense photon
//!   buffer's valid photons at (64 × 2^L)² (the same texels, any order; positions and power
//!   within float tolerance) when the geometry buffers have the photon grid's resolution, on the
//!   compute and the transform-feedback path, on `sphere_on_plane` (fitted photon view) and the
//!   bunny room (the papers' 90-degree view, most of it empty), and they splat the same caustic
//!   map as dense `wd-points`;
//! - every level's list of pending clusters is what a CPU model of the traversal makes of the
//!   previous level's, given the coverage pyramid (discard a cluster when no texel of its
//!   footprint is covered, else refine it into its four children), and the per-level counts the
//!   renderer reports are those lists' lengths.

use caustics::image_io::ImageF32;
use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::wyman_nichols2009::adaptive::AdaptivePhoton;
use caustics::techniques::PhotonView;
use std::collections::{BTreeMap, BTreeSet};
use std::path::PathBuf;
use vkcore::{Context, ShaderCompiler};

mod common;
use common::context;

/// `name` with `technique` at `photons`² and a caustic map of 4 × photons: the default
/// `gbuffer_scale` (0.25) then gives geometry buffers as fine as the photon grid.
fn scene(name: &str, technique: &str, photons: u32, path: &str) -> Scene {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../../scenes/{name}.toml"));
    let mut s = Scene::load(&p).expect("shipped scene");
    s.caustics.technique = technique.parse().expect("a known name");
    s.caustics.photons = photons;
    if technique == "adaptive" {
        s.caustics.path = path.parse().expect("a known name");
    }
    s.caustics.caustic_map_resolution = 4 * photons;
    if name == "bunny_in_room" {
        // The papers' setup: photons in a 90-degree view about the light's direction.
        s.caustics.photon_view = PhotonView::FixedFov;
    }
    s.camera.width = 64;
    s.camera.height = 64;
    s.receiver_map = None;
    s
}

/// What a render left: its dumps (by name), the adaptive photons and per-level counts.
struct Run {
    dumps: BTreeMap<String, ImageF32>,
    photons: Vec<AdaptivePhoton>,
    /// Light 0's pending clusters per level, then the photons output at each step.
    counts: (Vec<u64>, Vec<u64>),
}

fn run(ctx: &Context, sh: &ShaderCompiler, s: &Scene, dumps: &[&str]) -> Run {
    let mut r = Renderer::new(ctx, sh, s, &RendererOptions::default()).expect("renderer");
    r.frame(FrameStep::default()).expect("frame");
    let names: Vec<String> = dumps.iter().map(|d| d.to_string()).collect();
    let dumps = r.dumps(&names).expect("dumps").into_iter().map(|(d, img)| (d.name.to_string(), img)).collect();
    let (photons, counts) = match r.caustics().and_then(|c| c.adaptive()) {
        Some(a) => (a.read_photons(ctx).expect("photons"), a.level_counts(ctx).expect("counts").remove(0)),
        None => (vec![], (vec![], vec![])),
    };
    Run { dumps, photons, counts }
}

fn layer<'a>(img: &'a ImageF32, name: &str) -> &'a caustics::image_io::Layer {
    img.layer(Some(name)).unwrap_or_else(|| panic!("no layer {name}"))
}

/// The dense photon buffer's valid photons: texel -> (position, power).
fn dense_photons(pb: &ImageF32) -> BTreeMap<(u32, u32), ([f32; 3], [f32; 3])> {
    let (pos, pow) = (layer(pb, "light0.position"), layer(pb, "light0.power"));
    (0..pb.width * pb.height)
        .filter(|&i| pos.data[i as usize * 4 + 3] > 0.5)
        .map(|i| {
            let (p, w) = (&pos.data[i as usize * 4..][..3], &pow.data[i as usize * 3..][..3]);
            ((i % pb.width, i / pb.width), ([p[0], p[1], p[2]], [w[0], w[1], w[2]]))
        })
        .collect()
}

/// Mean-RGB texels of light 0's caustic map.
fn caustic_map(img: &ImageF32) -> Vec<f64> {
    let l = layer(img, "light0");
    l.data.chunks_exact(l.channels.len()).map(|p| (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0).collect()
}

#[test]
fn geometry_buffers_hold_the_dense_passes_surfaces() {
    let (ctx, sh) = context();
    for name in ["sphere_on_plane", "bunny_in_room"] {
        let n = 128;
        let dense = run(&ctx, &sh, &scene(name, "wd-points", n, "compute"), &["photon_buffer", "photon_back_faces"]);
        let adaptive = run(&ctx, &sh, &scene(name, "adaptive", n, "compute"), &["adaptive_geometry"]);
        let g = &adaptive.dumps["adaptive_geometry"];
        let p = g.width as usize;
        assert_eq!(p, n as usize, "{name}: geometry buffers of {p}² for {n}² photons");
        // Front coverage: every texel the photon buffer traced a photon from (its power is kept
        // for lost photons; a point light gives every photon some).
        let pb = &dense.dumps["photon_buffer"];
        let power = layer(pb, "light0.power");
        let front = layer(g, "light0.front.normal");
        let mut covered = 0;
        for i in 0..(n * n) as usize {
            let traced = power.data[i * 3..i * 3 + 3].iter().any(|&w| w > 0.0);
            let object = front.data[i * 4 + 3];
            assert_eq!(traced, object > 0.5, "{name}: texel {i}: photon traced {traced}, geometry object {object}");
            covered += traced as usize;
        }
        assert!(covered > 100 && covered < (n * n) as usize, "{name}: {covered} covered texels: a vacuous test");
        // The back layer is the dense back-face pass's image.
        let (back, dense_back) = (layer(g, "light0.back.normal"), layer(&dense.dumps["photon_back_faces"], "light0"));
        let worst = back.data.iter().zip(&dense_back.data).map(|(a, b)| (a - b).abs()).fold(0.0f32, f32::max);
        assert!(worst < 1e-5, "{name}: back faces differ by up to {worst}");
        assert!(dense_back.data.iter().any(|&v| v > 0.0), "{name}: no back faces: a vacuous test");
        // The coverage pyramid: level m is the max (any) and min (all) of level 0's blocks.
        let level0 = layer(g, "light0.coverage.level0");
        // A mip chain of the (power-of-two) side down to 1 texel: log2(p) levels above level 0.
        assert!(p.is_power_of_two(), "{name}: {p}");
        assert!(g.layer(Some(&format!("light0.coverage.level{}", p.trailing_zeros() + 1))).is_none());
        for m in 1..=p.trailing_zeros() as usize {
            let lm = g
                .layer(Some(&format!("light0.coverage.level{m}")))
                .unwrap_or_else(|| panic!("{name}: no coverage level {m} in the dump"));
            let s = p >> m;
            for y in 0..s {
                for x in 0..s {
                    let (mut any, mut all) = (0.0f32, 1.0f32);
                    for v in 0..1 << m {
                        for u in 0..1 << m {
                            let c = level0.data[((y << m) + v) * p * 2 + ((x << m) + u) * 2];
                            any = any.max(c);
                            all = all.min(c);
                        }
                    }
                    let got = &lm.data[(y * p + x) * 2..][..2];
                    assert_eq!(got, [any, all], "{name}: coverage level {m} texel ({x}, {y})");
                }
            }
        }
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

#[test]
fn max_traversal_emits_exactly_the_dense_buffers_valid_photons_on_both_paths() {
    let (ctx, sh) = context();
    for (name, n) in [("sphere_on_plane", 128), ("sphere_on_plane", 256), ("bunny_in_room", 256)] {
        let dense = run(&ctx, &sh, &scene(name, "wd-points", n, "compute"), &["photon_buffer", "caustic_map"]);
        let want = dense_photons(&dense.dumps["photon_buffer"]);
        assert!(want.len() > 100, "{name} {n}: only {} valid photons: a vacuous test", want.len());
        assert!(want.len() < (n * n) as usize, "{name} {n}: every texel valid: nothing to discard");
        let dense_map = caustic_map(&dense.dumps["caustic_map"]);
        let level = (n / 64).trailing_zeros();
        for path in ["compute", "xfb"] {
            let a = run(&ctx, &sh, &scene(name, "adaptive", n, path), &["caustic_map"]);
            let label = format!("{name} {n}² {path}");
            let mut got = BTreeMap::new();
            for ph in &a.photons {
                let [x, y, k] = ph.cell();
                assert_eq!(k, level, "{label}: a photon of level {k}");
                assert!(got.insert((x, y), ph).is_none(), "{label}: photon ({x}, {y}) twice");
            }
            let (got_set, want_set): (BTreeSet<_>, BTreeSet<_>) = (got.keys().collect(), want.keys().collect());
            if let Err(e) = same_sets(&got_set, &want_set) {
                panic!("{label}: not the dense buffer's valid photons: {e}");
            }
            for (t, (pos, power)) in &want {
                let ph = got[t];
                let dp = (0..3).map(|i| (ph.position[i] - pos[i]).abs()).fold(0.0f32, f32::max);
                let dw = (0..3).map(|i| (ph.power[i] - power[i]).abs() / power[i].max(1e-30)).fold(0.0f32, f32::max);
                assert!(
                    dp < 1e-4 && dw < 1e-5,
                    "{label}: photon {t:?} at {:?} {:?}, dense {pos:?} {power:?}",
                    ph.position,
                    ph.power
                );
            }
            assert_eq!(a.counts.1.iter().sum::<u64>(), want.len() as u64, "{label}: the per-step photon counts");
            assert_eq!(a.counts.1.last().copied(), Some(want.len() as u64), "{label}: photons before the last step");
            // Same photons, same splats: the maps agree up to the order of additive blending.
            let map = caustic_map(&a.dumps["caustic_map"]);
            let total: f64 = dense_map.iter().sum();
            let diff: f64 = map.iter().zip(&dense_map).map(|(a, b)| (a - b).abs()).sum();
            assert!(total > 0.0 && diff <= 1e-5 * total, "{label}: maps differ by {diff} of {total}");
        }
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

/// The texel range [lo, hi] (per axis) of the geometry buffers (side `g`) that cluster (x, y)
/// of level k (photons on the (64 × 2^k)² grid) and its descendants sample.
fn footprint(g: u64, c: [u32; 3]) -> ([u64; 2], [u64; 2]) {
    let clusters = 32u64 << c[2];
    let lo = |v: u32| (v as u64 * g) / clusters;
    let hi = |v: u32| ((v as u64 + 1) * g - 1) / clusters;
    ([lo(c[0]), lo(c[1])], [hi(c[0]), hi(c[1])])
}

/// Whether any texel of the footprint is covered, texel by texel at level 0 (`levels[0]`).
fn footprint_covered(levels: &[&[f32]], p: usize, g: u64, c: [u32; 3]) -> bool {
    let (lo, hi) = footprint(g, c);
    (lo[1]..=hi[1]).any(|y| (lo[0]..=hi[0]).any(|x| levels[0][(y as usize * p + x as usize) * 2] > 0.5))
}

/// The traversal's test: at the smallest pyramid level m where the footprint spans at most 2x2
/// texels, whether any of those is covered (each level of side P/2^m stored in a P-wide image).
fn pyramid_says_covered(levels: &[&[f32]], p: usize, g: u64, c: [u32; 3]) -> bool {
    let (lo, hi) = footprint(g, c);
    let m = (0..).find(|&m| (0..2).all(|a| (hi[a] >> m) - (lo[a] >> m) <= 1)).unwrap_or(0);
    (lo[1] >> m..=hi[1] >> m)
        .any(|y| (lo[0] >> m..=hi[0] >> m).any(|x| levels[m][(y as usize * p + x as usize) * 2] > 0.5))
}

/// `a` and `b` as sets, with what one has and the other lacks when they differ (a few of each).
fn same_sets<T: Ord + std::fmt::Debug>(a: &BTreeSet<T>, b: &BTreeSet<T>) -> Result<(), String> {
    if a == b {
        return Ok(());
    }
    let only_a: Vec<&T> = a.difference(b).take(8).collect();
    let only_b: Vec<&T> = b.difference(a).take(8).collect();
    Err(format!("{} vs {} elements; only in the first: {only_a:?}; only in the second: {only_b:?}", a.len(), b.len()))
}

#[test]
fn every_level_refines_the_covered_clusters_of_the_level_above() {
    let (ctx, sh) = context();
    // Geometry buffers coarser and finer than the photon grid, an odd (padded) side among them.
    for (name, n, scale) in [("bunny_in_room", 256, 0.25), ("sphere_on_plane", 256, 0.1), ("sphere_on_plane", 128, 0.5)]
    {
        for path in ["compute", "xfb"] {
            let mut s = scene(name, "adaptive", n, path);
            s.caustics.gbuffer_scale = scale;
            let a = run(&ctx, &sh, &s, &["adaptive_geometry", "adaptive_lists"]);
            let label = format!("{name} {n}² scale {scale} {path}");
            let (geometry, lists) = (&a.dumps["adaptive_geometry"], &a.dumps["adaptive_lists"]);
            let g = s.caustics.gbuffer_side() as u64;
            let p = geometry.width as usize;
            let levels: Vec<&[f32]> = (0..)
                .map_while(|m| geometry.layer(Some(&format!("light0.coverage.level{m}"))))
                .map(|l| l.data.as_slice())
                .collect();
            let clusters = |k: u32| -> BTreeSet<[u32; 3]> {
                let l = layer(lists, &format!("light0.clusters{k}"));
                l.data
                    .chunks_exact(11)
                    .filter(|r| r[10] > 0.5)
                    .map(|r| [r[0] as u32, r[1] as u32, r[2] as u32])
                    .collect()
            };
            let last = (n / 64).trailing_zeros();
            assert_eq!(clusters(0).len(), 32 * 32, "{label}: the coarse grid's clusters");
            for k in 0..=last {
                let pending = clusters(k);
                assert_eq!(pending.len() as u64, a.counts.0[k as usize], "{label}: level {k}'s count");
                let kept: Vec<[u32; 3]> =
                    pending.iter().copied().filter(|&c| pyramid_says_covered(&levels, p, g, c)).collect();
                // The test is conservative: every cluster with a covered texel in its footprint is kept.
                for c in &pending {
                    assert!(
                        !footprint_covered(&levels, p, g, *c) || pyramid_says_covered(&levels, p, g, *c),
                        "{label}: cluster {c:?} has a covered texel but is discarded"
                    );
                }
                assert!(
                    !kept.is_empty() && kept.len() < pending.len(),
                    "{label}: level {k} keeps {} of {}",
                    kept.len(),
                    pending.len()
                );
                let children: BTreeSet<[u32; 3]> = kept
                    .iter()
                    .flat_map(|c| (0..4).map(move |i| [2 * c[0] + (i & 1), 2 * c[1] + (i >> 1), c[2] + 1]))
                    .collect();
                if k < last {
                    if let Err(e) = same_sets(&clusters(k + 1), &children) {
                        panic!("{label}: level {}'s clusters against the CPU model: {e}", k + 1);
                    }
                } else {
                    // The last step outputs the photons that landed among the kept clusters'.
                    for ph in &a.photons {
                        let [x, y, l] = ph.cell();
                        assert!(children.contains(&[x, y, l + 1]), "{label}: photon ({x}, {y}) of a discarded cluster");
                    }
                }
            }
        }
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

/// With two lights, one set of geometry buffers and lists serves both in turn: each light's
/// output photons (read back light by light through the `adaptive_lists` dump) are exactly
/// that light's dense valid photons, and each light's per-level counts end with its own.
#[test]
fn every_light_creates_its_own_photons() {
    let (ctx, sh) = context();
    let n = 128;
    for path in ["compute", "xfb"] {
        let dense = run(&ctx, &sh, &scene("two_lights", "wd-points", n, path), &["photon_buffer"]);
        let s = scene("two_lights", "adaptive", n, path);
        let mut r = Renderer::new(&ctx, &sh, &s, &RendererOptions::default()).expect("renderer");
        r.frame(FrameStep::default()).expect("frame");
        let counts = r.caustics().and_then(|c| c.adaptive()).expect("adaptive").level_counts(&ctx).expect("counts");
        let lists = r.dump("adaptive_lists").expect("dump").expect("the lists");
        let pb = &dense.dumps["photon_buffer"];
        let mut per_light = vec![];
        for (l, (_, emitted)) in counts.iter().enumerate() {
            let pos = layer(pb, &format!("light{l}.position"));
            let want: BTreeSet<(u32, u32)> = (0..pb.width * pb.height)
                .filter(|&i| pos.data[i as usize * 4 + 3] > 0.5)
                .map(|i| (i % pb.width, i / pb.width))
                .collect();
            let photons = layer(&lists, &format!("light{l}.photons"));
            let got: BTreeSet<(u32, u32)> =
                photons.data.chunks_exact(11).filter(|r| r[10] > 0.5).map(|r| (r[0] as u32, r[1] as u32)).collect();
            assert!(want.len() > 100, "{path}: light {l}: {} valid photons: a vacuous test", want.len());
            if let Err(e) = same_sets(&got, &want) {
                panic!("{path}: light {l}'s photons are not its dense valid photons: {e}");
            }
            assert_eq!(emitted.iter().sum::<u64>(), want.len() as u64, "{path}: light {l}'s counts");
            per_light.push(want);
        }
        assert_eq!(per_light.len(), 2, "{path}: counts of {} lights", per_light.len());
        assert_ne!(per_light[0], per_light[1], "{path}: both lights see the same photons: a vacuous test");
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}
