//! Indexed triangle meshes: smooth area-weighted normals, affine transforms, bounds and volume.

use glam::{Affine3A, Mat3, Vec3};

/// An indexed triangle list. Triangles are counter-clockwise when seen from the side the
/// normals point to (for closed meshes: from outside), and `normals[i]` belongs to
/// `positions[i]`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    pub indices: Vec<u32>,
}

impl Mesh {
    /// Axis-aligned bounding box `(min, max)`. An empty mesh gives `(Vec3::ZERO, Vec3::ZERO)`.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        if self.positions.is_empty() {
            return (Vec3::ZERO, Vec3::ZERO);
        }
        self.positions
            .iter()
            .fold((Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)), |(lo, hi), &p| (lo.min(p), hi.max(p)))
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Iterates over triangles as `[a, b, c]` vertex indices.
    pub fn triangles(&self) -> impl Iterator<Item = [usize; 3]> + '_ {
        self.indices.chunks_exact(3).map(|t| [t[0] as usize, t[1] as usize, t[2] as usize])
    }

    /// Signed enclosed volume (divergence theorem). Positive for a closed mesh wound
    /// counter-clockwise seen from outside, negative for one seen from inside.
    pub fn signed_volume(&self) -> f64 {
        self.triangles()
            .map(|[a, b, c]| {
                let (a, b, c) =
                    (self.positions[a].as_dvec3(), self.positions[b].as_dvec3(), self.positions[c].as_dvec3());
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    /// Total surface area.
    pub fn area(&self) -> f64 {
        self.triangles()
            .map(|[a, b, c]| {
                let (a, b, c) = (self.positions[a], self.positions[b], self.positions[c]);
                0.5 * (b - a).cross(c - a).length() as f64
            })
            .sum()
    }

    /// Replaces `normals` with smooth, area-weighted vertex normals: each vertex gets the
    /// normalised sum of the (area-scaled) geometric normals of the triangles that use it.
    /// A vertex used by no triangle (or only by degenerate ones) gets `+Y`.
    pub fn compute_smooth_normals(&mut self) {
        let mut acc = vec![Vec3::ZERO; self.positions.len()];
        for [a, b, c] in self.triangles() {
            let (pa, pb, pc) = (self.positions[a], self.positions[b], self.positions[c]);
            // |cross| = 2 * area, so the sum is area-weighted.
            let n = (pb - pa).cross(pc - pa);
            acc[a] += n;
            acc[b] += n;
            acc[c] += n;
        }
        self.normals = acc.into_iter().map(|n| n.normalize_or(Vec3::Y)).collect();
    }

    /// Applies an affine transform: positions by `m`, normals by the inverse-transpose of its
    /// linear part (renormalised). A mirroring transform (negative determinant) also reverses
    /// the winding so that front faces stay counter-clockwise. The linear part must be
    /// invertible; callers validate that.
    pub fn transform(&mut self, m: &Affine3A) {
        let linear = Mat3::from(m.matrix3);
        let normal_matrix = linear.inverse().transpose();
        for p in &mut self.positions {
            *p = m.transform_point3(*p);
        }
        for n in &mut self.normals {
            *n = (normal_matrix * *n).normalize_or(Vec3::Y);
        }
        if linear.determinant() < 0.0 {
            for t in self.indices.chunks_exact_mut(3) {
                t.swap(1, 2);
            }
        }
    }

    /// Reverses the winding and negates the normals (turns an outside-facing closed mesh into
    /// one seen from inside).
    pub fn flip(&mut self) {
        for t in self.indices.chunks_exact_mut(3) {
            t.swap(1, 2);
        }
        for n in &mut self.normals {
            *n = -*n;
        }
    }

    /// Appends `other`, re-basing its indices.
    pub fn append(&mut self, other: &Mesh) {
        let base = self.positions.len() as u32;
        self.positions.extend_from_slice(&other.positions);
        self.normals.extend_from_slice(&other.normals);
        self.indices.extend(other.indices.iter().map(|i| i + base));
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use std::collections::HashMap;

    /// Every edge (with vertices welded by position) is used exactly twice, once in each
    /// direction: the mesh is closed and consistently oriented.
    pub fn assert_closed(mesh: &Mesh) {
        let key = |p: Vec3| {
            let q = (p * 1e5).round();
            (q.x as i64, q.y as i64, q.z as i64)
        };
        let mut edges: HashMap<_, i32> = HashMap::new();
        for [a, b, c] in mesh.triangles() {
            for (u, v) in [(a, b), (b, c), (c, a)] {
                let (ku, kv) = (key(mesh.positions[u]), key(mesh.positions[v]));
                assert_ne!(ku, kv, "degenerate edge");
                *edges.entry((ku, kv)).or_default() += 1;
            }
        }
        for (&(u, v), &n) in &edges {
            assert_eq!(n, 1, "directed edge {u:?}->{v:?} used {n} times");
            assert_eq!(edges.get(&(v, u)), Some(&1), "edge {u:?}-{v:?} is a boundary");
        }
    }

    pub fn assert_unit_normals(mesh: &Mesh) {
        assert_eq!(mesh.normals.len(), mesh.positions.len());
        for n in &mesh.normals {
            assert!((n.length() - 1.0).abs() < 1e-5, "normal {n} not unit");
        }
    }

    #[test]
    fn smooth_normals_of_a_tetrahedron_corner() {
        // Corner at the origin with three right-angled faces of different areas, wound so the
        // normals point into the negative octant (away from the 4th face):
        //   face in the xy plane (area 1*2/2 = 1)   -> normal -z
        //   face in the yz plane (area 2*3/2 = 3)   -> normal -x
        //   face in the zx plane (area 3*1/2 = 1.5) -> normal -y
        let mesh0 = Mesh {
            positions: vec![Vec3::ZERO, Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0), Vec3::new(0.0, 0.0, 3.0)],
            normals: vec![],
            indices: vec![0, 2, 1, 0, 3, 2, 0, 1, 3],
        };
        let mut mesh = mesh0.clone();
        mesh.compute_smooth_normals();
        // Hand computation: sum of area * unit normal = (-3, -1.5, -1), normalised.
        let expect = Vec3::new(-3.0, -1.5, -1.0) / (9.0f32 + 2.25 + 1.0).sqrt();
        assert!((mesh.normals[0] - expect).length() < 1e-6, "{}", mesh.normals[0]);
        // Vertex 1 = (1,0,0) touches the xy face (-z, area 1) and the zx face (-y, area 1.5).
        let expect1 = Vec3::new(0.0, -1.5, -1.0) / (2.25f32 + 1.0).sqrt();
        assert!((mesh.normals[1] - expect1).length() < 1e-6, "{}", mesh.normals[1]);
        assert_unit_normals(&mesh);
    }

    #[test]
    fn unused_vertex_gets_a_unit_normal() {
        let mut mesh =
            Mesh { positions: vec![Vec3::ZERO, Vec3::X, Vec3::Z, Vec3::ONE], normals: vec![], indices: vec![0, 2, 1] };
        mesh.compute_smooth_normals();
        assert!((mesh.normals[0] - Vec3::Y).length() < 1e-6);
        assert_unit_normals(&mesh);
    }

    #[test]
    fn mirror_transform_keeps_outward_winding() {
        let mut mesh = crate::scene::procedural::box_mesh(Vec3::new(1.0, 2.0, 3.0));
        let before = mesh.signed_volume();
        mesh.transform(&Affine3A::from_scale(Vec3::new(-1.0, 1.0, 1.0)));
        assert!((mesh.signed_volume() - before).abs() < 1e-5);
        assert_closed(&mesh);
        // Normals still point away from the centre.
        for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
            assert!(p.dot(*n) > 0.0);
        }
    }
}
