// Eye-space transform shared by the eye passes.
#version 450
#include "common/frame.glsl"
#include "common/mesh_vertex.glsl"
layout(location = 0) out vec3 v_world;
layout(location = 1) out vec3 v_normal;
layout(location = 2) out float v_thickness;

void main() {
    gl_Position = frame.view_proj * vec4(a_position, 1.0);
    v_world = a_position;
    v_normal = a_normal;
    v_thickness = a_thickness;
}
