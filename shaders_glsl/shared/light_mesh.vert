// Meshes seen from a light, through the photon frustum (PHOTON_VIEW) or the caustic-map frustum.
#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "common/mesh_vertex.glsl"
#include "common/mesh_constants.glsl"
layout(location = 0) out vec3 v_world;
layout(location = 1) out vec3 v_normal;
layout(location = 2) out float v_thickness;

void main() {
    CausticLight cl = caustics.lights[mesh.light];
#ifdef PHOTON_VIEW
    gl_Position = cl.photon_view_proj * vec4(a_position, 1.0);
#else
    gl_Position = cl.caustic_view_proj * vec4(a_position, 1.0);
#endif
    v_world = a_position;
    v_normal = a_normal;
    v_thickness = a_thickness;
}
