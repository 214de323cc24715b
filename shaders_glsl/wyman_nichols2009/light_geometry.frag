// Wyman & Nichols 2009 Sec. 3.2: the light-space geometry buffers photons are created from by
// deferred shading ("geometry buffers store object positions and normals"). The nearest face
// of each kind wins the depth test of its own layer (wyman_nichols2009/light_geometry.geom).
// Front (layer 0): what tracing a photon from this surface point needs, the interpolants the
// photon buffer's fragment shader traces from (shared/photon_buffer.frag) and the mesh's
// material; back (layer 1): what shared/back_faces.frag writes for the dense photon buffer.
#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "common/mesh_constants.glsl"
layout(location = 0) in vec3 g_world;
layout(location = 1) in vec3 g_normal;
layout(location = 2) in float g_thickness;
layout(location = 3) flat in int g_back;
layout(location = 0) out vec4 o_position;  // front: world position, Wyman 2005 d_N; back: position, distance to the light
layout(location = 1) out vec4 o_normal;    // front: interpolated normal, object + 1 (0: no surface); back: unit normal, distance
layout(location = 2) out vec4 o_material;  // colour, mean index of refraction (0: reflective)

void main() {
    float to_light = distance(g_world, caustics.lights[mesh.light].position.xyz);
    bool refractive = mesh.material == MATERIAL_REFRACTIVE;
    o_material = vec4(mesh.colour.rgb, refractive ? dot(mesh.ior.rgb, vec3(1.0 / 3.0)) : 0.0);
    if (g_back != 0) {
        o_position = vec4(g_world, to_light);
        o_normal = vec4(normalize(g_normal), to_light);
    } else {
        o_position = vec4(g_world, g_thickness);
        o_normal = vec4(g_normal, float(mesh.object + 1u));
    }
}
