//! The caustic techniques, one folder per paper, as a closed set: [`Technique`].
//!
//! | technique | paper | module |
//! |---|---|---|
//! | `none` | (the eye render alone: shadow maps, Wyman 2005 refraction) | `crate::render` |
//! | `shah`, `shah-vertex` | Shah, Konttinen & Pattanaik, caustics mapping | [`shah2007`] |
//! | `wd-points` | Wyman & Davis 2006, the photon buffer as points | [`wyman_davis2006`] |
//! | `hcm` | Wyman 2008, hierarchical caustic maps | [`wyman2008`] |
//! | `adaptive` | Wyman & Nichols 2009 Sec. 3.2-4.2, adaptive caustic maps | [`wyman_nichols2009`] |
//! | (`--refraction deferred`, any technique) | Wyman & Nichols 2009 Sec. 3.1, deferred refraction | [`wyman_nichols2009`] |
//! | `pool-convolution` | Trendall & Stewart 2000, pool caustics as convolutions | [`trendall_stewart2000`] |
//! | `photon-trace` | beyond the papers: exact photon tracing on the GPU | [`photon_trace`] |
//!
//! Stages that several papers share (photon emission, the point and compute splats, the
//! caustic-map targets and uniforms) are in [`shared`]; a technique is a choice of a photon
//! source, a selection and a deposit ([`stages`]), whose [`CausticPipeline`] records a frame's
//! caustic passes. Every technique writes power (W) into caustic-map
//! texels; `common/caustic_lookup.glsl` turns that into irradiance with the texel's area on the
//! receiver (Wyman & Davis 2006, Eq. 5-8).

mod mirrored;
pub mod photon_trace;
pub mod settings;
pub mod shah2007;
pub mod shared;
pub mod stages;
mod technique;
pub mod trendall_stewart2000;
pub mod uniforms;
mod value_enum;
pub mod variants;
pub mod wyman2008;
pub mod wyman_davis2006;
pub mod wyman_nichols2009;

pub use settings::{CausticOverrides, CausticSettings};
pub use shared::splat::record_cleared;
pub use shared::{CausticPasses, EyeView, FrameInputs};
pub use shared::{
    CausticPipelines, CausticTargets, ComputeSplat, Intersect, PhotonTargets, PhotonView, SplatKernel, SplatPath,
};
pub use stages::CausticPipeline;
pub use technique::Technique;
pub use wyman2008::photon_copy::{CopyType, PhotonCopy};
pub use wyman2008::Hierarchy;
pub use wyman_nichols2009::{AdaptiveCaustics, Metric, PhotonRefraction, Refraction};

use crate::dump::Dump;
use crate::gpu::frames::FrameRenderer;
use crate::gpu::FrameMode;
use crate::scene::Scene;
use vkcore::{Context, ShaderCompiler};

/// Every dump the techniques declare, owner by owner (after the eye render's, the order of
/// `--dump all`: `crate::render::dumps::all`).
pub fn technique_dumps() -> Vec<&'static Dump> {
    [
        shared::settings::DUMPS,
        &[&shared::settings::PHOTON_FOOTPRINTS],
        wyman_nichols2009::settings::DEFERRED_PHOTONS_DUMPS,
        wyman_davis2006::settings::DUMPS,
        wyman2008::DUMPS,
        wyman_nichols2009::settings::ADAPTIVE_DUMPS,
        trendall_stewart2000::DUMPS,
    ]
    .concat()
}

/// The renderer of a technique that renders its own frames rather than meshes through the eye
/// render (`Technique::renders_meshes` false): Trendall & Stewart 2000's pool renderer.
pub fn own_renderer<'c>(
    ctx: &'c Context,
    shaders: &'c ShaderCompiler,
    scene: &Scene,
    mode: FrameMode,
    pass_timestamps: bool,
) -> anyhow::Result<Box<dyn FrameRenderer + 'c>> {
    match scene.caustics.technique {
        Technique::PoolConvolution => {
            Ok(Box::new(trendall_stewart2000::PoolRenderer::new(ctx, shaders, scene, mode, pass_timestamps)?))
        }
        other => anyhow::bail!("`{other}` is rendered by the mesh renderer, not a renderer of its own"),
    }
}
