//! `photon-trace`, beyond the papers: photons traced exactly on the GPU, the modern baseline the
//! image-space techniques approximate (screen-space photon mapping, ray-guided water caustics).
//! A compute shader (`shaders_glsl/photon_trace/trace.comp`) emits each light's photons over
//! the cone that subtends the specular objects (stratified and seeded, each with the power a
//! photon-buffer texel would carry: I(w) Omega / N²) and traces them through a bounding volume
//! hierarchy of every triangle in the scene, the CPU reference's own [`Bvh`] flattened and
//! uploaded, with the reference's physics (`crate::reference`): exact Snell about the smooth
//! normal, Fresnel by Russian roulette and total internal reflection, mirrors, up to
//! `max_bounces` interactions. Where a photon first reaches a diffuse surface it is written into
//! the photon buffer, whose points the existing deposit stages splat into the caustic map.
//!
//! With `deposit = "receiver-map"` each photon that lands on the receiver rectangle is also
//! binned straight into the receiver map's texels (float atomics), as the CPU reference bins
//! it, and the receiver map's caustic term is read from there
//! (`shaders_glsl/receiver/receiver_map.comp`); the final image still reads the caustic map.
//!
//! With `trace = "ray-query"` the same shader finds each photon's next surface by `rayQueryEXT`
//! against Vulkan acceleration structures instead of its own BVH traversal ([`RayQueryScene`]:
//! a bottom level per object, built once and compacted, one top level over them), the
//! driver's traversal, on ray-tracing hardware where the device has it. Everything else (the
//! emission, the physics, the seeds, the deposit) is the same code. It needs
//! VK_KHR_acceleration_structure and VK_KHR_ray_query: Mesa 25's lavapipe has them, Mesa 22.3's
//! does not (the option is refused there by name).
//!
//! The BVH is built once, when the renderer is made: with it a pose that moves a mesh is
//! refused (`Renderer::set_pose`). The acceleration structures follow a pose that moves meshes
//! ([`instances`]): the device is waited for, a rigidly moved object's instance gets the motion
//! as its transform, and any other moved object's bottom level is rebuilt from its moved
//! vertices (every moved object's with `moving_objects = "rebuild"`; refitted in place with
//! `"refit"`); the top level is built again.

pub mod differential;
pub mod instances;
pub mod progressive;
pub mod push;
pub mod settings;

pub use instances::RayQueryScene;
use settings::{MovingObjects, Trace};

use super::shared::photon_buffer::record_receiver_positions;
use super::shared::CausticPasses;
use crate::bvh::{Bvh, Triangle};
use crate::gpu::{GpuMesh, Stage, MATERIAL_DIFFUSE, MATERIAL_REFRACTIVE};
use crate::reference::emit::bounding_sphere;
use crate::scene::Scene;
use anyhow::Result;
use push::PhotonTraceConstants;
use vkcore::{Access, Bind, Buffer, Context, Frame, Pipeline, ShaderCompiler, Use};

/// `PHOTON_TRACE_OUTSIDE_REFLECTION` in trace.comp.
const FLAG_OUTSIDE_REFLECTION: u32 = 1;
/// `PHOTON_TRACE_DISPERSIVE`: a material's IORs differ between channels.
const FLAG_DISPERSIVE: u32 = 2;
/// `PHOTON_TRACE_CENTRED`: each photon at its stratum's centre (`jitter = false`).
const FLAG_CENTRED: u32 = 4;

/// How the tracer finds the surface a photon meets next (`trace`).
enum Intersection {
    /// The CPU reference's BVH, its nodes in a buffer the shader walks (`photon_trace/bvh.glsl`).
    Bvh { nodes: Buffer },
    /// Ray queries against the Vulkan acceleration structures (`photon_trace/ray_query.glsl`).
    RayQuery(RayQueryScene),
}

/// The tracer's pipeline and the scene as it reads it.
pub struct PhotonTracer {
    pipeline: Pipeline,
    intersection: Intersection,
    /// The triangles it hits: in the BVH's order, or the scene's for ray queries.
    triangles: Buffer,
    /// Per triangle of `triangles`, its mesh's vertex normals at the three corners.
    normals: Buffer,
    /// Per object: material, IOR, colour (trace.comp's `Objects`).
    objects: Buffer,
    constants: PhotonTraceConstants,
    /// `deposit = "receiver-map"`: photons are binned into the receiver map too.
    receiver_deposit: bool,
    /// `differentials = true`: each photon's footprint is written beside the photon buffer.
    differentials: bool,
    /// Per object, whether it is specular (the emission cone subtends these).
    specular: Vec<bool>,
    /// How ray queries' structures follow a moving object.
    moving: MovingObjects,
    /// `progressive = true`: the running means and their frame count ([`progressive`]).
    accumulation: Option<progressive::Accumulation>,
}

impl PhotonTracer {
    /// Builds the BVH of `scene`'s triangles and uploads it with the objects' materials
    /// (`meshes`, uploaded from `scene`).
    pub fn new(ctx: &Context, sh: &ShaderCompiler, scene: &Scene, meshes: &[GpuMesh]) -> Result<PhotonTracer> {
        let s = &scene.caustics;
        let receiver_deposit = s.receiver_deposit();
        if receiver_deposit && scene.receiver_map.is_none() {
            return Err(crate::input_error!(
                "{}: deposit = \"receiver-map\" (technique photon-trace) bins photons into the receiver map, and the \
                 scene has no [receiver_map]",
                scene.path.display()
            )
            .into());
        }
        for (who, features) in settings::required_features(s) {
            ctx.require(who, features)?;
        }
        let ray_query = s.trace == Trace::RayQuery;
        let (tris, first) = scene_triangles(scene);
        let (intersection, ordered, triangles) = if ray_query {
            let records = tris.iter().map(triangle_record).collect();
            (Intersection::RayQuery(RayQueryScene::new(ctx, scene, &first, s.moving_objects)?), tris, records)
        } else {
            let bvh = Bvh::build(tris);
            if bvh.depth() > settings::MAX_BVH_DEPTH {
                return Err(crate::input_error!(
                    "{}: technique photon-trace: the scene's BVH is {} levels deep, more than the shader's \
                     traversal stack holds ({}); degenerate or duplicated triangles make it so",
                    scene.path.display(),
                    bvh.depth(),
                    settings::MAX_BVH_DEPTH
                )
                .into());
            }
            let (nodes, triangles) = bvh.flattened();
            let nodes = upload_or_one(ctx, "photon_trace BVH nodes", bytemuck::cast_slice(&nodes), 32)?;
            (Intersection::Bvh { nodes }, bvh.triangles().to_vec(), triangles)
        };
        let normals = shading_normals(scene, &ordered);
        let objects: Vec<[f32; 4]> = meshes
            .iter()
            .flat_map(|m| {
                let c = &m.constants;
                [[f32::from_bits(c.material), 0.0, 0.0, 0.0], c.ior, c.colour]
            })
            .collect();
        let dispersive = meshes.iter().any(|m| {
            let ior = m.constants.ior;
            m.constants.material == MATERIAL_REFRACTIVE && (ior[0] != ior[1] || ior[1] != ior[2])
        });
        let upload = |name: &str, bytes: &[u8], element: usize| upload_or_one(ctx, name, bytes, element);
        let specular: Vec<bool> = meshes.iter().map(|m| m.kind() != MATERIAL_DIFFUSE).collect();
        let (sphere, eps, receiver_tolerance) = placement(scene, &specular);
        let mut defines: Vec<(&str, &str)> = vec![];
        if receiver_deposit {
            defines.push(("RECEIVER_DEPOSIT", "1"));
        }
        if ray_query {
            defines.push(("RAY_QUERY", "1"));
        }
        if s.differentials {
            defines.push(("DIFFERENTIALS", "1"));
        }
        let accumulation = match s.progressive {
            true => {
                let lights = scene.lights.len().clamp(1, crate::gpu::MAX_LIGHTS) as u32;
                let flux = scene
                    .receiver_map
                    .as_ref()
                    .filter(|_| receiver_deposit)
                    .map(|r| 16 * u64::from(r.resolution).pow(2));
                let (side, layers) = (s.caustic_map_resolution, lights * s.caustic_levels());
                Some(progressive::Accumulation::new(ctx, sh, side, layers, flux, s.progressive_alpha, s.splat_radius)?)
            }
            false => None,
        };
        Ok(PhotonTracer {
            accumulation,
            pipeline: Pipeline::compute(ctx, "photon_trace", &sh.compile("photon_trace/trace.comp", &defines)?)?,
            intersection,
            triangles: upload("photon_trace BVH triangles", bytemuck::cast_slice(&triangles), 48)?,
            normals: upload("photon_trace shading normals", bytemuck::cast_slice(&normals), 16)?,
            objects: upload("photon_trace objects", bytemuck::cast_slice(&objects), 48)?,
            constants: PhotonTraceConstants {
                sphere,
                light: 0,
                seed: s.seed,
                max_bounces: s.max_bounces,
                flags: if s.outside_reflection { FLAG_OUTSIDE_REFLECTION } else { 0 }
                    | if dispersive { FLAG_DISPERSIVE } else { 0 }
                    | if s.jitter { 0 } else { FLAG_CENTRED },
                eps,
                receiver_tolerance,
            },
            receiver_deposit,
            differentials: s.differentials,
            specular,
            moving: s.moving_objects,
        })
    }

    /// Follows `scene`, a pose in which the objects `moved` moved: with ray queries, waits for
    /// the device and moves their instances, rebuilds or refits their bottom levels
    /// ([`RayQueryScene::follow`]), and uploads the triangles and normals again where a bottom
    /// level was rebuilt or refitted (the shader reads each object as its bottom level holds it);
    /// the BVH is built once (an input error naming the object).
    pub fn follow(&mut self, ctx: &Context, scene: &Scene, moved: &[&str]) -> Result<instances::Followed> {
        let Intersection::RayQuery(rq) = &mut self.intersection else {
            return Err(crate::input_error!(
                "technique photon-trace: object `{}` moves, and the tracer's BVH is built once, when the renderer \
                 is made (trace `ray-query` follows moving objects)",
                moved.first().copied().unwrap_or("?")
            )
            .into());
        };
        ctx.wait_idle()?;
        (self.constants.sphere, self.constants.eps, self.constants.receiver_tolerance) =
            placement(scene, &self.specular);
        let followed = rq.follow(ctx, scene, moved, self.moving)?;
        if followed.rebuilt + followed.refitted > 0 {
            let rest = rq.rest_scene(scene);
            let (tris, _) = scene_triangles(&rest);
            let records: Vec<[f32; 12]> = tris.iter().map(triangle_record).collect();
            ctx.upload_buffer(&self.triangles, bytemuck::cast_slice(&records))?;
            ctx.upload_buffer(&self.normals, bytemuck::cast_slice(&shading_normals(&rest, &tris)))?;
        }
        Ok(followed)
    }

    /// Progressive accumulation: the next frame (new photons, one more frame in the means);
    /// returns its splat radius. None without `progressive`.
    pub fn next_frame(&mut self) -> Option<f32> {
        self.accumulation.as_mut().map(|a| a.next_frame())
    }

    /// Progressive accumulation: the next frame is the first of new means (the lights or the
    /// objects changed).
    pub fn restart(&mut self) {
        if let Some(a) = &mut self.accumulation {
            a.restart();
        }
    }

    /// Progressive accumulation: frames in the means (None without `progressive`).
    pub fn accumulated_frames(&self) -> Option<u32> {
        self.accumulation.as_ref().map(|a| a.frames())
    }

    /// After every light's deposit: the running means (`progressive`; nothing otherwise).
    pub fn record_accumulation(&self, f: &mut Frame, c: &CausticPasses) -> Result<()> {
        match &self.accumulation {
            Some(a) => a.record(f, &c.targets.caustic_map, &c.targets.receiver_flux),
            None => Ok(()),
        }
    }

    /// Light `l`'s receiver positions (for the caustic map's lookup), then its photons traced
    /// into the photon buffer.
    pub fn record(&self, f: &mut Frame, c: &CausticPasses, l: u32) -> Result<()> {
        record_receiver_positions(f, c, l)?;
        let (pt, inp) = (c.photons, c.inputs);
        let flux = &c.targets.receiver_flux;
        if self.receiver_deposit && l == 0 {
            f.pass(&Stage::PhotonTraceClear.pass()).uses([Use::buffer(flux, Access::TRANSFER_WRITE)]).record(
                |cmd| {
                    cmd.fill_buffer(flux, 0);
                    Ok(())
                },
            )?;
        }
        let mut binds = vec![
            ("frame", Bind::Uniform(inp.frame_uniforms)),
            ("caustics", Bind::Uniform(inp.caustic_uniforms)),
            ("spot_textures", Bind::Sampled(inp.spot_textures, inp.linear)),
            match &self.intersection {
                Intersection::Bvh { nodes } => ("Nodes", Bind::BufferRead(nodes)),
                Intersection::RayQuery(rq) => ("scene", Bind::AccelerationStructure(&rq.top)),
            },
            ("Triangles", Bind::BufferRead(&self.triangles)),
            ("ShadingNormals", Bind::BufferRead(&self.normals)),
            ("Objects", Bind::BufferRead(&self.objects)),
            ("photon_position", Bind::Storage(&pt.position.view)),
            ("photon_direction", Bind::Storage(&pt.direction.view)),
            ("photon_power", Bind::Storage(&pt.power.view)),
        ];
        if self.receiver_deposit {
            binds.push(("ReceiverFlux", Bind::Buffer(flux)));
        }
        if self.differentials {
            binds.push(("photon_footprint_u", Bind::Storage(&pt.footprint_u.view)));
            binds.push(("photon_footprint_v", Bind::Storage(&pt.footprint_v.view)));
        }
        let side = pt.width;
        f.pass(&Stage::PhotonTrace.light(l)).bind(&self.pipeline, binds).record(|cmd| {
            let seed = match &self.accumulation {
                Some(a) => progressive::frame_seed(self.constants.seed, a.frames()),
                None => self.constants.seed,
            };
            cmd.push(&PhotonTraceConstants { light: l, seed, ..self.constants })?;
            cmd.dispatch(side.div_ceil(8), side.div_ceil(8), 1);
            Ok(())
        })?;
        Ok(())
    }
}

/// A triangle as `photon_trace/triangles.glsl` stores it: `[v0 xyz, object, e1 xyz, 0, e2 xyz,
/// 0]`, the object's bits in its `f32` slot (as `Bvh::flattened` writes the BVH's).
fn triangle_record(t: &Triangle) -> [f32; 12] {
    let [v0, v1, v2] = t.v;
    let (e1, e2) = (v1 - v0, v2 - v0);
    [v0.x, v0.y, v0.z, f32::from_bits(t.object), e1.x, e1.y, e1.z, 0.0, e2.x, e2.y, e2.z, 0.0]
}

/// A device buffer holding `bytes`; buffers may not be empty, so a scene without triangles gets
/// one unused element of `element` bytes.
fn upload_or_one(ctx: &Context, name: &str, bytes: &[u8], element: usize) -> Result<Buffer> {
    let data = if bytes.is_empty() { vec![0u8; element] } else { bytes.to_vec() };
    Ok(ctx.buffer_with_data(name, &data)?)
}

/// Every triangle of `scene` in its order (object by object), and each object's first.
fn scene_triangles(scene: &Scene) -> (Vec<Triangle>, Vec<u32>) {
    let mut tris = Vec::with_capacity(scene.triangle_count());
    let mut first = Vec::with_capacity(scene.objects.len());
    for (oi, obj) in scene.objects.iter().enumerate() {
        first.push(tris.len() as u32);
        let p = &obj.mesh.positions;
        for (pi, [a, b, c]) in obj.mesh.triangles().enumerate() {
            tris.push(Triangle { v: [p[a], p[b], p[c]], object: oi as u32, prim: pi as u32 });
        }
    }
    (tris, first)
}

/// Per triangle of `ordered`, its mesh's vertex normals at the three corners.
fn shading_normals(scene: &Scene, ordered: &[Triangle]) -> Vec<[f32; 4]> {
    ordered
        .iter()
        .flat_map(|t| {
            let m = &scene.objects[t.object as usize].mesh;
            let i = 3 * t.prim as usize;
            [0, 1, 2].map(|k| m.normals[m.indices[i + k] as usize].extend(0.0).to_array())
        })
        .collect()
}

/// What the tracer's constants take from where the objects are: the specular objects' bounding
/// sphere (`specular[o]`: object o is one), which the emission cone subtends, as the reference's
/// per object (`reference::emit::bounding_sphere`), here of them all; the reference's ray offset
/// against self-intersection (`reference::trace_reference`); and how far from the receiver's
/// plane a photon lands on it (the reference's: 1e-4 of the scene's diagonal).
fn placement(scene: &Scene, specular: &[bool]) -> ([f32; 4], f32, f32) {
    let (lo, hi) = scene.bounds();
    let finite = lo.is_finite() && hi.is_finite();
    let max_abs = if finite { lo.abs().max(hi.abs()).max_element() } else { 1.0 };
    let diag = if finite { (hi - lo).length() } else { 1.0 };
    let points: Vec<glam::Vec3> = scene
        .objects
        .iter()
        .zip(specular)
        .filter(|(_, &s)| s)
        .flat_map(|(o, _)| o.mesh.positions.iter().copied())
        .collect();
    let (centre, radius) = bounding_sphere(&points);
    let sphere = [centre.x as f32, centre.y as f32, centre.z as f32, radius as f32];
    (sphere, (1e-5 * max_abs).max(1e-6), 1e-4 * diag.max(1e-6))
}
