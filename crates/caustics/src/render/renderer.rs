//! The mesh renderer: keeps its pipelines, targets and photon buffers between frames, so that a
//! benchmark can render many frames of an animation (uniforms and moving meshes updated per
//! frame) and time each one. Its parts: the per-frame data (`super::slot_data`), the frame's
//! passes (`super::record`), dump routing (`super::dump_routing`) and the counts the bench
//! reports (`super::metrics`); frames are submitted by `crate::gpu::frames`, as a technique's
//! own renderer's are (the pool's: `techniques::own_renderer`).

use super::slot_data::SlotData;
use super::{dumps, pipelines, targets};
use crate::dump::Dump;
use crate::gpu::frames::{FrameRenderer, Frames, RecordFrame, Slot};
use crate::gpu::{self, setup, FrameMode, FrameStep};
use crate::image_io::ImageF32;
use crate::scene::Scene;
use crate::techniques::stages::{self, CausticPipeline, EyeRefraction};
use crate::techniques::{self, CopyType};
use anyhow::{Context as _, Result};
use vkcore::{Context, Filter, Frame, Sampler, ShaderCompiler};

/// Choices fixed for the renderer's lifetime.
#[derive(Debug, Clone, Copy, Default)]
pub struct RendererOptions {
    /// Copy the photon buffer into a vertex array before splatting (Wyman 2008 Table 1-2).
    pub photon_copy: Option<CopyType>,
    /// One-shot frames timed pass by pass, or a ring of frames in flight (`crate::gpu::frame_mode`).
    pub frame_mode: FrameMode,
    /// Throughput frames: a timestamp pair around every pass (without the per-pass frames'
    /// barrier), for the viewer's per-pass graph; else one around the frame.
    pub pass_timestamps: bool,
}

pub struct MeshRenderer<'c> {
    pub(super) ctx: &'c Context,
    pub(super) shaders: &'c ShaderCompiler,
    pub(super) scene: Scene,
    pub(super) active: bool,
    pub(super) pipelines: pipelines::EyePipelines,
    pub(super) meshes: Vec<setup::GpuMesh>,
    pub(super) frames: Frames,
    pub(super) slots: SlotData,
    pub(super) targets: targets::EyeTargets,
    pub(super) caustic_targets: techniques::CausticTargets,
    pub(super) nearest: Sampler,
    pub(super) linear: Sampler,
    /// The technique's caustic stages (none without caustics or specular objects).
    pub(super) caustic: Option<CausticPipeline>,
    pub(super) specular_vertices: u32,
    pub(super) photons_ready: bool,
    /// The eye's refraction (`caustics.refraction`): forward, or deferred refraction's passes.
    pub(super) refraction: EyeRefraction,
}

impl<'c> MeshRenderer<'c> {
    pub fn new(ctx: &'c Context, shaders: &'c ShaderCompiler, scene: &Scene, opts: &RendererOptions) -> Result<Self> {
        let settings = &scene.caustics;
        settings.validate_combination(&scene.path.display().to_string(), "caustics.")?;
        super::check_device(ctx, scene)?;
        if scene.lights.len() > gpu::MAX_LIGHTS {
            return Err(crate::input_error!(
                "{}: {} lights; at most {} are supported",
                scene.path.display(),
                scene.lights.len(),
                gpu::MAX_LIGHTS
            )
            .into());
        }
        stages::check_photon_copy(settings, opts.photon_copy)?;
        let active = settings.technique.has_caustics() && techniques::uniforms::specular_bounds(scene).is_some();
        let pipelines = pipelines::EyePipelines::new(ctx, shaders)?;
        let meshes = setup::upload_meshes(ctx, scene)?;
        let slots = SlotData::new(ctx, opts.frame_mode, uniforms_of(scene, active)?)?;
        let targets = targets::EyeTargets::new(ctx, scene)?;
        let caustic_targets = techniques::CausticTargets::new(ctx, scene, active)?;
        let spot = setup::spot_texture_layers(scene)?;
        for l in 0..targets.shadow.lights {
            let n = (setup::SPOT_TEXTURE_SIZE * setup::SPOT_TEXTURE_SIZE * 4) as usize;
            let layer = &spot[l as usize * n..(l as usize + 1) * n];
            ctx.upload_image(&targets.spot_textures.image, 0, l, bytemuck::cast_slice(layer))?;
        }
        let specular_vertices = stages::specular_vertices(&meshes);
        let caustic = match active {
            true => Some(CausticPipeline::new(ctx, shaders, scene, &meshes, opts.photon_copy)?),
            false => None,
        };
        Ok(MeshRenderer {
            ctx,
            shaders,
            scene: scene.clone(),
            active,
            pipelines,
            meshes,
            frames: Frames::new(ctx, opts.frame_mode, opts.pass_timestamps)?,
            slots,
            targets,
            caustic_targets,
            nearest: Sampler::new(ctx, Filter::Nearest)?,
            linear: Sampler::new(ctx, Filter::Linear)?,
            caustic,
            specular_vertices,
            photons_ready: false,
            refraction: EyeRefraction::new(ctx, shaders, scene)?,
        })
    }

    /// The technique's caustic stages (None without caustics or specular objects).
    pub fn caustics(&self) -> Option<&CausticPipeline> {
        self.caustic.as_ref()
    }

    /// `photon-trace --progressive`: the next frame starts its means again.
    pub fn restart_accumulation(&mut self) {
        if let Some(c) = self.caustic.as_mut() {
            c.restart_accumulation();
        }
    }
}

/// A frame: its uniforms (and moved meshes), then every pass (`super::record`).
impl RecordFrame for MeshRenderer<'_> {
    fn ctx(&self) -> &Context {
        self.ctx
    }

    fn frames(&mut self) -> &mut Frames {
        &mut self.frames
    }

    fn record(&mut self, f: &mut Frame, slot: Option<Slot>, step: FrameStep) -> Result<()> {
        if let Some(radius) = self.caustic.as_mut().and_then(|c| c.next_frame()) {
            self.slots.set_splat_radius(radius);
        }
        self.slots.record(self.ctx, f, slot, &self.meshes, &self.scene)?;
        self.record_frame(f, step)
    }

    fn final_view(&self) -> &vkcore::ImageView {
        &self.targets.final_image.view
    }

    fn submitted(&mut self) {
        self.photons_ready = true;
    }
}

impl FrameRenderer for MeshRenderer<'_> {
    /// Moves to `scene`, a pose of the scene this renderer was made for (same objects, lights
    /// and sizes; see `crate::animation`): new uniforms are written at the start of the next
    /// frame, and meshes whose vertices moved are uploaded now (outside any frame) or copied by
    /// the next throughput frame.
    fn set_pose(&mut self, scene: &Scene) -> Result<()> {
        anyhow::ensure!(
            scene.objects.len() == self.meshes.len() && scene.lights.len() == self.scene.lights.len(),
            "set_pose: {} is not a pose of the scene this renderer was made for",
            scene.path.display()
        );
        let lights_moved = scene.lights != self.scene.lights;
        if lights_moved {
            self.photons_ready = false;
        }
        // The light-space caustic map and the receiver map do not depend on the camera:
        // progressive means start again when anything else changes (after the structures follow).
        let new_light = lights_moved
            || scene.objects != self.scene.objects
            || scene.materials != self.scene.materials
            || scene.receiver_map != self.scene.receiver_map
            || scene.caustic_frame != self.scene.caustic_frame;
        let moved: Vec<&str> = scene
            .objects
            .iter()
            .zip(&self.scene.objects)
            .filter(|(obj, old)| obj.mesh.positions != old.mesh.positions || obj.mesh.normals != old.mesh.normals)
            .map(|(obj, _)| obj.name.as_str())
            .collect();
        if let (Some(c), false) = (self.caustic.as_mut(), moved.is_empty()) {
            c.follow_moved_meshes(self.ctx, scene, &moved)?;
        }
        if let (Some(c), true) = (self.caustic.as_mut(), new_light) {
            c.restart_accumulation();
        }
        for (i, ((obj, old), mesh)) in scene.objects.iter().zip(&self.scene.objects).zip(&self.meshes).enumerate() {
            if obj.mesh.positions == old.mesh.positions && obj.mesh.normals == old.mesh.normals {
                continue;
            }
            self.photons_ready = false;
            if !self.slots.mesh_moved(i) {
                let vertices = setup::mesh_vertices(&obj.mesh, &mesh.thickness);
                self.ctx
                    .upload_buffer(&mesh.vertices, bytemuck::cast_slice(&vertices))
                    .with_context(|| format!("uploading the moved object `{}`", obj.name))?;
            }
        }
        self.slots.set_uniforms(uniforms_of(scene, self.active)?);
        self.refraction.set_pose(scene);
        self.scene = scene.clone();
        Ok(())
    }

    fn final_image(&self) -> Result<ImageF32> {
        dumps::final_image(self.ctx, &self.targets)
    }

    fn dumps(&mut self, wanted: &[&'static Dump]) -> Result<Vec<(&'static Dump, ImageF32)>> {
        self.read_dumps(wanted)
    }

    fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The eye render's receiver map (`[receiver_map]`).
    fn receiver(&self) -> &'static Dump {
        &dumps::RECEIVER
    }
}

/// Frame and caustic uniforms of `scene`; the caustic pass is switched off when not `active`.
fn uniforms_of(scene: &Scene, active: bool) -> Result<(gpu::FrameUniforms, techniques::uniforms::CausticUniforms)> {
    let mut cu = techniques::uniforms::caustic_uniforms(scene, &scene.caustics)?;
    if !active {
        cu.settings[0] = 0;
    }
    Ok((setup::frame_uniforms(scene), cu))
}
