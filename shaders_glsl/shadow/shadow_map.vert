// Shadow map: one cube per light in six array layers, all faces in one instanced draw; the
// instance picks the face and writes gl_Layer directly (shaderOutputLayer).
#version 450
#extension GL_ARB_shader_viewport_layer_array : require
#include "common/frame.glsl"
#include "common/mesh_vertex.glsl"
#include "common/mesh_constants.glsl"
layout(location = 0) out vec3 v_world;

void main() {
    Light light = frame.lights[mesh.light];
    gl_Position = light.face_view_proj[gl_InstanceIndex] * vec4(a_position, 1.0);
    gl_Layer = gl_InstanceIndex;
    v_world = a_position;
}
