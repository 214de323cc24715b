//! `photon-trace --trace ray-query` (rayQueryEXT against Vulkan acceleration structures) against
//! `--trace compute` (the shader's own BVH traversal), validation layer on:
//! - on the five scenes tests/photon_trace.rs tests the tracer on, with the same seed:
//!   - where the specular objects are smooth analytic meshes (the spheres, the ring), the two
//!     paths trace the same photons: the same photons land (one may land on one path only where
//!     the two triangle tests disagree at an edge: at most 1 in 10,000), each where the other
//!     puts it within 1e-4 of the scene's diagonal (their hit distances differ in the last bits:
//!     the driver's triangle test is not the shader's Moller-Trumbore), with the same power, and
//!     the directly binned receiver maps agree within 2% relative RMSE (photons that cross a
//!     texel edge by that rounding);
//!   - through the scanned bunny (tens of thousands of small triangles) a photon meets many
//!     shared edges, where the shader's test (not watertight) and the driver's disagree, and a
//!     photon refracted a little differently several times lands elsewhere (about 5% of them at
//!     256² photons on Mesa 25's lavapipe). There the photons are the same in distribution, not
//!     one by one: at most 0.5% land on one path only, the caustic flux agrees within 0.1%, and
//!     the receiver maps differ by less than half of what two seeds of the compute path differ
//!     by (its noise);
//! - an object that moves (the compute path refuses it: its BVH is built once): with ray
//!   queries, in each pose of `sphere_on_plane`'s animated sphere (turned a quarter and moved,
//!   back, squashed, ...) the receiver map matches the CPU reference of that pose (caustic flux
//!   within 1%, relative RMSE under half of its RMSE against another pose's reference, which a
//!   stale structure would match instead), with `moving_objects = "transform"` (a rigid motion
//!   moves the sphere's instance and builds no bottom level; the squash rebuilds it) and
//!   `"rebuild"` (every pose rebuilds it) and `"refit"` (every pose refits it in place), each pose
//!   building one top level; a pose that
//!   changes the sphere's triangles is refused naming it;
//! - a device without acceleration structures or ray queries refuses `trace = "ray-query"`
//!   naming the feature (Mesa 22.3's lavapipe has neither; here they are also hidden).
//!
//! The first needs a device with ray queries: `scripts/mesa25_check.sh` runs it on Mesa 25's
//! lavapipe (`CAUSTICLAB_TEST_DEVICE`), with `CAUSTICLAB_REQUIRE_RAY_QUERY=1` so that it fails
//! rather than skips there; elsewhere it says it is skipped and passes.

// `!(error <= bound)` fails a NaN, where `error > bound` would pass it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use caustics::compare::compare;
use caustics::image_io::ImageF32;
use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::photon_trace::settings::Trace;
use vkcore::{Context, ContextOptions, Feature, ShaderCompiler};

mod common;
use common::{context, shipped};

/// Each scene, and whether its photons are compared one by one (else in distribution).
const SCENES: [(&str, bool); 5] = [
    ("sphere_on_plane.toml", true),
    ("sphere_oblique.toml", true),
    ("ring_cardioid.toml", true),
    ("stacked_spheres.toml", true),
    ("bunny_in_room.toml", false),
];

fn scene(name: &str, trace: Trace) -> Scene {
    let mut s = shipped(name);
    s.caustics.technique = "photon-trace".parse().expect("a known name");
    s.caustics.photons = 256;
    s.caustics.deposit = "receiver-map".parse().expect("a known name");
    s.caustics.trace = trace;
    s.camera.width = 64;
    s.camera.height = 64;
    s
}

/// The photon buffer and the receiver map of one frame of `s`.
fn trace(ctx: &Context, sh: &ShaderCompiler, s: &Scene) -> (ImageF32, ImageF32) {
    let mut r = Renderer::new(ctx, sh, s, &RendererOptions::default()).expect("renderer");
    r.frame(FrameStep::default()).expect("frame");
    let mut dumps = r.dumps(&["photon_buffer".to_string(), "receiver".to_string()]).expect("dumps");
    let (receiver, photons) = (dumps.pop().expect("receiver").1, dumps.pop().expect("photons").1);
    (photons, receiver)
}

/// Per photon: (x, y, z, landed) and its power's (r, g, b).
fn photons(buffer: &ImageF32) -> Vec<([f32; 4], [f32; 3])> {
    let pos = buffer.layer(Some("light0.position")).expect("positions");
    let pow = buffer.layer(Some("light0.power")).expect("power");
    let (np, nw) = (pos.channels.len(), pow.channels.len());
    pos.data
        .chunks_exact(np)
        .zip(pow.data.chunks_exact(nw))
        .map(|(p, w)| ([p[0], p[1], p[2], p[3]], [w[0], w[1], w[2]]))
        .collect()
}

/// The test context where it has ray queries; elsewhere None, after saying the test is
/// skipped (a failure with `CAUSTICLAB_REQUIRE_RAY_QUERY` set, as scripts/mesa25_check.sh sets it).
fn ray_query_context() -> Option<(Context, ShaderCompiler)> {
    let (ctx, sh) = context();
    if ctx.info().has(Feature::RayQuery) {
        return Some((ctx, sh));
    }
    let line =
        format!("`{}` has no ray queries (scripts/mesa25_check.sh runs this on Mesa 25's lavapipe)", ctx.info().name);
    assert!(std::env::var_os("CAUSTICLAB_REQUIRE_RAY_QUERY").is_none(), "{line}");
    println!("skipped: {line}");
    None
}

#[test]
fn ray_queries_trace_the_compute_paths_photons_on_five_scenes() {
    let Some((ctx, sh)) = ray_query_context() else { return };
    let mut failures = vec![];
    for (name, one_by_one) in SCENES {
        let (bvh, bvh_receiver) = trace(&ctx, &sh, &scene(name, Trace::Compute));
        let s = scene(name, Trace::RayQuery);
        let (rq, rq_receiver) = trace(&ctx, &sh, &s);
        let (lo, hi) = s.bounds();
        let tolerance = 1e-4 * (hi - lo).length();
        let (a, b) = (photons(&rq), photons(&bvh));
        let landed = b.iter().filter(|p| p.0[3] > 0.5).count();
        let mut one_side = 0;
        let mut far = 0;
        let mut worst = 0.0f32;
        for ((pa, wa), (pb, wb)) in a.iter().zip(&b) {
            if (pa[3] > 0.5) != (pb[3] > 0.5) {
                one_side += 1;
                continue;
            }
            if pb[3] < 0.5 {
                continue;
            }
            let d = ((pa[0] - pb[0]).powi(2) + (pa[1] - pb[1]).powi(2) + (pa[2] - pb[2]).powi(2)).sqrt();
            worst = worst.max(d);
            if !(d <= tolerance) || wa != wb {
                far += 1;
            }
        }
        let (c, _) = compare(&rq_receiver, &bvh_receiver).expect("compare");
        println!(
            "{name}: {landed} of {} photons landed; {one_side} on one path only; {far} apart by more than {tolerance:.2e} \
             or of another power; farthest {worst:.2e}; receiver map rel. RMSE {:.5}, flux ratio {:.6}",
            b.len(),
            c.rel_rmse,
            c.caustic_flux_ratio
        );
        if !((c.caustic_flux_ratio - 1.0).abs() <= 1e-3) || landed == 0 {
            failures.push(format!("{name}: {landed} landed; caustic flux ratio {}", c.caustic_flux_ratio));
        }
        if one_by_one {
            if one_side * 10_000 > b.len() || far * 10_000 > b.len() || !(c.rel_rmse <= 0.02) {
                failures.push(format!("{name}: {one_side} on one path only, {far} apart; {c:?}"));
            }
        } else {
            let mut other_seed = scene(name, Trace::Compute);
            other_seed.caustics.seed += 1;
            let (_, seed_receiver) = trace(&ctx, &sh, &other_seed);
            let (noise, _) = compare(&seed_receiver, &bvh_receiver).expect("compare");
            println!("{name}: two seeds of the compute path differ by rel. RMSE {:.5}", noise.rel_rmse);
            if one_side * 200 > b.len() || !(c.rel_rmse <= 0.5 * noise.rel_rmse) {
                failures.push(format!("{name}: {one_side} on one path only; {c:?} against the noise {noise:?}"));
            }
        }
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `base` with its object `name` squashed to `0.7` of its height about its centre (not a rigid
/// motion), the normals turned as a squash turns them.
fn squashed(base: &Scene, name: &str) -> Scene {
    let mut s = base.clone();
    let obj = s.objects.iter_mut().find(|o| o.name == name).expect("the object");
    let (lo, hi) = obj.mesh.bounds();
    let centre = 0.5 * (lo + hi);
    let k = glam::Vec3::new(1.0, 0.7, 1.0);
    obj.mesh.positions.iter_mut().for_each(|p| *p = centre + (*p - centre) * k);
    obj.mesh.normals.iter_mut().for_each(|n| *n = (*n / k).normalize_or_zero());
    s
}

#[test]
fn ray_queries_follow_a_moving_object_pose_by_pose() {
    use caustics::animation::{scene_at, Animation};
    use caustics::reference::{trace_reference, ReferenceOptions};
    use caustics::techniques::photon_trace::settings::MovingObjects;
    let Some((ctx, sh)) = ray_query_context() else { return };
    let mut base = scene("sphere_on_plane.toml", Trace::RayQuery);
    base.caustics.fresnel = false;
    base.receiver_map.as_mut().expect("a receiver map").resolution = 32;
    let anim = Animation { light: false, camera: false, object: true, period_frames: 4 };
    // Pose 1 turns the sphere a quarter about its vertical axis and moves it (rigid); pose 2
    // squashes it (not rigid).
    let mut poses: Vec<Scene> = [0, 1].iter().map(|&f| scene_at(&base, &anim, f)).collect();
    poses.push(squashed(&base, "sphere"));
    let references: Vec<ImageF32> = poses
        .iter()
        .map(|p| {
            let opts = ReferenceOptions { photons: 1_000_000, fresnel: false, ..Default::default() };
            trace_reference(p, &opts).expect("reference").image
        })
        .collect();
    let mut failures = vec![];
    for moving in [MovingObjects::Transform, MovingObjects::Rebuild, MovingObjects::Refit] {
        let mut first = poses[0].clone();
        first.caustics.moving_objects = moving;
        let mut r = Renderer::new(&ctx, &sh, &first, &RendererOptions::default()).expect("renderer");
        // Each pose after the one before it, with the bottom levels it should build: a rigid
        // motion from the mesh the sphere's bottom level was built over moves its instance
        // (`transform`), anything else rebuilds it. After the squash that mesh is the squashed
        // one, so pose 1 is not a rigid motion of it. `refit` builds none and refits one.
        let rigid_blas = u64::from(moving == MovingObjects::Rebuild);
        let refit = moving == MovingObjects::Refit;
        let steps = [(1, rigid_blas), (0, rigid_blas), (2, 1), (1, 1), (0, rigid_blas)];
        for (i, blas) in steps.map(|(i, b)| (i, if refit { 0 } else { b })) {
            let mut pose = poses[i].clone();
            pose.caustics.moving_objects = moving;
            let before = ctx.counters();
            let start = std::time::Instant::now();
            r.set_pose(&pose).expect("ray queries follow a moving object");
            let posed = start.elapsed();
            let built = ctx.counters().since(&before);
            r.frame(FrameStep::default()).expect("frame");
            let receiver = r.receiver_map().expect("read").expect("a receiver map");
            let (own, _) = compare(&receiver, &references[i]).expect("compare");
            let other = if i == 1 { 0 } else { 1 };
            let (against_other, _) = compare(&receiver, &references[other]).expect("compare");
            println!(
                "{moving}, pose {i}: set_pose {:.1} ms, {} bottom level(s) built, {} refitted, {} top level(s) built; \
                 against its reference rel. RMSE {:.4}, flux ratio {:.4}; against pose {other}'s rel. RMSE {:.4}",
                posed.as_secs_f64() * 1e3,
                built.blas_builds,
                built.blas_refits,
                built.tlas_builds,
                own.rel_rmse,
                own.caustic_flux_ratio,
                against_other.rel_rmse
            );
            let refits = u64::from(refit);
            if (built.blas_builds, built.blas_refits, built.tlas_builds) != (blas, refits, 1) {
                failures.push(format!(
                    "{moving}, pose {i}: {} bottom levels built, {} refitted and {} top levels built, expected {blas}, \
                     {refits} and 1",
                    built.blas_builds, built.blas_refits, built.tlas_builds
                ));
            }
            if !own.within(0.5 * against_other.rel_rmse, 0.01) {
                failures.push(format!(
                    "{moving}, pose {i}: {own:?} against its reference, {against_other:?} against pose {other}'s"
                ));
            }
        }
    }
    // A pose may move the sphere, not change its triangles (the tracer's buffers hold them).
    let mut r = Renderer::new(&ctx, &sh, &poses[0], &RendererOptions::default()).expect("renderer");
    let mut fewer = poses[1].clone();
    let sphere = fewer.objects.iter_mut().find(|o| o.name == "sphere").expect("the sphere");
    sphere.mesh.indices.truncate(sphere.mesh.indices.len() - 3);
    let e = r.set_pose(&fewer).err().map(|e| format!("{e:#}")).unwrap_or_default();
    if !(e.contains("`sphere`") && e.contains("triangles")) {
        failures.push(format!("a pose with a triangle fewer: {e:?}"));
    }
    // A refit moves vertices only: the same triangles in another order are refused, by name.
    let mut first = poses[0].clone();
    first.caustics.moving_objects = MovingObjects::Refit;
    let mut r = Renderer::new(&ctx, &sh, &first, &RendererOptions::default()).expect("renderer");
    let mut reordered = poses[1].clone();
    reordered.caustics.moving_objects = MovingObjects::Refit;
    let sphere = reordered.objects.iter_mut().find(|o| o.name == "sphere").expect("the sphere");
    sphere.mesh.indices.rotate_left(3);
    let e = r.set_pose(&reordered).err().map(|e| format!("{e:#}")).unwrap_or_default();
    if !(e.contains("`sphere`") && e.contains("other triangles") && e.contains("refit")) {
        failures.push(format!("refit, a pose with the triangles reordered: {e:?}"));
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_refit_needs_a_structure_built_for_it_and_the_same_triangles() {
    use vkcore::AccelerationStructure;
    let Some((ctx, _)) = ray_query_context() else { return };
    let quad = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    let moved = quad.map(|[x, y, z]| [x, y, z + 0.5]);
    let indices = [0, 1, 2, 0, 2, 3];
    let mut fixed = AccelerationStructure::triangles(&ctx, "fixed", &quad, &indices).expect("built");
    let e = fixed.refit(&ctx, &moved, &indices).expect_err("not updatable").to_string();
    assert!(e.contains("`fixed`") && e.contains("not built to be refitted"), "{e}");
    let mut updatable = AccelerationStructure::triangles_updatable(&ctx, "updatable", &quad, &indices).expect("built");
    let before = ctx.counters();
    updatable.refit(&ctx, &moved, &indices).expect("the same triangles, moved");
    let e = updatable.refit(&ctx, &moved, &indices[..3]).expect_err("a triangle fewer").to_string();
    assert!(e.contains("`updatable`") && e.contains("2 over 4") && e.contains("1 over 4"), "{e}");
    let swapped = [0, 2, 3, 0, 1, 2];
    let e = updatable.refit(&ctx, &moved, &swapped).expect_err("other indices").to_string();
    assert!(e.contains("`updatable`") && e.contains("with other indices"), "{e}");
    let counted = ctx.counters().since(&before);
    assert_eq!((counted.blas_refits, counted.blas_builds), (1, 0), "one refit, no build");
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

#[test]
fn a_device_without_ray_queries_refuses_them_by_name() {
    for hidden in [Feature::AccelerationStructure, Feature::RayQuery] {
        let ctx = Context::new(&ContextOptions::for_tests(vec![hidden])).expect("a device");
        let sh = ShaderCompiler::new(&caustics::render::shader_root()).expect("shaderc");
        assert!(!ctx.info().has(Feature::RayQuery), "hiding {hidden:?} hides ray queries");
        let s = scene("sphere_on_plane.toml", Trace::RayQuery);
        let e = Renderer::new(&ctx, &sh, &s, &RendererOptions::default()).err().expect("refused").to_string();
        // The first of the two the device lacks (Mesa 22.3's lavapipe lacks both).
        let missing = [Feature::AccelerationStructure, Feature::RayQuery].into_iter().find(|&f| !ctx.info().has(f));
        let missing = missing.expect("one is hidden").name();
        assert!(e.contains("trace `ray-query`") && e.contains(missing), "hiding {hidden:?}: {e}");
    }
}
