//! Adaptive caustic maps (Wyman & Nichols 2009 Sec. 3.2-4.2, technique `adaptive`):
//!
//! 1. render light-space geometry buffers for deferred photon creation
//!    ([`super::geometry_buffers`]);
//! 2. traverse a virtual photon hierarchy from a 64² grid of photons over the photon frustum,
//!    creating the photons of each pending 2×2 cluster by deferred shading, discarding the
//!    clusters that miss the refractor and refining the others into four clusters on the next
//!    finer grid, down to the last level L (64 × 2^L = `photons`), where the photons that landed
//!    are output ([`traversal`]); with the maximal caustic map error metric, a cluster whose
//!    photons converge to one caustic-map texel is output as one photon from the 512² level on;
//! 3. splat the output photons into the caustic map ([`splat`]);
//! 4. the eye render projects the caustic map onto the scene (as for every technique).
//!
//! With several specular objects, each also gets its own geometry buffers, and every photon
//! created is followed from the object it meets first through the others on its way to the
//! receiver (Sec. 3.1.1's multi-layer refraction for photons, as deferred photons do:
//! `deferred_photon_layers.glsl`, with its approximations); the traversal's coverage and
//! convergence tests read the buffers of all objects together, as with one.
//!
//! Two traversal paths, as for Wyman 2008's hierarchy: transform feedback (the paper's: a
//! geometry shader per kernel, the next kernel drawn with vkCmdDrawIndirectByteCountEXT; one
//! kernel per step for max-traversal, three for max-error, Sec. 4.1) or compute (one kernel
//! per step appending with atomic counters, dispatched indirectly). Nothing is read back
//! between steps. The GLSL is `shaders_glsl/wyman_nichols2009/adaptive*.{glsl,comp,geom,vert}`.
//!
//! Storage: each level's pending clusters are a list of packed u32 cells; the output is one list
//! of 32-byte [`AdaptivePhoton`]s (position, cell, power, varying splat radius) that every step appends
//! to, splatted by the point splat (or the compute splat) as a vertex array. Under a memory
//! limit the traversal is split into batches, each splatted before the next ([`batches`],
//! Sec. 4.3).

pub mod batches;
pub mod photon;
mod splat;
mod traversal;

pub use batches::BatchPlan;
pub use photon::{pack_cell, unpack_cell, AdaptivePhoton};
pub use traversal::{list_records, LightLists, Listed, Part, Splat, LIST_CHANNELS};

use super::geometry_buffers::LightGeometryBuffers;
use super::refractor_layers::{specular_objects, RefractorLayers, MAX_REFRACTORS};
use super::settings::{Metric, TOP_PHOTONS};
use crate::gpu::GpuMesh;
use crate::techniques::settings::CausticSettings;
use crate::techniques::shared::pipelines::point_splat_desc;
use crate::techniques::shared::settings::TraversalPath;
use anyhow::Result;
use photon::{CLUSTER_BYTES, HITS_BYTES, PHOTON_BYTES};
use vkcore::{
    Buffer, CompactStream, CompactionPath, Context, Finalize, Format, GraphicsDesc, Memory, Pipeline, ShaderCompiler,
    Topology, VertexAttribute, VertexLayout,
};

/// The transform-feedback path's kernels (`adaptive_step.geom`, Sec. 4.1).
struct XfbKernels {
    /// Clusters -> children (steps that test no convergence).
    subdivide: Pipeline,
    /// Clusters -> photons (the last step, when it tests no convergence).
    emit: Pipeline,
    /// Max-error: clusters -> their hits; hits -> converged photons; hits -> children.
    hits: Pipeline,
    converged: Pipeline,
    refine: Pipeline,
}

enum Kernels {
    Xfb(Box<XfbKernels>),
    /// The step kernel and vkcore's counter finalize.
    Compute {
        traverse: Pipeline,
        finalize: Finalize,
    },
}

pub struct AdaptiveCaustics {
    path: CompactionPath,
    metric: Metric,
    /// The last level L (photons on the (64 × 2^L)² grid).
    finest: u32,
    geometry: LightGeometryBuffers,
    /// With several specular objects, each one's own buffers; none with one.
    refractors: RefractorLayers,
    /// How the traversal is split into batches (one batch without a memory limit).
    plan: BatchPlan,
    /// clusters[k]: the pending clusters of level k; clusters[0], the 32² clusters of the 64²
    /// coarse grid, is uploaded once. Below the breadth-first levels, one batch's.
    clusters: Vec<CompactStream>,
    /// A batch's clusters of level B (batched traversals only).
    batch_input: Option<CompactStream>,
    /// What the last step's children would be written to (nothing is).
    spare: CompactStream,
    /// Max-error on the xfb path: the hits of one step's clusters.
    hits: Option<CompactStream>,
    /// Every output photon of the light traversed last.
    photons: CompactStream,
    /// Per light: each level's cluster count, then the photon count after each step, summed
    /// over the batches (u32 elements).
    counts: Buffer,
    lights: u32,
    kernels: Kernels,
    splat: Pipeline,
    /// The batch input's copy and the per-level counts (`adaptive_batch.comp`, `adaptive_counts.comp`).
    batch_select: Pipeline,
    count: Pipeline,
}

/// The traversal's bindings 0-8 (`adaptive.glsl`): the trace's (uniforms, back faces, receiver
/// positions, spot textures: `photon_buffer::trace_binds`), the geometry buffers and their
/// coverage pyramid; the kernels' own bindings follow.
const TEXTURES: usize = 9;

impl AdaptiveCaustics {
    /// Adaptive caustic maps of the specular meshes among `meshes`.
    pub fn new(
        ctx: &Context,
        sh: &ShaderCompiler,
        s: &CausticSettings,
        lights: u32,
        meshes: &[GpuMesh],
    ) -> Result<AdaptiveCaustics> {
        let traversal: TraversalPath = s.path;
        ctx.require(&format!("technique `adaptive` with --path {traversal}"), traversal.features())?;
        let path = traversal.compaction();
        let finest = s.adaptive_level().ok_or_else(|| {
            crate::input_error!(
                "caustics.photons: technique `adaptive` needs 64 × 2^L photons per side, got {}",
                s.photons
            )
        })?;
        let n = TOP_PHOTONS << finest;
        let xfb = path == CompactionPath::TransformFeedback;
        let limit = (s.photon_memory_limit > 0).then(|| s.photon_memory_limit as u64 * 1024 * 1024);
        let plan = batches::plan(finest, s.metric, xfb, limit, s.photon_batches, lights).map_err(|e| {
            let key = if limit.is_some() { "photon_memory_limit" } else { "photon_batches" };
            crate::input_error!("caustics.{key}: {e}")
        })?;
        // Every list is one buffer: the device must address the largest.
        let largest = (plan.photons as u64 * PHOTON_BYTES).max(plan.hits as u64 * HITS_BYTES);
        let device = match path {
            CompactionPath::TransformFeedback => {
                ("maxTransformFeedbackBufferSize", ctx.info().max_transform_feedback_buffer_size)
            }
            CompactionPath::Compute => ("maxStorageBufferRange", ctx.info().max_storage_buffer_range as u64),
        };
        if largest > device.1 {
            return Err(crate::input_error!(
                "caustics.photons: technique `adaptive` at {n}² photons needs a list of up to {largest} bytes, more \
                 than this device's {} ({}); use fewer photons, or a photon_memory_limit to split it into batches",
                device.0,
                device.1
            )
            .into());
        }
        let geometry = LightGeometryBuffers::new(ctx, sh, s.gbuffer_side())?;
        let specular = specular_objects(meshes);
        if specular.len() > MAX_REFRACTORS {
            return Err(crate::input_error!(
                "technique `adaptive`: the scene has {} specular objects; adaptive caustic maps follow photons \
                 through at most {MAX_REFRACTORS}",
                specular.len()
            )
            .into());
        }
        let refractors = RefractorLayers::new(ctx, sh, s.gbuffer_side(), &specular)?;
        let stream =
            |name: &str, capacity: u32, bytes: u64| CompactStream::with_element_bytes(ctx, name, path, capacity, bytes);
        let mut clusters = vec![];
        for (k, &capacity) in plan.clusters.iter().enumerate() {
            clusters.push(stream(&format!("adaptive clusters level {k}"), capacity, CLUSTER_BYTES)?);
        }
        let side = TOP_PHOTONS / 2;
        let seed: Vec<u32> = (0..side * side).map(|i| pack_cell([i % side, i / side, 0])).collect();
        ctx.upload_buffer(clusters[0].data(), bytemuck::cast_slice(&seed))?;
        clusters[0].upload_seeded_counter(ctx, seed.len() as u32)?;
        let spare = stream("adaptive spare clusters", 1, CLUSTER_BYTES)?;
        let batch_input =
            plan.batched().then(|| stream("adaptive batch clusters", plan.batch, CLUSTER_BYTES)).transpose()?;
        let hits = (plan.hits > 0).then(|| stream("adaptive cluster hits", plan.hits, HITS_BYTES)).transpose()?;
        let photons = stream("adaptive photons", plan.photons, PHOTON_BYTES)?;
        let counts = Buffer::new(ctx, "adaptive counts", (lights.max(1) * 2 * (finest + 1)) as u64 * 4, Memory::Gpu)?;
        let storage = |name: &str| -> Result<Pipeline> {
            Ok(Pipeline::compute(
                ctx,
                &format!("adaptive.{name}"),
                &sh.compile(&format!("wyman_nichols2009/adaptive_{name}.comp"), &[])?,
            )?)
        };
        let batch_select = storage("batch")?;
        let count = storage("counts")?;
        let kernels = match path {
            CompactionPath::TransformFeedback => Kernels::Xfb(Box::new(XfbKernels {
                subdivide: xfb_kernel(ctx, sh, "SUBDIVIDE", &refractors)?,
                emit: xfb_kernel(ctx, sh, "EMIT", &refractors)?,
                hits: xfb_kernel(ctx, sh, "HITS", &refractors)?,
                converged: xfb_kernel(ctx, sh, "CONVERGED", &refractors)?,
                refine: xfb_kernel(ctx, sh, "REFINE", &refractors)?,
            })),
            CompactionPath::Compute => {
                // The further refractors' buffers after the kernel's own six storage buffers.
                let (count, first) = (refractors.refractors_define(), (TEXTURES + 6).to_string());
                let defines = [("REFRACTORS", count.as_str()), ("LAYER_BINDING", first.as_str())];
                let spirv = sh.compile("wyman_nichols2009/adaptive_traverse.comp", &defines)?;
                Kernels::Compute {
                    traverse: Pipeline::compute(ctx, "adaptive.traverse", &spirv)?,
                    finalize: Finalize::new(ctx, sh, "adaptive.finalize")?,
                }
            }
        };
        // The point splat, fed the output photons as a vertex array.
        let mut splat = point_splat_desc(sh)?;
        splat.name = "splat_adaptive".into();
        splat.vertex = sh.compile("shared/splat.vert", &[("ADAPTIVE_PHOTONS", "1")])?;
        splat.vertex_layout = Some(VertexLayout {
            stride: PHOTON_BYTES as u32,
            attributes: vec![
                VertexAttribute { location: 0, format: Format::R32G32B32_SFLOAT, offset: 0 },
                VertexAttribute { location: 1, format: Format::R32G32B32_SFLOAT, offset: 16 },
                VertexAttribute { location: 2, format: Format::R32_SFLOAT, offset: 28 },
            ],
        });
        Ok(AdaptiveCaustics {
            path,
            metric: s.metric,
            finest,
            geometry,
            refractors,
            plan,
            clusters,
            batch_input,
            spare,
            hits,
            photons,
            counts,
            lights,
            kernels,
            splat: Pipeline::graphics(ctx, &splat)?,
            batch_select,
            count,
        })
    }

    /// `adaptive_geometry.exr` for the light traversed last: the buffers of all specular objects
    /// and their coverage pyramid ([`LightGeometryBuffers::dump`]), and with several objects
    /// each one's own surfaces, prefixed `refractor<k>.` (k in the scene's order of its specular
    /// objects), as `photon_geometry_buffers` names them.
    pub fn dump_geometry(&self, ctx: &Context) -> Result<crate::image_io::ImageF32> {
        let mut img = self.geometry.dump(ctx)?;
        self.refractors.dump_into(ctx, &mut img, self.geometry.padded)?;
        Ok(img)
    }

    /// The traversal's stream-compaction path.
    pub fn path(&self) -> CompactionPath {
        self.path
    }

    /// The refinement metric (Sec. 4.1).
    pub fn metric(&self) -> Metric {
        self.metric
    }

    /// The last level L (photons on the (64 × 2^L)² grid).
    pub fn finest(&self) -> u32 {
        self.finest
    }

    /// The light-space geometry buffers photons are made from (Sec. 3.2).
    pub fn geometry(&self) -> &LightGeometryBuffers {
        &self.geometry
    }

    /// With several specular objects, each one's own buffers.
    pub fn refractors(&self) -> &RefractorLayers {
        &self.refractors
    }

    /// How the traversal is split into batches.
    pub fn plan(&self) -> &BatchPlan {
        &self.plan
    }

    /// Every output photon of the light traversed last.
    pub fn photons(&self) -> &CompactStream {
        &self.photons
    }

    /// The photon list, as the compute splat reads it.
    pub fn splat_list(&self) -> crate::techniques::shared::SplatList {
        let kind = crate::techniques::shared::ListKind::AdaptivePhotons;
        crate::techniques::shared::SplatList { kind, path: self.path, element_bytes: photon::PHOTON_BYTES }
    }

    /// The photon storage allocated (bytes): every list of pending clusters, the batch input,
    /// the hits and the output photons, with their counters ([`BatchPlan::storage_bytes`]).
    pub fn photon_storage_bytes(&self) -> u64 {
        let streams =
            self.clusters.iter().chain([&self.spare, &self.photons]).chain(&self.batch_input).chain(&self.hits);
        streams.map(|s| s.data().size() + s.counter().size()).sum()
    }
}

/// One transform-feedback kernel of `adaptive_step.geom` (`kernel`: its define), the further
/// refractors' buffers bound after its own.
fn xfb_kernel(ctx: &Context, sh: &ShaderCompiler, kernel: &str, layers: &RefractorLayers) -> Result<Pipeline> {
    let from_hits = matches!(kernel, "CONVERGED" | "REFINE");
    let (count, first) = (layers.refractors_define(), (TEXTURES + from_hits as usize).to_string());
    let mut defines = vec![(kernel, "1"), ("REFRACTORS", count.as_str()), ("LAYER_BINDING", first.as_str())];
    if from_hits {
        defines.push(("FROM_HITS", "1"));
    }
    let mut d = GraphicsDesc::new(
        &format!("adaptive.{}", kernel.to_lowercase()),
        sh.compile("wyman_nichols2009/adaptive_step.vert", &defines)?,
        None,
    );
    d.geometry = Some(sh.compile("wyman_nichols2009/adaptive_step.geom", &defines)?);
    if !from_hits {
        d.vertex_layout = Some(VertexLayout {
            stride: CLUSTER_BYTES as u32,
            attributes: vec![VertexAttribute { location: 0, format: Format::R32_UINT, offset: 0 }],
        });
    }
    d.topology = Topology::Points;
    d.rasterizer_discard = true;
    Ok(Pipeline::graphics(ctx, &d)?)
}
