//! The eye render with `--technique none`: a shadow map per light, Lambertian shading with
//! physically scaled irradiance, two-sided image-space refraction (Wyman 2005) and reflection
//! lookups, and the receiver map E/E0 that every caustic technique is validated with.

mod dumps;
mod eye;
pub mod gpu;
pub mod pipelines;
mod renderer;
pub mod setup;
pub mod targets;

pub use renderer::{FrameStep, Renderer, RendererOptions};

use crate::image_io::ImageF32;
use crate::scene::Scene;
use anyhow::Result;
use vkcore::{Context, FrameReport, ShaderCompiler};

/// Every intermediate buffer `--dump` accepts (`all` = every one): those of every render, then
/// those of the caustic techniques ([`CAUSTIC_DUMPS`]), the last of them `hcm`'s
/// ([`HIERARCHY_DUMPS`]).
pub const DUMP_NAMES: &[&str] = &[
    "shadow_map",
    "background",
    "refractor_back_faces",
    "refractor_front_faces",
    "eye_gbuffer",
    "receiver",
    "receiver_positions",
    "photon_back_faces",
    "photon_buffer",
    "caustic_map",
    "hierarchy",
    "hierarchy_lists",
    "splats",
];

/// The buffers only a caustic technique has.
pub const CAUSTIC_DUMPS: &[&str] = DUMP_NAMES.split_at(6).1;
/// The buffers only `hcm` has.
pub const HIERARCHY_DUMPS: &[&str] = DUMP_NAMES.split_at(10).1;
/// The light-space buffers that serve every light in turn (dumped light by light, layers
/// `light<l>.<layer>`; see `Renderer::dumps`).
pub const LIGHT_SPACE_DUMPS: &[&str] =
    &["photon_back_faces", "photon_buffer", "hierarchy", "hierarchy_lists", "splats"];

/// Techniques `--technique` accepts.
pub use crate::scene::TECHNIQUES;

#[derive(Debug, Clone, Default)]
pub struct RenderRequest {
    /// Names from `DUMP_NAMES` (already validated by the caller).
    pub dumps: Vec<String>,
    /// Frames rendered (timings are kept for each; the image is the last frame's).
    pub frames: u32,
}

pub struct Rendered {
    /// Linear radiance, RGB, row 0 = top of the image.
    pub final_image: ImageF32,
    /// (file stem, image) for each requested dump, e.g. ("shadow_map", ...) -> shadow_map.exr.
    pub dumps: Vec<(String, ImageF32)>,
    /// Per-pass GPU timings of every frame.
    pub frames: Vec<FrameReport>,
    /// Photons emitted per frame, all lights (0 for `none`).
    pub photons_emitted: u64,
}

/// The device features technique `name` needs (checked by the caller with `ctx.require`).
pub fn required_features(name: &str) -> Option<&'static [vkcore::Feature]> {
    match name {
        "none" => Some(&[vkcore::Feature::ShaderOutputLayer]),
        // Splats are points wider than one pixel.
        "shah" | "wd-points" | "hcm" => Some(&[vkcore::Feature::ShaderOutputLayer, vkcore::Feature::LargePoints]),
        "shah-vertex" => Some(&[
            vkcore::Feature::ShaderOutputLayer,
            vkcore::Feature::LargePoints,
            vkcore::Feature::VertexPipelineStoresAndAtomics,
        ]),
        _ => None,
    }
}

/// Checks that the device has every feature the scene's caustic technique (and, for `hcm`, its
/// traversal path) needs; the error names the feature.
pub fn check_device(ctx: &Context, scene: &Scene) -> Result<()> {
    let c = &scene.caustics;
    ctx.require(&format!("technique `{}`", c.technique), required_features(&c.technique).unwrap_or(&[]))?;
    if c.technique == "hcm" {
        if let Some(path) = crate::caustic_map::hierarchy::parse_path(&c.path) {
            let features = crate::caustic_map::hierarchy::path_features(path);
            ctx.require(&format!("technique `hcm` with --path {}", c.path), features)?;
        }
    }
    if c.technique != "none" && c.splat_path == "compute" {
        ctx.require(
            "splat_path `compute` (float atomics in photons/splat.comp)",
            crate::caustic_map::compute_splat::FEATURES,
        )?;
    }
    Ok(())
}

/// Renders `scene` with the caustic technique in `scene.caustics` `req.frames` times (at
/// least once) and reads back the last frame.
pub fn render(ctx: &Context, shaders: &ShaderCompiler, scene: &Scene, req: &RenderRequest) -> Result<Rendered> {
    let mut renderer = Renderer::new(ctx, shaders, scene, &RendererOptions::default())?;
    let mut frames = vec![];
    for _ in 0..req.frames.max(1) {
        frames.push(renderer.frame(FrameStep { reuse_photons: false, pipeline_statistics: true })?);
    }
    let final_image = renderer.final_image()?;
    let dumps = renderer.dumps(&req.dumps)?;
    Ok(Rendered { final_image, dumps, frames, photons_emitted: renderer.photons_emitted() })
}

/// The shader folder: `$CAUSTICLAB_SHADERS`, else `shaders_glsl/` found by walking up from the
/// current directory and from the executable, else the source tree this binary was built from.
pub fn shader_root() -> std::path::PathBuf {
    if let Some(p) = std::env::var_os("CAUSTICLAB_SHADERS") {
        return p.into();
    }
    let mut starts = vec![];
    if let Ok(cwd) = std::env::current_dir() {
        starts.push(cwd);
    }
    if let Ok(exe) = std::env::current_exe() {
        if let Some(d) = exe.parent() {
            starts.push(d.to_path_buf());
        }
    }
    for s in starts {
        for dir in s.ancestors() {
            let c = dir.join("shaders_glsl");
            if c.join("vkcore").is_dir() {
                return c;
            }
        }
    }
    std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shaders_glsl"))
}

#[cfg(test)]
mod tests {
    #[test]
    fn dump_groups_start_where_their_buffers_do() {
        assert_eq!(super::CAUSTIC_DUMPS.first(), Some(&"receiver_positions"));
        assert_eq!(super::HIERARCHY_DUMPS, &["hierarchy", "hierarchy_lists", "splats"]);
        for light_space in super::LIGHT_SPACE_DUMPS {
            assert!(super::CAUSTIC_DUMPS.contains(light_space), "{light_space}");
        }
    }
}
