// The triangles the photon tracer hits, as both intersection paths read them: the compute path's
// in its BVH's order (`bvh.glsl`), the ray-query path's in the scene's order, object by object
// (`ray_query.glsl`), there as each object's bottom level was built (its instance's transform
// moves it). A hit names its triangle by its index here. Needs TRIANGLES_BINDING.
#ifndef PHOTON_TRACE_TRIANGLES_GLSL
#define PHOTON_TRACE_TRIANGLES_GLSL

// Read as uvec4, the floats by uintBitsToFloat: a small integer read as float bits is a denormal,
// which drivers that flush denormals (llvmpipe) read as zero.
struct StoredTriangle {
    uvec4 v0;   // xyz: first vertex (float bits); w: the scene's object index
    vec4 e1;    // xyz: v1 - v0
    vec4 e2;    // xyz: v2 - v0
};
layout(std430, binding = TRIANGLES_BINDING) readonly buffer Triangles { StoredTriangle triangles[]; };

struct BvhTriangle {
    vec3 v0;
    uint object;
    vec3 e1;
    vec3 e2;
};

BvhTriangle bvh_triangle(uint i) {
    StoredTriangle t = triangles[i];
    return BvhTriangle(uintBitsToFloat(t.v0.xyz), t.v0.w, t.e1.xyz, t.e2.xyz);
}

struct RayHit {
    float t;
    float u;        // barycentric weight of v1
    float v;        // barycentric weight of v2
    uint triangle;  // index into `triangles`
#ifdef RAY_QUERY
    // The hit instance's object-to-world rotation: `triangles` and the shading normals hold an
    // object as its bottom level was built, and a rigidly moved object's instance turns them.
    mat3 to_world;
#endif
};

// A direction or normal of the hit triangle's object (as `triangles` stores it) in the world.
vec3 hit_to_world(RayHit h, vec3 n) {
#ifdef RAY_QUERY
    return h.to_world * n;
#else
    return n;
#endif
}
#endif
