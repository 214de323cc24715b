//! Hierarchical caustic maps (Wyman 2008 Sec. 3.1-3.2), validation layer on:
//! - without clustering, the traversal emits exactly the valid photons of the dense photon
//!   buffer (same set, any order), on the transform-feedback and the compute path, at awkward
//!   (non-power-of-two) resolutions, and splats the same caustic map as dense `wd-points`;
//! - both paths give identical photon sets in every clustering mode;
//! - clustering conserves the caustic map's total power;
//! - every combination of path, clustering and splat mode runs with no validation message.

use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use std::collections::BTreeSet;
use std::path::PathBuf;
use vkcore::{Context, ShaderCompiler};

mod common;
use common::context;

fn scene(technique: &str, photons: u32, path: &str, cluster: &str) -> Scene {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/sphere_on_plane.toml");
    let mut s = Scene::load(&p).expect("shipped scene");
    s.caustics.technique = technique.parse().expect("a known name");
    s.caustics.photons = photons;
    s.caustics.path = path.parse().expect("a known name");
    s.caustics.cluster = cluster.parse().expect("a known name");
    s.caustics.caustic_map_resolution = 256;
    s.camera.width = 64;
    s.camera.height = 64;
    s.receiver_map = None;
    s
}

struct Run {
    /// (x, y, level, final) of the final list.
    entries: Vec<[u32; 4]>,
    /// Mean-RGB caustic map of light 0.
    map: Vec<f64>,
    /// Texels of the photon buffer holding a valid photon.
    valid: BTreeSet<(u32, u32)>,
    /// List sizes from level L down to 0.
    sizes: Vec<u64>,
}

fn run(ctx: &Context, sh: &ShaderCompiler, s: &Scene) -> Run {
    let mut r = Renderer::new(ctx, sh, s, &RendererOptions::default()).expect("renderer");
    r.frame(FrameStep::default()).expect("frame");
    let (entries, sizes) = match r.caustics().and_then(|c| c.hierarchy()) {
        Some(h) => (h.final_entries(ctx).expect("entries"), h.list_sizes(ctx).expect("sizes")[0].clone()),
        None => (vec![], vec![]),
    };
    let img = r.dump("caustic_map").expect("dump").expect("a caustic map");
    let layer = &img.layers[0];
    let nc = layer.channels.len();
    let map = layer.data.chunks_exact(nc).map(|p| (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0).collect();
    let pb = r.dump("photon_buffer").expect("dump").expect("a photon buffer");
    let pos = pb.layer(Some("light0.position")).expect("position layer");
    let valid = (0..pb.width * pb.height)
        .filter(|&i| pos.data[i as usize * 4 + 3] > 0.5)
        .map(|i| (i % pb.width, i / pb.width))
        .collect();
    Run { entries, map, valid, sizes }
}

fn photon_set(entries: &[[u32; 4]]) -> BTreeSet<(u32, u32)> {
    entries.iter().map(|e| (e[0], e[1])).collect()
}

fn total(map: &[f64]) -> f64 {
    map.iter().sum()
}

#[test]
fn unclustered_traversal_emits_exactly_the_valid_photons_on_both_paths() {
    let (ctx, sh) = context();
    for n in [100, 128, 200] {
        let dense = run(&ctx, &sh, &scene("wd-points", n, "xfb", "none"));
        assert!(dense.valid.len() > 100, "{n}: only {} valid photons: a vacuous test", dense.valid.len());
        assert!(dense.valid.len() < (n * n) as usize, "{n}: every texel valid: nothing to discard");
        for path in ["xfb", "compute"] {
            let h = run(&ctx, &sh, &scene("hcm", n, path, "none"));
            assert!(h.entries.iter().all(|e| e[2] == 0 && e[3] == 0), "{n} {path}: a non-photon entry");
            assert_eq!(h.entries.len(), dense.valid.len(), "{n} {path}: duplicates or missing photons");
            assert_eq!(photon_set(&h.entries), dense.valid, "{n} {path}: not the dense buffer's valid photons");
            assert_eq!(h.sizes.last().copied(), Some(dense.valid.len() as u64), "{n} {path}: counter");
            // Same photons, same splats: the maps agree up to the order of additive blending.
            let diff: f64 = h.map.iter().zip(&dense.map).map(|(a, b)| (a - b).abs()).sum();
            assert!(diff <= 1e-5 * total(&dense.map), "{n} {path}: maps differ by {diff} of {}", total(&dense.map));
        }
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

#[test]
fn both_paths_agree_and_clustering_conserves_power() {
    let (ctx, sh) = context();
    let n = 256;
    let dense = total(&run(&ctx, &sh, &scene("hcm", n, "compute", "none")).map);
    for cluster in ["last", "all"] {
        let x = run(&ctx, &sh, &scene("hcm", n, "xfb", cluster));
        let c = run(&ctx, &sh, &scene("hcm", n, "compute", cluster));
        let set = |r: &Run| r.entries.iter().map(|e| (e[0], e[1], e[2], e[3])).collect::<BTreeSet<_>>();
        assert_eq!(x.entries.len(), c.entries.len(), "{cluster}");
        assert_eq!(set(&x), set(&c), "{cluster}: the paths emit different photon sets");
        assert_eq!(x.sizes, c.sizes, "{cluster}: per-level list sizes differ");
        let clusters = x.entries.iter().filter(|e| e[3] == 1).count();
        assert!(clusters > 0, "{cluster}: no converging photons clustered at {n}²: a vacuous test");
        let ratio = total(&x.map) / dense;
        assert!((ratio - 1.0).abs() < 0.01, "{cluster}: clustering changed the caustic power by {ratio}");
        if cluster == "last" {
            assert!(x.entries.iter().all(|e| e[2] <= 1), "`last` clustered above level 1");
        }
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

/// (Σ power over every caustic-map layer, Σ over layers 1.. only, caustic flux on the receiver
/// map in W, caustic-map layers).
fn splat_totals(ctx: &Context, sh: &ShaderCompiler, splat: &str) -> (f64, f64, f64, usize) {
    let mut s = scene("hcm", 256, "compute", "last");
    s.caustics.splat = splat.parse().expect("a known name");
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/sphere_on_plane.toml");
    s.receiver_map = Scene::load(&p).expect("scene").receiver_map;
    let spec = s.receiver_map.clone().expect("the scene has a receiver map");
    let mut r = Renderer::new(ctx, sh, &s, &RendererOptions::default()).expect("renderer");
    r.frame(FrameStep::default()).expect("frame");
    let img = r.dump("caustic_map").expect("dump").expect("a caustic map");
    let mut all = 0.0;
    let mut coarse = 0.0;
    for (i, layer) in img.layers.iter().enumerate() {
        let nc = layer.channels.len();
        let t: f64 = layer.data.chunks_exact(nc).map(|p| (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0).sum();
        all += t;
        if i > 0 {
            coarse += t;
        }
    }
    let rec = r.dump("receiver").expect("dump").expect("a receiver map");
    let caustic = rec.layer(Some("caustic")).expect("caustic layer");
    let texel_area = (spec.x_range[1] - spec.x_range[0]) as f64 * (spec.z_range[1] - spec.z_range[0]) as f64
        / (spec.resolution as f64 * spec.resolution as f64);
    let flux: f64 =
        caustic.data.chunks_exact(3).map(|p| (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0).sum::<f64>() * texel_area;
    (all, coarse, flux, img.layers.len())
}

#[test]
fn varying_splats_conserve_power_and_the_multires_map_sums_to_the_single_map() {
    let (ctx, sh) = context();
    let (fixed, _, fixed_flux, _) = splat_totals(&ctx, &sh, "fixed");
    let (single, _, single_flux, single_layers) = splat_totals(&ctx, &sh, "varying-single");
    let (multi, multi_coarse, multi_flux, multi_layers) = splat_totals(&ctx, &sh, "varying-multires");
    assert!(fixed > 0.0 && fixed_flux > 0.0, "no caustic: a vacuous test");
    assert_eq!((single_layers, multi_layers), (1, 4), "caustic-map layers of one light: single map, Sec. 3.3 levels");
    assert!(
        multi_coarse > 0.01 * multi,
        "no splat went to a coarser level: a vacuous test ({multi_coarse} of {multi})"
    );
    // Varying splats only drop photons whose splat radius would reach 40 texels (level 4).
    assert!((single / fixed - 1.0).abs() < 0.01, "varying-single holds {single} W of the fixed map's {fixed} W");
    // The same splats, rasterised at coarser levels: the same power.
    assert!((multi / single - 1.0).abs() < 1e-3, "multires holds {multi} W, the single map {single} W");
    // Eq. 3 in the final render: the receiver sees the same caustic flux from either map.
    assert!(
        (multi_flux / single_flux - 1.0).abs() < 0.02,
        "receiver flux {multi_flux} W (multires) vs {single_flux} W"
    );
    assert!((single_flux / fixed_flux - 1.0).abs() < 0.02, "receiver flux {single_flux} W (varying) vs {fixed_flux} W");
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

/// Σ power (mean RGB, W) over every layer of the caustic map: with `varying-multires` the
/// levels of every light (Eq. 3 sums them the same way).
fn caustic_power(ctx: &Context, sh: &ShaderCompiler, path: &str, cluster: &str, splat: &str) -> f64 {
    let mut s = scene("hcm", 128, path, cluster);
    s.caustics.splat = splat.parse().expect("a known name");
    let mut r = Renderer::new(ctx, sh, &s, &RendererOptions::default()).expect("renderer");
    r.frame(FrameStep::default()).expect("frame");
    let img = r.dump("caustic_map").expect("dump").expect("a caustic map");
    img.layers
        .iter()
        .map(|layer| {
            let nc = layer.channels.len();
            layer.data.chunks_exact(nc).map(|p| (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0).sum::<f64>()
        })
        .sum()
}

#[test]
fn every_mode_runs_clean_and_keeps_the_caustic_power() {
    // Every combination of --path, --cluster and --splat: no validation message, and the
    // caustic map holds the unclustered fixed-splat map's power. Clustering sums power
    // (Sec. 3.2); varying splats (Sec. 3.3) only drop splats of radius 40 texels or more, few at 128²
    // photons into a 256² map.
    let (ctx, sh) = context();
    let reference = caustic_power(&ctx, &sh, "xfb", "none", "fixed");
    assert!(reference > 0.0, "no caustic: a vacuous test");
    for path in ["xfb", "compute"] {
        for cluster in ["none", "last", "all"] {
            for splat in ["fixed", "varying-single", "varying-multires"] {
                let p = caustic_power(&ctx, &sh, path, cluster, splat);
                let tolerance = if splat == "fixed" { 0.01 } else { 0.05 };
                assert!(
                    (p / reference - 1.0).abs() < tolerance,
                    "{path} {cluster} {splat}: {p} W against {reference} W unclustered"
                );
            }
        }
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

/// With two lights, one photon buffer and one set of lists serve both lights in turn: each
/// light's final list is exactly the valid photons of that light's own photon buffer (read back
/// light by light with `Renderer::dumps`), on both paths.
#[test]
fn every_light_traverses_its_own_photon_buffer() {
    let (ctx, sh) = context();
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/two_lights.toml");
    for path in ["xfb", "compute"] {
        let mut s = Scene::load(&p).expect("shipped scene");
        s.caustics.technique = "hcm".parse().expect("a known name");
        s.caustics.photons = 100;
        s.caustics.path = path.parse().expect("a known name");
        s.caustics.caustic_map_resolution = 256;
        s.camera.width = 64;
        s.camera.height = 48;
        let mut r = Renderer::new(&ctx, &sh, &s, &RendererOptions::default()).expect("renderer");
        r.frame(FrameStep::default()).expect("frame");
        let sizes = r.caustics().and_then(|c| c.hierarchy()).expect("hcm").list_sizes(&ctx).expect("sizes");
        let names = ["photon_buffer".to_string(), "hierarchy_lists".to_string()];
        let dumps = r.dumps(&names).expect("dumps");
        let (pb, lists) = (&dumps[0].1, &dumps[1].1);
        let mut per_light = vec![];
        for (l, light_sizes) in sizes.iter().enumerate() {
            let pos = pb.layer(Some(&format!("light{l}.position"))).expect("position layer");
            let valid: BTreeSet<(u32, u32)> = (0..pb.width * pb.height)
                .filter(|&i| pos.data[i as usize * 4 + 3] > 0.5)
                .map(|i| (i % pb.width, i / pb.width))
                .collect();
            let list = lists.layer(Some(&format!("light{l}.list0"))).expect("list layer");
            let listed: BTreeSet<(u32, u32)> =
                list.data.chunks_exact(5).filter(|e| e[4] > 0.5).map(|e| (e[0] as u32, e[1] as u32)).collect();
            assert!(valid.len() > 100, "light {l}: {} valid photons: a vacuous test", valid.len());
            assert_eq!(listed, valid, "{path}: light {l}'s final list is not its photon buffer's valid photons");
            assert_eq!(light_sizes.last().copied(), Some(valid.len() as u64), "{path}: light {l}'s counter");
            per_light.push(valid);
        }
        assert_eq!(per_light.len(), 2, "{path}: list sizes of {} lights", per_light.len());
        assert_ne!(per_light[0], per_light[1], "both lights see the same photons: a vacuous test");
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}
