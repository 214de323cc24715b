// Ray queries against the scene's bounding volume hierarchy, the CPU tracer's (`crates/caustics/
// src/bvh`) flattened and uploaded as it is: nodes in depth-first order (an interior node's
// children at `first` and `first + 1`), leaves of up to 4 triangles, contiguous. Ordered
// traversal (the nearer child first) with a fixed stack, slab tests, and Moller-Trumbore on both
// faces in f32: the same arithmetic as `Bvh::intersect`, so both tracers see the same hits up to
// the order of float operations (and the one case `slab` states). Needs NODES_BINDING and
// TRIANGLES_BINDING (the triangles in the BVH's order).
#ifndef PHOTON_TRACE_BVH_GLSL
#define PHOTON_TRACE_BVH_GLSL

#include "photon_trace/triangles.glsl"

// Read as uvec4, the floats by uintBitsToFloat (see triangles.glsl).
struct StoredNode {
    uvec4 lo;   // xyz: box minimum (float bits); w: first triangle, or the left child
    uvec4 hi;   // xyz: box maximum (float bits); w: triangles (0: interior node)
};
layout(std430, binding = NODES_BINDING) readonly buffer Nodes { StoredNode nodes[]; };

struct BvhNode {
    vec3 lo;
    uint first;
    vec3 hi;
    uint count;
};
BvhNode bvh_node(uint i) {
    StoredNode n = nodes[i];
    return BvhNode(uintBitsToFloat(n.lo.xyz), n.lo.w, uintBitsToFloat(n.hi.xyz), n.hi.w);
}

#define BVH_STACK 64

// Entry distance of the ray into box [lo, hi] within [t_min, t_max], or -1 where it misses; the
// far bound is widened against rounding (Ize 2013, 1 + 2 gamma(3)), as `SlabRay::hit` does. A
// zero direction component has the inverse 1e30 (`bvh_intersect`) where `SlabRay::hit` tests the
// origin against the slab: inside it the axis bounds nothing, outside it the entry lies beyond
// 1e20 or so (a box visited for nothing, never a hit lost), and only an origin exactly on the
// box's upper face, where the ray can at most graze an edge, reads outside. Without those tests
// the traversal's inner loop runs faster on lavapipe's SIMD lanes (issue 52 item 5).
float slab(vec3 o, vec3 inv_d, vec3 lo, vec3 hi, float t_min, float t_max) {
    vec3 t0 = (lo - o) * inv_d;
    vec3 t1 = (hi - o) * inv_d;
    vec3 near = min(t0, t1);
    vec3 far = max(t0, t1) * 1.0000004;
    float enter = max(max(near.x, near.y), max(near.z, t_min));
    float leave = min(min(far.x, far.y), min(far.z, t_max));
    return enter <= leave ? enter : -1.0;
}

// Moller-Trumbore on both faces (`bvh::moller_trumbore`): (t, u, v) of the hit with
// t_min < t < t_max.
bool moller_trumbore(vec3 o, vec3 d, BvhTriangle tri, float t_min, float t_max, out vec3 tuv) {
    tuv = vec3(0.0);
    vec3 p = cross(d, tri.e2);
    float det = dot(tri.e1, p);
    if (det == 0.0) return false;
    float inv = 1.0 / det;
    vec3 s = o - tri.v0;
    float u = dot(s, p) * inv;
    vec3 q = cross(s, tri.e1);
    float v = dot(d, q) * inv;
    float t = dot(tri.e2, q) * inv;
    tuv = vec3(t, u, v);
    return u >= 0.0 && u <= 1.0 && v >= 0.0 && u + v <= 1.0 && t > t_min && t < t_max;
}

// The nearest hit of the ray o + t d, t in (t_min, t_max), on either face of any triangle:
// `Bvh::traverse`'s loop (go to the nearer child, keep the farther on the stack), written as
// Aila & Laine 2009's "while-while": an inner loop down the interior nodes to a leaf, then the
// leaf's triangles, so that the lanes of a SIMD group (lavapipe runs 8 photons in one) do the
// same kind of work at once instead of each iteration paying for both. A first version that
// pushed both children and popped every node, with `continue` out of the leaf branch, never
// reached most leaves on llvmpipe (Mesa 22.3: up to 32768 pops per ray, no hit for two thirds
// of the rays; the cause was not found); this one has no `continue`.
bool bvh_intersect(vec3 o, vec3 d, float t_min, float t_max, out RayHit hit) {
    vec3 inv_d = vec3(d.x == 0.0 ? 1e30 : 1.0 / d.x, d.y == 0.0 ? 1e30 : 1.0 / d.y, d.z == 0.0 ? 1e30 : 1.0 / d.z);
    float best = t_max;
    vec2 best_uv = vec2(0.0);
    uint best_triangle = 0xffffffffu;
    uint stack[BVH_STACK];
    int top = 0;
    uint node = 0u;
    bool live = nodes.length() > 0;
    if (live) {
        BvhNode root = bvh_node(0u);
        live = slab(o, inv_d, root.lo, root.hi, t_min, best) >= 0.0;
    }
    while (live) {
        // Down the interior nodes to a leaf (the nearer child first, the farther on the stack),
        // all lanes of a SIMD group together; then the leaf's triangles, all together.
        BvhNode n = bvh_node(node);
        while (n.count == 0u) {
            BvhNode a = bvh_node(n.first);
            BvhNode b = bvh_node(n.first + 1u);
            float ta = slab(o, inv_d, a.lo, a.hi, t_min, best);
            float tb = slab(o, inv_d, b.lo, b.hi, t_min, best);
            if (ta >= 0.0 && tb >= 0.0) {
                // The depth is checked on the host (photon_trace::settings::MAX_BVH_DEPTH).
                if (top < BVH_STACK) stack[top++] = ta <= tb ? n.first + 1u : n.first;
                node = ta <= tb ? n.first : n.first + 1u;
            } else if (ta >= 0.0 || tb >= 0.0) {
                node = ta >= 0.0 ? n.first : n.first + 1u;
            } else if (top > 0) {
                node = stack[--top];
            } else {
                live = false;
                break;
            }
            n = bvh_node(node);
        }
        if (!live) break;
        for (uint k = n.first; k < n.first + n.count; ++k) {
            vec3 tuv;
            if (moller_trumbore(o, d, bvh_triangle(k), t_min, best, tuv)) {
                best = tuv.x;
                best_uv = tuv.yz;
                best_triangle = k;
            }
        }
        if (top == 0) break;
        node = stack[--top];
    }
    hit.t = best;
    hit.u = best_uv.x;
    hit.v = best_uv.y;
    hit.triangle = best_triangle;
    return best_triangle != 0xffffffffu;
}
#endif
