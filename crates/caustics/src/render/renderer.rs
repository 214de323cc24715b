//! The mesh renderer: keeps its pipelines, targets and photon buffers between frames, so that a
//! benchmark can render many frames of an animation (uniforms and moving meshes updated per
//! frame) and time each one. (Pool scenes have their own: see `super::dispatch`.)

use super::{dumps, eye, pipelines, targets};
use crate::dump::{Dump, Space};
use crate::gpu::frame_mode::{FrameMode, FrameStep, Slots};
use crate::gpu::{self, setup, Stage};
use crate::image_io::ImageF32;
use crate::scene::Scene;
use crate::techniques::shared::settings::PHOTON_BUFFER;
use crate::techniques::stages::{self, CausticPipeline};
use crate::techniques::wyman_nichols2009::deferred_refraction::DEFERRED_REFRACTION_DUMPS;
use crate::techniques::wyman_nichols2009::{deferred_refraction, DeferredRefraction, Refraction};
use crate::techniques::{self, CopyType, EyeView};
use anyhow::{Context as _, Result};
use vkcore::{Access, Buffer, Context, Filter, Frame, FrameOptions, FrameReport, Memory, Sampler, ShaderCompiler, Use};

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
    ctx: &'c Context,
    shaders: &'c ShaderCompiler,
    scene: Scene,
    active: bool,
    pipelines: pipelines::EyePipelines,
    meshes: Vec<setup::GpuMesh>,
    /// The uniform buffers the passes bind: one device buffer updated by a pass (per-pass
    /// frames), or one host-written buffer per ring slot (throughput frames); `slot` is the one
    /// the last frame used.
    uniforms: Vec<Buffer>,
    caustic_uniforms: Vec<Buffer>,
    slot: usize,
    /// The uniforms of the current pose.
    current_uniforms: (gpu::FrameUniforms, techniques::uniforms::CausticUniforms),
    /// New uniform contents to write at the start of the next frame.
    pending_uniforms: Option<(gpu::FrameUniforms, techniques::uniforms::CausticUniforms)>,
    /// Throughput frames: the ring, and per slot a staging buffer for moved meshes.
    slots: Option<Slots>,
    /// Meshes moved by the last pose, uploaded by the next throughput frame.
    moved_meshes: Vec<usize>,
    targets: targets::EyeTargets,
    caustic_targets: techniques::CausticTargets,
    nearest: Sampler,
    linear: Sampler,
    /// The technique's caustic stages (none without caustics or specular objects).
    caustic: Option<CausticPipeline>,
    specular_vertices: u32,
    photons_ready: bool,
    /// `--refraction deferred`: its passes and buffers.
    deferred: Option<DeferredRefraction>,
    /// The specular objects, farthest from the eye first (Wyman & Nichols 2009 Sec. 3.1.1).
    refraction_order: Vec<usize>,
}

impl<'c> MeshRenderer<'c> {
    pub fn new(ctx: &'c Context, shaders: &'c ShaderCompiler, scene: &Scene, opts: &RendererOptions) -> Result<Self> {
        let settings = &scene.caustics;
        let technique = settings.technique;
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
        let active = technique.has_caustics() && techniques::uniforms::specular_bounds(scene).is_some();
        let pipelines = pipelines::EyePipelines::new(ctx, shaders)?;
        let meshes = setup::upload_meshes(ctx, scene)?;
        let (fu, cu) = uniforms_of(scene, active)?;
        let (uniforms, caustic_uniforms, slots) = match opts.frame_mode {
            FrameMode::PerPass => (
                vec![ctx.buffer_with_data("frame uniforms", bytemuck::bytes_of(&fu))?],
                vec![ctx.buffer_with_data("caustic uniforms", bytemuck::bytes_of(&cu))?],
                None,
            ),
            FrameMode::Throughput { slots } => {
                let (mut u, mut c) = (vec![], vec![]);
                for s in 0..slots {
                    let mut b = Buffer::new(
                        ctx,
                        &format!("frame uniforms, slot {s}"),
                        size_of_val(&fu) as u64,
                        Memory::Upload,
                    )?;
                    b.write_mapped(0, bytemuck::bytes_of(&fu))?;
                    u.push(b);
                    let mut b = Buffer::new(
                        ctx,
                        &format!("caustic uniforms, slot {s}"),
                        size_of_val(&cu) as u64,
                        Memory::Upload,
                    )?;
                    b.write_mapped(0, bytemuck::bytes_of(&cu))?;
                    c.push(b);
                }
                (u, c, Some(Slots::new(ctx, slots, opts.pass_timestamps)?))
            }
        };
        let targets = targets::EyeTargets::new(ctx, scene)?;
        let caustic_targets = techniques::CausticTargets::new(ctx, scene, active)?;
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
        let specular_vertices = stages::specular_vertices(&meshes);
        let caustic = match active {
            true => Some(CausticPipeline::new(ctx, shaders, scene, &meshes, opts.photon_copy)?),
            false => None,
        };
        let refraction_order = deferred_refraction::back_to_front(scene);
        let deferred = match settings.refraction {
            Refraction::Forward => None,
            Refraction::Deferred => Some(DeferredRefraction::new(
                ctx,
                shaders,
                refraction_order.len(),
                scene.camera.width,
                scene.camera.height,
            )?),
        };
        Ok(MeshRenderer {
            ctx,
            shaders,
            scene: scene.clone(),
            active,
            pipelines,
            meshes,
            uniforms,
            caustic_uniforms,
            slot: 0,
            current_uniforms: (fu, cu),
            pending_uniforms: None,
            slots,
            moved_meshes: vec![],
            targets,
            caustic_targets,
            nearest: Sampler::new(ctx, Filter::Nearest)?,
            linear: Sampler::new(ctx, Filter::Linear)?,
            caustic,
            specular_vertices,
            photons_ready: false,
            deferred,
            refraction_order,
        })
    }

    /// Moves to `scene`, a pose of the scene this renderer was made for (same objects, lights
    /// and sizes; see `crate::animation`): new uniforms are written at the start of the next
    /// frame, and meshes whose vertices moved are uploaded now (outside any frame).
    pub fn set_pose(&mut self, scene: &Scene) -> Result<()> {
        anyhow::ensure!(
            scene.objects.len() == self.meshes.len() && scene.lights.len() == self.scene.lights.len(),
            "set_pose: {} is not a pose of the scene this renderer was made for",
            scene.path.display()
        );
        if scene.lights != self.scene.lights {
            self.photons_ready = false;
        }
        for (i, ((obj, old), mesh)) in scene.objects.iter().zip(&self.scene.objects).zip(&self.meshes).enumerate() {
            if obj.mesh.positions != old.mesh.positions || obj.mesh.normals != old.mesh.normals {
                if self.scene.caustics.technique == crate::techniques::Technique::PhotonTrace {
                    return Err(crate::input_error!(
                        "technique photon-trace: object `{}` moves, and the tracer's BVH is built once, when the \
                         renderer is made (moving objects are not supported yet)",
                        obj.name
                    )
                    .into());
                }
                self.photons_ready = false;
                if self.slots.is_some() {
                    // A throughput frame copies it from its slot's staging buffer.
                    if !self.moved_meshes.contains(&i) {
                        self.moved_meshes.push(i);
                    }
                    continue;
                }
                let vertices = setup::mesh_vertices(&obj.mesh, &mesh.thickness);
                self.ctx
                    .upload_buffer(&mesh.vertices, bytemuck::cast_slice(&vertices))
                    .with_context(|| format!("uploading the moved object `{}`", obj.name))?;
            }
        }
        let uniforms = uniforms_of(scene, self.active)?;
        self.current_uniforms = uniforms;
        self.pending_uniforms = Some(uniforms);
        self.refraction_order = deferred_refraction::back_to_front(scene);
        self.scene = scene.clone();
        Ok(())
    }

    /// Records, submits and waits for one frame; returns its per-pass timings (per-pass frames)
    /// or its frame time (a throughput frame, waited for alone: see [`MeshRenderer::submit`]).
    pub fn frame(&mut self, step: FrameStep) -> Result<FrameReport> {
        if self.slots.is_some() {
            self.submit(step)?;
            return self.finish()?.pop().context("the ring returned no report for its frame");
        }
        let mut f = self.ctx.frame(FrameOptions {
            timestamps: true,
            pipeline_statistics: step.pipeline_statistics,
            host_pass_times: step.host_pass_times,
            ..Default::default()
        })?;
        if let Some((fu, cu)) = self.pending_uniforms.take() {
            let (u, c) = (&self.uniforms[0], &self.caustic_uniforms[0]);
            let uses = [Use::buffer(u, Access::TRANSFER_WRITE), Use::buffer(c, Access::TRANSFER_WRITE)];
            f.pass(&Stage::Uniforms.pass()).uses(uses).record(|cmd| {
                cmd.update_buffer(u, 0, bytemuck::bytes_of(&fu))?;
                cmd.update_buffer(c, 0, bytemuck::bytes_of(&cu))?;
                Ok(())
            })?;
        }
        self.record_frame(&mut f, step)?;
        let report = f.submit()?;
        self.photons_ready = true;
        Ok(report)
    }

    /// Throughput frames: records the next frame into its ring slot and submits it without
    /// waiting (the slot's previous frame is waited for first). Its uniforms are written into
    /// the slot's own buffers and moved meshes copied from the slot's staging buffer inside the
    /// frame, so a warm frame creates nothing. Returns the reports of frames that finished.
    pub fn submit(&mut self, step: FrameStep) -> Result<Vec<FrameReport>> {
        self.submit_with(step, &mut |_, _| Ok(()))
    }

    /// [`MeshRenderer::submit`], with `after` recording more passes at the end of the frame
    /// (the viewer's display pass), given the frame and its final image.
    pub fn submit_with(
        &mut self,
        step: FrameStep,
        after: &mut dyn FnMut(&mut Frame, &vkcore::ImageView) -> Result<()>,
    ) -> Result<Vec<FrameReport>> {
        let slots = self.slots.as_mut().context("submit: this renderer draws one-shot frames (FrameMode::PerPass)")?;
        let s = slots.ring.slot();
        let mut f = slots.ring.frame()?;
        self.slot = s;
        self.pending_uniforms = None;
        let (fu, cu) = self.current_uniforms;
        self.uniforms[s].write_mapped(0, bytemuck::bytes_of(&fu))?;
        self.caustic_uniforms[s].write_mapped(0, bytemuck::bytes_of(&cu))?;
        self.record_moved_meshes(&mut f, s)?;
        self.record_frame(&mut f, step)?;
        after(&mut f, &self.targets.final_image.view)?;
        let slots = self.slots.as_mut().context("throughput slots")?;
        slots.ring.submit(f)?;
        self.photons_ready = true;
        Ok(slots.ring.reports())
    }

    /// Waits for every throughput frame in flight; returns the reports not yet returned.
    pub fn finish(&mut self) -> Result<Vec<FrameReport>> {
        match self.slots.as_mut() {
            Some(s) => Ok(s.ring.finish()?),
            None => Ok(vec![]),
        }
    }

    /// Copies the meshes the last pose moved from slot `s`'s staging buffer (every slot's made,
    /// each for every mesh's vertices at once, by the first frame that needs one).
    fn record_moved_meshes(&mut self, f: &mut Frame, s: usize) -> Result<()> {
        if self.moved_meshes.is_empty() {
            return Ok(());
        }
        let total: u64 = self.meshes.iter().map(|m| m.vertices.size()).sum();
        let slots = self.slots.as_mut().context("throughput slots")?;
        for (k, staging) in slots.staging.iter_mut().enumerate() {
            if staging.is_none() {
                *staging = Some(Buffer::new(self.ctx, &format!("moved meshes, slot {k}"), total, Memory::Upload)?);
            }
        }
        let staging = slots.staging[s].as_mut().context("staging")?;
        let mut regions = vec![];
        let mut offset = 0u64;
        for (i, mesh) in self.meshes.iter().enumerate() {
            if self.moved_meshes.contains(&i) {
                let obj = &self.scene.objects[i];
                let vertices = setup::mesh_vertices(&obj.mesh, &mesh.thickness);
                let bytes: &[u8] = bytemuck::cast_slice(&vertices);
                staging.write_mapped(offset, bytes)?;
                regions.push((i, offset, bytes.len() as u64));
            }
            offset += mesh.vertices.size();
        }
        self.moved_meshes.clear();
        let staging = &*staging;
        let mut uses = vec![Use::buffer(staging, Access::TRANSFER_READ)];
        uses.extend(regions.iter().map(|&(i, _, _)| Use::buffer(&self.meshes[i].vertices, Access::TRANSFER_WRITE)));
        f.pass(&Stage::UploadMeshes.pass()).uses(uses).record(|cmd| {
            for &(i, at, bytes) in &regions {
                cmd.copy_buffer_region(staging, at, &self.meshes[i].vertices, 0, bytes);
            }
            Ok(())
        })?;
        Ok(())
    }

    /// Every pass of one frame after its uniforms: eye-space backgrounds, caustics, the eye.
    fn record_frame(&self, f: &mut Frame, step: FrameStep) -> Result<()> {
        let eye_inputs = eye::EyeInputs {
            uniforms: &self.uniforms[self.slot],
            caustic_uniforms: &self.caustic_uniforms[self.slot],
            caustics: &self.caustic_targets,
            meshes: &self.meshes,
            nearest: &self.nearest,
            linear: &self.linear,
            receiver_view_caustic: self.caustic.as_ref().and_then(|c| c.receiver_caustic()),
            deferred: self.deferred.as_ref().map(|d| (d, self.refraction_order.as_slice())),
        };
        // Caustics deposited in the eye's view are drawn into it: the background and its
        // geometry buffer first.
        let eye_space = self.caustic.as_ref().is_some_and(|c| c.eye_space());
        if eye_space {
            eye::record_shadows_and_background(f, &self.pipelines, &self.targets, &eye_inputs)?;
        }
        match &self.caustic {
            Some(c) => {
                // One photon buffer serves every light: only one light's can be kept.
                let reuse = step.reuse_photons && self.photons_ready && self.targets.shadow.lights == 1;
                let inputs = self.caustic_inputs();
                let lights = self.targets.shadow.lights;
                c.record(f, &inputs, &self.caustic_targets, lights, Some(self.eye_view()), reuse)?;
            }
            None => techniques::record_cleared(f, &self.caustic_targets)?,
        }
        if eye_space {
            eye::record_after_background(f, &self.pipelines, &self.targets, &eye_inputs)?;
        } else {
            eye::record(f, &self.pipelines, &self.targets, &eye_inputs)?;
        }
        Ok(())
    }

    /// The last frame's linear radiance.
    pub fn final_image(&self) -> Result<ImageF32> {
        dumps::final_image(self.ctx, &self.targets)
    }

    /// The final image on the GPU (linear radiance, RGBA 32-bit float, row 0 at the top).
    pub fn final_view(&self) -> &vkcore::ImageView {
        &self.targets.final_image.view
    }

    /// The eye's view as this frame renders it (for caustics deposited in it).
    fn eye_view(&self) -> EyeView<'_> {
        EyeView {
            view_proj: glam::Mat4::from_cols_array(&self.current_uniforms.0.view_proj),
            eye: self.scene.camera.eye,
            position: &self.targets.position.view,
            normal: &self.targets.normal.view,
            albedo: &self.targets.albedo.view,
            background: &self.targets.background.view,
        }
    }

    /// What the caustic stages read of the frame: the uniforms of the slot in use, the meshes,
    /// samplers, spot textures and receiver positions.
    fn caustic_inputs(&self) -> techniques::FrameInputs<'_> {
        techniques::FrameInputs {
            frame_uniforms: &self.uniforms[self.slot],
            caustic_uniforms: &self.caustic_uniforms[self.slot],
            meshes: &self.meshes,
            nearest: &self.nearest,
            spot_textures: &self.targets.spot_textures.view,
            linear: &self.linear,
            receiver_positions: &self.caustic_targets.receiver_positions.view,
        }
    }

    /// The buffers `wanted` of the last frame that this render has, each with its image. The
    /// light-space buffers that serve every light in turn (`dump::Space::LightInTurn`) are read
    /// light by light by the caustic stages (`CausticPipeline::light_space_dumps`): layers
    /// `light<l>.<layer>`; the eye-space ones the eye render does not own by the caustic
    /// deposit; deferred refraction's by it; the rest from the eye render's targets.
    pub fn dumps(&mut self, wanted: &[&'static Dump]) -> Result<Vec<(&'static Dump, ImageF32)>> {
        let declared = super::dumps_for(&self.scene.caustics);
        let mut unique: Vec<&'static Dump> = vec![];
        for &d in wanted {
            if declared.contains(&d) && !unique.contains(&d) {
                unique.push(d);
            }
        }
        let in_turn: Vec<&'static Dump> = unique
            .iter()
            .copied()
            .filter(|&d| self.caustic.as_ref().is_some_and(|c| c.has_light_space_dump(d)))
            .collect();
        anyhow::ensure!(
            in_turn.is_empty() || self.pending_uniforms.is_none(),
            "dumps: the renderer moved to a new pose after its last frame; render a frame first"
        );
        if let Some(c) = self.caustic.as_mut() {
            c.prepare_dumps(self.ctx, self.shaders, &in_turn)?;
        }
        let mut read = match &self.caustic {
            Some(c) => {
                let lights = self.targets.shadow.lights;
                c.light_space_dumps(self.ctx, &self.caustic_inputs(), &self.caustic_targets, lights, &in_turn)?
            }
            None => vec![],
        };
        let mut out = vec![];
        for d in unique {
            let img = match read.iter().position(|(r, _)| *r == d) {
                Some(i) => Some(read.swap_remove(i).1),
                None if d.space == Space::LightInTurn => None,
                // An eye-space buffer the eye render does not own is its caustic deposit's.
                None if d.space == Space::Eye && !dumps::EYE_DUMPS.contains(&d) => match &self.caustic {
                    Some(c) => c.dump(self.ctx, d)?,
                    None => None,
                },
                None => match &self.deferred {
                    Some(r) if DEFERRED_REFRACTION_DUMPS.contains(&d) => {
                        Some(dumps::deferred(self.ctx, r, &self.targets, d)?)
                    }
                    _ => {
                        let photons = self.caustic.as_ref().map(|c| c.photon_targets());
                        dumps::dump(self.ctx, &self.targets, &self.caustic_targets, photons, d)?
                    }
                },
            };
            if let Some(img) = img {
                out.push((d, img));
            }
        }
        Ok(out)
    }

    /// The scene as this renderer was made for it (its pose may have moved since).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Photons emitted per frame over all lights (0 without a caustic technique).
    pub fn photons_emitted(&self) -> u64 {
        if !self.active {
            return 0;
        }
        let c = &self.scene.caustics;
        c.technique.photons_per_light(c, self.specular_vertices) * self.targets.shadow.lights as u64
    }

    /// Photons of the last frame that met a specular object and found a receiver (the photon
    /// buffer's texels with `valid` set, over all lights), read back from the GPU; `None` where
    /// the technique has no photon buffer. Against [`Self::photons_emitted`] this is the share
    /// of the light's view that the photon view spends on photons (Wyman & Nichols 2009 Table 1).
    /// `read`: the `photon_buffer` dump where the caller read it already (it is not read again).
    pub fn valid_photons(&mut self, read: Option<&ImageF32>) -> Result<Option<u64>> {
        if !self.active || !self.scene.caustics.technique.writes_photon_buffer() {
            return Ok(None);
        }
        if let Some(img) = read {
            return Ok(Some(valid_photons_in(img)?));
        }
        let Some((_, img)) = self.dumps(&[&PHOTON_BUFFER])?.pop() else { return Ok(None) };
        Ok(Some(valid_photons_in(&img)?))
    }

    /// The technique's caustic stages (None without caustics or specular objects).
    pub fn caustics(&self) -> Option<&CausticPipeline> {
        self.caustic.as_ref()
    }

    /// Per light, the sizes of the traversal's lists of the last frame
    /// (`CausticPipeline::list_sizes`); None for the other techniques.
    pub fn list_sizes(&self) -> Result<Option<Vec<Vec<u64>>>> {
        match &self.caustic {
            Some(c) => c.list_sizes(self.ctx),
            None => Ok(None),
        }
    }

    /// Points drawn (or compute-splat invocations) per frame over all lights
    /// (`CausticPipeline::splats_drawn`).
    pub fn splats_drawn(&self) -> Result<u64> {
        match &self.caustic {
            Some(c) => c.splats_drawn(self.ctx, self.targets.shadow.lights),
            None => Ok(0),
        }
    }
}

/// The texels with `valid` set in a `photon_buffer` dump, over all lights.
fn valid_photons_in(img: &ImageF32) -> Result<u64> {
    let mut valid = 0u64;
    for layer in img.layers.iter().filter(|l| l.name.as_deref().is_some_and(|n| n.ends_with("position"))) {
        let c = layer.channels.iter().position(|c| c == "valid").context("photon buffer without `valid`")?;
        valid += layer.data.chunks_exact(layer.channels.len()).filter(|p| p[c] > 0.5).count() as u64;
    }
    Ok(valid)
}

/// Frame and caustic uniforms of `scene`; the caustic pass is switched off when not `active`.
fn uniforms_of(scene: &Scene, active: bool) -> Result<(gpu::FrameUniforms, techniques::uniforms::CausticUniforms)> {
    let mut cu = techniques::uniforms::caustic_uniforms(scene, &scene.caustics)?;
    if !active {
        cu.settings[0] = 0;
    }
    Ok((setup::frame_uniforms(scene), cu))
}
