//! The pipelines of the eye render (`--technique none`), built once per run.

use anyhow::Result;
use vkcore::{
    BindingKind as K, Blend, Context, Cull, Format, GraphicsDesc, Pipeline, ShaderCompiler, Topology, VertexAttribute,
    VertexLayout,
};

pub const COLOR: Format = Format::R32G32B32A32_SFLOAT;
pub const DISTANCE: Format = Format::R32_SFLOAT;
pub const DEPTH: Format = Format::D32_SFLOAT;

pub struct EyePipelines {
    pub shadow_map: Pipeline,
    pub background: Pipeline,
    pub back_faces: Pipeline,
    pub front_faces: Pipeline,
    pub composite: Pipeline,
    pub receiver_map: Pipeline,
}

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
pub(crate) struct MeshPass<'a> {
    pub name: &'a str,
    pub vert: &'a str,
    /// Defines for the vertex shader.
    pub vert_defines: &'a [(&'a str, &'a str)],
    pub frag: &'a str,
    pub bindings: Vec<K>,
    pub colors: Vec<Format>,
    pub cull: Cull,
}

pub(crate) fn mesh_pipeline(ctx: &Context, sh: &ShaderCompiler, pass: MeshPass) -> Result<Pipeline> {
    let MeshPass { name, vert, vert_defines, frag, bindings, colors, cull } = pass;
    let mut d = GraphicsDesc::new(name, sh.compile(vert, vert_defines)?, Some(sh.compile(frag, &[])?));
    d.bindings = bindings;
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

impl EyePipelines {
    pub fn new(ctx: &Context, sh: &ShaderCompiler) -> Result<EyePipelines> {
        let eye = |name, frag, bindings, colors, cull| MeshPass {
            name,
            vert: "eye/mesh.vert",
            vert_defines: &[],
            frag,
            bindings,
            colors,
            cull,
        };
        Ok(EyePipelines {
            shadow_map: mesh_pipeline(
                ctx,
                sh,
                MeshPass {
                    name: "shadow_map",
                    vert: "shadow/shadow_map.vert",
                    vert_defines: &[],
                    frag: "shadow/shadow_map.frag",
                    bindings: vec![K::UniformBuffer],
                    colors: vec![DISTANCE],
                    cull: Cull::None,
                },
            )?,
            background: mesh_pipeline(
                ctx,
                sh,
                eye(
                    "background",
                    "eye/background.frag",
                    vec![
                        K::UniformBuffer,
                        K::SampledImage,
                        K::SampledImage,
                        K::UniformBuffer,
                        K::SampledImage,
                        K::SampledImage,
                    ],
                    vec![COLOR, COLOR, COLOR],
                    Cull::None,
                ),
            )?,
            back_faces: mesh_pipeline(
                ctx,
                sh,
                eye("refractor_back_faces", "eye/back_faces.frag", vec![K::UniformBuffer], vec![COLOR], Cull::Front),
            )?,
            front_faces: mesh_pipeline(
                ctx,
                sh,
                eye(
                    "refractor_front_faces",
                    "eye/front_faces.frag",
                    vec![K::UniformBuffer, K::SampledImage, K::SampledImage, K::SampledImage],
                    vec![COLOR],
                    Cull::Back,
                ),
            )?,
            composite: Pipeline::compute(
                ctx,
                "composite",
                &sh.compile("eye/composite.comp", &[])?,
                &[K::SampledImage, K::SampledImage, K::StorageImage],
            )?,
            receiver_map: Pipeline::compute(
                ctx,
                "receiver_map",
                &sh.compile("receiver/receiver_map.comp", &[])?,
                &[
                    K::UniformBuffer,
                    K::SampledImage,
                    K::SampledImage,
                    K::StorageImage,
                    K::StorageImage,
                    K::StorageImage,
                    K::UniformBuffer,
                    K::SampledImage,
                    K::SampledImage,
                ],
            )?,
        })
    }
}
