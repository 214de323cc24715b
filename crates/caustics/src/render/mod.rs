//! The eye render with `--technique none`: a shadow map per light, Lambertian shading with
//! physically scaled irradiance, two-sided image-space refraction (Wyman 2005) and reflection
//! lookups, and the receiver map E/E0 that every caustic technique is validated with.

mod dumps;
use crate::caustic_map;
mod eye;
pub mod gpu;
pub mod pipelines;
pub mod setup;
pub mod targets;

use crate::image_io::ImageF32;
use crate::scene::Scene;
use anyhow::Result;
use vkcore::{Context, Filter, FrameOptions, FrameReport, Sampler, ShaderCompiler};

/// Every intermediate buffer `--dump` accepts (`all` = every one).
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
];

/// The buffers only a caustic technique has.
pub const CAUSTIC_DUMPS: &[&str] = &["receiver_positions", "photon_back_faces", "photon_buffer", "caustic_map"];

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
        "shah" | "wd-points" => Some(&[vkcore::Feature::ShaderOutputLayer, vkcore::Feature::LargePoints]),
        "shah-vertex" => Some(&[
            vkcore::Feature::ShaderOutputLayer,
            vkcore::Feature::LargePoints,
            vkcore::Feature::VertexPipelineStoresAndAtomics,
        ]),
        _ => None,
    }
}

/// Renders `scene` with the caustic technique in `scene.caustics` `req.frames` times (at
/// least once) and reads back the last frame.
pub fn render(ctx: &Context, shaders: &ShaderCompiler, scene: &Scene, req: &RenderRequest) -> Result<Rendered> {
    let settings = &scene.caustics;
    let technique = settings.technique.as_str();
    ctx.require(&format!("technique `{technique}`"), required_features(technique).unwrap_or(&[]))?;
    if scene.lights.len() > gpu::MAX_LIGHTS {
        return Err(crate::input_error!(
            "{}: {} lights; at most {} are supported",
            scene.path.display(),
            scene.lights.len(),
            gpu::MAX_LIGHTS
        )
        .into());
    }
    let active = technique != "none" && caustic_map::gpu::specular_bounds(scene).is_some();
    let pipelines = pipelines::EyePipelines::new(ctx, shaders)?;
    let meshes = setup::upload_meshes(ctx, scene)?;
    let uniforms = ctx.buffer_with_data("frame uniforms", bytemuck::bytes_of(&setup::frame_uniforms(scene)))?;
    let mut cu = caustic_map::gpu::caustic_uniforms(scene, settings)?;
    if !active {
        cu.settings[0] = 0;
    }
    let caustic_uniforms = ctx.buffer_with_data("caustic uniforms", bytemuck::bytes_of(&cu))?;
    let targets = targets::EyeTargets::new(ctx, scene)?;
    let caustic_targets = caustic_map::CausticTargets::new(ctx, scene, active)?;
    let spot = setup::spot_texture_layers(scene)?;
    for l in 0..targets.shadow.lights {
        let n = (setup::SPOT_TEXTURE_SIZE * setup::SPOT_TEXTURE_SIZE * 4) as usize;
        ctx.upload_image(
            &targets.spot_textures.image,
            0,
            l,
            bytemuck::cast_slice(&spot[l as usize * n..(l as usize + 1) * n]),
        )?;
    }
    let nearest = Sampler::new(ctx, Filter::Nearest)?;
    let linear = Sampler::new(ctx, Filter::Linear)?;
    // The caustic technique's own resources.
    let vertex_photons = technique == "shah-vertex";
    let specular_vertices: u32 =
        meshes.iter().filter(|m| m.kind() != gpu::MATERIAL_DIFFUSE).map(|m| (m.vertices.size() / 28) as u32).sum();
    let caustic = if active {
        let photon_side =
            if vertex_photons { (specular_vertices as f64).sqrt().ceil() as u32 } else { settings.photons };
        let areas = if vertex_photons {
            setup::vertex_areas(ctx, scene)?
        } else {
            scene.objects.iter().map(|_| None).collect()
        };
        let ids: Vec<u32> = (0..caustic_map::passes_verts_per_instance()).collect();
        Some((
            caustic_map::CausticPipelines::new(ctx, shaders, technique)?,
            caustic_map::PhotonTargets::new(ctx, settings.photons, photon_side)?,
            areas,
            ctx.buffer_with_data("splat vertices", bytemuck::cast_slice(&ids))?,
        ))
    } else {
        None
    };
    let eye_inputs = eye::EyeInputs {
        uniforms: &uniforms,
        caustic_uniforms: &caustic_uniforms,
        caustics: &caustic_targets,
        meshes: &meshes,
        nearest: &nearest,
        linear: &linear,
    };
    let mut frames = vec![];
    for _ in 0..req.frames.max(1) {
        let mut f = ctx.frame(FrameOptions { timestamps: true, pipeline_statistics: true })?;
        match &caustic {
            Some((cp, pt, areas, splat_vertices)) => {
                let inputs = caustic_map::CausticInputs {
                    frame_uniforms: &uniforms,
                    caustic_uniforms: &caustic_uniforms,
                    meshes: &meshes,
                    vertex_areas: areas,
                    splat_vertices,
                    nearest: &nearest,
                };
                caustic_map::record_caustics(&mut f, cp, &caustic_targets, pt, &inputs, targets.shadow.lights)?;
            }
            None => caustic_map::record_cleared(&mut f, &caustic_targets)?,
        }
        eye::record(&mut f, &pipelines, &targets, &eye_inputs)?;
        frames.push(f.submit()?);
    }
    let final_image = dumps::final_image(ctx, &targets)?;
    let mut out = vec![];
    for name in &req.dumps {
        let photons = caustic.as_ref().map(|c| &c.1);
        if let Some(img) = dumps::dump(ctx, &targets, &caustic_targets, photons, name)? {
            out.push((name.clone(), img));
        }
    }
    let photons_emitted = caustic_map::photons_per_light(settings, specular_vertices)
        * if active { targets.shadow.lights as u64 } else { 0 };
    Ok(Rendered { final_image, dumps: out, frames, photons_emitted })
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
