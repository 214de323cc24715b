//! The point splat (Wyman & Davis 2006 Sec. 3.2; Shah et al.'s Gaussian point splats): every
//! photon of light `l` drawn as a point into its caustic-map layer with additive blending,
//! fetched instanced from the photon buffer (Wyman 2008 Sec. 4). The copy path of Wyman 2008
//! Table 1 splats from a vertex array instead (`wyman2008::photon_copy`).

use super::pipelines::point_splat_desc;
use super::targets::CausticTargets;
use super::CausticPasses;
use crate::gpu::PassName;
use crate::gpu::SplatConstants;
use crate::gpu::Stage;
use anyhow::Result;
use vkcore::{
    Access, Bind, Buffer, CompactStream, Context, Frame, ImageView, Named, Pipeline, ShaderCompiler, Targets, Use,
};

/// Where a list's point splat lands: light `light`'s caustic map `cmap`, its `layers` layers
/// (the multi-resolution map's, else 1), cleared first or added to.
pub(crate) struct ListSplat<'a> {
    pub cmap: &'a ImageView,
    pub layers: u32,
    pub clear: bool,
    pub light: u32,
}

/// The point splat over a traversal's list (Wyman 2008's final entries, Wyman & Nichols 2009's
/// photons): `pipeline` draws a point per element, the list as vertex buffer 0, as many as its
/// counter says (nothing read back).
pub(crate) fn record_list_splat<'a>(
    f: &mut Frame,
    name: &PassName,
    pipeline: &'a Pipeline,
    binds: impl IntoIterator<Item = Named<'a>>,
    list: &'a CompactStream,
    to: ListSplat<'a>,
) -> Result<()> {
    let uses = [
        Use::buffer(list.data(), Access::VERTEX_INPUT),
        list.arguments_use(),
        Use::view(to.cmap, Access::COLOR_ATTACHMENT),
    ];
    f.pass(name).bind(pipeline, binds).uses(uses).record(|cmd| {
        cmd.begin_rendering(&Targets::color(to.cmap, to.clear.then_some([0.0; 4])).layered(to.layers))?;
        cmd.push(&SplatConstants { light: to.light, vertices_per_instance: 0 })?;
        cmd.bind_vertex_buffer(list.data(), 0)?;
        list.draw(cmd)?;
        cmd.end_rendering();
        Ok(())
    })?;
    Ok(())
}

/// The point splat of the photon buffer: a point per photon-buffer texel, fetched instanced
/// from the photon texture (Wyman 2008 Sec. 4: one small vertex buffer of `0..per_instance`
/// drawn instanced; the vertex shader finds its photon from gl_InstanceIndex and the vertex's
/// index).
pub struct PointSplat {
    pipeline: Pipeline,
    vertices: Buffer,
    per_instance: u32,
}

impl PointSplat {
    /// `per_instance`: vertices per instance (`caustics.instance_vertices`).
    pub fn new(ctx: &Context, sh: &ShaderCompiler, per_instance: u32) -> Result<PointSplat> {
        Self::with_pipeline(ctx, Pipeline::graphics(ctx, &point_splat_desc(sh)?)?, per_instance)
    }

    /// The same instanced draw through another pipeline of [`point_splat_desc`]'s shape (its
    /// vertex shader a deposit's own, `shared/splat_points.glsl` with its radius, reading more
    /// bindings: see [`Self::record_with`]).
    pub fn with_pipeline(ctx: &Context, pipeline: Pipeline, per_instance: u32) -> Result<PointSplat> {
        let ids: Vec<u32> = (0..per_instance).collect();
        let vertices = ctx.buffer_with_data("splat vertices", bytemuck::cast_slice(&ids))?;
        Ok(PointSplat { pipeline, vertices, per_instance })
    }

    /// Splats light `l`'s photons into its caustic-map layer.
    pub fn record(&self, f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
        self.record_with(f, c, l, [])
    }

    /// [`Self::record`], the pipeline also bound to `more` (after the uniforms and the photon
    /// buffer's position and power).
    pub fn record_with<'a>(
        &'a self,
        f: &mut Frame,
        c: &CausticPasses<'a>,
        l: u32,
        more: impl IntoIterator<Item = Named<'a>>,
    ) -> Result<()> {
        let (ct, pt, inp) = (c.targets, c.photons, c.inputs);
        let (cmap, _, _) = &ct.per_light[l as usize];
        let binds = [
            ("frame", Bind::Uniform(inp.frame_uniforms)),
            ("caustics", Bind::Uniform(inp.caustic_uniforms)),
            ("photon_position", Bind::Sampled(&pt.position.view, inp.nearest)),
            ("photon_power", Bind::Sampled(&pt.power.view, inp.nearest)),
        ];
        let per_instance = self.per_instance;
        f.pass(&Stage::Splat.light(l))
            .bind(&self.pipeline, binds.into_iter().chain(more))
            .uses([Use::view(cmap, Access::COLOR_ATTACHMENT), Use::buffer(&self.vertices, Access::VERTEX_INPUT)])
            .record(|cmd| {
                cmd.begin_rendering(&Targets::color(cmap, Some([0.0; 4])))?;
                cmd.push(&SplatConstants { light: l, vertices_per_instance: per_instance })?;
                cmd.bind_vertex_buffer(&self.vertices, 0)?;
                let total = pt.width * pt.width;
                cmd.draw(per_instance, total.div_ceil(per_instance), 0, 0);
                cmd.end_rendering();
                Ok(())
            })?;
        Ok(())
    }
}

/// With technique `none`: clears the (1x1) caustic map and receiver positions the eye passes bind.
pub fn record_cleared(f: &mut Frame, ct: &CausticTargets) -> Result<()> {
    let uses = [
        Use::view(&ct.caustic_map.view, Access::TRANSFER_WRITE),
        Use::view(&ct.receiver_positions.view, Access::TRANSFER_WRITE),
    ];
    f.pass(&Stage::CausticsClear.pass()).uses(uses).record(|cmd| {
        cmd.clear_color(&ct.caustic_map.view, [0.0; 4]);
        cmd.clear_color(&ct.receiver_positions.view, [0.0; 4]);
        Ok(())
    })?;
    Ok(())
}
