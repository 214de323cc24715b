//! The image-space gather (Wyman & Davis 2006 Sec. 3.2.2 step 2,
//! `shaders_glsl/wyman_davis2006/gather.comp`): over the 7x7 neighbourhood of every pixel of a
//! view, Gaussian weights, neighbour areas from world positions, Eq. 6-8, Eq. 10 (9, 11), and
//! the discarding of neighbourhoods hit by fewer than three photons. With radius 0 and no
//! discarding it resolves `wd-eye-points` (each pixel its own photons). Also the shading that
//! adds the eye's caustics to its radiance (step 3), and the receiver view's geometry.

use super::push::ImageSpaceConstants;
use super::views::ViewBuffers;
use crate::techniques::shared::CausticPasses;
use anyhow::Result;
use vkcore::{Bind, Context, Frame, ImageView, Pipeline, ShaderCompiler};

/// The gather's half-width: 7x7 pixels (Sec. 3.2.2 step 2 (1)).
pub const RADIUS: u32 = 3;
/// Neighbourhoods hit by fewer photons are discarded (step 2 (5)).
pub const MIN_PHOTONS: u32 = 3;

pub fn pipeline(ctx: &Context, sh: &ShaderCompiler, light_space: bool) -> Result<Pipeline> {
    let defines: &[(&str, &str)] = if light_space { &[("LIGHT_SPACE", "1")] } else { &[] };
    let name = if light_space { "wd.gather.light_space" } else { "wd.gather" };
    Ok(Pipeline::compute(ctx, name, &sh.compile("wyman_davis2006/gather.comp", defines)?)?)
}

pub fn shade_pipeline(ctx: &Context, sh: &ShaderCompiler) -> Result<Pipeline> {
    Ok(Pipeline::compute(ctx, "wd.shade", &sh.compile("wyman_davis2006/shade.comp", &[])?)?)
}

pub fn receiver_view_pipeline(ctx: &Context, sh: &ShaderCompiler) -> Result<Pipeline> {
    Ok(Pipeline::compute(ctx, "wd.receiver_view", &sh.compile("wyman_davis2006/receiver_view.comp", &[])?)?)
}

#[allow(clippy::too_many_arguments)]
/// Gathers `from` (seen through `geometry`: position and normal) into `out` (a caustic
/// irradiance image, or light l's caustic-map layer).
pub fn record(
    f: &mut Frame,
    name: &str,
    c: &CausticPasses,
    pipeline: &Pipeline,
    from: &ViewBuffers,
    geometry: (&ImageView, &ImageView),
    out: &ImageView,
    constants: ImageSpaceConstants,
) -> Result<()> {
    let inp = c.inputs;
    let mut binds = vec![
        ("frame", Bind::Uniform(inp.frame_uniforms)),
        ("caustics", Bind::Uniform(inp.caustic_uniforms)),
        ("photons", Bind::Sampled(&from.photons.view, inp.nearest)),
        ("directions", Bind::Sampled(&from.directions.view, inp.nearest)),
        ("view_position", Bind::Sampled(geometry.0, inp.nearest)),
    ];
    // In light space (`LIGHT_SPACE`) the gather reads no normals.
    if pipeline.declares("view_normal") {
        binds.push(("view_normal", Bind::Sampled(geometry.1, inp.nearest)));
    }
    binds.push(("gathered", Bind::Storage(out)));
    f.pass(name).bind(pipeline, binds).record(|cmd| {
        cmd.push(&constants)?;
        cmd.dispatch(from.width.div_ceil(8), from.height.div_ceil(8), 1);
        Ok(())
    })?;
    Ok(())
}
