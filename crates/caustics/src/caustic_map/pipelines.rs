//! Pipelines of the caustic techniques.

use super::targets::{COLOR, DEPTH};
use crate::render::pipelines::mesh_layout;
use anyhow::Result;
use vkcore::{BindingKind as K, Blend, Context, Cull, Format, GraphicsDesc, Pipeline, ShaderCompiler, Topology, VertexAttribute, VertexLayout};

pub struct CausticPipelines {
    pub receiver_positions: Pipeline,
    pub back_faces: Pipeline,
    pub photon_buffer: Pipeline,
    pub vertex_photons: Option<Pipeline>,
    pub splat: Pipeline,
}

fn light_mesh(ctx: &Context, sh: &ShaderCompiler, name: &str, frag: &str, photon_view: bool, bindings: Vec<K>, colors: Vec<Format>, cull: Cull) -> Result<Pipeline> {
    let defines: &[(&str, &str)] = if photon_view { &[("PHOTON_VIEW", "1")] } else { &[] };
    let mut d = GraphicsDesc::new(name, sh.compile("photons/light_mesh.vert", defines)?, Some(sh.compile(frag, &[])?));
    d.bindings = bindings;
    d.vertex_layout = Some(mesh_layout());
    d.cull = cull;
    d.color_formats = colors;
    d.depth_format = Some(DEPTH);
    d.depth_test = true;
    d.depth_write = true;
    Ok(Pipeline::graphics(ctx, &d)?)
}

impl CausticPipelines {
    pub fn new(ctx: &Context, sh: &ShaderCompiler, technique: &str) -> Result<CausticPipelines> {
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
        let mut splat = GraphicsDesc::new("splat", sh.compile("photons/splat.vert", &[])?, Some(sh.compile("photons/splat.frag", &[])?));
        splat.bindings = vec![K::UniformBuffer, K::UniformBuffer, K::SampledImage, K::SampledImage];
        splat.vertex_layout = Some(VertexLayout { stride: 4, attributes: vec![VertexAttribute { location: 0, format: Format::R32_UINT, offset: 0 }] });
        splat.topology = Topology::Points;
        splat.blend = Blend::Additive;
        splat.color_formats = vec![COLOR];
        Ok(CausticPipelines {
            receiver_positions: light_mesh(ctx, sh, "receiver_positions", "photons/receiver_positions.frag", false, ubo2.clone(), vec![COLOR], Cull::None)?,
            back_faces: light_mesh(ctx, sh, "photon_back_faces", "photons/back_faces.frag", true, ubo2, vec![COLOR], Cull::Front)?,
            photon_buffer: light_mesh(ctx, sh, "photon_buffer", "photons/photon_buffer.frag", true, trace, vec![COLOR, COLOR, COLOR], Cull::Back)?,
            vertex_photons,
            splat: Pipeline::graphics(ctx, &splat)?,
        })
    }
}
