//! Photons drawn as points into a view (Wyman & Davis 2006 Sec. 3.2, Fig. 4; Sec. 3.2.2 step
//! 1): each photon of the photon buffer adds its power, a count of one and its incident
//! direction to the pixel it lands in (`shaders_glsl/wyman_davis2006/photons.vert`, `.frag`).
//! In the eye's view this is the eye-space photon buffer of `wd-eye-points` and the eye-space
//! gather; into light l's caustic map (LIGHT_SPACE), the light-space gather's.

use super::push::ImageSpaceConstants;
use super::views::ViewBuffers;
use crate::gpu::formats::COLOR;
use crate::techniques::shared::CausticPasses;
use anyhow::Result;
use vkcore::{
    Access, Blend, Context, Frame, GraphicsDesc, ImageView, Pipeline, ShaderCompiler, Targets, Topology, Use,
};

/// The photons' point pipeline into a view (`light_space`: into a caustic map).
pub fn pipeline(ctx: &Context, sh: &ShaderCompiler, light_space: bool) -> Result<Pipeline> {
    let defines: &[(&str, &str)] = if light_space { &[("LIGHT_SPACE", "1")] } else { &[] };
    let name = if light_space { "wd.photons.light_space" } else { "wd.photons" };
    let mut d = GraphicsDesc::new(
        name,
        sh.compile("wyman_davis2006/photons.vert", defines)?,
        Some(sh.compile("wyman_davis2006/photons.frag", defines)?),
    );
    d.topology = Topology::Points;
    d.blend = Blend::Additive;
    d.color_formats = vec![COLOR, COLOR];
    Ok(Pipeline::graphics(ctx, &d)?)
}

/// Where the points go: a view's photon layer `slot` and directions, seen through `geometry`
/// (world position, and normal: the position again in light space).
pub struct PointsInto<'a> {
    pub name: crate::gpu::PassName,
    pub buffers: &'a ViewBuffers,
    pub slot: u32,
    pub geometry: (&'a ImageView, &'a ImageView),
    /// Clear the layer and the directions first (the first light of a frame).
    pub clear: bool,
}

/// Draws light `l`'s photons (the photon buffer as it is now) as points into `into`.
pub fn record(
    f: &mut Frame,
    c: &CausticPasses,
    pipeline: &Pipeline,
    into: PointsInto,
    constants: ImageSpaceConstants,
) -> Result<()> {
    let pt = c.photons;
    let layer = &into.buffers.layers[into.slot as usize];
    let directions = &into.buffers.directions.view;
    let binds = super::views::photon_view_binds(c, pipeline, into.geometry);
    let clear = if into.clear { Some([0.0; 4]) } else { None };
    f.pass(&into.name)
        .bind(pipeline, binds)
        .uses([Use::view(layer, Access::COLOR_ATTACHMENT), Use::view(directions, Access::COLOR_ATTACHMENT)])
        .record(|cmd| {
            cmd.begin_rendering(&Targets::colors(vec![(layer, clear), (directions, clear)]))?;
            cmd.push(&constants)?;
            cmd.draw(pt.width * pt.width, 1, 0, 0);
            cmd.end_rendering();
            Ok(())
        })?;
    Ok(())
}
