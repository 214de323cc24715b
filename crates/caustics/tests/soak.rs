//! A short soak (`caustics::render::soak`): 400 animated throughput frames of a small scene.
//! After the first 100 the process's resident memory and the device memory stay within 1% and
//! no Vulkan object is made. (Alone in its test binary: resident memory is the process's.)

use caustics::render::soak::{drift, soak};
use caustics::scene::Scene;
use std::path::PathBuf;

mod common;
use common::context;

#[test]
fn animated_throughput_frames_hold_memory_and_objects_flat() {
    let (ctx, sh) = context();
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/sphere_on_plane.toml");
    let mut scene = Scene::load(&p).expect("shipped scene");
    scene.caustics.technique = "shah".parse().expect("technique");
    scene.caustics.photons = 64;
    scene.caustics.caustic_map_resolution = 128;
    scene.render.shadow_map_resolution = 128;
    scene.camera.width = 32;
    scene.camera.height = 32;
    scene.receiver_map = None;
    let samples = soak(&ctx, &sh, &scene, 400, 50, 20).expect("soak");
    assert_eq!(samples.len(), 8);
    assert!(samples.iter().all(|s| s.resident_bytes > 0 && s.device_reserved > 0), "{samples:?}");
    let (resident, device, objects) = drift(&samples, 100);
    assert_eq!(objects, 0, "Vulkan objects made after frame 100: {samples:?}");
    assert!(device < 0.01, "device memory drifted {:.2}%: {samples:?}", device * 100.0);
    assert!(resident < 0.01, "resident memory drifted {:.2}%: {samples:?}", resident * 100.0);
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}
