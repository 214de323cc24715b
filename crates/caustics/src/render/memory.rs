//! The device memory a frame's images need, checked before anything is allocated: a scene that
//! asks for more than the device has is an input error naming the keys that size it and the
//! memory they need against the device's, not an allocator's "out of memory" halfway through
//! making the renderer.
//!
//! The count is a lower bound: the images the scene's keys size, in the formats `targets.rs`,
//! `techniques/shared/targets.rs` and the receiver map make them (meshes, pipelines, buffers of
//! a technique's own and staging are left out), so a scene it refuses cannot be rendered, and
//! a scene it lets through may still fail in the allocator near the limit.

use super::targets::EyeTargets;
use crate::gpu::{formats, MAX_LIGHTS};
use crate::scene::Scene;
use crate::techniques::Technique;
use vkcore::Format;

/// Bytes per texel of one of the render targets' formats (`gpu::formats`).
fn texel(format: Format) -> u64 {
    vkcore::texel_size(format).expect("every render-target format has a texel size") as u64
}

/// Memory one scene key asks for.
#[derive(Debug, Clone, PartialEq)]
pub struct Need {
    /// The scene key (as in the scene file) that sizes it.
    pub key: &'static str,
    /// Its value, as the user wrote it.
    pub value: String,
    /// What it sizes.
    pub what: &'static str,
    pub bytes: u64,
}

/// What the mesh renderer's images need, by the key that sizes them.
pub fn needs(scene: &Scene) -> Vec<Need> {
    let (color, distance, depth) = (texel(formats::COLOR), texel(formats::DISTANCE), texel(formats::DEPTH));
    let lights = scene.lights.len().clamp(1, MAX_LIGHTS) as u64;
    let (w, h) = (scene.camera.width as u64, scene.camera.height as u64);
    let mut out = vec![Need {
        key: "camera.resolution",
        value: format!("{w}x{h}"),
        what: "the eye render's images",
        bytes: w * h * (EyeTargets::COLOR_IMAGES * color + EyeTargets::DEPTH_IMAGES * depth),
    }];
    let s = scene.render.shadow_map_resolution as u64;
    out.push(Need {
        key: "render.shadow_map_resolution",
        value: s.to_string(),
        what: "the shadow maps (six faces per light)",
        bytes: s * s * 6 * lights * (distance + depth),
    });
    if let Some(r) = &scene.receiver_map {
        let r = r.resolution as u64;
        out.push(Need {
            key: "receiver_map.resolution",
            value: r.to_string(),
            what: "the receiver map's three images",
            bytes: r * r * 3 * color,
        });
    }
    let c = &scene.caustics;
    if c.technique.has_caustics() && c.technique.renders_meshes() {
        let m = c.caustic_map_resolution as u64;
        out.push(Need {
            key: "caustics.caustic_map_resolution",
            value: m.to_string(),
            what: "the caustic maps and receiver positions",
            bytes: m * m * lights * (c.caustic_levels() as u64 * color + color + depth),
        });
        // The photon buffer (position, direction, power) and the light-space back faces and
        // depth, reused light after light; adaptive caustic maps have none (their photon
        // storage is planned under `photon_memory_limit`), vertex photons only the back faces.
        let n = c.photons as u64;
        let per_photon = match c.technique {
            Technique::Adaptive => 0,
            Technique::ShahVertex => color + depth,
            _ => 3 * color + color + depth,
        };
        if per_photon > 0 {
            out.push(Need {
                key: "caustics.photons",
                value: n.to_string(),
                what: "the photon buffer and the light-space back faces",
                bytes: n * n * per_photon,
            });
        }
    }
    out
}

/// The error when the images of `scene` need more than `device_bytes` (the device's largest
/// device-local heap) on `device`; None when they fit.
pub fn too_big(scene: &Scene, device: &str, device_bytes: u64) -> Option<String> {
    let mut needs = needs(scene);
    let total: u64 = needs.iter().map(|n| n.bytes).sum();
    if total <= device_bytes {
        return None;
    }
    needs.sort_by_key(|n| std::cmp::Reverse(n.bytes));
    let list: Vec<String> = needs
        .iter()
        .filter(|n| n.bytes > 0)
        .map(|n| format!("`{}` = {}: {} {}", n.key, n.value, mib(n.bytes), n.what))
        .collect();
    Some(format!(
        "{}: key `{}`: the frame's images need at least {} of device memory, but `{device}` has {} \
         (device-local heap); by key: {}",
        scene.path.display(),
        needs[0].key,
        mib(total),
        mib(device_bytes),
        list.join("; ")
    ))
}

fn mib(bytes: u64) -> String {
    format!("{:.0} MiB", bytes as f64 / (1024.0 * 1024.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_large_camera_is_named_first_with_its_bytes() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/sphere_on_plane.toml");
        let mut scene = Scene::load(&path).expect("shipped scene");
        scene.camera.width = 16384;
        scene.camera.height = 16384;
        let err = too_big(&scene, "dev", 2 << 30).expect("refused");
        // 16384² texels of seven RGBA32F images and two D32F depth images: 30720 MiB.
        assert!(err.contains("key `camera.resolution`") && err.contains("30720 MiB the eye render"), "{err}");
        assert!(err.contains("2048 MiB (device-local heap)"), "{err}");
        scene.camera.width = 512;
        scene.camera.height = 512;
        assert_eq!(too_big(&scene, "dev", 2 << 30), None);
    }
}
