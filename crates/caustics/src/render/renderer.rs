//! The mesh renderer: keeps its pipelines, targets and photon buffers between frames, so that a
//! benchmark can render many frames of an animation (uniforms and moving meshes updated per
//! frame) and time each one. (Pool scenes have their own: see `super::dispatch`.)

use super::{dumps, eye, pipelines, targets};
use crate::gpu::frame_mode::{FrameMode, FrameStep, Slots};
use crate::gpu::{self, setup, Stage};
use crate::image_io::ImageF32;
use crate::scene::Scene;
use crate::techniques::shah2007::VertexPhotons;
use crate::techniques::wyman2008::splat_footprints::{self, SplatFootprints};
use crate::techniques::wyman2008::{self, Hierarchy};
use crate::techniques::wyman_davis2006::{EyeView, ImageSpace};
use crate::techniques::wyman_nichols2009::adaptive::Part;
use crate::techniques::wyman_nichols2009::{
    self as wn2009, deferred_refraction, AdaptiveCaustics, DeferredPhotons, DeferredRefraction, Refraction,
};
use crate::techniques::{self, CausticFrame, CopyType, PhotonCopy, SplatPath, Technique};
use anyhow::{Context as _, Result};
use vkcore::{Access, Buffer, Context, Filter, Frame, FrameOptions, FrameReport, Memory, Sampler, ShaderCompiler, Use};

/// Choices fixed for the renderer's lifetime.
#[derive(Debug, Clone, Copy, Default)]
pub struct RendererOptions {
    /// Copy the photon buffer into a vertex array before splatting (Wyman 2008 Table 1-2).
    pub photon_copy: Option<CopyType>,
    /// One-shot frames timed pass by pass, or a ring of frames in flight (`crate::gpu::frame_mode`).
    pub frame_mode: FrameMode,
}

struct CausticResources {
    pipelines: techniques::CausticPipelines,
    photons: techniques::PhotonTargets,
    vertex_areas: Vec<Option<Buffer>>,
    splat_vertices: Buffer,
    /// Vertices per instance of the instanced photon fetch (`splat_vertices` holds 0..this).
    instance_vertices: u32,
    copy: Option<PhotonCopy>,
    vertex_photons: Option<VertexPhotons>,
    hierarchy: Option<Hierarchy>,
    /// Wyman & Nichols 2009's adaptive caustic maps.
    adaptive: Option<AdaptiveCaustics>,
    /// Wyman & Nichols 2009's deferred caustic maps (`photon_refraction = deferred`).
    deferred_photons: Option<DeferredPhotons>,
    /// What the `splats` dump reads the hierarchy's splats with (built by the first such dump).
    footprints: Option<SplatFootprints>,
    compute_splat: Option<techniques::ComputeSplat>,
    /// Wyman & Davis 2006's eye-space points, quads and gathers.
    image_space: Option<ImageSpace>,
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
    caustic: Option<CausticResources>,
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
        if opts.photon_copy.is_some() && !technique.splats_the_photon_buffer() {
            return Err(crate::input_error!(
                "photon_copy: copying the photon buffer into a vertex array needs a photon-buffer technique \
                 (wd-points or shah), not `{technique}`"
            )
            .into());
        }
        if opts.photon_copy.is_some() && settings.splat_path == SplatPath::Compute {
            return Err(crate::input_error!(
                "photon_copy: the copied vertex array is splatted as points; it has no compute splat \
                 (splat_path = \"compute\")"
            )
            .into());
        }
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
                (u, c, Some(Slots::new(ctx, slots)?))
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
        let vertex_photons = technique == Technique::ShahVertex;
        let specular_vertices: u32 = meshes
            .iter()
            .filter(|m| m.kind() != gpu::MATERIAL_DIFFUSE)
            .map(|m| (m.vertices.size() / std::mem::size_of::<gpu::MeshVertex>() as u64) as u32)
            .sum();
        let caustic = if active {
            let adaptive = technique == Technique::Adaptive;
            let photon_side = match () {
                _ if vertex_photons => (specular_vertices as f64).sqrt().ceil() as u32,
                // No photon buffer: its targets are placeholders.
                _ if adaptive => 1,
                _ => settings.photons,
            };
            let vertex_areas = if vertex_photons {
                setup::vertex_areas(ctx, scene)?
            } else {
                scene.objects.iter().map(|_| None).collect()
            };
            let ids: Vec<u32> = (0..settings.instance_vertices).collect();
            let copy = match opts.photon_copy {
                Some(ty) => Some(PhotonCopy::new(ctx, shaders, ty, photon_side)?),
                None => None,
            };
            let hierarchy = if technique == Technique::Hcm {
                let lights = scene.lights.len() as u32;
                Some(Hierarchy::new(ctx, shaders, photon_side, lights, settings.path, settings.cluster)?)
            } else {
                None
            };
            let adaptive = if adaptive {
                Some(AdaptiveCaustics::new(ctx, shaders, settings, scene.lights.len() as u32, &meshes)?)
            } else {
                None
            };
            let deferred_photons = match settings.photon_refraction {
                Refraction::Deferred if technique.has_photon_buffer() => {
                    Some(DeferredPhotons::new(ctx, shaders, settings.photons, &meshes)?)
                }
                _ => None,
            };
            let compute_splat = if settings.splat_path == SplatPath::Compute {
                let (side, layers) = (settings.caustic_map_resolution, settings.caustic_levels());
                let list = match (&hierarchy, &adaptive) {
                    (Some(h), _) => Some(h.splat_list()),
                    (None, Some(a)) => Some(a.splat_list()),
                    (None, None) => None,
                };
                Some(techniques::ComputeSplat::new(ctx, shaders, side, layers, list)?)
            } else {
                None
            };
            Some(CausticResources {
                pipelines: techniques::CausticPipelines::new(ctx, shaders)?,
                vertex_photons: if vertex_photons { Some(VertexPhotons::new(ctx, shaders)?) } else { None },
                photons: techniques::PhotonTargets::new(
                    ctx,
                    if adaptive.is_some() { 1 } else { settings.photons },
                    photon_side,
                )?,
                vertex_areas,
                splat_vertices: ctx.buffer_with_data("splat vertices", bytemuck::cast_slice(&ids))?,
                instance_vertices: settings.instance_vertices,
                copy,
                footprints: None,
                hierarchy,
                adaptive,
                deferred_photons,
                compute_splat,
                image_space: ImageSpace::new(ctx, shaders, scene)?,
            })
        } else {
            None
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
        let image_space = self.caustic.as_ref().and_then(|c| c.image_space.as_ref());
        let eye_inputs = eye::EyeInputs {
            uniforms: &self.uniforms[self.slot],
            caustic_uniforms: &self.caustic_uniforms[self.slot],
            caustics: &self.caustic_targets,
            meshes: &self.meshes,
            nearest: &self.nearest,
            linear: &self.linear,
            receiver_view_caustic: image_space.and_then(|i| i.receiver_caustic()),
            deferred: self.deferred.as_ref().map(|d| (d, self.refraction_order.as_slice())),
        };
        // Eye-space caustics are drawn into the eye's view: the background and its geometry
        // buffer first.
        let eye_space = image_space.is_some_and(|i| i.eye_space());
        if eye_space {
            eye::record_shadows_and_background(f, &self.pipelines, &self.targets, &eye_inputs)?;
        }
        match &self.caustic {
            Some(c) => {
                let view = self.eye_view();
                let frame = CausticFrame {
                    // One photon buffer serves every light: only one light's can be kept.
                    reuse_photons: step.reuse_photons && self.photons_ready && self.targets.shadow.lights == 1,
                    image_space: c.image_space.as_ref().map(|i| (i, Some(view))),
                    ..self.caustic_frame(c)
                };
                let inputs = self.caustic_inputs(c);
                let passes = self.caustic_passes(c, &inputs);
                techniques::record_caustics(f, &passes, self.targets.shadow.lights, frame)?;
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

    /// The eye's view as this frame renders it (for eye-space caustics).
    fn eye_view(&self) -> EyeView<'_> {
        let fu = setup::frame_uniforms(&self.scene);
        EyeView {
            view_proj: glam::Mat4::from_cols_array(&fu.view_proj),
            eye: self.scene.camera.eye,
            position: &self.targets.position.view,
            normal: &self.targets.normal.view,
            albedo: &self.targets.albedo.view,
            background: &self.targets.background.view,
        }
    }

    fn caustic_passes<'a>(
        &'a self,
        c: &'a CausticResources,
        inputs: &'a techniques::FrameInputs<'a>,
    ) -> techniques::CausticPasses<'a> {
        techniques::CausticPasses {
            pipelines: &c.pipelines,
            targets: &self.caustic_targets,
            photons: &c.photons,
            inputs,
        }
    }

    fn caustic_inputs<'a>(&'a self, c: &'a CausticResources) -> techniques::FrameInputs<'a> {
        techniques::FrameInputs {
            frame_uniforms: &self.uniforms[self.slot],
            caustic_uniforms: &self.caustic_uniforms[self.slot],
            meshes: &self.meshes,
            vertex_areas: &c.vertex_areas,
            splat_vertices: &c.splat_vertices,
            instance_vertices: c.instance_vertices,
            nearest: &self.nearest,
            spot_textures: &self.targets.spot_textures.view,
            linear: &self.linear,
            receiver_positions: &self.caustic_targets.receiver_positions.view,
        }
    }

    fn caustic_frame<'a>(&self, c: &'a CausticResources) -> CausticFrame<'a> {
        CausticFrame {
            reuse_photons: false,
            copy: c.copy.as_ref(),
            vertex_photons: c.vertex_photons.as_ref(),
            hierarchy: c.hierarchy.as_ref(),
            adaptive: c.adaptive.as_ref(),
            deferred_photons: c.deferred_photons.as_ref(),
            compute_splat: c.compute_splat.as_ref(),
            image_space: None,
        }
    }

    /// The named intermediate buffer of the last frame (None where this render has none).
    pub fn dump(&mut self, name: &str) -> Result<Option<ImageF32>> {
        Ok(self.dumps(&[name.to_string()])?.pop().map(|(_, img)| img))
    }

    /// The named intermediate buffers of the last frame, as (name, image), skipping those this
    /// render has none of. One photon buffer, back-face target and hierarchy serve every light
    /// in turn (`super::LIGHT_SPACE_DUMPS`), so a frame leaves only its last light's there:
    /// with several lights, each light's light-space passes are recorded again alone (the same
    /// inputs, so the same buffers) and read back. Their layers are named `light<l>.<layer>`.
    pub fn dumps(&mut self, names: &[String]) -> Result<Vec<(String, ImageF32)>> {
        let mut unique: Vec<&String> = vec![];
        for n in names {
            if !unique.contains(&n) {
                unique.push(n);
            }
        }
        let light_space = |n: &str| super::LIGHT_SPACE_DUMPS.contains(&n);
        let declared = super::dumps_for(&self.scene.caustics);
        let has = |n: &str| {
            declared.contains(&n)
                && match (wyman2008::DUMPS.contains(&n), wn2009::settings::ADAPTIVE_DUMPS.contains(&n)) {
                    (true, _) => self.hierarchy().is_some(),
                    (_, true) => self.adaptive().is_some(),
                    _ => self.caustic.is_some(),
                }
        };
        let wanted: Vec<&str> = unique.iter().map(|n| n.as_str()).filter(|n| light_space(n) && has(n)).collect();
        anyhow::ensure!(
            wanted.is_empty() || self.pending_uniforms.is_none(),
            "dumps: the renderer moved to a new pose after its last frame; render a frame first"
        );
        if let Some(c) = self.caustic.as_mut().filter(|c| c.footprints.is_none() && wanted.contains(&"splats")) {
            c.footprints = Some(SplatFootprints::new(self.ctx, self.shaders)?);
        }
        let mut per_light: Vec<Option<ImageF32>> = vec![None; wanted.len()];
        let (mut lists, mut splats, mut adaptive_lists) = (vec![], vec![], vec![]);
        let lights = self.targets.shadow.lights;
        for l in 0..if wanted.is_empty() { 0 } else { lights } {
            if lights > 1 {
                self.record_light_space_alone(l)?;
            }
            let Some(c) = &self.caustic else { break };
            for (i, name) in wanted.iter().enumerate() {
                let img = match (*name, &c.hierarchy) {
                    (wn2009::settings::DEFERRED_PHOTONS_DUMP, _) => match &c.deferred_photons {
                        Some(d) => d.dump(self.ctx)?,
                        None => continue,
                    },
                    // Deferred photons: the back faces are the geometry buffers' back layer.
                    ("photon_back_faces", _) if c.deferred_photons.is_some() => {
                        c.deferred_photons.as_ref().context("deferred photons")?.dump_back_faces(self.ctx)?
                    }
                    ("adaptive_geometry", _) => match &c.adaptive {
                        Some(a) => a.dump_geometry(self.ctx)?,
                        None => continue,
                    },
                    ("adaptive_lists", _) => {
                        if let Some(a) = &c.adaptive {
                            adaptive_lists.push(self.adaptive_lists(c, a, l)?);
                        }
                        continue;
                    }
                    ("hierarchy", Some(h)) => h.dump_levels(self.ctx)?,
                    ("hierarchy_lists", Some(h)) => {
                        lists.push(h.read_lists(self.ctx)?);
                        continue;
                    }
                    ("splats", Some(h)) => {
                        let footprints = c.footprints.as_ref().context("no splat footprints pipeline")?;
                        let inputs = self.caustic_inputs(c);
                        splats.push(footprints.read(self.ctx, h, &inputs, &c.photons, l)?);
                        continue;
                    }
                    _ => dumps::photon_targets(self.ctx, &c.photons, name)?,
                };
                per_light[i] = Some(dumps::merge(per_light[i].take(), dumps::for_light(img, l))?);
            }
        }
        let mut out = vec![];
        for name in unique {
            let img = match wanted.iter().position(|w| w == name) {
                Some(_) if name == "hierarchy_lists" => Some(wyman2008::lists_image(&lists)),
                Some(_) if name == "adaptive_lists" => Some(wn2009::adaptive::lists_image(&adaptive_lists)),
                Some(_) if name == "splats" => Some(splat_footprints::splats_image(&splats)),
                Some(i) => per_light[i].take(),
                None if light_space(name) => None,
                None if !super::dumps_for(&self.scene.caustics).contains(&name.as_str()) => None,
                None if name == "eye_caustic" => match self.caustic.as_ref().and_then(|c| c.image_space.as_ref()) {
                    Some(is) => is.dump_eye(self.ctx)?,
                    None => None,
                },
                None => match &self.deferred {
                    Some(d) if Refraction::Deferred.dumps().contains(&name.as_str()) => {
                        Some(dumps::deferred(self.ctx, d, &self.targets, name)?)
                    }
                    _ => {
                        let photons = self.caustic.as_ref().map(|c| &c.photons);
                        dumps::dump(self.ctx, &self.targets, &self.caustic_targets, photons, name)?
                    }
                },
            };
            if let Some(img) = img {
                out.push((name.clone(), img));
            }
        }
        Ok(out)
    }

    /// Light `l`'s adaptive lists, after its light-space passes were recorded last. A batched
    /// traversal leaves only its last batch's, so it is recorded again part by part, and each
    /// part read back: the breadth-first levels, then batch after batch. Level B's list is
    /// written once, so every batch selects its slice of the same list (the compute path
    /// appends in no fixed order: a traversal recorded again per batch could slice another).
    fn adaptive_lists(
        &self,
        c: &CausticResources,
        a: &AdaptiveCaustics,
        l: u32,
    ) -> Result<wn2009::adaptive::LightLists> {
        if !a.plan().batched() {
            return a.read_lists(self.ctx, None);
        }
        let inputs = self.caustic_inputs(c);
        let passes = self.caustic_passes(c, &inputs);
        let mut lists = vec![];
        let parts = std::iter::once(Part::Breadth).chain((0..a.plan().batches).map(Part::Batch));
        for part in parts {
            let mut f = self.ctx.frame(FrameOptions::default())?;
            techniques::record_adaptive_part(&mut f, &passes, a, l, part)?;
            f.submit()?;
            lists.extend(a.read_lists(self.ctx, Some(part))?);
        }
        Ok(lists)
    }

    /// Records light `l`'s light-space passes (`techniques::record_light_space`) alone, as
    /// the last frame recorded them, and waits for them.
    fn record_light_space_alone(&mut self, l: u32) -> Result<()> {
        let Some(c) = &self.caustic else { return Ok(()) };
        let mut f = self.ctx.frame(FrameOptions::default())?;
        let inputs = self.caustic_inputs(c);
        let frame = self.caustic_frame(c);
        techniques::record_light_space(&mut f, &self.caustic_passes(c, &inputs), l, frame)?;
        f.submit()?;
        Ok(())
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
        if !self.active || !self.scene.caustics.technique.has_photon_buffer() {
            return Ok(None);
        }
        if let Some(img) = read {
            return Ok(Some(valid_photons_in(img)?));
        }
        let Some(img) = self.dump("photon_buffer")? else { return Ok(None) };
        Ok(Some(valid_photons_in(&img)?))
    }

    /// The hierarchy of `hcm` (None for the other techniques).
    pub fn hierarchy(&self) -> Option<&Hierarchy> {
        self.caustic.as_ref().and_then(|c| c.hierarchy.as_ref())
    }

    /// The adaptive caustic maps of `adaptive` (None for the other techniques).
    pub fn adaptive(&self) -> Option<&AdaptiveCaustics> {
        self.caustic.as_ref().and_then(|c| c.adaptive.as_ref())
    }

    /// Per light, the sizes of the traversal's lists of the last frame: `hcm`'s from its 16²
    /// level down to the splatted list; `adaptive`'s pending clusters of each level (0 to L),
    /// then the photons it splatted. None for the other techniques.
    pub fn list_sizes(&self) -> Result<Option<Vec<Vec<u64>>>> {
        if let Some(h) = self.hierarchy() {
            return Ok(Some(h.list_sizes(self.ctx)?));
        }
        let Some(a) = self.adaptive() else { return Ok(None) };
        let counts = a.level_counts(self.ctx)?;
        Ok(Some(
            counts
                .into_iter()
                .map(|(mut clusters, emitted)| {
                    clusters.push(emitted.iter().sum());
                    clusters
                })
                .collect(),
        ))
    }

    /// Points drawn (or compute-splat invocations) per frame over all lights: every
    /// photon-buffer texel for the dense techniques (invalid ones are culled in the vertex
    /// shader; the instanced draw rounds up to whole instances), the final list
    /// of the last traversal for `hcm` and the output photons for `adaptive` (read back from
    /// the GPU: Wyman & Nichols 2009 Table 1's "photons splatted").
    pub fn splats_drawn(&self) -> Result<u64> {
        if let Some(sizes) = self.list_sizes()? {
            return Ok(sizes.iter().map(|s| s.last().copied().unwrap_or(0)).sum());
        }
        Ok(match &self.caustic {
            Some(c) => {
                let per_light = match (&c.copy, &c.compute_splat) {
                    (Some(copy), _) => copy.vertices() as u64,
                    // One invocation per photon-buffer texel.
                    (None, Some(_)) => (c.photons.width * c.photons.width) as u64,
                    (None, None) => {
                        let total = c.photons.width * c.photons.width;
                        let per = c.instance_vertices;
                        (total.div_ceil(per) * per) as u64
                    }
                };
                per_light * self.targets.shadow.lights as u64
            }
            None => 0,
        })
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
