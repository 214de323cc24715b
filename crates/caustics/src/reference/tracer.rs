//! The photon path: specular interactions (exact Snell / Fresnel / mirror) until the first
//! diffuse surface, where the photon is binned if it lies on the receiver rectangle.

use super::emit::Pcg32;
use super::optics::{fresnel_dielectric, reflect, refract};
use super::receiver::Receiver;
use super::ReferenceOptions;
use crate::bvh::{Bvh, Hit};
use crate::scene::{MaterialKind, Scene};
use glam::DVec3;

/// How one object's surface scatters photons.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Surface {
    Diffuse,
    Refractive { ior: [f64; 3], transmission: [f64; 3] },
    Reflective { specular: [f64; 3] },
}

impl Surface {
    pub(crate) fn of(kind: &MaterialKind) -> Surface {
        let a = |v: glam::Vec3| [v.x as f64, v.y as f64, v.z as f64];
        match kind {
            MaterialKind::Diffuse { .. } => Surface::Diffuse,
            MaterialKind::Refractive { ior, transmission } => {
                Surface::Refractive { ior: a(*ior), transmission: a(*transmission) }
            }
            MaterialKind::Reflective { specular } => Surface::Reflective { specular: a(*specular) },
        }
    }

    pub(crate) fn is_specular(&self) -> bool {
        !matches!(self, Surface::Diffuse)
    }
}

/// What happened to a photon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Fate {
    /// Its first hit was not specular (or nothing): direct light, not a caustic photon.
    NotCaustic,
    /// Landed on the receiver rectangle, in this texel (row-major index).
    Deposit(usize),
    /// Total internal reflection at the exit interface with `fresnel = false`.
    Tir,
    /// Interacted with a specular object but never reached the receiver rectangle
    /// (escaped, landed elsewhere, or ran out of bounces).
    Lost,
}

/// Everything a photon path needs, shared read-only by all worker threads.
pub(crate) struct Tracer<'a> {
    pub bvh: &'a Bvh,
    /// Unit geometric normal of each BVH triangle (BVH order), from the winding.
    pub normals: Vec<DVec3>,
    /// The mesh's vertex normals at each BVH triangle's corners, when photons refract and
    /// reflect with the interpolated (shading) normal: the smooth surface the mesh stands for,
    /// as the GPU techniques see it. None: the facets' geometric normals.
    pub shading: Option<Vec<[DVec3; 3]>>,
    /// Per object index.
    pub surfaces: Vec<Surface>,
    pub receiver: Receiver,
    pub fresnel: bool,
    pub max_bounces: u32,
    /// With `fresnel`: whether light reflected off a refractive object's outside (where it would
    /// enter) is traced on; false drops it (see [`super::ReferenceOptions::outside_reflection`]).
    pub outside_reflection: bool,
    /// Ray offset (absolute, world units) against self-intersection.
    pub eps: f32,
}

/// Guard against pathological loops when skipping specular surfaces.
const MAX_SKIPS: u32 = 256;

impl<'a> Tracer<'a> {
    /// The tracer of `opts`' physics (`fresnel`, `max_bounces`, `outside_reflection`,
    /// `smooth_normals`).
    pub(crate) fn new(
        scene: &Scene,
        bvh: &'a Bvh,
        receiver: Receiver,
        opts: &ReferenceOptions,
        eps: f32,
    ) -> Tracer<'a> {
        let normals = bvh
            .triangles()
            .iter()
            .map(|t| {
                let [a, b, c] = t.v.map(|v| v.as_dvec3());
                (b - a).cross(c - a).normalize_or_zero()
            })
            .collect();
        let surfaces = scene.objects.iter().map(|o| Surface::of(&scene.material_of(o).kind)).collect();
        let shading = opts.smooth_normals.then(|| {
            bvh.triangles()
                .iter()
                .map(|t| {
                    let m = &scene.objects[t.object as usize].mesh;
                    let i = 3 * t.prim as usize;
                    [0, 1, 2].map(|k| m.normals[m.indices[i + k] as usize].as_dvec3())
                })
                .collect()
        });
        Tracer {
            bvh,
            normals,
            shading,
            surfaces,
            receiver,
            fresnel: opts.fresnel,
            max_bounces: opts.max_bounces,
            outside_reflection: opts.outside_reflection,
            eps,
        }
    }

    /// The normal photons scatter about at `hit`, on the same side as the geometric normal.
    #[inline]
    fn scatter_normal(&self, hit: &Hit) -> DVec3 {
        let ng = self.normals[hit.triangle as usize];
        let Some(shading) = &self.shading else { return ng };
        let [n0, n1, n2] = shading[hit.triangle as usize];
        let (u, v) = (hit.u as f64, hit.v as f64);
        let n = (n0 * (1.0 - u - v) + n1 * u + n2 * v).normalize_or_zero();
        if n == DVec3::ZERO {
            ng
        } else if n.dot(ng) < 0.0 {
            -n
        } else {
            n
        }
    }

    #[inline]
    fn intersect(&self, o: DVec3, d: DVec3) -> Option<Hit> {
        self.bvh.intersect(o.as_vec3(), d.as_vec3(), self.eps, f32::INFINITY)
    }

    /// First hit on a diffuse surface, passing through specular ones.
    fn intersect_diffuse(&self, mut o: DVec3, d: DVec3) -> Option<(Hit, DVec3)> {
        for _ in 0..MAX_SKIPS {
            let hit = self.intersect(o, d)?;
            let p = o + d * hit.t as f64;
            if !self.surfaces[hit.object as usize].is_specular() {
                return Some((hit, p));
            }
            o = p;
        }
        None
    }

    /// Traces one photon from `origin` along unit `dir`. `power` is scaled in place by the
    /// surface colours met on the way. `channel` selects the IOR channel for dispersive
    /// materials (`None`: channel 0, used when all IORs are channel-independent).
    pub(crate) fn trace(
        &self,
        mut origin: DVec3,
        mut dir: DVec3,
        power: &mut [f64; 3],
        channel: Option<usize>,
        rng: &mut Pcg32,
    ) -> Fate {
        let ch = channel.unwrap_or(0);
        let mut interactions = 0u32;
        let mut refractions = 0u32;
        // `fresnel = false`: after the image-space path (two refractions, or one mirror
        // reflection) the photon goes straight to the first diffuse surface.
        let mut straight = false;
        loop {
            let found = if straight {
                self.intersect_diffuse(origin, dir)
            } else {
                self.intersect(origin, dir).map(|h| (h, origin + dir * h.t as f64))
            };
            let Some((hit, p)) = found else {
                return if interactions == 0 { Fate::NotCaustic } else { Fate::Lost };
            };
            let surface = self.surfaces[hit.object as usize];
            match surface {
                Surface::Diffuse => {
                    if interactions == 0 {
                        return Fate::NotCaustic;
                    }
                    return match self.receiver.texel_of(p) {
                        Some(t) => Fate::Deposit(t),
                        None => Fate::Lost,
                    };
                }
                _ if interactions >= self.max_bounces => return Fate::Lost,
                Surface::Reflective { specular } => {
                    let n = self.scatter_normal(&hit);
                    dir = reflect(dir, n).normalize();
                    for c in 0..3 {
                        power[c] *= specular[c];
                    }
                    if !self.fresnel {
                        straight = true;
                    }
                }
                Surface::Refractive { ior, transmission } => {
                    let ng = self.scatter_normal(&hit);
                    let entering = dir.dot(self.normals[hit.triangle as usize]) < 0.0;
                    let n = if entering { ng } else { -ng };
                    let (n_i, n_t) = if entering { (1.0, ior[ch]) } else { (ior[ch], 1.0) };
                    let cos_i = -dir.dot(n);
                    let reflect_now = if self.fresnel {
                        // Russian roulette with probability F; power unchanged.
                        rng.next_f64() < fresnel_dielectric(cos_i, n_i, n_t)
                    } else {
                        false
                    };
                    if reflect_now {
                        if entering && !self.outside_reflection {
                            return Fate::Lost;
                        }
                        dir = reflect(dir, n).normalize();
                    } else {
                        match refract(dir, n, n_i / n_t) {
                            Some(t) => dir = t,
                            None if self.fresnel => dir = reflect(dir, n).normalize(),
                            None => return Fate::Tir,
                        }
                        if !entering {
                            for c in 0..3 {
                                power[c] *= transmission[c];
                            }
                        }
                        refractions += 1;
                        if !self.fresnel && refractions >= 2 {
                            straight = true;
                        }
                    }
                }
            }
            interactions += 1;
            origin = p;
        }
    }
}
