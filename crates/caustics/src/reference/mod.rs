//! Exact CPU photon reference: the ground truth for Wyman & Davis 2006 ("Interactive
//! Image-Space Techniques for Approximating Caustics") and Shah et al. ("Caustics Mapping:
//! An Image-space Technique for Real-time Caustics") caustic maps.
//!
//! # Physics
//! * One [`Bvh`] over every object's triangles (`Triangle::object` = object index).
//! * The receiver is the rectangle of [`ReceiverMapSpec`](crate::scene::ReceiverMapSpec),
//!   normal `+y`, `N × N` texels of area `A = (x1 − x0)(z1 − z0)/N²`, row 0 at `z0`.
//! * `E0` per texel and RGB channel: `Σ_lights I · max(cos θ, 0) / r²` at the texel centre;
//!   spot lights contribute zero outside their cone and their projected texture's colour inside
//!   it (`scene::spot_projector`, sampled as the renderer samples it).
//! * Direct `E`: the same terms times a binary visibility of the segment texel centre →
//!   light against *every* triangle (glass blocks direct light; the caustic adds it back).
//! * Caustic `E`: from each light, photons are sampled uniformly in solid angle over the
//!   cone subtending each specular (refractive or reflective) object's bounding sphere
//!   (half-angle `asin(R/d)`; the whole sphere when the light is inside). The photon budget
//!   of a light is split between objects in proportion to the cones' solid angles
//!   `Ω = 2π(1 − cos α)`, and a photon carries `Φ = I / Σ_k [ω ∈ cone_k] M_k/Ω_k` (balance
//!   heuristic over overlapping cones), i.e. `Φ = I · Ω / M` for a single cone. A photon
//!   whose first hit is not specular is discarded (direct light, counted above).
//!   - Refraction: exact Snell with the material's per-channel IOR (each RGB channel traced
//!     as its own photon when a material's IORs differ between channels), entering/exiting
//!     from the geometric normal vs the ray direction, outside medium = vacuum (no nested
//!     dielectrics). The transmission colour is applied on every exit.
//!   - `fresnel = true`: exact unpolarised dielectric Fresnel; reflect with probability `F`
//!     (Russian roulette, power unchanged), TIR reflects; at most `max_bounces` specular
//!     interactions (a photon that would need more is dropped). `outside_reflection = false`
//!     drops the photons reflected off a refractive object's outside (none of the image-space
//!     techniques draws that light).
//!   - `fresnel = false` (what the image-space techniques approximate): all power is
//!     transmitted, the path is two refractions (or one mirror reflection); a photon that
//!     meets TIR is dropped and its power added to `lost_tir`; after the second refraction
//!     the photon goes straight to the first diffuse surface (passing through specular
//!     ones), as the image-space method splats it there.
//!   - Mirrors: exact mirror reflection, power times the specular colour.
//!   - A photon hitting a diffuse surface after ≥ 1 specular interaction is binned if the
//!     point lies on the receiver plane (`|y − plane_y| < 1e-4 ·` scene diagonal) inside
//!     the rectangle, then stops (no diffuse bounces). Caustic `E = flux / A`.
//! * Determinism: photons are split into chunks of [`CHUNK`]; each chunk has its own PCG32
//!   stream seeded from `(seed, light, object, chunk)`, and the per-chunk flux grids are
//!   summed in chunk order in `f64`, so the result is bit-identical for any thread count.
//!
//! Output ([`ReferenceResult::image`], `receiver.exr`): main layer `R,G,B` =
//! `(E_direct + E_caustic)/E0` (0 where `E0 = 0`) and `E0` (mean of the RGB `E0`, W/m²);
//! layer `irradiance` (`R,G,B` = `E_direct + E_caustic`, W/m²); layer `caustic` (`R,G,B`
//! = `E_caustic`, W/m²).

pub mod emit;
pub mod optics;
pub mod receiver;
mod tracer;

use crate::bvh::{Bvh, Triangle};
use crate::error::InputError;
use crate::image_io::ImageF32;
use crate::scene::Scene;
use emit::{bounding_sphere, Cone, Pcg32};
use receiver::{Emitter, Receiver};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use tracer::{Fate, Surface, Tracer};

/// Photons per chunk (one RNG stream and one flux grid each).
pub const CHUNK: u64 = 65_536;

#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceOptions {
    /// Photon samples per light (split between the specular objects).
    pub photons: u64,
    pub seed: u64,
    /// Exact Fresnel (true) or the image-space two-refraction model (false).
    pub fresnel: bool,
    /// Maximum number of specular interactions per photon.
    pub max_bounces: u32,
    /// With `fresnel`: trace the light a refractive object reflects off its outside (true, the
    /// physics), or drop it (false: counted in `lost_other`), leaving the paths that enter the
    /// object, the only ones the image-space techniques draw.
    pub outside_reflection: bool,
    /// Worker threads; 0 = `available_parallelism`.
    pub threads: usize,
    /// Scatter about the interpolated vertex normals (the smooth surface a mesh stands for, as
    /// the renderer shades it) rather than the facets' geometric normals.
    pub smooth_normals: bool,
}

impl Default for ReferenceOptions {
    fn default() -> Self {
        Self {
            photons: 1 << 22,
            seed: 1,
            fresnel: false,
            max_bounces: 8,
            outside_reflection: true,
            threads: 0,
            smooth_normals: true,
        }
    }
}

#[derive(Clone, Debug)]
pub struct ReferenceResult {
    /// `receiver.exr` content (see the module docs).
    pub image: ImageF32,
    /// W landing in the receiver rectangle, per channel.
    pub caustic_flux: [f64; 3],
    /// W sent toward specular objects (sampled photons, spot cones applied).
    pub emitted_flux: [f64; 3],
    /// W dropped by total internal reflection (`fresnel = false` only).
    pub lost_tir: [f64; 3],
    /// W of photons that met a specular object but never reached the rectangle (escaped,
    /// landed outside it or on another diffuse surface, or ran out of bounces).
    pub lost_other: [f64; 3],
    /// W of sampled photons whose first hit was not specular (direct light).
    /// `emitted = caustic + lost_tir + lost_other + missed` exactly up to rounding.
    pub missed_flux: [f64; 3],
    /// Photon samples emitted (over all lights and objects).
    pub photons_traced: u64,
    /// Worker threads that traced (fewer than asked where the system would start no more:
    /// the others' photons were shared among them, the image the same).
    pub threads: usize,
    /// Threads asked for (`--threads`, or the machine's parallelism, at most one per task).
    pub threads_asked: usize,
    /// Why the system refused the first thread it did not start, where it refused one.
    pub thread_refused: Option<String>,
    /// Seconds of the photons' tracing and binning alone, by every worker, from the first task
    /// taken to the last merged: without the BVH build before it and the direct light after it,
    /// as `photon-trace`'s trace pass has its BVH (or acceleration structures) built beforehand.
    pub trace_seconds: f64,
}

/// One unit of work: `count` photons from `light` sampled in `cone` of object `object`.
struct Task {
    light: usize,
    object: usize,
    chunk: u64,
    count: u64,
}

/// Per-light emission data: every specular cone with its photon density `M/Ω`.
struct LightCones {
    cones: Vec<(usize, Cone, u64, f64)>, // (object, cone, photons M, M/Ω)
    emitter: Emitter,
}

#[derive(Default)]
struct Totals {
    caustic: [f64; 3],
    emitted: [f64; 3],
    tir: [f64; 3],
    other: [f64; 3],
    missed: [f64; 3],
    photons: u64,
}

impl Totals {
    fn add(&mut self, o: &Totals) {
        for c in 0..3 {
            self.caustic[c] += o.caustic[c];
            self.emitted[c] += o.emitted[c];
            self.tir[c] += o.tir[c];
            self.other[c] += o.other[c];
            self.missed[c] += o.missed[c];
        }
        self.photons += o.photons;
    }
}

struct Merger {
    next: usize,
    pending: BTreeMap<usize, (Vec<f64>, Totals)>,
    grid: Vec<f64>,
    totals: Totals,
    pool: Vec<Vec<f64>>,
}

fn add3(a: &mut [f64; 3], b: &[f64; 3]) {
    for c in 0..3 {
        a[c] += b[c];
    }
}

/// Traces the exact photon reference for `scene` (see the module docs). Errors with
/// [`InputError`] when the scene has no `[receiver_map]`.
pub fn trace_reference(scene: &Scene, opts: &ReferenceOptions) -> anyhow::Result<ReferenceResult> {
    let spec = scene.receiver_map.as_ref().ok_or_else(|| {
        InputError::new(format!("{}: the exact photon reference needs a [receiver_map] section", scene.path.display()))
    })?;
    let increasing = |r: [f32; 2]| r[1] > r[0];
    if spec.resolution == 0 || !increasing(spec.x_range) || !increasing(spec.z_range) {
        return Err(InputError::new(format!(
            "{}: [receiver_map] needs resolution > 0 and increasing x_range/z_range",
            scene.path.display()
        ))
        .into());
    }

    let mut tris = Vec::with_capacity(scene.triangle_count());
    for (oi, obj) in scene.objects.iter().enumerate() {
        for (pi, [a, b, c]) in obj.mesh.triangles().enumerate() {
            let p = &obj.mesh.positions;
            tris.push(Triangle { v: [p[a], p[b], p[c]], object: oi as u32, prim: pi as u32 });
        }
    }
    let bvh = Bvh::build(tris);

    let (lo, hi) = scene.bounds();
    let (lo, hi) = (lo.as_dvec3(), hi.as_dvec3());
    let diag = if lo.is_finite() && hi.is_finite() { (hi - lo).length() } else { 1.0 };
    let max_abs = if lo.is_finite() && hi.is_finite() { lo.abs().max(hi.abs()).max_element() } else { 1.0 };
    let eps = (1e-5 * max_abs).max(1e-6) as f32;
    let rx = Receiver::new(spec, 1e-4 * diag.max(1e-6));
    let n = rx.n;

    let tracer = Tracer::new(scene, &bvh, rx, opts, eps);
    let dispersive = tracer.surfaces.iter().any(|s| match s {
        Surface::Refractive { ior, .. } => ior[0] != ior[1] || ior[1] != ior[2],
        _ => false,
    });

    // Emission cones and the task list.
    let mut lights = Vec::new();
    let mut tasks = Vec::new();
    for (li, light) in scene.lights.iter().enumerate() {
        let apex = light.position.as_dvec3();
        let mut cones: Vec<(usize, Cone)> = Vec::new();
        for (oi, obj) in scene.objects.iter().enumerate() {
            if tracer.surfaces[oi].is_specular() && !obj.mesh.positions.is_empty() {
                let (c, r) = bounding_sphere(&obj.mesh.positions);
                cones.push((oi, Cone::towards_sphere(apex, c, r)));
            }
        }
        let total_omega: f64 = cones.iter().map(|(_, c)| c.solid_angle()).sum();
        let mut left = opts.photons;
        let mut with_m = Vec::new();
        for (k, (oi, cone)) in cones.iter().enumerate() {
            let m = if k + 1 == cones.len() {
                left
            } else {
                ((opts.photons as f64 * cone.solid_angle() / total_omega).round() as u64).min(left)
            };
            left -= m;
            if m == 0 {
                continue;
            }
            with_m.push((*oi, *cone, m, m as f64 / cone.solid_angle()));
            let chunks = m.div_ceil(CHUNK);
            for chunk in 0..chunks {
                tasks.push(Task { light: li, object: *oi, chunk, count: (m - chunk * CHUNK).min(CHUNK) });
            }
        }
        lights.push(LightCones { cones: with_m, emitter: Emitter::of(light)? });
    }

    let threads =
        if opts.threads == 0 { std::thread::available_parallelism().map_or(1, |n| n.get()) } else { opts.threads }
            .clamp(1, tasks.len().max(1));
    // A grid of n² RGB f64 per worker, the merged one and the image: refused up front when the
    // machine has not that much memory available, rather than aborting half way.
    let need = (n * n * 3 * 8) as u64 * (threads as u64 + 2);
    if let Some(available) = available_memory() {
        if need > available {
            return Err(crate::input_error!(
                "{}: receiver_map.resolution {n} with {threads} thread(s) needs {} MiB, more than the {} MiB \
                 available: lower the resolution or the thread count",
                scene.path.display(),
                need >> 20,
                available >> 20
            )
            .into());
        }
    }

    let merger = Mutex::new(Merger {
        next: 0,
        pending: BTreeMap::new(),
        grid: vec![0.0; n * n * 3],
        totals: Totals::default(),
        pool: Vec::new(),
    });
    let counter = AtomicUsize::new(0);
    let worker = || loop {
        let ti = counter.fetch_add(1, Ordering::Relaxed);
        let Some(task) = tasks.get(ti) else { break };
        let mut grid = merger.lock().unwrap().pool.pop().unwrap_or_default();
        grid.clear();
        grid.resize(n * n * 3, 0.0);
        let totals = run_task(scene, &lights, &tracer, task, opts.seed, dispersive, &mut grid);
        let mut m = merger.lock().unwrap();
        m.pending.insert(ti, (grid, totals));
        loop {
            let next = m.next;
            let Some((g, t)) = m.pending.remove(&next) else { break };
            for (a, b) in m.grid.iter_mut().zip(&g) {
                *a += *b;
            }
            m.totals.add(&t);
            m.pool.push(g);
            m.next += 1;
        }
    };
    // Workers take tasks from one counter (crate::workers).
    let trace_start = std::time::Instant::now();
    let started = crate::workers::run(threads, "reference", worker);
    let trace_seconds = trace_start.elapsed().as_secs_f64();
    let merger = merger.into_inner().unwrap();
    debug_assert_eq!(merger.next, tasks.len());

    let area = rx.texel_area();
    let caustic: Vec<f64> = merger.grid.iter().map(|f| f / area).collect();
    let emitters: Vec<&Emitter> = lights.iter().map(|l| &l.emitter).collect();
    let (e0, direct) = receiver::direct_irradiance(&rx, &scene.lights, &emitters, &bvh);
    let image = receiver::build_image(n, &e0, &direct, &caustic);
    let t = merger.totals;
    Ok(ReferenceResult {
        image,
        caustic_flux: t.caustic,
        emitted_flux: t.emitted,
        lost_tir: t.tir,
        lost_other: t.other,
        missed_flux: t.missed,
        threads: started.threads,
        threads_asked: threads,
        thread_refused: started.refused,
        photons_traced: t.photons,
        trace_seconds,
    })
}

/// Traces one chunk into `grid` (flux per texel and channel, W).
fn run_task(
    scene: &Scene,
    lights: &[LightCones],
    tracer: &Tracer,
    task: &Task,
    seed: u64,
    dispersive: bool,
    grid: &mut [f64],
) -> Totals {
    let light = &scene.lights[task.light];
    let apex = light.position.as_dvec3();
    let intensity = light.intensity.as_dvec3().to_array();
    let cones = &lights[task.light].cones;
    let cone = cones.iter().find(|c| c.0 == task.object).expect("task cone").1;
    let mut rng = Pcg32::for_chunk(seed, &[task.light as u64, task.object as u64, task.chunk]);
    let mut tot = Totals::default();
    for _ in 0..task.count {
        tot.photons += 1;
        let dir = cone.sample(&mut rng);
        let density: f64 = cones.iter().filter(|c| c.1.contains(dir) || c.0 == task.object).map(|c| c.3).sum();
        let f = lights[task.light].emitter.emission(dir);
        if f == [0.0; 3] {
            continue;
        }
        let phi: [f64; 3] = std::array::from_fn(|c| intensity[c] * f[c] / density);
        add3(&mut tot.emitted, &phi);
        let channels: &[Option<usize>] = if dispersive { &[Some(0), Some(1), Some(2)] } else { &[None] };
        for &ch in channels {
            let mut p = match ch {
                None => phi,
                Some(c) => {
                    let mut p = [0.0; 3];
                    p[c] = phi[c];
                    p
                }
            };
            let start = p;
            match tracer.trace(apex, dir, &mut p, ch, &mut rng) {
                Fate::NotCaustic => add3(&mut tot.missed, &start),
                Fate::Deposit(t) => {
                    for c in 0..3 {
                        grid[t * 3 + c] += p[c];
                    }
                    add3(&mut tot.caustic, &p);
                    // Power absorbed by coloured surfaces on the way counts as lost.
                    add3(&mut tot.other, &[start[0] - p[0], start[1] - p[1], start[2] - p[2]]);
                }
                Fate::Tir => {
                    add3(&mut tot.tir, &p);
                    add3(&mut tot.other, &[start[0] - p[0], start[1] - p[1], start[2] - p[2]]);
                }
                Fate::Lost => add3(&mut tot.other, &start),
            }
        }
    }
    tot
}

/// `MemAvailable` of /proc/meminfo in bytes (Linux); `None` elsewhere.
fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
