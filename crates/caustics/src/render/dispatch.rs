//! `Renderer`: what `causticlab render`, the bench and the tests drive frame by frame. A scene of
//! meshes and lights is rendered by the [`MeshRenderer`] (the eye render and the photon
//! techniques); a technique with a renderer of its own by that one, made by the techniques'
//! module (`techniques::own_renderer`: Trendall & Stewart 2000's pool, which has no photons, meshes or
//! shadow maps). Both are a `gpu::frames::FrameRenderer`, whose frames one path submits.

use super::renderer::{MeshRenderer, RendererOptions};
use super::FrameStep;
use crate::dump::Dump;
use crate::gpu::frames::{self, After, FrameRenderer};
use crate::image_io::ImageF32;
use crate::scene::Scene;
use crate::techniques::CausticPipeline;
use anyhow::Result;
use vkcore::{Context, FrameReport, ShaderCompiler};

pub enum Renderer<'c> {
    Mesh(Box<MeshRenderer<'c>>),
    /// A technique that renders its own frames (`techniques::own_renderer`: the pool).
    Own(Box<dyn FrameRenderer + 'c>),
}

impl<'c> Renderer<'c> {
    /// The renderer of `scene`'s technique; a pool scene needs `pool-convolution` and
    /// `pool-convolution` a pool scene (input errors naming the file otherwise).
    pub fn new(ctx: &'c Context, shaders: &'c ShaderCompiler, scene: &Scene, opts: &RendererOptions) -> Result<Self> {
        let technique = scene.caustics.technique;
        settings_belong(scene)?;
        if technique.renders_meshes() {
            if scene.pool.is_some() {
                return Err(crate::input_error!(
                    "{}: a pool scene ([pool]) is rendered by technique `pool-convolution` alone, not `{technique}`",
                    scene.path.display()
                )
                .into());
            }
            return Ok(Renderer::Mesh(Box::new(MeshRenderer::new(ctx, shaders, scene, opts)?)));
        }
        if opts.photon_copy.is_some() {
            return Err(crate::input_error!("photon_copy: `{technique}` has no photon buffer to copy").into());
        }
        Ok(Renderer::Own(crate::techniques::own_renderer(ctx, shaders, scene, opts.frame_mode, opts.pass_timestamps)?))
    }

    /// Either renderer, as what every renderer does.
    fn any(&mut self) -> &mut dyn FrameRenderer {
        match self {
            Renderer::Mesh(r) => r.as_mut(),
            Renderer::Own(r) => r.as_mut(),
        }
    }

    fn any_ref(&self) -> &dyn FrameRenderer {
        match self {
            Renderer::Mesh(r) => r.as_ref(),
            Renderer::Own(r) => r.as_ref(),
        }
    }

    /// Moves to `scene`, a pose of the scene this renderer was made for (`crate::animation`).
    pub fn set_pose(&mut self, scene: &Scene) -> Result<()> {
        self.any().set_pose(scene)
    }

    /// Records, submits and waits for one frame; returns its per-pass timings (per-pass
    /// frames) or its frame time (a throughput frame waited for alone).
    pub fn frame(&mut self, step: FrameStep) -> Result<FrameReport> {
        frames::frame(self.any(), step)
    }

    /// Throughput frames: records and submits the next frame without waiting for it; returns
    /// the reports of the frames that finished meanwhile (`FrameMode::Throughput` only).
    pub fn submit(&mut self, step: FrameStep) -> Result<Vec<FrameReport>> {
        self.submit_with(step, &mut |_, _| Ok(()))
    }

    /// [`Renderer::submit`], with `after` recording more passes at the end of the frame (the
    /// viewer's display pass).
    pub fn submit_with(&mut self, step: FrameStep, after: After) -> Result<Vec<FrameReport>> {
        frames::submit_with(self.any(), step, after)
    }

    /// The final image on the GPU (linear radiance, RGBA 32-bit float, row 0 at the top).
    pub fn final_view(&self) -> &vkcore::ImageView {
        self.any_ref().final_view()
    }

    /// Waits for every throughput frame in flight; returns the reports not yet returned.
    pub fn finish(&mut self) -> Result<Vec<FrameReport>> {
        frames::finish(self.any())
    }

    /// The last frame's linear radiance.
    pub fn final_image(&self) -> Result<ImageF32> {
        self.any_ref().final_image()
    }

    /// The named intermediate buffer of the last frame (None where this render has none).
    pub fn dump(&mut self, name: &str) -> Result<Option<ImageF32>> {
        Ok(self.dumps(&[name.to_string()])?.pop().map(|(_, img)| img))
    }

    /// The intermediate buffer `d` of the last frame (None where this render has none).
    pub fn read_dump(&mut self, d: &'static Dump) -> Result<Option<ImageF32>> {
        Ok(self.declared_dumps(&[d])?.pop().map(|(_, img)| img))
    }

    /// The buffers `wanted` of the last frame, each checked against its declaration's layers
    /// and channels (`Dump::check`: a buffer read otherwise is a bug, reported, never written).
    fn declared_dumps(&mut self, wanted: &[&'static Dump]) -> Result<Vec<(&'static Dump, ImageF32)>> {
        let read = self.any().dumps(wanted)?;
        for (d, img) in &read {
            d.check(img)?;
        }
        Ok(read)
    }

    /// The last frame's receiver map (the eye render's `receiver`, or the pool bottom's).
    pub fn receiver_map(&mut self) -> Result<Option<ImageF32>> {
        let d = self.any_ref().receiver();
        self.read_dump(d)
    }

    /// The named intermediate buffers of the last frame (`--dump` names: each is read here
    /// once, as the declaration of that name this render has), skipping those it has none of.
    pub fn dumps(&mut self, names: &[String]) -> Result<Vec<(&'static Dump, ImageF32)>> {
        let settings = &self.any_ref().scene().caustics;
        let wanted: Vec<&'static Dump> = names.iter().filter_map(|n| super::dumps::named(n, settings)).collect();
        self.declared_dumps(&wanted)
    }

    /// Photons emitted per frame over all lights (a pool has none).
    pub fn photons_emitted(&self) -> u64 {
        match self {
            Renderer::Mesh(r) => r.photons_emitted(),
            Renderer::Own(_) => 0,
        }
    }

    /// Valid photons of the last frame (see `MeshRenderer::valid_photons`; a pool has none).
    pub fn valid_photons(&mut self, read: Option<&ImageF32>) -> Result<Option<u64>> {
        match self {
            Renderer::Mesh(r) => r.valid_photons(read),
            Renderer::Own(_) => Ok(None),
        }
    }

    /// The caustic stages of a mesh technique (`CausticPipeline::stages`); none for `none` and
    /// the pool.
    pub fn caustic_stages(&self) -> Option<[(&'static str, &'static [crate::gpu::Stage]); 3]> {
        self.caustics().map(|c| c.stages())
    }

    /// The technique's caustic stages (None for `none` and a technique's own renderer).
    pub fn caustics(&self) -> Option<&CausticPipeline> {
        match self {
            Renderer::Mesh(r) => r.caustics(),
            Renderer::Own(_) => None,
        }
    }

    /// `photon-trace --progressive`: the next frame starts its means again (nothing for the
    /// other techniques).
    pub fn restart_accumulation(&mut self) {
        if let Renderer::Mesh(r) = self {
            r.restart_accumulation();
        }
    }

    /// Points drawn per frame over all lights (a pool draws none).
    pub fn splats_drawn(&self) -> Result<u64> {
        match self {
            Renderer::Mesh(r) => r.splats_drawn(),
            Renderer::Own(_) => Ok(0),
        }
    }
}

/// The final settings must belong together (a `[caustics]` may leave the technique to the
/// command line; see `CausticSettings::validate_combination`).
fn settings_belong(scene: &Scene) -> Result<()> {
    scene.caustics.validate_combination(&scene.path.display().to_string(), "caustics.")
}
