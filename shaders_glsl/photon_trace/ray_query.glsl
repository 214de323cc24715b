// The nearest hit by `rayQueryEXT` (GL_EXT_ray_query) against the scene's top-level acceleration
// structure: a bottom level per object over its triangles in the scene's order, opaque, both faces
// (the instances disable facing culling), each instance's custom index the object's first
// triangle in `triangles` (`photon_trace::RayQueryScene`), so a hit's triangle is that plus its
// primitive index. An instance's transform is the identity or, where its object moved rigidly since
// its bottom level was built, that motion: the hit carries its rotation (`hit_to_world`). The driver's traversal and triangle test (watertight on most hardware) replace
// `bvh.glsl`'s: hits agree with it but at edges, where one may find a triangle the other misses.
// Needs SCENE_BINDING, TRIANGLES_BINDING and `#extension GL_EXT_ray_query` (before any code).
#ifndef PHOTON_TRACE_RAY_QUERY_GLSL
#define PHOTON_TRACE_RAY_QUERY_GLSL
#include "photon_trace/triangles.glsl"

layout(binding = SCENE_BINDING) uniform accelerationStructureEXT scene;

bool ray_query_intersect(vec3 o, vec3 d, float t_min, float t_max, out RayHit hit) {
    rayQueryEXT q;
    rayQueryInitializeEXT(q, scene, gl_RayFlagsOpaqueEXT, 0xffu, o, t_min, d, t_max);
    while (rayQueryProceedEXT(q)) {
    }
    hit = RayHit(t_max, 0.0, 0.0, 0xffffffffu, mat3(1.0));
    if (rayQueryGetIntersectionTypeEXT(q, true) != gl_RayQueryCommittedIntersectionTriangleEXT) return false;
    // Rigid: its first three columns turn normals as they turn positions.
    hit.to_world = mat3(rayQueryGetIntersectionObjectToWorldEXT(q, true));
    vec2 uv = rayQueryGetIntersectionBarycentricsEXT(q, true);
    hit.t = rayQueryGetIntersectionTEXT(q, true);
    hit.u = uv.x;
    hit.v = uv.y;
    hit.triangle = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(q, true))
        + uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, true));
    return true;
}
#endif
