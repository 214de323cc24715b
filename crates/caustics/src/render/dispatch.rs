//! `Renderer`: what `causticlab render`, the bench and the tests drive frame by frame. A scene of
//! meshes and lights is rendered by the [`MeshRenderer`] (the eye render and the photon
//! techniques); a pool scene (`[pool]`) by Trendall & Stewart 2000's `PoolRenderer`, which has no
//! photons, meshes or shadow maps.

use super::renderer::{MeshRenderer, RendererOptions};
use super::FrameStep;
use crate::dump::Dump;
use crate::image_io::ImageF32;
use crate::scene::Scene;
use crate::techniques::trendall_stewart2000::PoolRenderer;
use crate::techniques::wyman2008::Hierarchy;
use anyhow::Result;
use vkcore::{Context, FrameReport, ShaderCompiler};

pub enum Renderer<'c> {
    Mesh(Box<MeshRenderer<'c>>),
    Pool(Box<PoolRenderer<'c>>),
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
        Ok(Renderer::Pool(Box::new(PoolRenderer::new(ctx, shaders, scene, opts.frame_mode, opts.pass_timestamps)?)))
    }

    /// Moves to `scene`, a pose of the scene this renderer was made for (`crate::animation`).
    pub fn set_pose(&mut self, scene: &Scene) -> Result<()> {
        match self {
            Renderer::Mesh(r) => r.set_pose(scene),
            Renderer::Pool(r) => r.set_pose(scene),
        }
    }

    /// Records, submits and waits for one frame; returns its per-pass timings (per-pass
    /// frames) or its frame time (a throughput frame waited for alone).
    pub fn frame(&mut self, step: FrameStep) -> Result<FrameReport> {
        match self {
            Renderer::Mesh(r) => r.frame(step),
            Renderer::Pool(r) => r.frame(step),
        }
    }

    /// Throughput frames: records and submits the next frame without waiting for it; returns
    /// the reports of the frames that finished meanwhile (`FrameMode::Throughput` only).
    pub fn submit(&mut self, step: FrameStep) -> Result<Vec<FrameReport>> {
        match self {
            Renderer::Mesh(r) => r.submit(step),
            Renderer::Pool(r) => r.submit(),
        }
    }

    /// [`Renderer::submit`], with `after` recording more passes at the end of the frame (the
    /// viewer's display pass).
    pub fn submit_with(
        &mut self,
        step: FrameStep,
        after: &mut dyn FnMut(&mut vkcore::Frame, &vkcore::ImageView) -> Result<()>,
    ) -> Result<Vec<FrameReport>> {
        match self {
            Renderer::Mesh(r) => r.submit_with(step, after),
            Renderer::Pool(r) => r.submit_with(after),
        }
    }

    /// The final image on the GPU (linear radiance, RGBA 32-bit float, row 0 at the top).
    pub fn final_view(&self) -> &vkcore::ImageView {
        match self {
            Renderer::Mesh(r) => r.final_view(),
            Renderer::Pool(r) => r.final_view(),
        }
    }

    /// Waits for every throughput frame in flight; returns the reports not yet returned.
    pub fn finish(&mut self) -> Result<Vec<FrameReport>> {
        match self {
            Renderer::Mesh(r) => r.finish(),
            Renderer::Pool(r) => r.finish(),
        }
    }

    /// The last frame's linear radiance.
    pub fn final_image(&self) -> Result<ImageF32> {
        match self {
            Renderer::Mesh(r) => r.final_image(),
            Renderer::Pool(r) => r.final_image(),
        }
    }

    /// The named intermediate buffer of the last frame (None where this render has none).
    pub fn dump(&mut self, name: &str) -> Result<Option<ImageF32>> {
        Ok(self.dumps(&[name.to_string()])?.pop().map(|(_, img)| img))
    }

    /// The intermediate buffer `d` of the last frame (None where this render has none).
    pub fn read_dump(&mut self, d: &'static Dump) -> Result<Option<ImageF32>> {
        Ok(match self {
            Renderer::Mesh(r) => r.dumps(&[d])?,
            Renderer::Pool(r) => r.dumps(&[d])?,
        }
        .pop()
        .map(|(_, img)| img))
    }

    /// The last frame's receiver map (the eye render's `receiver`, or the pool bottom's).
    pub fn receiver_map(&mut self) -> Result<Option<ImageF32>> {
        let d = match self {
            Renderer::Mesh(_) => &super::dumps::RECEIVER,
            Renderer::Pool(_) => &crate::techniques::trendall_stewart2000::settings::RECEIVER,
        };
        self.read_dump(d)
    }

    /// The named intermediate buffers of the last frame (`--dump` names: each is read here
    /// once, as the declaration of that name this render has), skipping those it has none of.
    pub fn dumps(&mut self, names: &[String]) -> Result<Vec<(&'static Dump, ImageF32)>> {
        let settings = match self {
            Renderer::Mesh(r) => &r.scene().caustics,
            Renderer::Pool(r) => &r.scene().caustics,
        };
        let wanted: Vec<&'static Dump> = names.iter().filter_map(|n| super::dumps::named(n, settings)).collect();
        match self {
            Renderer::Mesh(r) => r.dumps(&wanted),
            Renderer::Pool(r) => r.dumps(&wanted),
        }
    }

    /// Photons emitted per frame over all lights (a pool has none).
    pub fn photons_emitted(&self) -> u64 {
        match self {
            Renderer::Mesh(r) => r.photons_emitted(),
            Renderer::Pool(_) => 0,
        }
    }

    /// Valid photons of the last frame (see `MeshRenderer::valid_photons`; a pool has none).
    pub fn valid_photons(&mut self, read: Option<&ImageF32>) -> Result<Option<u64>> {
        match self {
            Renderer::Mesh(r) => r.valid_photons(read),
            Renderer::Pool(_) => Ok(None),
        }
    }

    /// The hierarchy of `hcm` (None for the other techniques).
    /// The caustic stages of a mesh technique (`CausticPipeline::stages`); none for `none` and
    /// the pool.
    pub fn caustic_stages(&self) -> Option<[(&'static str, &'static [crate::gpu::Stage]); 3]> {
        match self {
            Renderer::Mesh(r) => r.caustics().map(|c| c.stages()),
            Renderer::Pool(_) => None,
        }
    }

    pub fn hierarchy(&self) -> Option<&Hierarchy> {
        match self {
            Renderer::Mesh(r) => r.caustics().and_then(|c| c.hierarchy()),
            Renderer::Pool(_) => None,
        }
    }

    /// The adaptive caustic maps of `adaptive` (None for the other techniques).
    pub fn adaptive(&self) -> Option<&crate::techniques::AdaptiveCaustics> {
        match self {
            Renderer::Mesh(r) => r.caustics().and_then(|c| c.adaptive()),
            Renderer::Pool(_) => None,
        }
    }

    /// Per light, the traversal's list sizes of `hcm` or `adaptive` (see
    /// `MeshRenderer::list_sizes`; None for the other techniques).
    pub fn list_sizes(&self) -> Result<Option<Vec<Vec<u64>>>> {
        match self {
            Renderer::Mesh(r) => r.list_sizes(),
            Renderer::Pool(_) => Ok(None),
        }
    }

    /// Points drawn per frame over all lights (a pool draws none).
    pub fn splats_drawn(&self) -> Result<u64> {
        match self {
            Renderer::Mesh(r) => r.splats_drawn(),
            Renderer::Pool(_) => Ok(0),
        }
    }
}

/// The final settings must belong together (a `[caustics]` may leave the technique to the
/// command line; see `CausticSettings::validate_combination`).
fn settings_belong(scene: &Scene) -> Result<()> {
    scene.caustics.validate_combination(&scene.path.display().to_string(), "caustics.")
}
