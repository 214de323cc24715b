//! Photon batching under a memory limit (Wyman & Nichols 2009 Sec. 4.3), validation layer on:
//! with `photon_memory_limit` the traversal goes breadth-first as deep as fits, then refines and
//! splats the pending clusters batch after batch; the photon storage it allocates is within the
//! limit, and the caustic map, the per-level counts and the photons splatted are the unbatched
//! traversal's, on both paths, for both metrics (including clusters that converge above the
//! batches' level, splatted before them), with the point and the compute splat; the same with
//! `photon_batches` = N, which gives N batches. A limit too small to make progress is an input
//! error naming the setting.

use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use std::path::PathBuf;
use vkcore::{Context, ShaderCompiler};

mod common;
use common::context;

fn scene(path: &str, metric: &str, splat_path: &str, limit_mib: u32) -> Scene {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/sphere_on_plane.toml");
    let mut s = Scene::load(&p).expect("shipped scene");
    s.caustics.technique = "adaptive".parse().expect("a known name");
    s.caustics.photons = 1024;
    s.caustics.caustic_map_resolution = 512;
    s.caustics.path = path.parse().expect("a known name");
    s.caustics.metric = metric.parse().expect("a known name");
    s.caustics.splat_path = splat_path.parse().expect("a known name");
    s.caustics.photon_memory_limit = limit_mib;
    s.camera.width = 64;
    s.camera.height = 64;
    s.receiver_map = None;
    s
}

struct Run {
    map: Vec<f64>,
    counts: (Vec<u64>, Vec<u64>),
    splatted: u64,
    storage: u64,
    /// (the last breadth-first level, batches)
    plan: (u32, u32),
}

fn run(ctx: &Context, sh: &ShaderCompiler, s: &Scene) -> Run {
    let mut r = Renderer::new(ctx, sh, s, &RendererOptions::default()).expect("renderer");
    r.frame(FrameStep::default()).expect("frame");
    let img = r.dump("caustic_map").expect("dump").expect("a caustic map");
    let l = img.layer(Some("light0")).expect("light0");
    let map = l.data.chunks_exact(l.channels.len()).map(|p| (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0).collect();
    let splatted = r.splats_drawn().expect("splats");
    let a = r.adaptive().expect("adaptive");
    let storage = a.photon_storage_bytes();
    assert_eq!(storage, a.plan.storage_bytes(), "allocated storage vs the plan's");
    Run {
        map,
        counts: a.level_counts(ctx).expect("counts").remove(0),
        splatted,
        storage,
        plan: (a.plan.breadth, a.plan.batches),
    }
}

#[test]
fn batches_within_the_limit_splat_the_unbatched_map() {
    let (ctx, sh) = context();
    let mut breadth_clusters_splatted = false;
    for (path, splat_path) in [("compute", "compute"), ("xfb", "raster")] {
        for metric in ["max-traversal", "max-error"] {
            let whole = run(&ctx, &sh, &scene(path, metric, splat_path, 0));
            assert_eq!(whole.plan, (4, 1), "{path} {metric}: unbatched plan");
            let total: f64 = whole.map.iter().sum();
            assert!(total > 0.0 && whole.splatted > 1000, "{path} {metric}: no caustic: a vacuous test");
            for limit in [4u32, 1] {
                let label = format!("{path} {metric} {limit} MiB");
                let b = run(&ctx, &sh, &scene(path, metric, splat_path, limit));
                println!(
                    "{label}: breadth-first to level {}, {} batches, {} of {} bytes",
                    b.plan.0, b.plan.1, b.storage, whole.storage
                );
                assert!(b.plan.1 > 1, "{label}: not batched");
                assert!(b.storage <= limit as u64 * 1024 * 1024, "{label}: {} bytes allocated", b.storage);
                assert_eq!(b.counts, whole.counts, "{label}: per-level counts differ from unbatched");
                assert_eq!(b.splatted, whole.splatted, "{label}: photons splatted");
                let diff: f64 = b.map.iter().zip(&whole.map).map(|(x, y)| (x - y).abs()).sum();
                assert!(diff <= 1e-5 * total, "{label}: maps differ by {diff} of {total}");
                breadth_clusters_splatted |= metric == "max-error" && b.plan.0 > 3;
            }
        }
    }
    assert!(breadth_clusters_splatted, "no batched max-error run converged clusters above its batches: untested");
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

/// `photon_batches` (Fig. 8's sweep): the plan with N batches records N batches, with or without
/// a memory limit, and they splat the unbatched map.
#[test]
fn photon_batches_give_that_many_batches_and_the_unbatched_map() {
    let (ctx, sh) = context();
    for (path, splat_path, metric) in [("compute", "raster", "max-traversal"), ("xfb", "compute", "max-error")] {
        let whole = run(&ctx, &sh, &scene(path, metric, splat_path, 0));
        let total: f64 = whole.map.iter().sum();
        assert!(total > 0.0 && whole.splatted > 1000, "{path} {metric}: no caustic: a vacuous test");
        for (n, limit) in [(2u32, 0u32), (5, 0), (16, 0), (8, 4)] {
            let label = format!("{path} {metric} {n} batches, limit {limit} MiB");
            let mut s = scene(path, metric, splat_path, limit);
            s.caustics.photon_batches = n;
            let b = run(&ctx, &sh, &s);
            assert!(b.plan.1 >= n, "{label}: {} batches", b.plan.1);
            if limit == 0 {
                assert_eq!(b.plan, (4, n), "{label}: the last level's clusters in exactly {n} batches");
            } else {
                assert!(b.storage <= limit as u64 * 1024 * 1024, "{label}: {} bytes allocated", b.storage);
            }
            assert_eq!(b.counts, whole.counts, "{label}: per-level counts differ from unbatched");
            assert_eq!(b.splatted, whole.splatted, "{label}: photons splatted");
            let diff: f64 = b.map.iter().zip(&whole.map).map(|(x, y)| (x - y).abs()).sum();
            assert!(diff <= 1e-5 * total, "{label}: maps differ by {diff} of {total}");
        }
    }
    // Out of range: an input error naming the setting.
    let mut s = scene("compute", "max-traversal", "raster", 0);
    s.caustics.photon_batches = 0;
    let err = s.caustics.validate("test", "--").expect_err("refused").to_string();
    assert!(err.contains("--photon-batches"), "{err}");
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

#[test]
fn a_limit_too_small_to_make_progress_is_an_input_error() {
    let (ctx, sh) = context();
    let mut s = scene("compute", "max-traversal", "raster", 1);
    s.caustics.photons = 16384;
    let err = Renderer::new(&ctx, &sh, &s, &RendererOptions::default()).err().expect("refused").to_string();
    assert!(err.contains("photon_memory_limit") && err.contains("16384²"), "{err}");
    // And the settings' own check, for the command line and scene files.
    let err = s.caustics.validate("test", "--").expect_err("refused").to_string();
    assert!(err.contains("--photon-memory-limit") && err.contains("at least"), "{err}");
}
