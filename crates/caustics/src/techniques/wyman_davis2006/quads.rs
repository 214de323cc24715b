//! Caustic quads (Wyman & Davis 2006 Sec. 3.2.1, `shaders_glsl/wyman_davis2006/quads.*`): a
//! polygon between every 2x2 block of adjacent landed photons, carrying R = w_B / w_P
//! (Eq. 1-2), lit with Eq. 3 or 4 and blended additively into the eye's caustic irradiance or
//! into light l's caustic map. The culling test is stated in quads.vert. Polygons under a pixel
//! of the view are drawn by a second pipeline as one point each, carrying the beam's whole
//! power (`QUAD_POINTS`, see quads.vert): the rasterizer would hit or miss them whole; slivers
//! (a pixel or more long, under one wide) by a third as a line sharing that power among its
//! fragments (`QUAD_LINES`). With `quad_draw = "polygons"` every quad is its polygon whatever its
//! size, as the paper draws them (`QUAD_POLYGONS`).

use super::push::ImageSpaceConstants;
use super::settings::QuadDraw;
use crate::gpu::formats::COLOR;
use crate::techniques::shared::CausticPasses;
use anyhow::Result;
use vkcore::{
    Access, Bind, Blend, Context, Cull, Frame, GraphicsDesc, ImageView, Pipeline, ShaderCompiler, Targets, Topology,
    Use,
};

/// How the quads' pipelines draw a block's polygon (same bindings and push constants).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Primitive {
    /// Two triangles: every polygon (Eq. 1-4 as the paper draws them).
    Polygons,
    /// Two triangles: polygons a pixel or more wide.
    Triangles,
    /// One point with the beam's power: polygons under a pixel.
    Points,
    /// A line along the longer diagonal sharing the beam's power: slivers.
    Lines,
}

/// The quads' pipelines, by [`QuadDraw`].
pub enum QuadPipelines {
    /// Every quad as two triangles.
    Polygons(Pipeline),
    /// Each quad as two triangles, a point or a line ([`Primitive`]).
    Exact { triangles: Pipeline, points: Pipeline, lines: Pipeline },
}

pub fn pipeline(ctx: &Context, sh: &ShaderCompiler, light_space: bool, draw: QuadDraw) -> Result<QuadPipelines> {
    let build = |primitive: Primitive| -> Result<Pipeline> {
        let mut defines: Vec<(&str, &str)> = vec![];
        if light_space {
            defines.push(("LIGHT_SPACE", "1"));
        }
        let (define, topology, base) = match primitive {
            Primitive::Polygons => (Some("QUAD_POLYGONS"), Topology::Triangles, "wd.quads.polygons"),
            Primitive::Triangles => (None, Topology::Triangles, "wd.quads"),
            Primitive::Points => (Some("QUAD_POINTS"), Topology::Points, "wd.quads.points"),
            Primitive::Lines => (Some("QUAD_LINES"), Topology::Lines, "wd.quads.lines"),
        };
        if let Some(d) = define {
            defines.push((d, "1"));
        }
        let name = if light_space { format!("{base}.light_space") } else { base.to_string() };
        let mut d = GraphicsDesc::new(
            &name,
            sh.compile("wyman_davis2006/quads.vert", &defines)?,
            Some(sh.compile("wyman_davis2006/quads.frag", &defines)?),
        );
        d.topology = topology;
        d.cull = Cull::None;
        d.blend = Blend::Additive;
        d.color_formats = vec![COLOR];
        Ok(Pipeline::graphics(ctx, &d)?)
    };
    Ok(match draw {
        QuadDraw::Polygons => QuadPipelines::Polygons(build(Primitive::Polygons)?),
        QuadDraw::Exact => QuadPipelines::Exact {
            triangles: build(Primitive::Triangles)?,
            points: build(Primitive::Points)?,
            lines: build(Primitive::Lines)?,
        },
    })
}

/// Draws light `l`'s caustic quads into `out`, seen through `geometry` (world position and
/// normal; not read in light space), clearing it first if `clear`.
#[allow(clippy::too_many_arguments)]
pub fn record(
    f: &mut Frame,
    name: &str,
    c: &CausticPasses,
    pipelines: &QuadPipelines,
    out: &ImageView,
    geometry: (&ImageView, &ImageView),
    clear: bool,
    constants: ImageSpaceConstants,
) -> Result<()> {
    let (pt, inp) = (c.photons, c.inputs);
    let triangles = match pipelines {
        QuadPipelines::Polygons(polygons) => polygons,
        QuadPipelines::Exact { triangles, .. } => triangles,
    };
    // The pipelines share their bindings.
    let mut binds = super::views::photon_view_binds(c, triangles, geometry);
    binds.push(("receiver_positions", Bind::Sampled(&c.targets.per_light[constants.light as usize].1, inp.nearest)));
    let n = pt.width;
    f.pass(name).bind(triangles, binds.clone()).uses([Use::view(out, Access::COLOR_ATTACHMENT)]).record(|cmd| {
        cmd.begin_rendering(&Targets::color(out, if clear { Some([0.0; 4]) } else { None }))?;
        cmd.push(&constants)?;
        // Two triangles for each of the (N - 1)^2 blocks of 2x2 photons.
        cmd.draw((n - 1) * (n - 1) * 6, 1, 0, 0);
        if let QuadPipelines::Exact { points, lines, .. } = pipelines {
            // One point for each block under a pixel.
            cmd.bind_pipeline(points);
            cmd.bind(&binds)?;
            cmd.push(&constants)?;
            cmd.draw((n - 1) * (n - 1), 1, 0, 0);
            // A line (two vertices) for each sliver.
            cmd.bind_pipeline(lines);
            cmd.bind(&binds)?;
            cmd.push(&constants)?;
            cmd.draw((n - 1) * (n - 1) * 2, 1, 0, 0);
        }
        cmd.end_rendering();
        Ok(())
    })?;
    Ok(())
}
