// The per-frame uniform block, shared by every pass. Mirrored by `FrameUniforms` in
// crates/caustics/src/gpu/structs.rs (std140, built only from vec4/uvec4/mat4 members).
#ifndef FRAME_GLSL
#define FRAME_GLSL

#define MAX_LIGHTS 4

struct Light {
    vec4 position;        // xyz world position; w: 1 = spot light, 0 = point light
    vec4 intensity;       // rgb radiant intensity, W/sr; w: 1 = projected texture
    vec4 spot;            // xyz cone axis; w: cos(cone half-angle)
    vec4 spot_u;          // xyz: right / tan(half-angle), for the projected texture
    vec4 spot_v;          // xyz: up / tan(half-angle)
    vec4 shadow;          // x near, y far, z angular size of a shadow-map texel, w first layer
    mat4 face_view_proj[6];   // shadow-map cube faces +X -X +Y -Y +Z -Z, one array layer each
};

layout(std140, binding = 0) uniform Frame {
    mat4 view_proj;
    mat4 inv_view_proj;
    vec4 eye;             // xyz camera position
    vec4 viewport;        // width, height, 1/width, 1/height
    vec4 background;      // rgb radiance of rays that leave the scene
    uvec4 counts;         // x: lights
    vec4 receiver;        // x: plane_y, y: resolution
    vec4 receiver_range;  // x0, x1, z0, z1
    Light lights[MAX_LIGHTS];
} frame;

#endif
