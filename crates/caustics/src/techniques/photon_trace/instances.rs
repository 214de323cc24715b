//! The scene as `trace = "ray-query"` sees it, and how it follows a pose that moves objects: a
//! bottom-level acceleration structure per object over its triangles as they were when it was
//! built (the object's *rest*), one top-level structure with an instance of each, whose custom
//! index is the object's first triangle in the tracer's triangle buffer.
//!
//! A pose that moves objects gets a new top level. With `moving_objects = "transform"` (the
//! default) an object that moved rigidly since its rest ([`rigid_motion`]: one rotation and
//! translation put every vertex and normal where the pose has it) keeps its bottom level and its
//! instance carries the motion; the tracer reads its triangles and normals at rest and turns them
//! by the instance's rotation (`hit_to_world` in `photon_trace/triangles.glsl`). Any other
//! motion, and every motion with `moving_objects = "rebuild"`, rebuilds the object's bottom level
//! from its moved vertices, which become its rest. With `moving_objects = "refit"` every bottom
//! level is built updatable and a moved object's is refitted in place to its moved vertices: the
//! first build's tree keeps its topology and its boxes grow with the motion (cheaper to update,
//! possibly slower to trace: `bench_configs/photon_trace_moving.toml` measures both).

use super::settings::MovingObjects;
use crate::scene::{Mesh, Scene};
use anyhow::Result;
use glam::{DMat3, DVec3, Vec3};

use vkcore::{AccelerationStructure, Context, TlasInstance};

/// Object to world, the top three rows of a 4x4 matrix (row-major), as a top level's instance
/// stores it.
pub type Transform = [[f32; 4]; 3];

const IDENTITY: Transform = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]];

/// One object's bottom level, the mesh it was built over, and where its instance puts it.
struct Instance {
    object: usize,
    blas: AccelerationStructure,
    rest: Mesh,
    transform: Transform,
}

/// The acceleration structures of a scene's objects with triangles.
pub struct RayQueryScene {
    pub top: AccelerationStructure,
    instances: Vec<Instance>,
    /// Per object of the scene, its first triangle in the tracer's triangle buffer.
    first: Vec<u32>,
}

/// What following a pose did, object by object.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct Followed {
    /// Objects whose instance got their rigid motion as its transform.
    pub moved_instances: usize,
    /// Objects whose bottom level was rebuilt.
    pub rebuilt: usize,
    /// Objects whose bottom level was refitted in place.
    pub refitted: usize,
}

impl RayQueryScene {
    /// Builds the structures of `scene`'s objects at rest where they are (updatable where
    /// `moving` refits them); `first[o]` is object o's first triangle.
    pub fn new(ctx: &Context, scene: &Scene, first: &[u32], moving: MovingObjects) -> Result<RayQueryScene> {
        let mut instances = vec![];
        for (o, obj) in scene.objects.iter().enumerate() {
            if obj.mesh.indices.is_empty() {
                continue;
            }
            let blas = bottom_level(ctx, o, &obj.mesh, moving == MovingObjects::Refit)?;
            instances.push(Instance { object: o, blas, rest: obj.mesh.clone(), transform: IDENTITY });
        }
        let top = top_level(ctx, instances.iter().map(|i| (&i.blas, i.transform, i.object)), first)?;
        Ok(RayQueryScene { top, instances, first: first.to_vec() })
    }

    /// Follows `scene`, a pose of the scene these structures were built for in which the
    /// objects named `moved` moved, as `moving` says (the device must be idle: structures in use
    /// are replaced). The new top level is built before any old structure is dropped, so that
    /// on an error the old ones stand together (a refit, in place, is the exception: after a
    /// failed one the scene is not to be traced). A pose may move an object's vertices, not change
    /// its triangles (the tracer's buffers hold them): an error naming the object.
    pub fn follow(&mut self, ctx: &Context, scene: &Scene, moved: &[&str], moving: MovingObjects) -> Result<Followed> {
        let mut transforms: Vec<(usize, Transform)> = vec![];
        let mut rebuilt: Vec<(usize, AccelerationStructure)> = vec![];
        let mut refitted = 0;
        let is_moved = |inst: &Instance| moved.contains(&scene.objects[inst.object].name.as_str());
        // Every check before the first structure changes (a refit is in place).
        for inst in self.instances.iter().filter(|i| is_moved(i)) {
            let obj = &scene.objects[inst.object];
            anyhow::ensure!(
                obj.mesh.indices.len() == inst.rest.indices.len(),
                "technique photon-trace (trace ray-query): object `{}` has {} triangles in this pose and had {}: a pose \
                 may move an object's vertices, not change its triangles",
                obj.name,
                obj.mesh.indices.len() / 3,
                inst.rest.indices.len() / 3
            );
            anyhow::ensure!(
                moving != MovingObjects::Refit
                    || (obj.mesh.indices == inst.rest.indices && obj.mesh.positions.len() == inst.rest.positions.len()),
                "technique photon-trace (trace ray-query): object `{}` has other triangles in this pose (its indices or \
                 vertex count changed), which moving_objects = \"refit\" cannot follow: a refit moves vertices only",
                obj.name
            );
        }
        for (k, inst) in self.instances.iter_mut().enumerate() {
            if !is_moved(inst) {
                continue;
            }
            let obj = &scene.objects[inst.object];
            if moving == MovingObjects::Refit {
                inst.blas.refit(ctx, &positions(&obj.mesh), &obj.mesh.indices)?;
                inst.rest = obj.mesh.clone();
                refitted += 1;
                continue;
            }
            let rigid = match moving {
                MovingObjects::Transform => rigid_motion(&inst.rest, &obj.mesh),
                MovingObjects::Rebuild | MovingObjects::Refit => None,
            };
            match rigid {
                Some(t) => transforms.push((k, t)),
                None => rebuilt.push((k, bottom_level(ctx, inst.object, &obj.mesh, false)?)),
            }
        }
        let done = Followed { moved_instances: transforms.len(), rebuilt: rebuilt.len(), refitted };
        if done == Followed::default() {
            return Ok(done);
        }
        // Each instance as it will be: the new bottom levels and transforms, not yet stored.
        let next = self.instances.iter().enumerate().map(|(k, inst)| match rebuilt.iter().find(|(j, _)| *j == k) {
            Some((_, blas)) => (blas, IDENTITY, inst.object),
            None => {
                let transform = transforms.iter().find(|(j, _)| *j == k).map_or(inst.transform, |(_, t)| *t);
                (&inst.blas, transform, inst.object)
            }
        });
        self.top = top_level(ctx, next, &self.first)?;
        for (k, t) in transforms {
            self.instances[k].transform = t;
        }
        for (k, blas) in rebuilt {
            let inst = &mut self.instances[k];
            inst.blas = blas;
            inst.rest = scene.objects[inst.object].mesh.clone();
            inst.transform = IDENTITY;
        }
        Ok(done)
    }

    /// The meshes the tracer's triangle and normal buffers hold: each object at its rest.
    pub fn rest_scene(&self, scene: &Scene) -> Scene {
        let mut s = scene.clone();
        for inst in &self.instances {
            s.objects[inst.object].mesh = inst.rest.clone();
        }
        s
    }
}

fn positions(mesh: &Mesh) -> Vec<[f32; 3]> {
    mesh.positions.iter().map(|p| p.to_array()).collect()
}

/// Object `o`'s bottom level over `mesh`: compacted, or built to be refitted (`updatable`).
fn bottom_level(ctx: &Context, o: usize, mesh: &Mesh, updatable: bool) -> Result<AccelerationStructure> {
    let name = format!("photon_trace object {o}");
    let build = if updatable { AccelerationStructure::triangles_updatable } else { AccelerationStructure::triangles };
    Ok(build(ctx, &name, &positions(mesh), &mesh.indices)?)
}

/// The top level over `instances`: each a bottom level, its transform and its object, whose
/// first triangle (`first`) is the instance's custom index.
fn top_level<'a>(
    ctx: &Context,
    instances: impl Iterator<Item = (&'a AccelerationStructure, Transform, usize)>,
    first: &[u32],
) -> Result<AccelerationStructure> {
    let records: Vec<TlasInstance> = instances
        .map(|(blas, transform, object)| TlasInstance { blas, transform, custom_index: first[object] })
        .collect();
    Ok(AccelerationStructure::instances(ctx, "photon_trace scene", &records)?)
}

/// How far a vertex may lie from where the fitted motion puts it, relative to the rest mesh's
/// size (its bounding box's diagonal): far below anything a photon resolves...
const POSITION_TOLERANCE: f64 = 1e-5;
/// ...or, for a small object far from the origin, this many times f32's epsilon (1.2e-7) of the
/// largest coordinate of the two meshes, about 8 units in its last place: a pose's rotation in
/// f32 rounds a vertex by one or two.
const POSITION_EPSILONS: f64 = 4.0;
/// How far a unit normal, and the fitted rotation's columns, may be from a rotation's.
const NORMAL_TOLERANCE: f64 = 1e-4;

/// The rigid motion (a rotation, det +1, and a translation) that takes `rest` to `now`, where
/// one does within the tolerances above: every vertex and every normal; `None` for any other
/// motion (a scale, a shear, a mirror, a vertex moved alone) or meshes of different sizes. Fitted
/// from three vertices of `rest` spanning it (the first, the farthest from it, the farthest from
/// their line), checked on all.
pub fn rigid_motion(rest: &Mesh, now: &Mesh) -> Option<Transform> {
    let (p, q) = (&rest.positions, &now.positions);
    if p.len() != q.len() || rest.normals.len() != now.normals.len() || p.is_empty() || rest.indices != now.indices {
        return None;
    }
    let at = |v: &[Vec3], i: usize| v[i].as_dvec3();
    let i1 = (0..p.len()).max_by(|&a, &b| dist(at(p, a), at(p, 0)).total_cmp(&dist(at(p, b), at(p, 0))))?;
    let a = at(p, i1) - at(p, 0);
    let off_line = |i: usize| (at(p, i) - at(p, 0)).cross(a).length();
    let i2 = (0..p.len()).max_by(|&x, &y| off_line(x).total_cmp(&off_line(y)))?;
    let b = at(p, i2) - at(p, 0);
    let c = a.cross(b);
    if c.length() <= 1e-9 * a.length_squared().max(f64::MIN_POSITIVE) {
        return None;
    }
    let (qa, qb) = (at(q, i1) - at(q, 0), at(q, i2) - at(q, 0));
    let m = DMat3::from_cols(qa, qb, qa.cross(qb)) * DMat3::from_cols(a, b, c).inverse();
    let t = at(q, 0) - m * at(p, 0);
    if (m.transpose() * m - DMat3::IDENTITY).to_cols_array().iter().any(|e| e.abs() > NORMAL_TOLERANCE) {
        return None;
    }
    let largest = p.iter().chain(q).map(|v| v.abs().max_element() as f64).fold(0.0, f64::max);
    let (lo, hi) = rest.bounds();
    let size = (hi - lo).as_dvec3().length();
    let tol = (POSITION_TOLERANCE * size).max(POSITION_EPSILONS * f32::EPSILON as f64 * largest);
    if p.iter().zip(q).any(|(&x, &y)| !within(dist(m * x.as_dvec3() + t, y.as_dvec3()), tol)) {
        return None;
    }
    if rest
        .normals
        .iter()
        .zip(&now.normals)
        .any(|(&n, &o)| !within(dist(m * n.as_dvec3(), o.as_dvec3()), NORMAL_TOLERANCE))
    {
        return None;
    }
    let row = |i: usize| [m.row(i).x as f32, m.row(i).y as f32, m.row(i).z as f32, t[i] as f32];
    Some([row(0), row(1), row(2)])
}

/// `d <= tol`, false for a NaN.
fn within(d: f64, tol: f64) -> bool {
    d <= tol
}

fn dist(a: DVec3, b: DVec3) -> f64 {
    (a - b).length()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Mat3, Quat};

    /// An irregular tetrahedron's corners and normals (not symmetric: no rotation maps it to
    /// itself but the identity).
    fn mesh() -> Mesh {
        let positions = vec![
            Vec3::new(0.1, 0.2, 0.3),
            Vec3::new(1.3, 0.1, 0.2),
            Vec3::new(0.2, 0.9, 0.1),
            Vec3::new(0.4, 0.3, 1.7),
        ];
        let c = positions.iter().sum::<Vec3>() / 4.0;
        let normals = positions.iter().map(|&p| (p - c).normalize()).collect();
        Mesh { positions, normals, indices: vec![0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2] }
    }

    fn moved(m: &Mesh, rot: Mat3, shift: Vec3, scale: Vec3) -> Mesh {
        let mut out = m.clone();
        out.positions = m.positions.iter().map(|&p| rot * (p * scale) + shift).collect();
        out.normals = m.normals.iter().map(|&n| (rot * (n / scale)).normalize()).collect();
        out
    }

    fn apply(t: &Transform, p: Vec3) -> Vec3 {
        let r = |i: usize| t[i][0] * p.x + t[i][1] * p.y + t[i][2] * p.z + t[i][3];
        Vec3::new(r(0), r(1), r(2))
    }

    #[test]
    fn a_rotation_and_translation_is_found_and_reproduces_every_vertex() {
        let rest = mesh();
        let rot = Mat3::from_quat(Quat::from_axis_angle(Vec3::new(0.3, 1.0, -0.2).normalize(), 2.1));
        let now = moved(&rest, rot, Vec3::new(5.0, -2.0, 0.5), Vec3::ONE);
        let t = rigid_motion(&rest, &now).expect("a rigid motion");
        for (p, q) in rest.positions.iter().zip(&now.positions) {
            assert!((apply(&t, *p) - *q).length() < 1e-5, "{p} goes to {}, the pose has {q}", apply(&t, *p));
        }
        let expected = rot.transpose();
        for (i, row) in t.iter().enumerate() {
            assert!((Vec3::from_slice(&row[..3]) - expected.col(i)).length() < 1e-5, "row {i}: {row:?}");
        }
        let still = rigid_motion(&rest, &rest).expect("no motion is rigid");
        assert!(still.iter().flatten().zip(IDENTITY.iter().flatten()).all(|(a, b)| (a - b).abs() < 1e-6), "{still:?}");
    }

    #[test]
    fn a_scale_a_shear_a_mirror_or_one_vertex_moved_is_not_rigid() {
        let rest = mesh();
        let turned = Mat3::from_rotation_y(0.7);
        let scaled = moved(&rest, turned, Vec3::X, Vec3::splat(1.01));
        assert_eq!(rigid_motion(&rest, &scaled), None, "a uniform scale by 1.01");
        let squashed = moved(&rest, Mat3::IDENTITY, Vec3::ZERO, Vec3::new(1.0, 0.8, 1.0));
        assert_eq!(rigid_motion(&rest, &squashed), None, "a squash");
        let sheared = Mat3::from_cols(Vec3::X, Vec3::new(0.2, 1.0, 0.0), Vec3::Z);
        assert_eq!(rigid_motion(&rest, &moved(&rest, sheared, Vec3::ZERO, Vec3::ONE)), None, "a shear");
        let mirror = Mat3::from_diagonal(Vec3::new(-1.0, 1.0, 1.0));
        assert_eq!(rigid_motion(&rest, &moved(&rest, mirror, Vec3::ZERO, Vec3::ONE)), None, "a mirror");
        let mut one = moved(&rest, turned, Vec3::Y, Vec3::ONE);
        one.positions[3] += Vec3::new(0.0, 1e-3, 0.0);
        assert_eq!(rigid_motion(&rest, &one), None, "one vertex 1e-3 off");
        let mut normal = moved(&rest, turned, Vec3::Y, Vec3::ONE);
        normal.normals[2] = -normal.normals[2];
        assert_eq!(rigid_motion(&rest, &normal), None, "one normal flipped");
        // Far from the origin the tolerance follows the mesh's size, not its coordinates: at
        // x = 1000 a unit-sized object with one vertex moved by 5e-3 (an interior one, which the
        // fit never picks) is not rigid, though that is within 1e-5 of the coordinates.
        let mut far = moved(&rest, Mat3::IDENTITY, Vec3::new(1000.0, 0.0, 0.0), Vec3::ONE);
        let centre = far.positions.iter().sum::<Vec3>() / 4.0;
        far.positions.push(centre);
        far.normals.push(Vec3::Y);
        let mut dented = far.clone();
        dented.positions[4].y += 5e-3;
        assert!(rigid_motion(&rest, &moved(&rest, Mat3::IDENTITY, Vec3::new(1000.0, 0.0, 0.0), Vec3::ONE)).is_some());
        assert!(rigid_motion(&far, &far).is_some(), "no motion at x = 1000 is rigid");
        assert!(rigid_motion(&far, &dented).is_none(), "a vertex moved by 5e-3 at x = 1000");
        let mut fewer = rest.clone();
        fewer.positions.pop();
        assert_eq!(rigid_motion(&rest, &fewer), None, "a vertex fewer");
    }
}
