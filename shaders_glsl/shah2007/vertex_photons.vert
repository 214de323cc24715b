// Shah et al.'s original first pass: a photon at every vertex of the refractor's mesh (so the
// caustic's quality follows the tessellation). The vertex's share of the surface, seen from the
// light, gives its solid angle: a third of its triangles' area, projected. Photons are written
// into a photon texture (vertex i at texel (i % width, i / width)) for the same splat pass.
#version 450
#include "shared/trace.glsl"
#include "common/mesh_vertex.glsl"
layout(std430, binding = 8) readonly buffer Areas { float areas[]; };   // a third of each vertex's triangles' area
layout(binding = 5, rgba32f) uniform writeonly image2D photon_position;
layout(binding = 6, rgba32f) uniform writeonly image2D photon_direction;
layout(binding = 7, rgba32f) uniform writeonly image2D photon_power;

void main() {
    uint l = mesh.light;
    CausticLight cl = caustics.lights[l];
    int width = imageSize(photon_position).x;
    int id = gl_VertexIndex + int(mesh.first_photon);
    ivec2 texel = ivec2(id % width, id / width);
    float a_area = areas[gl_VertexIndex];
    vec3 to_p = a_position - cl.position.xyz;
    float d2 = dot(to_p, to_p);
    float cos_l = dot(normalize(a_normal), -to_p * inversesqrt(d2));
    Photon ph;
    ph.position = vec4(0.0); ph.direction = vec4(0.0); ph.power = vec4(0.0);
    bool inside;
    project_ndc(cl.photon_view_proj, a_position, inside);
    // Vertices facing the light (the refractors here are convex or nearly so).
    if (cos_l > 0.0 && inside) {
        ph = trace_photon(l, a_position, normalize(a_normal), a_thickness, a_area * cos_l / d2);
    }
    imageStore(photon_position, texel, ph.position);
    imageStore(photon_direction, texel, ph.direction);
    imageStore(photon_power, texel, ph.power);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    gl_PointSize = 1.0;
}
