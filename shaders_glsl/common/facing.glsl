// Which way a triangle faces a viewer, decided as the rasterizer decides it (the sign of its
// area in framebuffer space, counter-clockwise = front, vkcore's pipelines' front face), for a
// geometry shader that routes each face to the front or back layer of geometry buffers
// (Wyman & Nichols 2009 Sec. 3.1: the eye's deferred refraction; Sec. 3.2: the light's
// geometry buffers of adaptive caustic maps).
#ifndef FACING_GLSL
#define FACING_GLSL

// c*: the corners in clip space; w*: in world space; viewer: the eye or the light.
bool faces_viewer(vec4 c0, vec4 c1, vec4 c2, vec3 w0, vec3 w1, vec3 w2, vec3 viewer) {
    if (c0.w > 0.0 && c1.w > 0.0 && c2.w > 0.0) {
        // Vulkan's a = -1/2 sum(x_i y_(i+1) - x_(i+1) y_i) > 0 in framebuffer (and NDC) space.
        vec2 a = c0.xy / c0.w, b = c1.xy / c1.w, c = c2.xy / c2.w;
        return (a.x * b.y - b.x * a.y) + (b.x * c.y - c.x * b.y) + (c.x * a.y - a.x * c.y) < 0.0;
    }
    // Crossing the viewer's plane: the world-space equivalent (counter-clockwise seen from it).
    return dot(cross(w1 - w0, w2 - w0), viewer - w0) > 0.0;
}
#endif
