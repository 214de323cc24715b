//! The photon source: where a light's photons come from, before any is selected or deposited.

use crate::dump::Dump;
use crate::gpu::{GpuMesh, Stage};
use crate::image_io::ImageF32;
use crate::scene::Scene;
use crate::techniques::photon_trace::PhotonTracer;
use crate::techniques::shah2007::VertexPhotons;
use crate::techniques::shared::settings::PHOTON_BACK_FACES;
use crate::techniques::shared::{photon_buffer, CausticPasses};
use crate::techniques::wyman_nichols2009::settings::PHOTON_GEOMETRY_BUFFERS;
use crate::techniques::wyman_nichols2009::{DeferredPhotons, PhotonRefraction};
use crate::techniques::Technique;
use anyhow::Result;
use vkcore::{Context, Frame, ShaderCompiler};

/// Where a light's photons come from.
// One per renderer: boxing the larger variants would save nothing.
#[allow(clippy::large_enum_variant)]
pub enum Source {
    /// The photon buffer by rasterizing the specular objects from the light: a photon per
    /// light-space texel (Wyman & Davis 2006 Sec. 3.1; Shah et al.'s first pass as the
    /// tutorial draws it).
    Rasterized,
    /// The photon buffer by deferred shading of light-space geometry buffers
    /// (`photon_refraction = deferred`, Wyman & Nichols 2009 Sec. 3.2 and 3.1.1).
    Deferred(DeferredPhotons),
    /// A photon per vertex of the specular meshes (Shah et al.'s original first pass).
    PerVertex(VertexPhotons),
    /// Photons created from light-space geometry buffers while the adaptive traversal refines
    /// them (Wyman & Nichols 2009 Sec. 3.2): the geometry buffers are the traversal's
    /// (`super::Selection::Adaptive`), drawn by its first pass; this stage draws the receivers.
    GeometryBuffers,
    /// Photons traced exactly through the scene's BVH (`photon-trace`, beyond the papers).
    Traced(PhotonTracer),
}

impl Source {
    /// The variant's name, as the stages table in `stages/mod.rs` writes it.
    pub fn name(&self) -> &'static str {
        match self {
            Source::Rasterized => "Rasterized",
            Source::Deferred(_) => "Deferred",
            Source::PerVertex(_) => "PerVertex",
            Source::GeometryBuffers => "GeometryBuffers",
            Source::Traced(_) => "Traced",
        }
    }

    /// The passes it records, by their [`Stage`] (`tests/frame_graph_stages.rs` holds each
    /// frame's graph to them).
    pub fn stages(&self) -> &'static [Stage] {
        match self {
            Source::Rasterized => &[Stage::PhotonBackFaces, Stage::PhotonBuffer],
            Source::Deferred(_) => &[Stage::DeferredPhotonsGeometry, Stage::DeferredPhotons],
            Source::PerVertex(_) => &[Stage::PhotonBackFaces, Stage::VertexPhotonsClear, Stage::VertexPhotons],
            // The geometry buffers are drawn by the adaptive selection's first pass.
            Source::GeometryBuffers => &[],
            Source::Traced(_) => &[Stage::PhotonTraceClear, Stage::PhotonTrace, Stage::PhotonTraceAccumulate],
        }
    }

    pub fn new(ctx: &Context, sh: &ShaderCompiler, scene: &Scene, meshes: &[GpuMesh]) -> Result<Source> {
        let s = &scene.caustics;
        Ok(match s.technique {
            Technique::ShahVertex => Source::PerVertex(VertexPhotons::new(ctx, sh, scene)?),
            Technique::Adaptive => Source::GeometryBuffers,
            Technique::PhotonTrace => Source::Traced(PhotonTracer::new(ctx, sh, scene, meshes)?),
            t if t.has_photon_buffer() && s.photon_refraction == PhotonRefraction::Deferred => {
                Source::Deferred(DeferredPhotons::new(ctx, sh, s.photons, meshes)?)
            }
            _ => Source::Rasterized,
        })
    }

    /// Light `l`'s receiver positions and photons (the refractors' back faces first where the
    /// photons are traced through them).
    pub fn record(&self, f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
        match self {
            Source::Rasterized => {
                photon_buffer::record_light_views(f, c, l)?;
                photon_buffer::record_photon_buffer(f, c, l)
            }
            // Wyman & Nichols 2009 Sec. 3.2: the geometry buffers hold the back faces.
            Source::Deferred(dp) => {
                photon_buffer::record_receiver_positions(f, c, l)?;
                dp.record(f, c, l)
            }
            Source::PerVertex(vp) => {
                photon_buffer::record_light_views(f, c, l)?;
                vp.record(f, c, l)
            }
            Source::GeometryBuffers => photon_buffer::record_receiver_positions(f, c, l),
            Source::Traced(tracer) => tracer.record(f, c, l),
        }
    }

    /// The light-space dump `dump` that this stage owns, as its buffers hold it now (None:
    /// not this stage's).
    pub fn dump(&self, ctx: &Context, dump: &'static Dump) -> Result<Option<ImageF32>> {
        Ok(match self {
            Source::Deferred(d) if dump == &PHOTON_GEOMETRY_BUFFERS => Some(d.dump(ctx)?),
            // Deferred photons: the back faces are the geometry buffers' back layer.
            Source::Deferred(d) if dump == &PHOTON_BACK_FACES => Some(d.dump_back_faces(ctx)?),
            Source::Deferred(_) => None,
            Source::Rasterized | Source::PerVertex(_) | Source::GeometryBuffers | Source::Traced(_) => None,
        })
    }

    /// Follows `scene`, a pose in which the objects `moved` moved: the tracer's acceleration
    /// structures follow them (`trace = "ray-query"`: moved instances or rebuilt bottom levels,
    /// `photon_trace::instances`); its BVH is built once, when it is made (an input error naming
    /// the object otherwise). The other sources read the meshes as they are drawn.
    pub fn follow_moved_meshes(&mut self, ctx: &Context, scene: &Scene, moved: &[&str]) -> anyhow::Result<()> {
        match self {
            Source::Traced(tracer) => tracer.follow(ctx, scene, moved).map(|_| ()),
            _ => Ok(()),
        }
    }

    /// `photon-trace` with `progressive`: the next frame of its accumulation, and its splat
    /// radius (None for every other source).
    pub fn next_frame(&mut self) -> Option<f32> {
        match self {
            Source::Traced(tracer) => tracer.next_frame(),
            _ => None,
        }
    }

    /// `photon-trace` with `progressive`: its accumulation starts again with the next frame.
    pub fn restart_accumulation(&mut self) {
        if let Source::Traced(tracer) = self {
            tracer.restart();
        }
    }

    /// After every light's deposit: `photon-trace`'s running means (`progressive`).
    pub fn record_after_deposit(&self, f: &mut Frame, c: &CausticPasses) -> Result<()> {
        match self {
            Source::Traced(tracer) => tracer.record_accumulation(f, c),
            _ => Ok(()),
        }
    }

    /// Whether this stage has the light-space buffer `d` (one it owns but does not have, it
    /// never dumps).
    pub fn has_dump(&self, d: &'static Dump) -> bool {
        match self {
            Source::Deferred(_) => true,
            Source::Rasterized | Source::PerVertex(_) | Source::GeometryBuffers => d != &PHOTON_GEOMETRY_BUFFERS,
            // No back faces: photons cross the refractors' triangles themselves.
            Source::Traced(_) => d != &PHOTON_GEOMETRY_BUFFERS && d != &PHOTON_BACK_FACES,
        }
    }
}
