//! Pipelines of the caustic techniques.

use super::photon_copy::CopyType;
use super::targets::COLOR;
use crate::render::pipelines::{mesh_layout, mesh_pipeline, MeshPass};
use anyhow::Result;
use vkcore::{
    BindingKind as K, Blend, Context, Cull, Format, GraphicsDesc, Pipeline, ShaderCompiler, Topology, VertexAttribute,
    VertexLayout,
};

pub struct CausticPipelines {
    pub receiver_positions: Pipeline,
    pub back_faces: Pipeline,
    pub photon_buffer: Pipeline,
    pub vertex_photons: Option<Pipeline>,
    pub splat: Pipeline,
    /// Splats from the copied vertex array (the faithful Wyman & Davis 2006 path).
    pub splat_vertex_array: Option<Pipeline>,
}

/// Mesh passes from a light see through the photon frustum with this define, else through the
/// caustic map's.
const PHOTON_VIEW: &[(&str, &str)] = &[("PHOTON_VIEW", "1")];
const LIGHT_MESH_VERT: &str = "photons/light_mesh.vert";

impl CausticPipelines {
    pub fn new(
        ctx: &Context,
        sh: &ShaderCompiler,
        technique: &str,
        copy: Option<CopyType>,
    ) -> Result<CausticPipelines> {
        let ubo2 = vec![K::UniformBuffer, K::UniformBuffer];
        let trace = vec![K::UniformBuffer, K::UniformBuffer, K::SampledImage, K::SampledImage];
        let vertex_photons = if technique == "shah-vertex" {
            let mut d = GraphicsDesc::new("vertex_photons", sh.compile("photons/vertex_photons.vert", &[])?, None);
            let mut b = trace.clone();
            b.extend([K::StorageImage, K::StorageImage, K::StorageImage, K::StorageBuffer]);
            d.bindings = b;
            d.vertex_layout = Some(mesh_layout());
            d.topology = Topology::Points;
            d.rasterizer_discard = true;
            Some(Pipeline::graphics(ctx, &d)?)
        } else {
            None
        };
        let mut splat = GraphicsDesc::new(
            "splat",
            sh.compile("photons/splat.vert", &[])?,
            Some(sh.compile("photons/splat.frag", &[])?),
        );
        splat.bindings = vec![K::UniformBuffer, K::UniformBuffer, K::SampledImage, K::SampledImage];
        splat.vertex_layout = Some(VertexLayout {
            stride: 4,
            attributes: vec![VertexAttribute { location: 0, format: Format::R32_UINT, offset: 0 }],
        });
        splat.topology = Topology::Points;
        splat.blend = Blend::Additive;
        splat.color_formats = vec![COLOR];
        let splat_vertex_array = match copy {
            Some(ty) => {
                let half = ty.vertices_are_half();
                let mut defines = vec![("PHOTON_VERTEX_ARRAY", "1")];
                if half {
                    defines.push(("PHOTON_HALF", "1"));
                }
                let mut d = splat.clone();
                d.name = "splat_vertex_array".into();
                d.vertex = sh.compile("photons/splat.vert", &defines)?;
                d.bindings = vec![K::UniformBuffer, K::UniformBuffer, K::StorageBuffer];
                let (format, stride) =
                    if half { (Format::R16G16B16A16_SFLOAT, 8) } else { (Format::R32G32B32A32_SFLOAT, 16) };
                d.vertex_layout =
                    Some(VertexLayout { stride, attributes: vec![VertexAttribute { location: 0, format, offset: 0 }] });
                Some(Pipeline::graphics(ctx, &d)?)
            }
            None => None,
        };
        Ok(CausticPipelines {
            receiver_positions: mesh_pipeline(
                ctx,
                sh,
                MeshPass {
                    name: "receiver_positions",
                    vert: LIGHT_MESH_VERT,
                    vert_defines: &[],
                    frag: "photons/receiver_positions.frag",
                    bindings: ubo2.clone(),
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
                    frag: "photons/back_faces.frag",
                    bindings: ubo2,
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
                    frag: "photons/photon_buffer.frag",
                    bindings: trace,
                    colors: vec![COLOR, COLOR, COLOR],
                    cull: Cull::Back,
                },
            )?,
            vertex_photons,
            splat: Pipeline::graphics(ctx, &splat)?,
            splat_vertex_array,
        })
    }
}
