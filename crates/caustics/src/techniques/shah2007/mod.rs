//! Shah, Konttinen & Pattanaik, "Caustics mapping: an image-space technique for real-time
//! caustics" (IEEE TVCG 2007; the tutorial in `shared/papers`): techniques `shah` and
//! `shah-vertex`.
//!
//! - `shah`: a photon per light-space texel of the specular objects (the refractive vertex grid
//!   rendered as the photon buffer, `techniques::shared::photon_buffer`), whose refracted ray
//!   meets the receivers by the tutorial's iterative image-space intersection rayGeo
//!   (`shaders_glsl/shah2007/ray_geo.glsl`, `iterations` steps), splatted as Gaussian points.
//! - `shah-vertex`: Shah's original first pass, a photon per vertex of the specular meshes
//!   (here, [`record_vertex_photons`]), each with a third of its triangles' area.
//!
//! Where the defaults differ from the tutorial (`docs/papers.md` says so too): photons refract
//! into and out of the object (the tutorial once, where the light meets it: `refractions =
//! "one"`), rayGeo runs 4 iterations (the tutorial 1: `iterations = 1`), and the caustic map
//! holds power that the lookup turns into irradiance (the tutorial shades with
//! `diffuse * pow(caustic, 1.3)` on top of the diffuse term: `lookup = "tutorial"`,
//! `common/caustic_lookup.glsl`'s `tutorial_lookup`). `faithful = true` sets all three.

pub mod settings;
pub use settings::{PAPER, VERTEX_PHOTON_FEATURES};

use super::shared::photon_buffer::trace_binds;
use super::shared::CausticPasses;
use crate::gpu::mesh_pipeline::mesh_layout;
use crate::gpu::setup::vertex_areas;
use crate::gpu::{mesh_uses, MeshConstants, Stage, MATERIAL_DIFFUSE};
use crate::scene::Scene;
use anyhow::Result;
use vkcore::{Access, Bind, Buffer, Context, Frame, GraphicsDesc, Pipeline, ShaderCompiler, Targets, Topology, Use};

/// Shah's first pass: a photon per vertex of the specular meshes.
pub struct VertexPhotons {
    pipeline: Pipeline,
    /// Per object: a third of each vertex's triangle areas (None for diffuse objects).
    areas: Vec<Option<Buffer>>,
}

impl VertexPhotons {
    /// The vertex-photon pipeline: a point per vertex, rasterization discarded, each photon
    /// stored into the photon buffer's images; and the vertex areas of `scene`'s specular objects.
    pub fn new(ctx: &Context, sh: &ShaderCompiler, scene: &Scene) -> Result<VertexPhotons> {
        let mut d = GraphicsDesc::new("vertex_photons", sh.compile("shah2007/vertex_photons.vert", &[])?, None);
        d.vertex_layout = Some(mesh_layout());
        d.topology = Topology::Points;
        d.rasterizer_discard = true;
        Ok(VertexPhotons { pipeline: Pipeline::graphics(ctx, &d)?, areas: vertex_areas(ctx, scene)? })
    }

    /// Light `l`'s photons: clears the photon buffer, then traces a photon per vertex of every
    /// specular mesh into it (`shaders_glsl/shah2007/vertex_photons.vert`).
    pub fn record(&self, f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
        let (pt, inp) = (c.photons, c.inputs);
        let vp = &self.pipeline;
        let photons = [&pt.position, &pt.direction, &pt.power];
        let clear: Vec<Use> = photons.iter().map(|t| Use::view(&t.view, Access::TRANSFER_WRITE)).collect();
        f.pass(&Stage::VertexPhotonsClear.light(l)).uses(clear).record(|cmd| {
            for t in photons {
                cmd.clear_color(&t.view, [0.0; 4]);
            }
            Ok(())
        })?;
        // One descriptor set per specular mesh: the tracing inputs, the photon buffer's images
        // and the mesh's vertex areas.
        let specular: Vec<_> = inp
            .meshes
            .iter()
            .zip(&self.areas)
            .filter_map(|(m, areas)| Some((m, areas.as_ref()?)).filter(|(m, _)| m.kind() != MATERIAL_DIFFUSE))
            .collect();
        let sets: Vec<_> = specular
            .iter()
            .map(|(_, areas)| {
                let mut binds = trace_binds(c);
                binds.extend(
                    ["photon_position", "photon_direction", "photon_power"]
                        .into_iter()
                        .zip(photons.map(|t| Bind::Storage(&t.view))),
                );
                binds.push(("Areas", Bind::BufferRead(areas)));
                binds
            })
            .collect();
        let mut pass = f.pass(&Stage::VertexPhotons.light(l)).uses(mesh_uses(inp.meshes));
        for binds in &sets {
            pass = pass.declare(vp, binds);
        }
        pass.record(|cmd| {
            cmd.begin_rendering(&Targets::none())?;
            cmd.bind_pipeline(vp);
            let mut first = 0u32;
            for ((m, _), binds) in specular.iter().zip(&sets) {
                cmd.bind(binds)?;
                cmd.push(&MeshConstants { light: l, first_photon: first, ..m.constants })?;
                cmd.bind_vertex_buffer(&m.vertices, 0)?;
                let vertices = (m.vertices.size() / 28) as u32;
                cmd.draw(vertices, 1, 0, 0);
                first += vertices;
            }
            cmd.end_rendering();
            Ok(())
        })?;
        Ok(())
    }
}
