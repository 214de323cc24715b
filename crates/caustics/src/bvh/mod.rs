//! CPU bounding volume hierarchy over triangles.
//!
//! Used by the exact CPU photon tracer and to precompute the per-vertex thickness
//! `d_N` of Wyman 2005 ("An Approximate Image-Space Approach for Interactive
//! Refraction"): the distance from each vertex, along the inward normal, to the far
//! side of the mesh.
//!
//! Build: binned SAH (16 bins per axis over the centroid bounds), leaves of at most
//! [`MAX_LEAF`] triangles. When SAH cannot separate the triangles (all centroids in
//! one bin: duplicates, degenerate or non-finite geometry) or the tree gets deep,
//! the range is split in half by count, so every split makes progress and the depth
//! stays bounded. Traversal: ordered (near child first), fixed-size stack,
//! slab test that handles zero (and negative zero) direction components exactly.
//! Triangle test: Möller–Trumbore in `f32`, both faces.

// NaN-rejecting comparisons are written as negated `<=`/`>=` on purpose.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use glam::Vec3;

/// Maximum number of triangles in a leaf.
pub const MAX_LEAF: usize = 4;
const BINS: usize = 16;
/// Past this depth, splits are forced to halve the range (bounds total depth to
/// about `FORCE_MEDIAN_DEPTH + log2(n)`, well under the traversal stack size).
const FORCE_MEDIAN_DEPTH: u32 = 64;
const STACK_SIZE: usize = 128;

/// One input triangle, tagged with the caller's object and primitive ids.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    pub v: [Vec3; 3],
    pub object: u32,
    pub prim: u32,
}

/// A ray–triangle hit. `u`, `v` are the barycentric weights of `v[1]` and `v[2]`
/// (the point is `(1-u-v)*v0 + u*v1 + v*v2`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f32,
    pub u: f32,
    pub v: f32,
    /// Index into the BVH's (reordered) triangle list, see [`Bvh::triangle`].
    pub triangle: u32,
    pub object: u32,
    pub prim: u32,
}

#[derive(Clone, Copy, Debug)]
struct Node {
    min: Vec3,
    max: Vec3,
    /// Leaf: first triangle. Interior: index of the left child (right = left + 1).
    first: u32,
    /// Number of triangles; 0 for interior nodes.
    count: u32,
}

/// A flattened BVH. Triangles are reordered so that every leaf is a contiguous range.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    triangles: Vec<Triangle>,
    /// Per triangle: `v0`, `e1 = v1 - v0`, `e2 = v2 - v0`.
    edges: Vec<[Vec3; 3]>,
    depth: u32,
}

#[derive(Clone, Copy)]
struct Aabb {
    min: Vec3,
    max: Vec3,
}

impl Aabb {
    const EMPTY: Aabb = Aabb { min: Vec3::splat(f32::INFINITY), max: Vec3::splat(f32::NEG_INFINITY) };
    fn grow_point(&mut self, p: Vec3) {
        // f32::min/max ignore NaN operands, so NaN vertices never poison a box.
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }
    fn grow(&mut self, b: &Aabb) {
        self.min = self.min.min(b.min);
        self.max = self.max.max(b.max);
    }
    /// Half surface area; 0 for empty or inverted boxes.
    fn half_area(&self) -> f32 {
        let d = (self.max - self.min).max(Vec3::ZERO);
        let a = d.x * d.y + d.y * d.z + d.z * d.x;
        if a.is_finite() {
            a
        } else {
            f32::MAX
        }
    }
}

struct BuildTask {
    node: usize,
    start: usize,
    end: usize,
    depth: u32,
}

impl Bvh {
    /// Builds the BVH (binned SAH). Never panics on degenerate input; 0 triangles give
    /// an empty BVH that never reports hits.
    pub fn build(triangles: Vec<Triangle>) -> Bvh {
        let n = triangles.len();
        assert!(n <= u32::MAX as usize / 2, "too many triangles for a u32-indexed BVH");
        if n == 0 {
            return Bvh::default();
        }
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|t| {
                let mut b = Aabb::EMPTY;
                t.v.iter().for_each(|&p| b.grow_point(p));
                b
            })
            .collect();
        let centroids: Vec<Vec3> = boxes.iter().map(|b| (b.min + b.max) * 0.5).collect();
        let mut order: Vec<u32> = (0..n as u32).collect();
        let mut nodes = Vec::with_capacity(2 * n.div_ceil(MAX_LEAF.max(2)) + 1);
        nodes.push(Node { min: Vec3::ZERO, max: Vec3::ZERO, first: 0, count: 0 });
        let mut tasks = vec![BuildTask { node: 0, start: 0, end: n, depth: 0 }];
        let mut max_depth = 0;

        while let Some(task) = tasks.pop() {
            max_depth = max_depth.max(task.depth);
            let range = &mut order[task.start..task.end];
            let mut bounds = Aabb::EMPTY;
            let mut cbounds = Aabb::EMPTY;
            for &i in range.iter() {
                bounds.grow(&boxes[i as usize]);
                cbounds.grow_point(centroids[i as usize]);
            }
            nodes[task.node].min = bounds.min;
            nodes[task.node].max = bounds.max;
            let count = range.len();
            let make_leaf = |nodes: &mut Vec<Node>| {
                nodes[task.node].first = task.start as u32;
                nodes[task.node].count = count as u32;
            };
            if count <= 1 {
                make_leaf(&mut nodes);
                continue;
            }

            let split = if task.depth < FORCE_MEDIAN_DEPTH {
                sah_split(range, &boxes, &centroids, &cbounds, bounds.half_area())
            } else {
                SahResult::Unsplittable
            };
            let mid = match split {
                SahResult::Split(mid) => mid,
                SahResult::LeafCheaper if count <= MAX_LEAF => {
                    make_leaf(&mut nodes);
                    continue;
                }
                SahResult::Unsplittable if count <= MAX_LEAF => {
                    make_leaf(&mut nodes);
                    continue;
                }
                // Too many triangles for a leaf but SAH can't (or shouldn't) split:
                // halve by count along the widest centroid axis.
                _ => median_split(range, &centroids, &cbounds),
            };
            debug_assert!(mid > 0 && mid < count);
            let left = nodes.len();
            nodes.push(Node { min: Vec3::ZERO, max: Vec3::ZERO, first: 0, count: 0 });
            nodes.push(Node { min: Vec3::ZERO, max: Vec3::ZERO, first: 0, count: 0 });
            nodes[task.node].first = left as u32;
            nodes[task.node].count = 0;
            let depth = task.depth + 1;
            tasks.push(BuildTask { node: left + 1, start: task.start + mid, end: task.end, depth });
            tasks.push(BuildTask { node: left, start: task.start, end: task.start + mid, depth });
        }

        let triangles: Vec<Triangle> = order.iter().map(|&i| triangles[i as usize]).collect();
        let edges = triangles.iter().map(|t| [t.v[0], t.v[1] - t.v[0], t.v[2] - t.v[0]]).collect();
        Bvh { nodes, triangles, edges, depth: max_depth }
    }

    /// The hierarchy as the GPU photon tracer reads it (`shaders_glsl/photon_trace/bvh.glsl`):
    /// per node `[min xyz, first, max xyz, count]` and per triangle `[v0 xyz, object, e1 xyz, 0,
    /// e2 xyz, 0]`, the integers' bits stored in the `f32` slots (the shader declares them
    /// `uint`), in this BVH's order.
    pub fn flattened(&self) -> (Vec<[f32; 8]>, Vec<[f32; 12]>) {
        let bits = f32::from_bits;
        let nodes = self
            .nodes
            .iter()
            .map(|n| [n.min.x, n.min.y, n.min.z, bits(n.first), n.max.x, n.max.y, n.max.z, bits(n.count)])
            .collect();
        let triangles = self
            .triangles
            .iter()
            .zip(&self.edges)
            .map(|(t, [v0, e1, e2])| [v0.x, v0.y, v0.z, bits(t.object), e1.x, e1.y, e1.z, 0.0, e2.x, e2.y, e2.z, 0.0])
            .collect();
        (nodes, triangles)
    }

    /// Triangle `i` of the BVH's reordered list (the index reported in [`Hit::triangle`]).
    pub fn triangle(&self, i: u32) -> &Triangle {
        &self.triangles[i as usize]
    }

    /// All triangles, in the BVH's order.
    pub fn triangles(&self) -> &[Triangle] {
        &self.triangles
    }

    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Bounds of all triangles (`None` when empty).
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        self.nodes.first().map(|n| (n.min, n.max))
    }

    /// Depth of the tree (root alone = 0).
    pub fn depth(&self) -> u32 {
        self.depth
    }

    /// Closest hit with `t_min < t < t_max` (in units of `dir`'s length), either face.
    pub fn intersect(&self, origin: Vec3, dir: Vec3, t_min: f32, t_max: f32) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut t_max = t_max;
        self.traverse(origin, dir, t_min, &mut t_max, |i, t_max| {
            let [v0, e1, e2] = self.edges[i];
            if let Some((t, u, v)) = moller_trumbore(origin, dir, v0, e1, e2, t_min, *t_max) {
                *t_max = t;
                let tri = &self.triangles[i];
                best = Some(Hit { t, u, v, triangle: i as u32, object: tri.object, prim: tri.prim });
            }
            false
        });
        best
    }

    /// Whether any triangle is hit with `t_min < t < t_max`.
    pub fn occluded(&self, origin: Vec3, dir: Vec3, t_min: f32, t_max: f32) -> bool {
        let mut t_max = t_max;
        let mut hit = false;
        self.traverse(origin, dir, t_min, &mut t_max, |i, t_max| {
            let [v0, e1, e2] = self.edges[i];
            hit = moller_trumbore(origin, dir, v0, e1, e2, t_min, *t_max).is_some();
            hit
        });
        hit
    }

    /// Visits the triangles of every leaf whose box the ray segment overlaps, nearest
    /// child first. `leaf_tri` may shrink `t_max`; returning `true` stops traversal.
    #[inline]
    fn traverse(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_min: f32,
        t_max: &mut f32,
        mut leaf_tri: impl FnMut(usize, &mut f32) -> bool,
    ) {
        if self.nodes.is_empty() || !(t_min <= *t_max) {
            return;
        }
        let ray = SlabRay::new(origin, dir);
        if ray.hit(&self.nodes[0], t_min, *t_max).is_none() {
            return;
        }
        let mut stack = [0u32; STACK_SIZE];
        let mut sp = 0usize;
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            if n.count > 0 {
                let first = n.first as usize;
                for i in first..first + n.count as usize {
                    if leaf_tri(i, t_max) {
                        return;
                    }
                }
            } else {
                let l = n.first as usize;
                let r = l + 1;
                let tl = ray.hit(&self.nodes[l], t_min, *t_max);
                let tr = ray.hit(&self.nodes[r], t_min, *t_max);
                match (tl, tr) {
                    (Some(a), Some(b)) => {
                        let (near, far) = if a <= b { (l, r) } else { (r, l) };
                        // Depth is bounded at build time, so this never overflows;
                        // checked anyway to never go out of bounds.
                        if sp < STACK_SIZE {
                            stack[sp] = far as u32;
                            sp += 1;
                        }
                        node = near;
                        continue;
                    }
                    (Some(_), None) => {
                        node = l;
                        continue;
                    }
                    (None, Some(_)) => {
                        node = r;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // Pop, skipping nodes that the (possibly shrunk) t_max now excludes.
            loop {
                if sp == 0 {
                    return;
                }
                sp -= 1;
                let cand = stack[sp] as usize;
                if ray.hit(&self.nodes[cand], t_min, *t_max).is_some() {
                    node = cand;
                    break;
                }
            }
        }
    }
}

enum SahResult {
    /// Partitioned: `range[..mid]` left, `range[mid..]` right.
    Split(usize),
    /// A split exists but costs more than a leaf.
    LeafCheaper,
    /// All centroids fall in one bin on every axis.
    Unsplittable,
}

fn sah_split(range: &mut [u32], boxes: &[Aabb], centroids: &[Vec3], cbounds: &Aabb, parent_area: f32) -> SahResult {
    #[derive(Clone, Copy)]
    struct Bin {
        bounds: Aabb,
        count: u32,
    }
    let extent = cbounds.max - cbounds.min;
    let bin_of = |c: f32, axis: usize| -> usize {
        let scale = BINS as f32 / extent[axis];
        // `as usize` saturates (and maps NaN to 0), so this never goes out of range.
        (((c - cbounds.min[axis]) * scale) as usize).min(BINS - 1)
    };
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, last left bin)
    for axis in 0..3 {
        if !(extent[axis] > 0.0) || !extent[axis].is_finite() {
            continue;
        }
        let mut bins = [Bin { bounds: Aabb::EMPTY, count: 0 }; BINS];
        for &i in range.iter() {
            let b = &mut bins[bin_of(centroids[i as usize][axis], axis)];
            b.count += 1;
            b.bounds.grow(&boxes[i as usize]);
        }
        // Right-to-left sweep: area*count of bins[k+1..].
        let mut right_cost = [0.0f32; BINS];
        let mut acc = Aabb::EMPTY;
        let mut cnt = 0u32;
        for k in (1..BINS).rev() {
            acc.grow(&bins[k].bounds);
            cnt += bins[k].count;
            right_cost[k - 1] = if cnt > 0 { acc.half_area() * cnt as f32 } else { f32::NAN };
        }
        let mut acc = Aabb::EMPTY;
        let mut cnt = 0u32;
        for k in 0..BINS - 1 {
            acc.grow(&bins[k].bounds);
            cnt += bins[k].count;
            if cnt == 0 || cnt as usize == range.len() {
                continue;
            }
            let cost = acc.half_area() * cnt as f32 + right_cost[k];
            if cost.is_finite() && !matches!(best, Some((c, _, _)) if c <= cost) {
                best = Some((cost, axis, k));
            }
        }
    }
    let Some((cost, axis, k)) = best else {
        return SahResult::Unsplittable;
    };
    // Leaf cost = intersecting every triangle; traversal step costs about one triangle.
    let leaf_cost = parent_area * range.len() as f32;
    let split_cost = parent_area + cost;
    if range.len() <= MAX_LEAF && split_cost >= leaf_cost {
        return SahResult::LeafCheaper;
    }
    let mid = partition(range, |i| bin_of(centroids[i as usize][axis], axis) <= k);
    if mid == 0 || mid == range.len() {
        // Cannot happen (bins are recomputed identically), but never loop on it.
        return SahResult::Unsplittable;
    }
    SahResult::Split(mid)
}

fn median_split(range: &mut [u32], centroids: &[Vec3], cbounds: &Aabb) -> usize {
    let e = cbounds.max - cbounds.min;
    let axis = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let mid = range.len() / 2;
    range.select_nth_unstable_by(mid, |&a, &b| centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis]));
    mid
}

fn partition(s: &mut [u32], pred: impl Fn(u32) -> bool) -> usize {
    let mut mid = 0;
    for i in 0..s.len() {
        if pred(s[i]) {
            s.swap(i, mid);
            mid += 1;
        }
    }
    mid
}

/// Per-ray slab-test data.
struct SlabRay {
    origin: Vec3,
    inv: Vec3,
    /// Axis with a zero (or -0) direction component: the slab test on it is "origin
    /// inside the closed slab", with no t constraint.
    zero: [bool; 3],
}

impl SlabRay {
    fn new(origin: Vec3, dir: Vec3) -> SlabRay {
        let zero = [dir.x == 0.0, dir.y == 0.0, dir.z == 0.0];
        SlabRay { origin, inv: dir.recip(), zero }
    }

    /// Entry distance into the box if the ray overlaps it within `[t_min, t_max]`.
    #[inline]
    fn hit(&self, n: &Node, t_min: f32, t_max: f32) -> Option<f32> {
        let mut near = t_min;
        let mut far = t_max;
        for a in 0..3 {
            if self.zero[a] {
                if !(self.origin[a] >= n.min[a] && self.origin[a] <= n.max[a]) {
                    return None;
                }
                continue;
            }
            let t0 = (n.min[a] - self.origin[a]) * self.inv[a];
            let t1 = (n.max[a] - self.origin[a]) * self.inv[a];
            let (lo, hi) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
            // Conservative far bound against rounding (Ize 2013, 1 + 2*gamma(3)).
            let hi = hi * 1.000_000_4;
            // Written so that NaN (NaN ray or box) rejects.
            if lo > near {
                near = lo;
            }
            if hi < far {
                far = hi;
            }
            if !(near <= far) {
                return None;
            }
        }
        Some(near)
    }
}

/// Möller–Trumbore ray/triangle test (no culling) on a triangle given as
/// `v0`, `e1 = v1 - v0`, `e2 = v2 - v0`. Returns `(t, u, v)` with `t_min < t < t_max`.
/// NaN inputs and rays parallel to the triangle plane (including degenerate
/// triangles) never hit.
#[inline]
pub fn moller_trumbore(
    origin: Vec3,
    dir: Vec3,
    v0: Vec3,
    e1: Vec3,
    e2: Vec3,
    t_min: f32,
    t_max: f32,
) -> Option<(f32, f32, f32)> {
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv_det = 1.0 / det;
    let s = origin - v0;
    let u = s.dot(p) * inv_det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv_det;
    if !(v >= 0.0 && u + v <= 1.0) {
        return None;
    }
    let t = e2.dot(q) * inv_det;
    if !(t > t_min && t < t_max) {
        return None;
    }
    Some((t, u, v))
}

/// [`moller_trumbore`] on a [`Triangle`] (the same arithmetic as [`Bvh::intersect`]).
pub fn intersect_triangle(origin: Vec3, dir: Vec3, tri: &Triangle, t_min: f32, t_max: f32) -> Option<(f32, f32, f32)> {
    moller_trumbore(origin, dir, tri.v[0], tri.v[1] - tri.v[0], tri.v[2] - tri.v[0], t_min, t_max)
}

/// Per-vertex thickness `d_N` (Wyman 2005): for each vertex, the distance from the
/// vertex along the inward normal `-n` to the first surface of the mesh, 0 when the
/// ray escapes (open mesh, zero normal, or bad input).
///
/// The ray starts at `p - n̂·eps` (`eps` = 1e-5 of the mesh's bounding-box diagonal)
/// to step off the vertex's own triangles; the reported distance is measured from `p`
/// (hit `t + eps`). `normals` need not be normalised. Triangles with out-of-range
/// indices are skipped; a trailing partial triangle is ignored. Runs on all cores.
pub fn vertex_thickness(positions: &[Vec3], normals: &[Vec3], indices: &[u32]) -> Vec<f32> {
    let nv = positions.len();
    let tris: Vec<Triangle> = indices
        .chunks_exact(3)
        .enumerate()
        .filter(|(_, c)| c.iter().all(|&i| (i as usize) < nv))
        .map(|(k, c)| Triangle {
            v: [positions[c[0] as usize], positions[c[1] as usize], positions[c[2] as usize]],
            object: 0,
            prim: k as u32,
        })
        .collect();
    let skipped = indices.len() / 3 - tris.len();
    if skipped > 0 {
        log::warn!("vertex_thickness: skipped {skipped} triangles with out-of-range indices");
    }
    let bvh = Bvh::build(tris);
    let mut out = vec![0.0f32; nv];
    let Some((bmin, bmax)) = bvh.bounds() else {
        return out;
    };
    let diag = (bmax - bmin).length();
    let eps = if diag.is_finite() && diag > 0.0 { diag * 1e-5 } else { 1e-6 };

    let thickness = |i: usize| -> f32 {
        let p = positions[i];
        let n = normals.get(i).copied().unwrap_or(Vec3::ZERO).normalize_or_zero();
        if n == Vec3::ZERO || !p.is_finite() {
            return 0.0;
        }
        let origin = p - n * eps;
        if let Some(h) = bvh.intersect(origin, -n, 0.0, f32::INFINITY) {
            return h.t + eps;
        }
        // Möller–Trumbore is not watertight: a ray through a shared vertex or edge
        // (e.g. to the antipode of a UV-sphere vertex) can slip between triangles.
        // Retry with directions tilted by 1e-4 rad (distance error ~5e-9 relative).
        let (t, b) = n.any_orthonormal_pair();
        const TILT: f32 = 1e-4;
        [t, -t, b, -b, (t + b) * std::f32::consts::FRAC_1_SQRT_2, -(t + b) * std::f32::consts::FRAC_1_SQRT_2]
            .iter()
            .find_map(|&off| bvh.intersect(origin, (-n + off * TILT).normalize(), 0.0, f32::INFINITY))
            .map_or(0.0, |h| h.t + eps)
    };

    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).min(nv.div_ceil(256)).max(1);
    let chunk = nv.div_ceil(threads).max(1);
    if threads == 1 {
        out.iter_mut().enumerate().for_each(|(i, d)| *d = thickness(i));
        return out;
    }
    // Each thread takes chunks until none is left (crate::workers).
    let chunks = std::sync::Mutex::new(out.chunks_mut(chunk).enumerate().collect::<Vec<_>>());
    crate::workers::run(threads, "vertex-thickness", || loop {
        let Some((c, slice)) = chunks.lock().unwrap().pop() else { break };
        for (j, d) in slice.iter_mut().enumerate() {
            *d = thickness(c * chunk + j);
        }
    });
    out
}

mod memo;
pub use memo::vertex_thickness_memo;

#[cfg(test)]
mod tests;
