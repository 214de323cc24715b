// Wyman & Nichols 2009 Sec. 3.2, step 1: "render geometry buffers for deferred photon creation".
// The specular objects seen from the light through the photon frustum (the photon buffer's) in
// one pass, as the eye's deferred refraction renders its geometry buffers (Sec. 3.1): this
// geometry shader routes each face to the front (layer 0) or back (layer 1) buffers by its
// facing from the light, decided as the rasterizer decides it (common/facing.glsl). The back
// layer is what the photon trace reads as the light-space back faces (Wyman 2005), which the
// dense photon buffer's back-face pass renders from the refractive objects alone: back faces of
// reflective objects are dropped.
#version 450
#define CAUSTICS_BINDING 1
#include "common/caustics.glsl"
#include "common/mesh_constants.glsl"
#include "common/facing.glsl"
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
layout(location = 0) in vec3 v_world[];
layout(location = 1) in vec3 v_normal[];
layout(location = 2) in float v_thickness[];
layout(location = 0) out vec3 g_world;
layout(location = 1) out vec3 g_normal;
layout(location = 2) out float g_thickness;
layout(location = 3) flat out int g_back;

void main() {
    vec3 light = caustics.lights[mesh.light].position.xyz;
    bool front = faces_viewer(gl_in[0].gl_Position, gl_in[1].gl_Position, gl_in[2].gl_Position, v_world[0],
                              v_world[1], v_world[2], light);
    if (!front && mesh.material != MATERIAL_REFRACTIVE) return;
    for (int i = 0; i < 3; ++i) {
        gl_Position = gl_in[i].gl_Position;
        gl_Layer = front ? 0 : 1;
        g_world = v_world[i];
        g_normal = v_normal[i];
        g_thickness = v_thickness[i];
        g_back = front ? 0 : 1;
        EmitVertex();
    }
    EndPrimitive();
}
