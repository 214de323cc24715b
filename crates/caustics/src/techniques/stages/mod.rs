//! A caustic technique as three stages: a photon [`Source`], a [`Selection`] of the photons to
//! deposit, and a [`Deposit`] of them into the caustic map or the eye's view. Each stage is an
//! enum whose variants own their GPU resources, record their passes and read back their dumps;
//! a [`CausticPipeline`] is a technique's choice of the three, made from its settings, and all
//! that `crate::render` knows of the papers' caustics. The eye's refraction, forward or
//! deferred (Wyman & Nichols 2009 Sec. 3.1), reaches it the same way: [`EyeRefraction`].
//!
//! | technique | source | selection | deposit |
//! |---|---|---|---|
//! | `shah`, `wd-points` | `Rasterized` (or `Deferred`) | `Dense` (or `Copy`) | `Points`, `Compute` or `ThinLens` |
//! | `shah-vertex` | `PerVertex` | `Dense` | `Points` or `Compute` |
//! | `wd-eye-points`, `wd-quads`, `wd-gather` | `Rasterized` (or `Deferred`) | `Dense` | `ImageSpace` |
//! | `hcm` | `Rasterized` (or `Deferred`) | `Hierarchy` | `Points`, `Compute` or `Interpolated` |
//! | `adaptive` | `GeometryBuffers` | `Adaptive` | `Points` or `Compute` |
//! | `photon-trace` | `Traced` | `Dense` | `Points`, `Compute`, `Differential` or `ImageSpace` |
//!
//! Each stage declares the pass stages it records (`Source::stages`, `Selection::stages`,
//! `Deposit::stages`); `tests/frame_graph_stages.rs` renders every row of the registry of
//! variants and holds its frame graph, and this table, to them.

mod deposit;
mod dumps;
pub mod refraction;
mod selection;
mod source;

pub use deposit::Deposit;
pub use refraction::EyeRefraction;
pub use selection::Selection;
pub use source::Source;

use super::settings::CausticSettings;
use super::shared::{CausticPasses, CausticPipelines, CausticTargets, EyeView, FrameInputs, PhotonTargets, SplatPath};
use super::wyman2008::photon_copy::CopyType;
use super::wyman2008::Hierarchy;
use super::wyman_nichols2009::AdaptiveCaustics;
use super::Technique;
use crate::gpu::{self, BatchPart, GpuMesh};
use crate::scene::Scene;
use anyhow::Result;
use vkcore::{Context, Frame, ImageView, ShaderCompiler};

/// A technique's caustic stages and the light-space targets they share.
pub struct CausticPipeline {
    source: Source,
    selection: Selection,
    deposit: Deposit,
    pipelines: CausticPipelines,
    photons: PhotonTargets,
    /// What [`Self::splats_drawn`] counts by: the splat path and the instanced draw's
    /// vertices per instance (`caustics.splat_path`, `caustics.instance_vertices`).
    splat_path: SplatPath,
    instance_vertices: u32,
}

/// Checks Wyman 2008 Table 1's copy of the photon buffer into a vertex array (`photon_copy`)
/// against `settings`: only a photon buffer can be copied, and the copy is splatted as points.
pub fn check_photon_copy(settings: &CausticSettings, copy: Option<CopyType>) -> Result<()> {
    let technique = settings.technique;
    if copy.is_some() && !technique.splats_the_photon_buffer() {
        return Err(crate::input_error!(
            "photon_copy: copying the photon buffer into a vertex array needs a photon-buffer technique \
             (wd-points or shah), not `{technique}`"
        )
        .into());
    }
    if let Some(why) = settings.splat.needs().own_points.filter(|_| copy.is_some()) {
        return Err(crate::input_error!("photon_copy: `{}` splats (splat = \"{0}\") {why}", settings.splat).into());
    }
    if copy.is_some() && settings.splat_path == SplatPath::Compute {
        return Err(crate::input_error!(
            "photon_copy: the copied vertex array is splatted as points; it has no compute splat \
             (splat_path = \"compute\")"
        )
        .into());
    }
    Ok(())
}

/// Vertices of the specular meshes among `meshes` (a photon each for `shah-vertex`).
pub fn specular_vertices(meshes: &[GpuMesh]) -> u32 {
    meshes
        .iter()
        .filter(|m| m.kind() != gpu::MATERIAL_DIFFUSE)
        .map(|m| (m.vertices.size() / std::mem::size_of::<gpu::MeshVertex>() as u64) as u32)
        .sum()
}

impl CausticPipeline {
    /// The stages of `scene`'s technique and settings, for `meshes` (uploaded); `copy` as for
    /// [`check_photon_copy`], which the caller has run.
    pub fn new(
        ctx: &Context,
        sh: &ShaderCompiler,
        scene: &Scene,
        meshes: &[GpuMesh],
        copy: Option<CopyType>,
    ) -> Result<CausticPipeline> {
        let s = &scene.caustics;
        let photon_side = match s.technique {
            Technique::ShahVertex => (specular_vertices(meshes) as f64).sqrt().ceil() as u32,
            // No photon buffer: its targets are placeholders.
            Technique::Adaptive => 1,
            _ => s.photons,
        };
        let selection = Selection::new(ctx, sh, scene, meshes, photon_side, copy)?;
        let deposit = Deposit::new(ctx, sh, scene, &selection)?;
        let buffer_side = if s.technique == Technique::Adaptive { 1 } else { s.photons };
        Ok(CausticPipeline {
            source: Source::new(ctx, sh, scene, meshes)?,
            selection,
            deposit,
            pipelines: CausticPipelines::new(ctx, sh)?,
            photons: PhotonTargets::new(ctx, buffer_side, photon_side, s.differentials)?,
            splat_path: s.splat_path,
            instance_vertices: s.instance_vertices,
        })
    }

    fn passes<'a>(&'a self, inputs: &'a FrameInputs<'a>, targets: &'a CausticTargets) -> CausticPasses<'a> {
        CausticPasses { pipelines: &self.pipelines, targets, photons: &self.photons, inputs }
    }

    /// Records the caustic passes of one frame, light after light: each light's source and
    /// selection (skipped with `reuse`: the last frame's photons are kept, static lighting in
    /// Wyman & Davis 2006 Table 1, where "the photon buffer does not need rerendering"), then
    /// its deposit; the deposit's last pass after every light. `eye`: the eye's view as this
    /// frame renders it.
    pub fn record(
        &self,
        f: &mut Frame,
        inputs: &FrameInputs,
        targets: &CausticTargets,
        lights: u32,
        eye: Option<EyeView>,
        reuse: bool,
    ) -> Result<()> {
        let c = self.passes(inputs, targets);
        for l in 0..lights {
            if let Selection::Adaptive(a) = &self.selection {
                // Adaptive caustic maps deposit batch after batch inside their traversal (Sec. 4.3).
                let splat = self.deposit.adaptive_splat(&c, l);
                if reuse && !a.plan().batched() {
                    a.record_splat_batch(f, &splat, l, BatchPart::Whole, true, true)?;
                } else {
                    self.source.record(f, &c, l)?;
                    a.record_traversal(f, inputs, l, Some(&splat))?;
                }
                continue;
            }
            if !reuse {
                self.record_light_space_passes(f, &c, l)?;
            }
            self.deposit.record(f, &c, &self.selection, l, eye, reuse)?;
        }
        self.source.record_after_deposit(f, &c)?;
        self.deposit.record_after_lights(f, &c, eye, reuse)
    }

    /// The next frame of `photon-trace`'s progressive accumulation (`Source::next_frame`): its
    /// splat radius, None without one.
    pub fn next_frame(&mut self) -> Option<f32> {
        self.source.next_frame()
    }

    /// Progressive accumulation starts again with the next frame (the lights or objects changed).
    pub fn restart_accumulation(&mut self) {
        self.source.restart_accumulation()
    }

    /// Whether every frame traces new photons into running means (`progressive`): the last
    /// frame's photons are never reused.
    pub fn progressive(&self) -> bool {
        matches!(&self.source, Source::Traced(t) if t.accumulated_frames().is_some())
    }

    /// Frames in `photon-trace`'s progressive means (None without `progressive`).
    pub fn accumulated_frames(&self) -> Option<u32> {
        match &self.source {
            Source::Traced(t) => t.accumulated_frames(),
            _ => None,
        }
    }

    /// Light `l`'s light-space passes before its deposit: its source and selection. One set
    /// of these buffers serves every light, light after light; the dumps record this alone to
    /// read a light's back.
    pub fn record_light_space(
        &self,
        f: &mut Frame,
        inputs: &FrameInputs,
        targets: &CausticTargets,
        l: u32,
    ) -> Result<()> {
        self.record_light_space_passes(f, &self.passes(inputs, targets), l)
    }

    fn record_light_space_passes(&self, f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
        self.source.record(f, c, l)?;
        self.selection.record(f, c, l)
    }

    /// Whether the caustics are deposited in the eye's view.
    /// The three stages, each by its name in the table above with the pass stages it records
    /// (source, selection, deposit).
    pub fn stages(&self) -> [(&'static str, &'static [crate::gpu::Stage]); 3] {
        [
            (self.source.name(), self.source.stages()),
            (self.selection.name(), self.selection.stages()),
            (self.deposit.name(), self.deposit.stages()),
        ]
    }

    /// Follows `scene`, a pose in which the objects `moved` moved (see
    /// `Source::follow_moved_meshes`).
    pub fn follow_moved_meshes(&mut self, ctx: &Context, scene: &Scene, moved: &[&str]) -> Result<()> {
        self.source.follow_moved_meshes(ctx, scene, moved)
    }

    pub fn eye_space(&self) -> bool {
        self.deposit.eye_space()
    }

    /// The caustic irradiance of the receiver view, which the receiver map reads (eye space).
    pub fn receiver_caustic(&self) -> Option<&ImageView> {
        self.deposit.receiver_caustic()
    }

    /// The photon buffer's targets (placeholders where the source makes none).
    pub fn photon_targets(&self) -> &PhotonTargets {
        &self.photons
    }

    /// The hierarchy of `hcm` (None for the other techniques).
    pub fn hierarchy(&self) -> Option<&Hierarchy> {
        match &self.selection {
            Selection::Hierarchy(h, _) => Some(h),
            _ => None,
        }
    }

    /// The adaptive caustic maps of `adaptive` (None for the other techniques).
    pub fn adaptive(&self) -> Option<&AdaptiveCaustics> {
        match &self.selection {
            Selection::Adaptive(a) => Some(a),
            _ => None,
        }
    }

    /// Per light, the sizes of the selection's lists of the last frame: `hcm`'s from its 16²
    /// level down to the splatted list; `adaptive`'s pending clusters of each level (0 to L),
    /// then the photons it splatted. None for a dense selection.
    pub fn list_sizes(&self, ctx: &Context) -> Result<Option<Vec<Vec<u64>>>> {
        Ok(match &self.selection {
            Selection::Hierarchy(h, _) => Some(h.list_sizes(ctx)?),
            Selection::Adaptive(a) => Some(
                a.level_counts(ctx)?
                    .into_iter()
                    .map(|(mut clusters, emitted)| {
                        clusters.push(emitted.iter().sum());
                        clusters
                    })
                    .collect(),
            ),
            Selection::Dense | Selection::Copy(_) => None,
        })
    }

    /// Points drawn (or compute-splat invocations) per frame over `lights` lights: every
    /// photon-buffer texel for a dense selection (invalid ones are culled in the vertex shader;
    /// the instanced draw rounds up to whole instances), the copied vertices, or the final list
    /// of the last traversal (read back from the GPU: Wyman & Nichols 2009 Table 1's "photons
    /// splatted").
    pub fn splats_drawn(&self, ctx: &Context, lights: u32) -> Result<u64> {
        if let Some(sizes) = self.list_sizes(ctx)? {
            return Ok(sizes.iter().map(|s| s.last().copied().unwrap_or(0)).sum());
        }
        let texels = self.photons.width * self.photons.width;
        let per_light = match &self.selection {
            Selection::Copy(copy) => copy.vertices() as u64,
            _ => match self.splat_path {
                // One invocation per photon-buffer texel.
                SplatPath::Compute => texels as u64,
                SplatPath::Raster => (texels.div_ceil(self.instance_vertices) * self.instance_vertices) as u64,
            },
        };
        Ok(per_light * lights as u64)
    }
}
