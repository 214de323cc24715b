//! Photon batching under a memory limit (Wyman & Nichols 2009 Sec. 4.3), validation layer on:
//! with `photon_memory_limit` the traversal goes breadth-first as deep as fits, then refines and
//! splats the pending clusters batch after batch; the photon storage it allocates is within the
//! limit, and the caustic map, the per-level counts and the photons splatted are the unbatched
//! traversal's, on both paths, for both metrics (including clusters that converge above the
//! batches' level, splatted before them), with the point and the compute splat; the same with
//! `photon_batches` = N, which gives N batches. Every batched frame records no more passes than
//! its plan counted against `vkcore::MAX_PASSES`. A limit too small to make progress is an input
//! error naming the setting.

use caustics::image_io::ImageF32;
use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::wyman_nichols2009::adaptive::batches::OTHER_PASSES;
use std::collections::BTreeSet;
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
    let report = r.frame(FrameStep::default()).expect("frame");
    let img = r.dump("caustic_map").expect("dump").expect("a caustic map");
    let l = img.layer(Some("light0")).expect("light0");
    let map = l.data.chunks_exact(l.channels.len()).map(|p| (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0).collect();
    let splatted = r.splats_drawn().expect("splats");
    let a = r.caustics().and_then(|c| c.adaptive()).expect("adaptive");
    let storage = a.photon_storage_bytes();
    assert_eq!(storage, a.plan().storage_bytes(), "allocated storage vs the plan's");
    // The plan fits the frame's pass limit by counting its traversal's passes (Sec. 4.3's
    // batches multiply them); the frame must record no more than it counted. One light here.
    let names: Vec<&str> = report.passes.iter().map(|p| p.name.as_str()).collect();
    let traversal = |n: &&&str| {
        (n.starts_with("adaptive.") && !n.starts_with("adaptive.geometry") && !n.starts_with("adaptive.coverage"))
            || n.starts_with("splat.")
    };
    let recorded = names.iter().filter(traversal).count() as u64;
    assert!(recorded >= 2 * a.plan().batches as u64, "each batch records a traversal and a splat: {names:?}");
    assert!(
        recorded <= a.plan().traversal_passes(),
        "the traversal recorded {recorded} passes, its plan counted {}: {names:?}",
        a.plan().traversal_passes()
    );
    let others = names.len() as u64 - recorded;
    assert!(others <= OTHER_PASSES as u64, "{others} passes besides the traversal, {OTHER_PASSES} left for them");
    Run {
        map,
        counts: a.level_counts(ctx).expect("counts").remove(0),
        splatted,
        storage,
        plan: (a.plan().breadth, a.plan().batches),
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

/// The records of one `adaptive_lists` layer: (x, y, level) of each.
fn records(lists: &ImageF32, name: &str) -> Vec<[u32; 3]> {
    let l = lists.layer(Some(name)).unwrap_or_else(|| panic!("no layer {name}"));
    l.data.chunks_exact(11).filter(|r| r[10] > 0.5).map(|r| [r[0] as u32, r[1] as u32, r[2] as u32]).collect()
}

/// Whether two lists hold the same cells as often: on failure, their lengths and a few cells
/// each holds more often (the lists are large; the assertion prints only this).
fn same_cells(mut got: Vec<[u32; 3]>, mut want: Vec<[u32; 3]>) -> Result<(), String> {
    got.sort();
    want.sort();
    if got == want {
        return Ok(());
    }
    let count = |v: &[[u32; 3]]| {
        let mut m = std::collections::BTreeMap::new();
        v.iter().for_each(|c| *m.entry(*c).or_insert(0) += 1);
        m
    };
    let (g, w) = (count(&got), count(&want));
    let more = |a: &std::collections::BTreeMap<[u32; 3], i32>, b: &std::collections::BTreeMap<[u32; 3], i32>| {
        a.iter().filter(|(c, n)| b.get(*c).copied().unwrap_or(0) < **n).map(|(c, _)| *c).take(6).collect::<Vec<_>>()
    };
    Err(format!(
        "{} vs {} cells; more often in the first: {:?}; in the second: {:?}",
        got.len(),
        want.len(),
        more(&g, &w),
        more(&w, &g)
    ))
}

/// Every batch is dumpable (Sec. 4.3): a batched traversal's `adaptive_lists` holds the
/// breadth-first levels, the photons converged above them and each batch's clusters and
/// photons. The batches' slices of level B partition level B's list; their photons, with those
/// converged above B, are the unbatched traversal's photons, each once; every batch below
/// level B is the unbatched list restricted to that batch's descendants. Both paths, both metrics.
#[test]
fn every_batch_is_dumped_and_together_they_are_the_unbatched_traversal() {
    let (ctx, sh) = context();
    let lists = |s: &Scene| -> (ImageF32, (u32, u32)) {
        let mut r = Renderer::new(&ctx, &sh, s, &RendererOptions::default()).expect("renderer");
        r.frame(FrameStep::default()).expect("frame");
        let a = r.caustics().and_then(|c| c.adaptive()).expect("adaptive");
        let plan = (a.plan().breadth, a.plan().batches);
        (r.dump("adaptive_lists").expect("dump").expect("the lists"), plan)
    };
    for (path, metric) in
        [("compute", "max-error"), ("xfb", "max-error"), ("compute", "max-traversal"), ("xfb", "max-traversal")]
    {
        let mut s = scene(path, metric, "raster", 0);
        let (whole, _) = lists(&s);
        let whole_photons = records(&whole, "light0.photons");
        let distinct: BTreeSet<&[u32; 3]> = whole_photons.iter().collect();
        assert_eq!(distinct.len(), whole_photons.len(), "{path} {metric}: unbatched, a photon output twice");
        assert!(whole_photons.len() > 1000, "{path} {metric}: {} photons: a vacuous test", whole_photons.len());
        s.caustics.photon_memory_limit = 1;
        let (batched, (b, n)) = lists(&s);
        let label = format!("{path} {metric}, breadth-first to level {b}, {n} batches");
        assert!(n > 1 && b < 4, "{label}: not batched below a level");
        // The breadth-first levels are the unbatched ones.
        for k in 0..=b {
            let name = format!("light0.clusters{k}");
            if let Err(e) = same_cells(records(&batched, &name), records(&whole, &name)) {
                panic!("{label}: {name}: {e}");
            }
        }
        let mut photons = records(&batched, "light0.breadth.photons");
        let (mut slices, mut filled) = (vec![], 0);
        for i in 0..n {
            let slice = records(&batched, &format!("light0.batch{i}.clusters{b}"));
            // Batches are sized for the worst case (every cluster kept), so the last may be empty.
            filled += !slice.is_empty() as u32;
            // Below level B, the batch's lists are the unbatched ones restricted to its clusters.
            let ancestors: BTreeSet<[u32; 3]> = slice.iter().copied().collect();
            let of_batch = |c: [u32; 3], level: u32| ancestors.contains(&[c[0] >> (level - b), c[1] >> (level - b), b]);
            for k in b + 1..=4 {
                let got = records(&batched, &format!("light0.batch{i}.clusters{k}"));
                let want = records(&whole, &format!("light0.clusters{k}")).into_iter().filter(|&c| of_batch(c, k));
                if let Err(e) = same_cells(got, want.collect()) {
                    panic!("{label}: batch {i}'s clusters of level {k}: {e}");
                }
            }
            let batch_photons = records(&batched, &format!("light0.batch{i}.photons"));
            // A photon of level l has the coordinates of a cluster of level l + 1 (a converged
            // cluster of level k is stored as level k - 1): its ancestor of level B is l + 1 - B
            // levels up.
            for p in &batch_photons {
                let [x, y, l] = *p;
                let up = (l + 1)
                    .checked_sub(b)
                    .unwrap_or_else(|| panic!("{label}: batch {i}: photon {:?} above level {b}", *p));
                assert!(
                    ancestors.contains(&[x >> up, y >> up, b]),
                    "{label}: batch {i}: photon {:?} of another batch",
                    *p
                );
            }
            photons.extend(batch_photons);
            slices.extend(slice);
        }
        assert!(filled > 1, "{label}: {filled} batches hold clusters: a vacuous test");
        if let Err(e) = same_cells(slices, records(&whole, &format!("light0.clusters{b}"))) {
            panic!("{label}: the batches' slices of level {b} vs its list: {e}");
        }
        // Each photon once: the same cells as often as unbatched (where each cell is once).
        if let Err(e) = same_cells(photons, whole_photons) {
            panic!("{label}: the batches' photons vs the unbatched: {e}");
        }
    }
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
