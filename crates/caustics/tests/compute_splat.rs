//! The compute splat (shared/splat.comp, `splat_path = compute`) must give the caustic map the
//! point splat gives: the same texels with the same weights in the same layers, so the same map
//! up to the order of float additions. Checked texel by texel on every channel (power and
//! photon count) and every layer, for the dense photon buffer (`wd-points` with both kernels,
//! radii from 0.25 to 4.5 and two lights; `shah`; `shah-vertex`) and for the hierarchical
//! traversal's final list on both traversal paths, with clustering and with varying splats in
//! one map and in the multi-resolution map, and with two lights. Validation layer on; any
//! message fails.

use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use vkcore::{Context, ShaderCompiler};

mod common;
use common::{context, shipped};

fn scene(file: &str, technique: &str) -> Scene {
    let mut s = shipped(file);
    s.caustics.technique = technique.parse().expect("a known name");
    s.caustics.photons = 128;
    s.caustics.caustic_map_resolution = 256;
    s.camera.width = 64;
    s.camera.height = 64;
    s.receiver_map = None;
    s
}

/// Every channel of every caustic-map layer after one frame.
fn caustic_map(ctx: &Context, sh: &ShaderCompiler, scene: &Scene) -> Vec<f64> {
    let mut r = Renderer::new(ctx, sh, scene, &RendererOptions::default()).expect("renderer");
    let report = r.frame(FrameStep::default()).expect("frame");
    // Which path ran: only the compute splat has a resolve pass.
    let compute = scene.caustics.splat_path == caustics::techniques::SplatPath::Compute;
    assert_eq!(
        report.pass("splat.resolve.light0").is_some(),
        compute,
        "splat_path `{}` did not take effect",
        scene.caustics.splat_path
    );
    let img = r.dump("caustic_map").expect("dump").expect("a caustic map");
    img.layers.iter().flat_map(|l| l.data.iter().map(|&v| v as f64)).collect()
}

/// (relative difference of the totals, Σ|a − b| / Σ|b|, largest |a − b| / largest |b|).
fn difference(a: &[f64], b: &[f64]) -> (f64, f64, f64) {
    assert_eq!(a.len(), b.len(), "maps of different sizes");
    let (sa, sb): (f64, f64) = (a.iter().sum(), b.iter().sum());
    let l1: f64 = a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum();
    let max_diff = a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    let peak = b.iter().map(|x| x.abs()).fold(0.0, f64::max);
    ((sa - sb).abs() / sb, l1 / b.iter().map(|x| x.abs()).sum::<f64>(), max_diff / peak)
}

/// Renders `s` with both splat paths and compares; `what` names the case in failures.
fn assert_same_map(ctx: &Context, sh: &ShaderCompiler, mut s: Scene, what: &str) {
    s.caustics.splat_path = "raster".parse().expect("a known name");
    let raster = caustic_map(ctx, sh, &s);
    assert!(raster.iter().sum::<f64>() > 0.0, "{what}: no caustic, the comparison would be vacuous");
    s.caustics.splat_path = "compute".parse().expect("a known name");
    let compute = caustic_map(ctx, sh, &s);
    let (dt, dl1, dmax) = difference(&compute, &raster);
    // Float additions in another order: relative rounding of a few ulps per texel.
    assert!(
        dt < 1e-5 && dl1 < 1e-5 && dmax < 1e-5,
        "{what}: compute splat differs from the point splat: totals by {dt}, texels by {dl1} (L1), at most {dmax} of the peak"
    );
}

#[test]
fn the_compute_splat_gives_the_point_splats_map_for_dense_photons() {
    let (ctx, sh) = context();
    // Radius 0.25 misses most texel centres: those photons go whole to the nearest texel.
    for (technique, kernel, radius) in [
        ("wd-points", "gaussian", 1.5),
        ("wd-points", "box", 1.5),
        ("wd-points", "gaussian", 4.5),
        ("wd-points", "gaussian", 0.25),
        ("shah", "gaussian", 2.0),
        ("shah-vertex", "box", 2.0),
    ] {
        let mut s = scene("sphere_on_plane.toml", technique);
        s.caustics.splat_kernel = kernel.parse().expect("a known name");
        s.caustics.splat_radius = radius;
        assert_same_map(&ctx, &sh, s, &format!("{technique}, {kernel} kernel, radius {radius}"));
    }
    // Two lights: one caustic-map layer each, the accumulation buffer reused light after light.
    assert_same_map(&ctx, &sh, scene("two_lights.toml", "wd-points"), "wd-points, two lights");
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

#[test]
fn the_compute_splat_gives_the_point_splats_map_for_the_hierarchys_final_list() {
    let (ctx, sh) = context();
    for path in ["xfb", "compute"] {
        for (cluster, splat) in
            [("none", "fixed"), ("all", "fixed"), ("last", "varying-single"), ("last", "varying-multires")]
        {
            let mut s = scene("sphere_on_plane.toml", "hcm");
            s.caustics.path = path.parse().expect("a known name");
            s.caustics.cluster = cluster.parse().expect("a known name");
            s.caustics.splat = splat.parse().expect("a known name");
            assert_same_map(&ctx, &sh, s, &format!("hcm, path {path}, cluster {cluster}, {splat} splats"));
        }
    }
    let mut s = scene("two_lights.toml", "hcm");
    s.caustics.splat = "varying-multires".parse().expect("a known name");
    assert_same_map(&ctx, &sh, s, "hcm, two lights, varying multi-res");
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}
