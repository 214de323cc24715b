//! Pipelines of the photon buffer's light-space passes, and the point splat's description.

use crate::gpu::formats::COLOR;
use crate::gpu::mesh_pipeline::{mesh_pipeline, MeshPass};
use anyhow::Result;
use vkcore::{
    Blend, Context, Cull, Format, GraphicsDesc, Pipeline, ShaderCompiler, Topology, VertexAttribute, VertexLayout,
};

pub struct CausticPipelines {
    pub receiver_positions: Pipeline,
    pub back_faces: Pipeline,
    pub photon_buffer: Pipeline,
}

/// The point splat's pipeline description (`shared/splat.vert`, `shared/splat.frag`): points
/// blended additively into the caustic map, each vertex a photon index.
pub fn point_splat_desc(sh: &ShaderCompiler) -> Result<GraphicsDesc> {
    let mut splat =
        GraphicsDesc::new("splat", sh.compile("shared/splat.vert", &[])?, Some(sh.compile("shared/splat.frag", &[])?));
    splat.vertex_layout = Some(VertexLayout {
        stride: 4,
        attributes: vec![VertexAttribute { location: 0, format: Format::R32_UINT, offset: 0 }],
    });
    splat.topology = Topology::Points;
    splat.blend = Blend::Additive;
    splat.color_formats = vec![COLOR];
    Ok(splat)
}

/// Mesh passes from a light see through the photon frustum with this define, else through the
/// caustic map's.
const PHOTON_VIEW: &[(&str, &str)] = &[("PHOTON_VIEW", "1")];
const LIGHT_MESH_VERT: &str = "shared/light_mesh.vert";

impl CausticPipelines {
    pub fn new(ctx: &Context, sh: &ShaderCompiler) -> Result<CausticPipelines> {
        Ok(CausticPipelines {
            receiver_positions: mesh_pipeline(
                ctx,
                sh,
                MeshPass {
                    name: "receiver_positions",
                    vert: LIGHT_MESH_VERT,
                    vert_defines: &[],
                    frag: "shared/receiver_positions.frag",
                    colors: vec![COLOR],
                    cull: Cull::None,
                },
            )?,
            back_faces: mesh_pipeline(
                ctx,
                sh,
                MeshPass {
                    name: "photon_back_faces",
                    vert: LIGHT_MESH_VERT,
                    vert_defines: PHOTON_VIEW,
                    frag: "shared/back_faces.frag",
                    colors: vec![COLOR],
                    cull: Cull::Front,
                },
            )?,
            photon_buffer: mesh_pipeline(
                ctx,
                sh,
                MeshPass {
                    name: "photon_buffer",
                    vert: LIGHT_MESH_VERT,
                    vert_defines: PHOTON_VIEW,
                    frag: "shared/photon_buffer.frag",
                    colors: vec![COLOR, COLOR, COLOR],
                    cull: Cull::Back,
                },
            )?,
        })
    }
}
