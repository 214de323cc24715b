//! Pipelines that draw the scene's meshes (the eye passes and the light-space passes alike).

use super::formats::DEPTH;
use anyhow::Result;
use vkcore::{
    Blend, Context, Cull, Format, GraphicsDesc, Pipeline, ShaderCompiler, Topology, VertexAttribute, VertexLayout,
};

pub fn mesh_layout() -> VertexLayout {
    VertexLayout {
        stride: 28,
        attributes: vec![
            VertexAttribute { location: 0, format: Format::R32G32B32_SFLOAT, offset: 0 },
            VertexAttribute { location: 1, format: Format::R32G32B32_SFLOAT, offset: 12 },
            VertexAttribute { location: 2, format: Format::R32_SFLOAT, offset: 24 },
        ],
    }
}

/// A depth-tested pass over scene meshes.
pub struct MeshPass<'a> {
    pub name: &'a str,
    pub vert: &'a str,
    /// Defines for the vertex shader.
    pub vert_defines: &'a [(&'a str, &'a str)],
    pub frag: &'a str,
    pub colors: Vec<Format>,
    pub cull: Cull,
}

pub fn mesh_pipeline(ctx: &Context, sh: &ShaderCompiler, pass: MeshPass) -> Result<Pipeline> {
    let MeshPass { name, vert, vert_defines, frag, colors, cull } = pass;
    let mut d = GraphicsDesc::new(name, sh.compile(vert, vert_defines)?, Some(sh.compile(frag, &[])?));
    d.vertex_layout = Some(mesh_layout());
    d.topology = Topology::Triangles;
    d.cull = cull;
    d.color_formats = colors;
    d.blend = Blend::Replace;
    d.depth_format = Some(DEPTH);
    d.depth_test = true;
    d.depth_write = true;
    Ok(Pipeline::graphics(ctx, &d)?)
}
