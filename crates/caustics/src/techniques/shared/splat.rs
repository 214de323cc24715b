//! The point splat (Wyman & Davis 2006 Sec. 3.2; Shah et al.'s Gaussian point splats): every
//! photon of light `l` drawn as a point into its caustic-map layer with additive blending,
//! fetched instanced from the photon buffer (Wyman 2008 Sec. 4). The copy path of Wyman 2008
//! Table 1 splats from a vertex array instead (`wyman2008::photon_copy`).

use super::targets::CausticTargets;
use super::CausticPasses;
use crate::gpu::PassName;
use crate::gpu::SplatConstants;
use crate::gpu::Stage;
use anyhow::Result;
use vkcore::{Access, Bind, CompactStream, Frame, ImageView, Named, Pipeline, Targets, Use};

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

/// Splats light `l`'s photons into its caustic-map layer, fetched instanced from the photon
/// texture (Wyman 2008 Sec. 4).
pub(crate) fn record_splat(f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
    let (p, ct, pt, inp) = (c.pipelines, c.targets, c.photons, c.inputs);
    let (cmap, _, _) = &ct.per_light[l as usize];
    let binds = [
        ("frame", Bind::Uniform(inp.frame_uniforms)),
        ("caustics", Bind::Uniform(inp.caustic_uniforms)),
        ("photon_position", Bind::Sampled(&pt.position.view, inp.nearest)),
        ("photon_power", Bind::Sampled(&pt.power.view, inp.nearest)),
    ];
    f.pass(&Stage::Splat.light(l))
        .bind(&p.splat, binds)
        .uses([Use::view(cmap, Access::COLOR_ATTACHMENT), Use::buffer(inp.splat_vertices, Access::VERTEX_INPUT)])
        .record(|cmd| {
            cmd.begin_rendering(&Targets::color(cmap, Some([0.0; 4])))?;
            cmd.push(&SplatConstants { light: l, vertices_per_instance: inp.instance_vertices })?;
            cmd.bind_vertex_buffer(inp.splat_vertices, 0)?;
            let total = pt.width * pt.width;
            // Wyman 2008 Sec. 4: one small vertex buffer drawn instanced; the vertex shader
            // finds its photon from gl_InstanceIndex and the vertex's index.
            cmd.draw(inp.instance_vertices, total.div_ceil(inp.instance_vertices), 0, 0);
            cmd.end_rendering();
            Ok(())
        })?;
    Ok(())
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
