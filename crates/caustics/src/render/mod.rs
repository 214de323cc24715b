//! The eye render with `--technique none`: a shadow map per light, Lambertian shading with
//! physically scaled irradiance, two-sided image-space refraction (Wyman 2005) and reflection
//! lookups, and the receiver map E/E0 that every caustic technique is validated with.

mod dispatch;
pub mod display;
mod dump_routing;
pub mod dumps;
mod eye;
pub mod graph;
pub mod memory;
mod metrics;
pub mod pipelines;
mod record;
mod renderer;
mod slot_data;
pub mod soak;
pub mod targets;

pub use crate::gpu::frame_mode::{FrameMode, FrameStep};
pub use dispatch::Renderer;
pub use renderer::{MeshRenderer, RendererOptions};

use crate::dump::Dump;
use crate::image_io::ImageF32;
use crate::scene::Scene;
use crate::techniques::shared::settings::PHOTON_BUFFER;
use crate::techniques::{Refraction, Technique};
use anyhow::Result;
use vkcore::{Context, FrameReport, ShaderCompiler};

pub use dumps::EYE_DUMPS;

/// The buffers `technique` can dump under any of its settings: the eye render's (both
/// refractions'), then the technique's own.
pub fn dumps_of(technique: Technique) -> Vec<&'static Dump> {
    if !technique.renders_meshes() {
        return technique.dumps();
    }
    [EYE_DUMPS.to_vec(), technique.dumps()].concat()
}

/// The buffers a render with `settings` dumps: the eye render's (with its refraction's), then
/// its technique's own under those settings.
pub fn dumps_for(settings: &crate::techniques::CausticSettings) -> Vec<&'static Dump> {
    if !settings.technique.renders_meshes() {
        return settings.dumps();
    }
    let other = |d: &&'static Dump| {
        Refraction::ALL.iter().any(|r| *r != settings.refraction && dumps::refraction_dumps(*r).contains(d))
    };
    EYE_DUMPS.iter().copied().filter(|d| !other(d)).chain(settings.dumps()).collect()
}

/// Every buffer some technique can dump (what `--dump` accepts): [`dumps::all_names`].
pub fn all_dump_names() -> Vec<&'static str> {
    dumps::all_names()
}

#[derive(Debug, Clone, Default)]
pub struct RenderRequest {
    /// `--dump` names (those the render does not have are skipped).
    pub dumps: Vec<String>,
    /// Frames rendered (timings are kept for each; the image is the last frame's).
    pub frames: u32,
    /// One-shot frames timed pass by pass, or throughput frames in flight.
    pub frame_mode: FrameMode,
}

pub struct Rendered {
    /// Linear radiance, RGB, row 0 = top of the image.
    pub final_image: ImageF32,
    /// Each requested dump the render has and its image (written as `<name>.exr`).
    pub dumps: Vec<(&'static Dump, ImageF32)>,
    /// Per-pass GPU timings of every frame.
    pub frames: Vec<FrameReport>,
    /// Per-pass frames: each frame's host wall time (record, submit, wait), ms.
    pub host_ms: Vec<f64>,
    /// What the last frame drew, read back from the GPU.
    pub counts: Counts,
}

/// The photon counts of a frame that the bench reports (`bench::metrics`): the same numbers
/// for the same scene and settings, whatever the frame mode or the code's shape, so a render's
/// `timings.json` holds them and `causticlab diff` compares them exactly.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Counts {
    /// Photons emitted per frame over all lights.
    pub photons_emitted: u64,
    /// Photon-buffer texels with `valid` set, all lights (photon-buffer techniques only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub valid_photons: Option<u64>,
    /// Points drawn or compute-splat invocations, all lights.
    pub splats_drawn: u64,
    /// Per light, the traversal's list sizes (`hcm`, `adaptive`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub list_sizes: Option<Vec<Vec<u64>>>,
}

/// Checks that the device has every feature the scene's caustic technique (and, for `hcm`, its
/// traversal path; for the compute splat, float atomics) needs, and the memory its images need
/// (`memory.rs`); the error names the feature, or the keys and the memory.
pub fn check_device(ctx: &Context, scene: &Scene) -> Result<()> {
    check_memory(ctx, scene)?;
    for (who, features) in scene.caustics.device_needs() {
        ctx.require(&who, features)?;
    }
    Ok(())
}

/// The memory check of [`check_device`] alone (a mesh scene's images against the device-local
/// heap, `memory.rs`): an input error naming the keys and the memory.
pub fn check_memory(ctx: &Context, scene: &Scene) -> Result<()> {
    if scene.caustics.technique.renders_meshes() {
        let info = ctx.info();
        if let Some(e) = memory::too_big(scene, &info.name, info.device_local_bytes) {
            return Err(crate::input_error!("{e}").into());
        }
    }
    Ok(())
}

/// Renders `scene` with the caustic technique in `scene.caustics` `req.frames` times (at
/// least once) and reads back the last frame.
pub fn render(ctx: &Context, shaders: &ShaderCompiler, scene: &Scene, req: &RenderRequest) -> Result<Rendered> {
    let opts = RendererOptions { frame_mode: req.frame_mode, ..Default::default() };
    let mut renderer = Renderer::new(ctx, shaders, scene, &opts)?;
    let mut frames = vec![];
    let mut host_ms = vec![];
    for _ in 0..req.frames.max(1) {
        let step = FrameStep { pipeline_statistics: true, ..FrameStep::default() };
        match req.frame_mode {
            FrameMode::PerPass => {
                let start = std::time::Instant::now();
                frames.push(renderer.frame(step)?);
                host_ms.push(start.elapsed().as_secs_f64() * 1e3);
            }
            FrameMode::Throughput { .. } => frames.extend(renderer.submit(step)?),
        }
    }
    frames.extend(renderer.finish()?);
    let final_image = renderer.final_image()?;
    let dumps = renderer.dumps(&req.dumps)?;
    // The photon buffer is read back once: from its dump where one was asked for.
    let photon_buffer = dumps.iter().find(|(d, _)| *d == &PHOTON_BUFFER).map(|(_, img)| img);
    let valid_photons = renderer.valid_photons(photon_buffer)?;
    let counts = Counts {
        photons_emitted: renderer.photons_emitted(),
        valid_photons,
        splats_drawn: renderer.splats_drawn()?,
        list_sizes: renderer.caustics().map(|c| c.list_sizes(ctx)).transpose()?.flatten(),
    };
    Ok(Rendered { final_image, dumps, frames, host_ms, counts })
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
    use super::*;

    #[test]
    fn a_render_has_each_name_once_and_its_refractions_buffers() {
        use crate::dump::Space;
        use dumps::all;
        // The eye render's buffers are read from its own targets, none light by light.
        for d in EYE_DUMPS {
            assert!(matches!(d.space, Space::Eye | Space::LightLayers), "{d}");
        }
        // One name, one declaration, but the pool's receiver map (a render has one or the other).
        for (i, a) in all().iter().enumerate() {
            for b in &all()[i + 1..] {
                let pool_and_eye = (a.space == Space::Pool) != (b.space == Space::Pool);
                assert!(a != b && (a.name != b.name || pool_and_eye), "{a} declared twice");
            }
        }
        for t in Technique::ALL {
            let names: Vec<&str> = dumps_of(*t).iter().map(|d| d.name).collect();
            let mut unique = names.clone();
            unique.sort();
            unique.dedup();
            assert_eq!(unique.len(), names.len(), "{t}: {names:?}");
        }
        let names = |c: &crate::techniques::CausticSettings| dumps_for(c).iter().map(|d| d.name).collect::<Vec<_>>();
        let mut c = crate::techniques::CausticSettings::default();
        assert_eq!(
            names(&c),
            ["shadow_map", "background", "refractor_back_faces", "refractor_front_faces", "eye_gbuffer", "receiver"]
        );
        c.refraction = Refraction::Deferred;
        assert_eq!(
            names(&c),
            ["shadow_map", "background", "refractor_geometry", "refraction_layers", "eye_gbuffer", "receiver"]
        );
    }
}
