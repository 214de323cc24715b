use super::*;

/// PCG32 (O'Neill), enough for reproducible test geometry.
struct Pcg(u64);

impl Pcg {
    fn new(seed: u64) -> Pcg {
        let mut p = Pcg(seed.wrapping_add(0x853c_49e6_748f_ea9b));
        p.next_u32();
        p
    }
    fn next_u32(&mut self) -> u32 {
        let old = self.0;
        self.0 = old.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }
    /// Uniform in [0, 1).
    fn f(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 / (1u32 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.f()
    }
    fn vec(&mut self, lo: f32, hi: f32) -> Vec3 {
        Vec3::new(self.range(lo, hi), self.range(lo, hi), self.range(lo, hi))
    }
    fn dir(&mut self) -> Vec3 {
        loop {
            let v = self.vec(-1.0, 1.0);
            let l = v.length_squared();
            if l > 1e-4 && l <= 1.0 {
                return v / l.sqrt();
            }
        }
    }
}

fn soup(rng: &mut Pcg, n: usize, extent: f32, size: f32) -> Vec<Triangle> {
    (0..n)
        .map(|k| {
            let c = rng.vec(-extent, extent);
            Triangle {
                v: [c + rng.vec(-size, size), c + rng.vec(-size, size), c + rng.vec(-size, size)],
                object: (k % 3) as u32,
                prim: k as u32,
            }
        })
        .collect()
}

/// Brute force over the BVH's own triangle list (so indices are comparable).
fn brute(bvh: &Bvh, o: Vec3, d: Vec3, t_min: f32, t_max: f32) -> Option<(f32, u32)> {
    let mut best: Option<(f32, u32)> = None;
    for i in 0..bvh.len() as u32 {
        if let Some((t, _, _)) = intersect_triangle(o, d, bvh.triangle(i), t_min, t_max) {
            if !matches!(best, Some((bt, _)) if bt <= t) {
                best = Some((t, i));
            }
        }
    }
    best
}

fn check_ray(bvh: &Bvh, o: Vec3, d: Vec3, t_min: f32, t_max: f32) -> bool {
    let got = bvh.intersect(o, d, t_min, t_max);
    let want = brute(bvh, o, d, t_min, t_max);
    match (got, want) {
        (None, None) => {}
        (Some(h), Some((t, id))) => {
            assert!((h.t - t).abs() <= 1e-5 * t.abs().max(1e-6), "t mismatch: bvh {} brute {} ray {o} {d}", h.t, t);
            if h.triangle != id {
                // Only exact (or rounding-level) ties may pick another triangle.
                let (t2, _, _) = intersect_triangle(o, d, bvh.triangle(h.triangle), t_min, t_max).unwrap();
                assert!((t2 - t).abs() <= 1e-6 * t.abs(), "different triangle without a tie");
            }
            let tri = bvh.triangle(h.triangle);
            assert_eq!((h.object, h.prim), (tri.object, tri.prim));
            assert!(h.u >= 0.0 && h.v >= 0.0 && h.u + h.v <= 1.0);
            // The reported point lies on the ray.
            let p = (1.0 - h.u - h.v) * tri.v[0] + h.u * tri.v[1] + h.v * tri.v[2];
            assert!((p - (o + d * h.t)).length() <= 1e-3 * (1.0 + p.length()));
        }
        (g, w) => panic!("bvh {g:?} vs brute {w:?} for ray {o} {d} [{t_min}, {t_max}]"),
    }
    assert_eq!(bvh.occluded(o, d, t_min, t_max), want.is_some(), "occluded disagrees for ray {o} {d}");
    want.is_some()
}

#[test]
fn random_soups_match_brute_force() {
    let mut rng = Pcg::new(7);
    for (n, extent, size) in
        [(2usize, 1.0f32, 0.5f32), (5, 1.0, 0.3), (37, 2.0, 0.4), (500, 2.0, 0.5), (3000, 4.0, 0.4)]
    {
        let tris = soup(&mut rng, n, extent, size);
        let bvh = Bvh::build(tris.clone());
        assert_eq!(bvh.len(), n);
        // Every input triangle is present exactly once.
        let mut prims: Vec<u32> = bvh.triangles().iter().map(|t| t.prim).collect();
        prims.sort_unstable();
        assert_eq!(prims, (0..n as u32).collect::<Vec<_>>());
        let mut hits = 0;
        let rays = 2000;
        for k in 0..rays {
            // Half from outside aiming at the soup, half from inside the bounding box.
            let (o, d) = if k % 2 == 0 {
                let o = rng.dir() * extent * 4.0;
                let target = rng.vec(-extent, extent);
                (o, (target - o).normalize())
            } else {
                (rng.vec(-extent, extent), rng.dir())
            };
            // Unnormalised directions too.
            let d = if k % 5 == 0 { d * 3.7 } else { d };
            if check_ray(&bvh, o, d, 0.0, f32::INFINITY) {
                hits += 1;
            }
            // Finite interval.
            check_ray(&bvh, o, d, 0.1, extent);
        }
        if n >= 500 {
            assert!(hits > rays / 5, "test rays should mostly hit ({hits}/{rays})");
        }
    }
}

#[test]
fn rays_that_miss() {
    let mut rng = Pcg::new(11);
    let bvh = Bvh::build(soup(&mut rng, 200, 1.0, 0.2));
    // Pointing away from the soup.
    for _ in 0..200 {
        let o = rng.dir() * 5.0;
        let d = (o + rng.vec(-0.5, 0.5)).normalize();
        assert!(bvh.intersect(o, d, 0.0, f32::INFINITY).is_none());
        assert!(!bvh.occluded(o, d, 0.0, f32::INFINITY));
        // Toward it, but the interval ends before.
        assert!(bvh.intersect(o, -d, 0.0, 1.0).is_none());
    }
    // Empty / NaN interval and NaN / zero rays.
    assert!(bvh.intersect(Vec3::ZERO, Vec3::X, 1.0, 0.5).is_none());
    assert!(bvh.intersect(Vec3::ZERO, Vec3::X, f32::NAN, 1.0).is_none());
    assert!(bvh.intersect(Vec3::ZERO, Vec3::ZERO, 0.0, f32::INFINITY).is_none());
    assert!(bvh.intersect(Vec3::NAN, Vec3::X, 0.0, f32::INFINITY).is_none());
    assert!(bvh.intersect(Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 1.0), 0.0, f32::INFINITY).is_none());
    assert!(!bvh.occluded(Vec3::ZERO, Vec3::ZERO, 0.0, f32::INFINITY));
}

#[test]
fn axis_aligned_directions_with_zeros() {
    // A grid of axis-aligned quads; rays along ±axes (with +0 and -0 in the other
    // components), some starting exactly on node bounding planes.
    let mut tris = Vec::new();
    for k in 0..8 {
        let z = k as f32 * 0.25;
        for (i, j) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let (x, y) = (i as f32, j as f32);
            let a = Vec3::new(x, y, z);
            let b = Vec3::new(x + 1.0, y, z);
            let c = Vec3::new(x + 1.0, y + 1.0, z);
            let d = Vec3::new(x, y + 1.0, z);
            let p = tris.len() as u32;
            tris.push(Triangle { v: [a, b, c], object: k, prim: p });
            tris.push(Triangle { v: [a, c, d], object: k, prim: p + 1 });
        }
    }
    let bvh = Bvh::build(tris);
    for dz in [1.0f32, -1.0] {
        for zero in [0.0f32, -0.0] {
            let d = Vec3::new(zero, zero, dz);
            // Origins: inside cells, on the outer box planes x=0 / y=2, and interior.
            for o in [
                Vec3::new(0.3, 0.6, -1.0),
                Vec3::new(1.7, 1.2, 3.0),
                Vec3::new(0.0, 0.5, -1.0),
                Vec3::new(2.0, 1.3, 3.0),
                Vec3::new(0.5, 2.0, 0.6),
                Vec3::new(1.25, 0.75, 0.9),
            ] {
                let hit = check_ray(&bvh, o, d, 0.0, f32::INFINITY);
                let expect_hit = (dz > 0.0 && o.z < 1.75) || (dz < 0.0 && o.z > 0.0);
                assert_eq!(hit, expect_hit, "ray {o} {d}");
                if dz > 0.0 && o.z < 0.0 {
                    let h = bvh.intersect(o, d, 0.0, f32::INFINITY).unwrap();
                    assert!((h.t - (0.0 - o.z)).abs() < 1e-6);
                    assert_eq!(h.object, 0);
                }
            }
            // Outside the x/y extent: misses, even though the z slab is crossed.
            assert!(!check_ray(&bvh, Vec3::new(2.01, 0.5, -1.0), d, 0.0, f32::INFINITY));
            assert!(!check_ray(&bvh, Vec3::new(0.5, -0.01, -1.0), d, 0.0, f32::INFINITY));
        }
    }
    // Rays along x and y lie parallel to every quad: no hits.
    for d in [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::new(1.0, -0.0, 0.0)] {
        assert!(!check_ray(&bvh, Vec3::new(-1.0, 0.5, 0.5), d, 0.0, f32::INFINITY));
    }
    // Axis-aligned rays with zeros on a random soup.
    let mut rng = Pcg::new(3);
    let bvh = Bvh::build(soup(&mut rng, 400, 1.0, 0.3));
    for _ in 0..500 {
        let o = rng.vec(-1.5, 1.5);
        for d in [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z, Vec3::new(-0.0, 1.0, -0.0)] {
            check_ray(&bvh, o, d, 0.0, f32::INFINITY);
        }
    }
}

#[test]
fn zero_and_one_triangle() {
    let empty = Bvh::build(Vec::new());
    assert!(empty.is_empty());
    assert_eq!(empty.len(), 0);
    assert!(empty.bounds().is_none());
    assert!(empty.intersect(Vec3::ZERO, Vec3::X, 0.0, f32::INFINITY).is_none());
    assert!(!empty.occluded(Vec3::ZERO, Vec3::X, 0.0, f32::INFINITY));

    let tri = Triangle {
        v: [Vec3::new(-1.0, -1.0, 2.0), Vec3::new(1.0, -1.0, 2.0), Vec3::new(0.0, 1.0, 2.0)],
        object: 4,
        prim: 9,
    };
    let one = Bvh::build(vec![tri]);
    assert_eq!(one.len(), 1);
    assert!(!one.is_empty());
    assert_eq!(*one.triangle(0), tri);
    let h = one.intersect(Vec3::ZERO, Vec3::Z, 0.0, f32::INFINITY).unwrap();
    assert_eq!((h.t, h.triangle, h.object, h.prim), (2.0, 0, 4, 9));
    // Back face is hit too (no culling).
    let h = one.intersect(Vec3::new(0.0, 0.0, 4.0), Vec3::NEG_Z, 0.0, f32::INFINITY).unwrap();
    assert_eq!(h.t, 2.0);
    assert!(one.occluded(Vec3::ZERO, Vec3::Z, 0.0, 3.0));
    assert!(!one.occluded(Vec3::ZERO, Vec3::Z, 0.0, 1.5));
    assert!(!one.occluded(Vec3::ZERO, Vec3::NEG_Z, 0.0, f32::INFINITY));
}

#[test]
fn degenerate_triangles() {
    let mut rng = Pcg::new(5);
    let p = Vec3::new(0.1, 0.2, 0.3);
    let mut tris = Vec::new();
    // Many exact duplicates (identical centroids: SAH cannot split them).
    let dup = Triangle { v: [Vec3::ZERO, Vec3::X, Vec3::Y], object: 0, prim: 0 };
    for k in 0..1000 {
        tris.push(Triangle { prim: k, ..dup });
    }
    // Zero-area: points and collinear.
    for k in 0..300 {
        tris.push(Triangle { v: [p, p, p], object: 1, prim: 1000 + k });
        let a = rng.vec(-1.0, 1.0);
        let b = rng.vec(-1.0, 1.0);
        tris.push(Triangle { v: [a, b, (a + b) * 0.5], object: 2, prim: 2000 + k });
    }
    // A few normal ones.
    tris.extend(soup(&mut rng, 50, 1.0, 0.3).into_iter().map(|t| Triangle { object: 3, ..t }));
    let bvh = Bvh::build(tris.clone());
    assert_eq!(bvh.len(), tris.len());
    assert!(bvh.depth() < 100);
    for _ in 0..500 {
        let o = rng.vec(-2.0, 2.0);
        check_ray(&bvh, o, rng.dir(), 0.0, f32::INFINITY);
    }
    let h = bvh.intersect(Vec3::new(0.25, 0.25, 1.0), Vec3::NEG_Z, 0.0, f32::INFINITY).unwrap();
    assert_eq!(h.object, 0);
    assert!((h.t - 1.0).abs() < 1e-6);

    // Only degenerate / non-finite triangles.
    let only_bad = vec![
        Triangle { v: [p, p, p], object: 0, prim: 0 },
        Triangle { v: [Vec3::NAN, p, p], object: 0, prim: 1 },
        Triangle { v: [Vec3::INFINITY, Vec3::NEG_INFINITY, p], object: 0, prim: 2 },
        Triangle { v: [Vec3::ZERO, Vec3::X, Vec3::X * 2.0], object: 0, prim: 3 },
    ];
    let many_bad: Vec<Triangle> = (0..200).map(|k| only_bad[k % 4]).collect();
    for tris in [only_bad, many_bad] {
        let bvh = Bvh::build(tris);
        for _ in 0..100 {
            let o = rng.vec(-2.0, 2.0);
            let d = rng.dir();
            // Nothing of zero area or with a non-finite vertex can be hit.
            assert!(bvh.intersect(o, d, 0.0, f32::INFINITY).is_none(), "a ray from {o} along {d} hit a bad triangle");
            assert!(!bvh.occluded(o, d, 0.0, f32::INFINITY), "a ray from {o} along {d} occluded by a bad triangle");
        }
    }
}

#[test]
fn large_soup_depth_bounded() {
    let mut rng = Pcg::new(99);
    // Highly clustered: most triangles in a tiny region, a few far away.
    let mut tris = soup(&mut rng, 20_000, 0.001, 0.0005);
    tris.extend(soup(&mut rng, 20, 1000.0, 1.0));
    let bvh = Bvh::build(tris);
    assert!(bvh.depth() <= FORCE_MEDIAN_DEPTH + 32);
    for _ in 0..200 {
        check_ray(&bvh, rng.vec(-0.002, 0.002), rng.dir(), 0.0, f32::INFINITY);
    }
}

/// UV sphere centred at the origin, outward normals, shared vertices per ring.
fn uv_sphere(radius: f32, stacks: u32, slices: u32) -> (Vec<Vec3>, Vec<Vec3>, Vec<u32>) {
    let mut pos = Vec::new();
    let mut nrm = Vec::new();
    for i in 0..=stacks {
        let theta = std::f32::consts::PI * i as f32 / stacks as f32;
        for j in 0..=slices {
            let phi = 2.0 * std::f32::consts::PI * j as f32 / slices as f32;
            let n = Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
            pos.push(n * radius);
            nrm.push(n);
        }
    }
    let row = slices + 1;
    let mut idx = Vec::new();
    for i in 0..stacks {
        for j in 0..slices {
            let a = i * row + j;
            let b = a + row;
            if i != 0 {
                idx.extend([a, b, a + 1]);
            }
            if i != stacks - 1 {
                idx.extend([a + 1, b, b + 1]);
            }
        }
    }
    (pos, nrm, idx)
}

#[test]
fn thickness_of_sphere_is_diameter() {
    let (pos, nrm, idx) = uv_sphere(0.5, 48, 96);
    let d = vertex_thickness(&pos, &nrm, &idx);
    assert_eq!(d.len(), pos.len());
    for (i, &t) in d.iter().enumerate() {
        assert!((t - 1.0).abs() <= 0.01, "vertex {i} at {}: thickness {t}", pos[i]);
    }
}

#[test]
fn thickness_of_unit_cube_is_one() {
    // Flat-shaded unit cube: 4 vertices per face with the face normal.
    let mut pos = Vec::new();
    let mut nrm = Vec::new();
    let mut idx = Vec::new();
    for axis in 0..3 {
        for sign in [1.0f32, -1.0] {
            let mut n = Vec3::ZERO;
            n[axis] = sign;
            let u = Vec3::from_array(std::array::from_fn(|k| if k == (axis + 1) % 3 { 1.0 } else { 0.0 }));
            let v = n.cross(u);
            let base = pos.len() as u32;
            for (a, b) in [(-0.5f32, -0.5f32), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
                pos.push(n * 0.5 + u * a + v * b);
                nrm.push(n);
            }
            idx.extend([base, base + 1, base + 2, base, base + 2, base + 3]);
        }
    }
    let d = vertex_thickness(&pos, &nrm, &idx);
    for (i, &t) in d.iter().enumerate() {
        assert!((t - 1.0).abs() <= 1e-4, "vertex {i} at {}: thickness {t}", pos[i]);
    }
}

#[test]
fn thickness_edge_cases() {
    assert!(vertex_thickness(&[], &[], &[]).is_empty());
    // Open mesh (a single triangle): rays escape, thickness 0; zero normal -> 0;
    // missing normals and out-of-range indices don't panic.
    let pos = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
    let nrm = [Vec3::Z, Vec3::Z, Vec3::ZERO];
    let d = vertex_thickness(&pos, &nrm, &[0, 1, 2, 0, 1, 7, 3]);
    assert_eq!(d, vec![0.0; 4]);
    // Many vertices (exercises the threaded path) on a sphere: same result.
    let (pos, nrm, idx) = uv_sphere(2.0, 64, 128);
    let d = vertex_thickness(&pos, &nrm, &idx);
    assert!(d.iter().all(|&t| (t - 4.0).abs() <= 0.04));
}
