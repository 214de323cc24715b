//! `shape = "water"`: the body of water of the caustics-mapping tutorial's underwater caustics
//! (Shah et al., Fig. 1a) as a closed refractive mesh, so that every technique (each assumes a
//! closed refractor: a front face where light enters, a back face where it leaves) and the CPU
//! reference (which traces meshes) can render it.
//!
//! Its top is the water surface of a Trendall & Stewart pool (the `[pool]` of the scene named by
//! `file`: its side, depth, waves and time, Sec. 4.3), sampled on a `segments`² grid; its
//! four sides are vertical walls from the surface down to y = 0; its bottom is the square at y
//! = 0 (a fan of triangles). So the pool of `pool-convolution` and this mesh share one surface. The water spans
//! [-side/2, side/2]² in x and z and rises `depth` above its bottom (plus the waves), in object
//! space; a scene puts its bottom a hair above the pool floor (the floor then is the first
//! surface a photon meets after leaving the water, and no face of the water lies in the
//! floor's plane).

use super::mesh::Mesh;
use super::pool::PoolSpec;
use super::water_surface::{height_at, sources};
use glam::{DVec3, Vec3};

/// Most grid cells a side (2048² cells: 8M triangles on top).
pub const MAX_WATER_SEGMENTS: u32 = 2048;

/// The closed water volume of `pool` with its surface on a `segments`² grid: smooth normals on
/// top (the height field's gradient), flat ones on the walls and bottom; wound
/// counter-clockwise seen from outside.
pub fn water(pool: &PoolSpec, segments: u32) -> Mesh {
    let n = segments as usize;
    let src = sources(pool);
    let half = pool.half();
    let cell = pool.side / n as f64;
    let coord = |i: usize| -half + i as f64 * cell;
    let height = |x: f64, z: f64| pool.depth + height_at(&pool.wave, &src, x, z);
    let mut mesh = Mesh::default();

    // The surface: (n + 1)² vertices, row j at z_j, column i at x_i.
    // The normal is the height field's gradient at the vertex (a step far under a cell).
    let e = 1e-6 * pool.side;
    for j in 0..=n {
        for i in 0..=n {
            let (x, z) = (coord(i), coord(j));
            let dx = (height(x + e, z) - height(x - e, z)) / (2.0 * e);
            let dz = (height(x, z + e) - height(x, z - e)) / (2.0 * e);
            mesh.positions.push(Vec3::new(x as f32, height(x, z) as f32, z as f32));
            mesh.normals.push(DVec3::new(-dx, 1.0, -dz).normalize().as_vec3());
        }
    }
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    for j in 0..n {
        for i in 0..n {
            // Counter-clockwise seen from above (+y): x then z is clockwise there, so go z first.
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            mesh.indices.extend_from_slice(&[a, d, c, a, c, b]);
        }
    }

    // The walls: one quad per boundary cell, from the surface's edge down to y = 0, with the
    // surface's edge positions repeated exactly; the bottom: a fan from its centre to every
    // wall's bottom edge (no edge meets another's middle: the mesh stays watertight).
    let top = |i: usize, j: usize| mesh.positions[at(i, j) as usize];
    let mut walls = Mesh::default();
    let mut wall = |p0: Vec3, p1: Vec3, normal: Vec3| {
        let base = walls.positions.len() as u32;
        let (b0, b1) = (Vec3::new(p0.x, 0.0, p0.z), Vec3::new(p1.x, 0.0, p1.z));
        walls.positions.extend_from_slice(&[b0, b1, p1, p0]);
        walls.normals.extend_from_slice(&[normal; 4]);
        // (b1 - b0) x (p1 - b0) points along `normal` for the orders below.
        walls.indices.extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
        // The bottom's triangle on this wall's foot, facing -y: the centre, b1, b0.
        walls.positions.extend_from_slice(&[Vec3::ZERO, b1, b0]);
        walls.normals.extend_from_slice(&[Vec3::NEG_Y; 3]);
        walls.indices.extend_from_slice(&[base + 4, base + 5, base + 6]);
    };
    for k in 0..n {
        wall(top(k + 1, 0), top(k, 0), Vec3::NEG_Z); // z = -half: x decreasing, seen from -z
        wall(top(k, n), top(k + 1, n), Vec3::Z);
        wall(top(0, k), top(0, k + 1), Vec3::NEG_X);
        wall(top(n, k + 1), top(n, k), Vec3::X);
    }
    let base = mesh.positions.len() as u32;
    mesh.positions.extend(walls.positions);
    mesh.normals.extend(walls.normals);
    mesh.indices.extend(walls.indices.iter().map(|i| i + base));
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;
    use std::collections::HashMap;

    fn pool() -> PoolSpec {
        let p = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/pool.toml");
        Scene::load(&p).expect("shipped scene").pool.expect("a pool")
    }

    /// Every edge of a closed mesh is shared by exactly two triangles, once in each direction.
    #[test]
    fn the_water_is_closed_and_wound_outward() {
        let pool = pool();
        let m = water(&pool, 32);
        let key = |v: Vec3| (v.x.to_bits(), v.y.to_bits(), v.z.to_bits());
        let mut edges: HashMap<_, i32> = HashMap::new();
        for [a, b, c] in m.triangles() {
            for (u, v) in [(a, b), (b, c), (c, a)] {
                *edges.entry((key(m.positions[u]), key(m.positions[v]))).or_default() += 1;
            }
        }
        for ((u, v), count) in &edges {
            assert_eq!(*count, 1, "edge {u:?} -> {v:?} used {count} times");
            assert_eq!(edges.get(&(*v, *u)), Some(&1), "edge {u:?} -> {v:?} has no opposite");
        }
        // Its volume: the side squared times the mean water height (the waves' mean over the
        // grid, by the trapezoid rule the mesh's top is).
        let src = sources(&pool);
        let n = 32;
        let mut mean = 0.0;
        for j in 0..=n {
            for i in 0..=n {
                let w = |k: usize| if k == 0 || k == n { 0.5 } else { 1.0 };
                let (x, z) =
                    (-pool.half() + i as f64 * pool.side / n as f64, -pool.half() + j as f64 * pool.side / n as f64);
                mean += w(i) * w(j) * (pool.depth + height_at(&pool.wave, &src, x, z));
            }
        }
        mean /= (n * n) as f64;
        let want = pool.side * pool.side * mean;
        assert!((m.signed_volume() - want).abs() < 1e-5 * want, "{} vs {want}", m.signed_volume());
    }

    /// The top follows the pool's height field, and its normals are the field's.
    #[test]
    fn the_top_is_the_pools_surface() {
        let pool = pool();
        let src = sources(&pool);
        let m = water(&pool, 64);
        let mut waves = 0.0f64;
        for (p, nrm) in m.positions.iter().zip(&m.normals).take(65 * 65) {
            let (x, z) = (p.x as f64, p.z as f64);
            let h = pool.depth + height_at(&pool.wave, &src, x, z);
            assert!((p.y as f64 - h).abs() < 1e-6, "height at ({x}, {z}): {} vs {h}", p.y);
            let e = 1e-5;
            let dx = (height_at(&pool.wave, &src, x + e, z) - height_at(&pool.wave, &src, x - e, z)) / (2.0 * e);
            let dz = (height_at(&pool.wave, &src, x, z + e) - height_at(&pool.wave, &src, x, z - e)) / (2.0 * e);
            let want = DVec3::new(-dx, 1.0, -dz).normalize();
            assert!(nrm.as_dvec3().dot(want) > 1.0 - 1e-4, "normal at ({x}, {z}): {nrm} vs {want}");
            waves = waves.max((h - pool.depth).abs());
        }
        // The pool at its time has waves (a flat top would pass the checks above trivially).
        assert!(waves > 1e-3, "largest wave {waves}");
    }
}
