// Wyman & Nichols 2009 Sec. 3.1: steps 2 and 3 of deferred refraction combined, "touching
// refractor geometry to output front and back faces just once": the geometry shader routes
// each triangle to layer 0 (front faces) or layer 1 (back faces) of the geometry buffers by
// its facing, which it decides as the rasterizer does (the sign of its area in framebuffer
// space, counter-clockwise = front).
#version 450
#include "common/frame.glsl"
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
layout(location = 0) in vec3 v_world[];
layout(location = 1) in vec3 v_normal[];
layout(location = 2) in float v_thickness[];
layout(location = 0) out vec3 g_world;
layout(location = 1) out vec3 g_normal;
layout(location = 2) out float g_thickness;

bool front_facing() {
    vec4 c0 = gl_in[0].gl_Position, c1 = gl_in[1].gl_Position, c2 = gl_in[2].gl_Position;
    if (c0.w > 0.0 && c1.w > 0.0 && c2.w > 0.0) {
        // Vulkan's a = -1/2 sum(x_i y_(i+1) - x_(i+1) y_i) > 0 in framebuffer (and NDC) space.
        vec2 a = c0.xy / c0.w, b = c1.xy / c1.w, c = c2.xy / c2.w;
        return (a.x * b.y - b.x * a.y) + (b.x * c.y - c.x * b.y) + (c.x * a.y - a.x * c.y) < 0.0;
    }
    // Crossing the eye plane: the world-space equivalent (counter-clockwise seen from the eye).
    vec3 p = v_world[0];
    return dot(cross(v_world[1] - p, v_world[2] - p), frame.eye.xyz - p) > 0.0;
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
