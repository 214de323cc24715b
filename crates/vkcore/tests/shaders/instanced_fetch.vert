#version 450
// Wyman 2008 Sec. 4: no copy of the photon image into a vertex buffer. A small vertex buffer
// of VERTS_PER_INSTANCE vertices is drawn instanced; each vertex finds its photon from
// gl_InstanceIndex and gl_VertexIndex and fetches it from the photon texture.
layout(binding = 0) uniform sampler2D photons;
layout(push_constant) uniform FetchConstants { uint count; uint width; uint verts_per_instance; uint target_size; };
layout(location = 0) in uint a_vertex;   // the small vertex buffer holds 0..VERTS-1
void main() {
    uint id = gl_InstanceIndex * verts_per_instance + a_vertex;
    vec4 p = texelFetch(photons, ivec2(id % width, id / width), 0);
    if (id >= count || p.w == 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);   // outside the clip volume: culled
    } else {
        // p.xy are texel coordinates in the target; aim at the texel centre.
        gl_Position = vec4((p.xy + 0.5) / float(target_size) * 2.0 - 1.0, 0.0, 1.0);
    }
    gl_PointSize = 1.0;
}
