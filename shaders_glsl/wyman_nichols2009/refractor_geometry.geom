// Wyman & Nichols 2009 Sec. 3.1: steps 2 and 3 of deferred refraction combined, "touching
// refractor geometry to output front and back faces just once": the geometry shader routes
// each triangle to layer 0 (front faces) or layer 1 (back faces) of the geometry buffers by
// its facing, which it decides as the rasterizer does (common/facing.glsl).
#version 450
#include "common/frame.glsl"
#include "common/facing.glsl"
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
layout(location = 0) in vec3 v_world[];
layout(location = 1) in vec3 v_normal[];
layout(location = 2) in float v_thickness[];
layout(location = 0) out vec3 g_world;
layout(location = 1) out vec3 g_normal;
layout(location = 2) out float g_thickness;

bool front_facing() {
    return faces_viewer(gl_in[0].gl_Position, gl_in[1].gl_Position, gl_in[2].gl_Position, v_world[0], v_world[1],
                        v_world[2], frame.eye.xyz);
}

void main() {
    int layer = front_facing() ? 0 : 1;
    for (int i = 0; i < 3; ++i) {
        gl_Position = gl_in[i].gl_Position;
        gl_Layer = layer;
        g_world = v_world[i];
        g_normal = v_normal[i];
        g_thickness = v_thickness[i];
        EmitVertex();
    }
    EndPrimitive();
}
