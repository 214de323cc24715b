//! Deterministic animation paths for benchmarks. Several of the papers' tables average over an
//! animation (Wyman 2008 Table 4; Wyman & Davis 2006 Table 1 "dynamic lighting"): the light,
//! the camera or the specular objects move along a closed path, one step per frame, so every
//! run of a config renders exactly the same frames.

use crate::scene::{LightKind, MaterialKind, Scene};
use glam::{Mat3, Vec3};

/// Names accepted for a path in bench configs.
pub const PATHS: &[&str] = &["static", "orbit"];

/// What moves, and over how many frames one loop of the path takes.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Animation {
    /// Lights orbit the vertical axis through the specular objects' centre.
    pub light: bool,
    /// The eye orbits the vertical axis through the camera target.
    pub camera: bool,
    /// Specular objects turn about their own vertical axis and circle a quarter of their
    /// radius around their rest position; a pool's water advances by `pool.time_step` a frame.
    pub object: bool,
    /// Frames per full turn (≥ 1).
    pub period_frames: u32,
}

impl Animation {
    pub fn is_static(&self) -> bool {
        !(self.light || self.camera || self.object)
    }
}

/// The angle (radians) of frame `frame` along a loop of `period` frames.
fn angle(frame: u32, period: u32) -> f32 {
    std::f32::consts::TAU * (frame % period.max(1)) as f32 / period.max(1) as f32
}

fn is_specular(scene: &Scene, o: &crate::scene::Object) -> bool {
    !matches!(scene.material_of(o).kind, MaterialKind::Diffuse { .. })
}

/// Centre of the specular objects' bounds (of the whole scene when there are none).
fn specular_centre(scene: &Scene) -> Vec3 {
    let (lo, hi) = scene
        .objects
        .iter()
        .filter(|o| is_specular(scene, o))
        .map(|o| o.mesh.bounds())
        .fold((Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)), |(lo, hi), (a, b)| (lo.min(a), hi.max(b)));
    if lo.x.is_finite() {
        0.5 * (lo + hi)
    } else {
        let (lo, hi) = scene.bounds();
        0.5 * (lo + hi)
    }
}

/// Rotation by `a` about the vertical axis through `pivot`, applied to point `p`.
fn orbit(p: Vec3, pivot: Vec3, a: f32) -> Vec3 {
    pivot + Mat3::from_rotation_y(a) * (p - pivot)
}

/// `base` at frame `frame` of `anim`. Frame 0 is `base` itself.
pub fn scene_at(base: &Scene, anim: &Animation, frame: u32) -> Scene {
    let mut s = base.clone();
    let a = angle(frame, anim.period_frames);
    if a == 0.0 {
        return s;
    }
    if anim.light {
        let pivot = specular_centre(base);
        for l in &mut s.lights {
            l.position = orbit(l.position, pivot, a);
            if let LightKind::Spot { direction, .. } = &mut l.kind {
                *direction = (Mat3::from_rotation_y(a) * *direction).normalize();
            }
        }
    }
    if anim.camera {
        s.camera.eye = orbit(s.camera.eye, s.camera.target, a);
    }
    if let Some(pool) = &mut s.pool {
        // A pool's light turns like the others; its water moves by time, not by turning.
        if anim.light {
            pool.light_direction = glam::DMat3::from_rotation_y(a as f64) * pool.light_direction;
        }
        if anim.object {
            pool.time += (frame % anim.period_frames.max(1)) as f64 * pool.time_step;
        }
    }
    if anim.object {
        let turn = Mat3::from_rotation_y(a);
        for i in 0..s.objects.len() {
            if !is_specular(base, &base.objects[i]) {
                continue;
            }
            let (lo, hi) = base.objects[i].mesh.bounds();
            let centre = 0.5 * (lo + hi);
            let radius = 0.5 * (hi - lo).length();
            let offset = 0.25 * radius * Vec3::new(a.cos() - 1.0, 0.0, a.sin());
            let m = &mut s.objects[i].mesh;
            for p in &mut m.positions {
                *p = centre + offset + turn * (*p - centre);
            }
            for n in &mut m.normals {
                *n = turn * *n;
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Scene {
        let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/sphere_on_plane.toml"));
        Scene::load(path).expect("shipped scene loads")
    }

    #[test]
    fn the_path_is_periodic() {
        let base = scene();
        let anim = Animation { light: true, camera: true, object: true, period_frames: 8 };
        assert_eq!(scene_at(&base, &anim, 0).lights, base.lights);
        let (a, b) = (scene_at(&base, &anim, 3), scene_at(&base, &anim, 3 + 8));
        assert_ne!(a.camera, base.camera, "frame 3 is not the rest pose");
        assert_eq!(a.camera, b.camera);
        assert_eq!(a.lights, b.lights);
        assert_eq!(a.objects, b.objects);
    }

    #[test]
    fn light_orbit_keeps_height_and_distance_to_the_pivot() {
        let base = scene();
        let anim = Animation { light: true, camera: false, object: false, period_frames: 12 };
        let pivot = specular_centre(&base);
        let p0 = base.lights[0].position;
        for f in 1..12 {
            let p = scene_at(&base, &anim, f).lights[0].position;
            assert!((p.y - p0.y).abs() < 1e-5, "frame {f}: height {} vs {}", p.y, p0.y);
            let r = |q: Vec3| Vec3::new(q.x - pivot.x, 0.0, q.z - pivot.z).length();
            assert!((r(p) - r(p0)).abs() < 1e-4, "frame {f}: radius {} vs {}", r(p), r(p0));
        }
        // Only the light moves.
        assert_eq!(scene_at(&base, &anim, 3).camera, base.camera);
    }

    #[test]
    fn object_motion_is_rigid() {
        let base = scene();
        let anim = Animation { light: false, camera: false, object: true, period_frames: 10 };
        let moved = scene_at(&base, &anim, 3);
        let mut changed = false;
        for (a, b) in base.objects.iter().zip(&moved.objects) {
            let (pa, pb) = (&a.mesh.positions, &b.mesh.positions);
            changed |= pa.iter().zip(pb).any(|(x, y)| x.distance(*y) > 1e-4);
            // Distances between vertices are preserved.
            for i in (1..pa.len()).step_by(97) {
                let (da, db) = (pa[i].distance(pa[0]), pb[i].distance(pb[0]));
                assert!((da - db).abs() < 1e-4 * (1.0 + da), "{}: {da} vs {db}", a.name);
            }
        }
        assert!(changed, "the specular object did not move");
    }
}
