#version 460
// Pass 1 (Sec. 4.2): N, the normal to the plane through h(i, j), h(i+1, j) and h(i, j+1)
// (Sec. 4.1; the last column and row use the texel before). FAITHFUL: the two discrete partial
// derivatives (a convolution), adjusted by the slope's scale and bias, index the 256 x 256
// pixel texture that holds the normalised normal, adjusted (Sec. 3.2, "height field normals").
#include "pass.glsl"

layout(set = 0, binding = 1) uniform sampler2D height_field;
#ifdef FAITHFUL
layout(set = 0, binding = 2) uniform sampler2D pixel_texture;
#endif

layout(location = 0) out vec4 out_normal;

float h(ivec2 ij) {
    float v = texelFetch(height_field, ij, 0).r;
#ifdef FAITHFUL
    v = unadjust(v, u.enc_height_slope.x, u.enc_height_slope.y);
#endif
    return v;
}

void main() {
    ivec2 ij = grid_texel();
    int last = int(u.grid.x) - 1;
    float dx = ij.x < last ? h(ij + ivec2(1, 0)) - h(ij) : h(ij) - h(ij - ivec2(1, 0));
    float dz = ij.y < last ? h(ij + ivec2(0, 1)) - h(ij) : h(ij) - h(ij - ivec2(0, 1));
    vec2 slope = vec2(dx, dz) / u.pool.z;
#ifdef FAITHFUL
    ivec2 index = ivec2(table_index(adjust(slope.x, u.enc_height_slope.z, u.enc_height_slope.w)),
                        table_index(adjust(slope.y, u.enc_height_slope.z, u.enc_height_slope.w)));
    out_normal = vec4(texelFetch(pixel_texture, index, 0).rgb, 1.0);
#else
    out_normal = vec4(normalize(vec3(-slope.x, 1.0, -slope.y)), 1.0);
#endif
}
