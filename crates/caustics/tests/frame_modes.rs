//! The two frame modes (`caustics::gpu::frame_mode`) render the same frames: one-shot
//! per-pass frames and throughput frames in flight (per-slot uniforms, moved meshes and a pool's
//! CPU-path fields copied from per-slot staging inside the frame) give the same final image and
//! caustic map along an animation. A warm throughput frame creates or allocates no Vulkan object
//! and submits once. `photon-trace --progressive`'s running means, shared by the frames in
//! flight, accumulate the same. Validation layer on; any message fails.

use caustics::animation::{scene_at, Animation};
use caustics::render::{FrameMode, FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use vkcore::{Context, ShaderCompiler};

mod common;
use common::{context, shipped};

fn small(mut s: Scene, technique: &str) -> Scene {
    s.caustics.technique = technique.parse().expect("a known technique");
    s.caustics.photons = 64;
    s.caustics.caustic_map_resolution = 128;
    s.render.shadow_map_resolution = 128;
    s.camera.width = 48;
    s.camera.height = 48;
    s.receiver_map = None;
    s
}

/// Channels of every layer of an image, flattened.
fn pixels(img: &caustics::image_io::ImageF32) -> Vec<f32> {
    img.layers.iter().flat_map(|l| l.data.iter().copied()).collect()
}

struct Frames {
    final_image: Vec<f32>,
    caustic_map: Option<Vec<f32>>,
    /// Per frame after the first `FrameMode::SLOTS`: (objects created, submits).
    warm: Vec<(u64, u64)>,
}

fn render(
    ctx: &Context,
    sh: &ShaderCompiler,
    scene: &Scene,
    anim: &Animation,
    mode: FrameMode,
    frames: u32,
    step: FrameStep,
) -> Frames {
    let opts = RendererOptions { frame_mode: mode, ..Default::default() };
    let mut r = Renderer::new(ctx, sh, scene, &opts).expect("renderer");
    let mut warm = vec![];
    for f in 0..frames {
        let before = ctx.counters();
        if f > 0 && !anim.is_static() {
            r.set_pose(&scene_at(scene, anim, f)).expect("pose");
        }
        match mode {
            FrameMode::PerPass => {
                r.frame(step).expect("frame");
            }
            FrameMode::Throughput { .. } => {
                r.submit(step).expect("submit");
            }
        }
        let used = ctx.counters().since(&before);
        if f >= FrameMode::SLOTS as u32 {
            warm.push((used.objects, used.submits));
        }
    }
    r.finish().expect("finish");
    let final_image = pixels(&r.final_image().expect("final image"));
    let caustic_map = r.dump("caustic_map").expect("dump").map(|i| pixels(&i));
    Frames { final_image, caustic_map, warm }
}

/// Renders `frames` and `frames + 1` frames of `scene` along `anim` in both modes (so that the
/// last frame is once in each ring slot) and compares the last frame's images: equal, or
/// (compute splats and appends: float atomics and atomic counters order photons differently from
/// run to run) within `tolerance` of the largest value.
fn same_in_both_modes(scene: &Scene, anim: Animation, frames: u32, step: FrameStep, tolerance: f32) {
    for n in [frames, frames + 1] {
        same_after(scene, anim.clone(), n, step, tolerance);
    }
}

fn same_after(scene: &Scene, anim: Animation, frames: u32, step: FrameStep, tolerance: f32) {
    let (ctx, sh) = context();
    let a = render(&ctx, &sh, scene, &anim, FrameMode::PerPass, frames, step);
    let b = render(&ctx, &sh, scene, &anim, FrameMode::throughput(), frames, step);
    let compare = |what: &str, x: &[f32], y: &[f32]| {
        assert_eq!(x.len(), y.len(), "{what}: sizes differ");
        // f32::max passes NaN over: every value must be finite for `worst` to mean anything.
        assert!(x.iter().chain(y).all(|v| v.is_finite()), "{what} of {}: a value is not finite", scene.path.display());
        let peak = x.iter().fold(0f32, |m, v| m.max(v.abs()));
        assert!(peak > 0.0, "{what} of {}: all zero, nothing to compare", scene.path.display());
        let worst = x.iter().zip(y).map(|(p, q)| (p - q).abs()).fold(0f32, f32::max);
        assert!(
            worst <= tolerance * peak,
            "{what} of {}: per-pass and throughput differ by {worst} (peak {peak})",
            scene.path.display()
        );
    };
    compare("final image", &a.final_image, &b.final_image);
    match (&a.caustic_map, &b.caustic_map) {
        (Some(x), Some(y)) => compare("caustic map", x, y),
        (None, None) => {}
        _ => panic!("one mode has a caustic map and the other not"),
    }
    assert!(!b.warm.is_empty());
    for (k, (objects, submits)) in b.warm.iter().enumerate() {
        assert_eq!(
            *objects,
            0,
            "warm throughput frame {} created or allocated {objects} Vulkan objects",
            k + FrameMode::SLOTS
        );
        assert_eq!(*submits, 1, "warm throughput frame {} submitted {submits} times", k + FrameMode::SLOTS);
    }
    assert!(a.warm.iter().all(|(objects, _)| *objects > 0), "a one-shot frame makes its own command buffer and fence");
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

fn orbit(light: bool, camera: bool, object: bool) -> Animation {
    Animation { light, camera, object, period_frames: 8 }
}

#[test]
fn shah_with_moving_objects_light_and_camera() {
    let scene = small(shipped("sphere_on_plane.toml"), "shah");
    same_in_both_modes(&scene, orbit(true, true, true), 5, FrameStep::default(), 0.0);
}

#[test]
fn eye_space_gather_with_static_lighting_reused() {
    let mut scene = small(shipped("sphere_on_plane.toml"), "wd-gather");
    scene.caustics.space = "eye".parse().expect("space");
    let step = FrameStep { reuse_photons: true, ..FrameStep::default() };
    same_in_both_modes(&scene, orbit(false, true, false), 5, step, 0.0);
}

#[test]
fn hierarchical_caustic_maps_on_both_traversal_paths() {
    // Transform feedback keeps the primitives' order, so its photons blend in a fixed order and
    // both modes agree bit for bit. The compute traversal appends photons with an atomic counter
    // (wyman2008/traverse.comp): their order, and so the rounding of the additive splat, changes
    // from run to run (CI saw 4.8e-7 on a peak of 12.6, 3.8e-8 of it).
    for (path, tolerance) in [("xfb", 0.0), ("compute", 1e-6)] {
        let mut scene = small(shipped("sphere_on_plane.toml"), "hcm");
        scene.caustics.path = path.parse().expect("path");
        scene.caustics.cluster = "all".parse().expect("cluster");
        same_in_both_modes(&scene, orbit(true, false, true), 4, FrameStep::default(), tolerance);
    }
}

#[test]
fn host_pass_times_submit_every_pass_and_render_the_same_frames() {
    // The bench's `pass_host_ms` frames (every pass submitted and waited for alone) render what
    // the throughput frames render, transform feedback traversal included.
    let mut scene = small(shipped("sphere_on_plane.toml"), "hcm");
    scene.caustics.cluster = "all".parse().expect("cluster");
    let step = FrameStep { host_pass_times: true, ..FrameStep::default() };
    same_in_both_modes(&scene, orbit(true, false, true), 3, step, 0.0);
    let (ctx, sh) = context();
    let frames = render(&ctx, &sh, &scene, &orbit(true, false, true), FrameMode::PerPass, 4, step);
    for (objects, submits) in &frames.warm {
        // Some 20 passes each submitted, and the frame's own last submit.
        assert!(*submits > 10, "a frame with host pass times submitted {submits} times ({objects} objects)");
    }
}

#[test]
fn adaptive_caustic_maps_batched_with_a_compute_splat() {
    let mut scene = small(shipped("sphere_on_plane.toml"), "adaptive");
    scene.caustics.photons = 128;
    scene.caustics.photon_batches = 2;
    scene.caustics.splat_path = "compute".parse().expect("splat path");
    same_in_both_modes(&scene, orbit(false, false, true), 4, FrameStep::default(), 1e-5);
}

#[test]
fn deferred_refraction_and_deferred_photons() {
    let mut scene = small(shipped("sphere_on_plane.toml"), "wd-points");
    scene.caustics.refraction = "deferred".parse().expect("refraction");
    scene.caustics.photon_refraction = "deferred".parse().expect("photon refraction");
    same_in_both_modes(&scene, orbit(true, true, true), 4, FrameStep::default(), 0.0);
}

#[test]
fn the_pool_on_its_gpu_and_cpu_paths() {
    for precision in ["float", "f64"] {
        let mut scene = shipped("pool.toml");
        scene.caustics.precision = precision.parse().expect("precision");
        scene.caustics.photons = 64;
        scene.camera.width = 48;
        scene.camera.height = 48;
        scene.receiver_map = None;
        same_in_both_modes(&scene, orbit(false, false, true), 4, FrameStep::default(), 0.0);
    }
}

#[test]
fn progressive_photons_accumulate_the_same_in_flight() {
    // The running means are one image shared by every ring slot: frames in flight must add to
    // them in order. A moving camera keeps accumulating; a moving light starts again each frame.
    for light in [false, true] {
        let mut scene = small(shipped("sphere_on_plane.toml"), "photon-trace");
        scene.caustics.progressive = true;
        same_in_both_modes(&scene, orbit(light, true, false), 6, FrameStep::default(), 0.0);
    }
}

#[test]
fn photon_differentials_splat_the_same_in_flight() {
    // A compute splat with float atomics: the order of the additions changes from run to run.
    let mut scene = small(shipped("sphere_on_plane.toml"), "photon-trace");
    scene.caustics.differentials = true;
    same_in_both_modes(&scene, orbit(true, true, false), 4, FrameStep::default(), 1e-5);
}
