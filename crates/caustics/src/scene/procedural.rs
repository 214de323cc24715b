//! Procedural shapes, all in object space. Closed shapes are watertight, wound
//! counter-clockwise seen from outside, with outward unit normals; they are centred on the
//! origin. The plane lies in y = 0 facing +y.

use super::mesh::Mesh;
use glam::Vec3;
use std::collections::HashMap;
use std::f32::consts::TAU;

/// Appends a flat quad `c ± u ± v`; `u × v` must point along `normal`.
fn push_quad(mesh: &mut Mesh, c: Vec3, u: Vec3, v: Vec3, normal: Vec3) {
    let base = mesh.positions.len() as u32;
    mesh.positions.extend_from_slice(&[c - u - v, c + u - v, c + u + v, c - u + v]);
    mesh.normals.extend_from_slice(&[normal; 4]);
    mesh.indices.extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
}

/// A `size.x` × `size.y` rectangle in the plane y = 0, centred on the origin, normal +y.
pub fn plane(size_x: f32, size_z: f32) -> Mesh {
    let mut mesh = Mesh::default();
    push_quad(&mut mesh, Vec3::ZERO, Vec3::new(0.0, 0.0, 0.5 * size_z), Vec3::new(0.5 * size_x, 0.0, 0.0), Vec3::Y);
    mesh
}

/// The six faces of a box as (outward normal, u, v) with u × v = normal.
const BOX_FACES: [(Vec3, Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::Y, Vec3::Z),
    (Vec3::NEG_X, Vec3::Z, Vec3::Y),
    (Vec3::Y, Vec3::Z, Vec3::X),
    (Vec3::NEG_Y, Vec3::X, Vec3::Z),
    (Vec3::Z, Vec3::X, Vec3::Y),
    (Vec3::NEG_Z, Vec3::Y, Vec3::X),
];

fn box_faces(size: Vec3, skip_top: bool) -> Mesh {
    let h = 0.5 * size;
    let mut mesh = Mesh::default();
    for (n, u, v) in BOX_FACES {
        if skip_top && n == Vec3::Y {
            continue;
        }
        push_quad(&mut mesh, n * h, u * h, v * h, n);
    }
    mesh
}

/// An axis-aligned box centred on the origin with flat faces (4 vertices per face).
pub fn box_mesh(size: Vec3) -> Mesh {
    box_faces(size, false)
}

/// A box seen from inside: normals point inward and triangles are counter-clockwise seen
/// from inside. With `open_top` the ceiling (+y face) is left out.
pub fn room(size: Vec3, open_top: bool) -> Mesh {
    let mut mesh = box_faces(size, open_top);
    mesh.flip();
    mesh
}

/// A regular octahedron with vertices at distance `radius` on the axes; flat faces.
pub fn octahedron(radius: f32) -> Mesh {
    let mut mesh = Mesh::default();
    for sx in [1.0f32, -1.0] {
        for sy in [1.0f32, -1.0] {
            for sz in [1.0f32, -1.0] {
                let (a, b, c) = (Vec3::X * sx * radius, Vec3::Y * sy * radius, Vec3::Z * sz * radius);
                let base = mesh.positions.len() as u32;
                // (X, Y, Z) is counter-clockwise from outside; an odd number of sign flips
                // mirrors the face, so swap two vertices.
                if sx * sy * sz > 0.0 {
                    mesh.positions.extend_from_slice(&[a, b, c]);
                } else {
                    mesh.positions.extend_from_slice(&[a, c, b]);
                }
                mesh.normals.extend_from_slice(&[Vec3::new(sx, sy, sz).normalize(); 3]);
                mesh.indices.extend_from_slice(&[base, base + 1, base + 2]);
            }
        }
    }
    mesh
}

/// An icosahedron subdivided `subdivisions` times (20·4^s triangles), every vertex exactly
/// on the sphere, shared vertices, normals = position direction.
pub fn icosphere(radius: f32, subdivisions: u32) -> Mesh {
    let t = (1.0 + 5.0f32.sqrt()) / 2.0;
    let mut dirs: Vec<Vec3> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|&p| Vec3::from_array(p).normalize())
    .collect();
    let mut tris: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
        let mut mid = |a: u32, b: u32, dirs: &mut Vec<Vec3>| -> u32 {
            let key = (a.min(b), a.max(b));
            *midpoints.entry(key).or_insert_with(|| {
                dirs.push((dirs[a as usize] + dirs[b as usize]).normalize());
                dirs.len() as u32 - 1
            })
        };
        let mut next = Vec::with_capacity(tris.len() * 4);
        for [a, b, c] in tris {
            let ab = mid(a, b, &mut dirs);
            let bc = mid(b, c, &mut dirs);
            let ca = mid(c, a, &mut dirs);
            next.extend_from_slice(&[[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        tris = next;
    }
    Mesh {
        positions: dirs.iter().map(|&d| d * radius).collect(),
        normals: dirs,
        indices: tris.into_iter().flatten().collect(),
    }
}

/// A torus around the y axis: tube centre circle of radius `major` in the xz plane, tube
/// radius `minor`; `segments_u` around the y axis, `segments_v` around the tube. Shared
/// vertices with analytic (smooth) normals.
pub fn torus(major: f32, minor: f32, segments_u: u32, segments_v: u32) -> Mesh {
    let (nu, nv) = (segments_u, segments_v);
    let mut mesh = Mesh::default();
    for i in 0..nu {
        let u = TAU * i as f32 / nu as f32;
        let d = Vec3::new(u.cos(), 0.0, u.sin());
        for j in 0..nv {
            let v = TAU * j as f32 / nv as f32;
            let n = d * v.cos() + Vec3::Y * v.sin();
            mesh.positions.push(d * major + n * minor);
            mesh.normals.push(n);
        }
    }
    let idx = |i: u32, j: u32| (i % nu) * nv + (j % nv);
    for i in 0..nu {
        for j in 0..nv {
            let (a00, a01, a11, a10) = (idx(i, j), idx(i, j + 1), idx(i + 1, j + 1), idx(i + 1, j));
            mesh.indices.extend_from_slice(&[a00, a01, a11, a00, a11, a10]);
        }
    }
    mesh
}

/// A thick open cylinder (a napkin/wedding ring) around the y axis, centred on the origin:
/// inner radius `radius`, outer radius `radius + thickness`, spanning y in ±height/2.
/// Four walls (outer, inner, top, bottom), each with its own vertices so the rims are sharp;
/// normals are smooth around the circumference.
pub fn ring(radius: f32, height: f32, thickness: f32, segments: u32) -> Mesh {
    let n = segments;
    let (ri, ro) = (radius, radius + thickness);
    let (y0, y1) = (-0.5 * height, 0.5 * height);
    let dir = |i: u32| {
        let u = TAU * (i % n) as f32 / n as f32;
        Vec3::new(u.cos(), 0.0, u.sin())
    };
    let mut mesh = Mesh::default();
    // Each wall: two rings of n vertices, `lo[i]` and `hi[i]`; `flip` picks the winding.
    let mut wall = |lo: &dyn Fn(u32) -> Vec3, hi: &dyn Fn(u32) -> Vec3, normal: &dyn Fn(u32) -> Vec3, flip: bool| {
        let base = mesh.positions.len() as u32;
        for i in 0..n {
            mesh.positions.push(lo(i));
            mesh.normals.push(normal(i));
        }
        for i in 0..n {
            mesh.positions.push(hi(i));
            mesh.normals.push(normal(i));
        }
        for i in 0..n {
            let j = (i + 1) % n;
            let (l0, l1, h0, h1) = (base + i, base + j, base + n + i, base + n + j);
            if flip {
                mesh.indices.extend_from_slice(&[l0, l1, h0, l1, h1, h0]);
            } else {
                mesh.indices.extend_from_slice(&[l0, h0, l1, l1, h0, h1]);
            }
        }
    };
    let y = |h: f32| Vec3::Y * h;
    // Outer wall (normal +d), inner wall (normal -d).
    wall(&|i| dir(i) * ro + y(y0), &|i| dir(i) * ro + y(y1), &dir, false);
    wall(&|i| dir(i) * ri + y(y0), &|i| dir(i) * ri + y(y1), &|i| -dir(i), true);
    // Top (normal +y) and bottom (normal -y) annuli: "lo" = outer rim, "hi" = inner rim.
    wall(&|i| dir(i) * ro + y(y1), &|i| dir(i) * ri + y(y1), &|_| Vec3::Y, false);
    wall(&|i| dir(i) * ro + y(y0), &|i| dir(i) * ri + y(y0), &|_| Vec3::NEG_Y, true);
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::mesh::tests::{assert_closed, assert_unit_normals};
    use std::f64::consts::PI;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    #[test]
    fn icosphere_is_exact_closed_and_outward() {
        for s in 0..=5 {
            let r = 0.7f32;
            let m = icosphere(r, s);
            assert_eq!(m.triangle_count(), 20 * 4usize.pow(s));
            // Euler: V - E + F = 2 with E = 3F/2.
            assert_eq!(m.positions.len(), 2 + m.triangle_count() / 2);
            for (p, n) in m.positions.iter().zip(&m.normals) {
                assert!((p.length() - r).abs() < 1e-5, "vertex {p} off the sphere");
                assert!((*n - p.normalize()).length() < 1e-5);
            }
            assert_unit_normals(&m);
            assert_closed(&m);
            assert!(m.signed_volume() > 0.0);
        }
        let r = 0.5;
        let v = icosphere(r as f32, 5).signed_volume();
        assert!(rel(v, 4.0 / 3.0 * PI * r * r * r) < 0.01, "volume {v}");
    }

    #[test]
    fn box_is_closed_outward_with_exact_volume() {
        let m = box_mesh(Vec3::new(1.0, 2.0, 3.0));
        assert_eq!(m.triangle_count(), 12);
        assert_closed(&m);
        assert_unit_normals(&m);
        assert!(rel(m.signed_volume(), 6.0) < 1e-6);
        let (lo, hi) = m.bounds();
        assert_eq!((lo, hi), (Vec3::new(-0.5, -1.0, -1.5), Vec3::new(0.5, 1.0, 1.5)));
        // Flat faces: each triangle's geometric normal equals its vertex normals and points
        // away from the centre.
        for [a, b, c] in m.triangles() {
            let g = (m.positions[b] - m.positions[a]).cross(m.positions[c] - m.positions[a]).normalize();
            for v in [a, b, c] {
                assert!((m.normals[v] - g).length() < 1e-6);
            }
            assert!(g.dot(m.positions[a]) > 0.0);
        }
    }

    #[test]
    fn room_faces_inward() {
        let m = room(Vec3::new(6.0, 4.0, 6.0), false);
        assert_closed(&m);
        assert!(rel(m.signed_volume(), -144.0) < 1e-6, "{}", m.signed_volume());
        for (p, n) in m.positions.iter().zip(&m.normals) {
            assert!(p.dot(*n) < 0.0, "normal {n} at {p} points outward");
        }
        let open = room(Vec3::new(6.0, 4.0, 6.0), true);
        assert_eq!(open.triangle_count(), 10);
        assert!(open.positions.iter().zip(&open.normals).all(|(p, n)| !(p.y > 1.9 && n.y < -0.5)));
    }

    #[test]
    fn octahedron_is_closed_outward_with_exact_volume() {
        let r = 0.6f64;
        let m = octahedron(r as f32);
        assert_eq!(m.triangle_count(), 8);
        assert_closed(&m);
        assert_unit_normals(&m);
        assert!(rel(m.signed_volume(), 4.0 / 3.0 * r * r * r) < 1e-5);
        for [a, b, c] in m.triangles() {
            let g = (m.positions[b] - m.positions[a]).cross(m.positions[c] - m.positions[a]);
            assert!((m.normals[a] - g.normalize()).length() < 1e-5);
        }
    }

    #[test]
    fn torus_is_closed_outward_with_near_analytic_volume() {
        let (big_r, r) = (1.0f64, 0.25f64);
        let m = torus(big_r as f32, r as f32, 96, 48);
        assert_eq!(m.triangle_count(), 2 * 96 * 48);
        assert_closed(&m);
        assert_unit_normals(&m);
        let exact = 2.0 * PI * PI * big_r * r * r;
        assert!(rel(m.signed_volume(), exact) < 0.01, "{} vs {exact}", m.signed_volume());
        // Normals point away from the tube centre circle.
        for (p, n) in m.positions.iter().zip(&m.normals) {
            let c = Vec3::new(p.x, 0.0, p.z).normalize() * big_r as f32;
            assert!((*p - c).normalize().dot(*n) > 0.999);
        }
    }

    #[test]
    fn ring_is_closed_outward_with_near_analytic_volume() {
        let (ri, h, t) = (0.8f64, 0.3f64, 0.05f64);
        let m = ring(ri as f32, h as f32, t as f32, 256);
        assert_closed(&m);
        assert_unit_normals(&m);
        let ro = ri + t;
        let exact = PI * (ro * ro - ri * ri) * h;
        assert!(rel(m.signed_volume(), exact) < 0.005, "{} vs {exact}", m.signed_volume());
        let (lo, hi) = m.bounds();
        assert!((hi.y - 0.15).abs() < 1e-6 && (lo.y + 0.15).abs() < 1e-6);
        // The inner wall's normals point toward the axis.
        let inner = m
            .positions
            .iter()
            .zip(&m.normals)
            .filter(|(p, n)| (Vec3::new(p.x, 0.0, p.z).length() - ri as f32).abs() < 1e-5 && n.y == 0.0);
        let mut count = 0;
        for (p, n) in inner {
            assert!(p.dot(*n) < 0.0);
            count += 1;
        }
        assert_eq!(count, 2 * 256);
    }

    #[test]
    fn plane_faces_up() {
        let m = plane(2.0, 4.0);
        assert_eq!(m.triangle_count(), 2);
        for [a, b, c] in m.triangles() {
            let g = (m.positions[b] - m.positions[a]).cross(m.positions[c] - m.positions[a]);
            assert!(g.normalize().dot(Vec3::Y) > 0.9999);
        }
        assert_eq!(m.bounds(), (Vec3::new(-1.0, 0.0, -2.0), Vec3::new(1.0, 0.0, 2.0)));
        assert!((m.area() - 8.0).abs() < 1e-6);
    }
}
