// Hierarchical traversal, transform-feedback path, stage 2 (Wyman 2008 Sec. 3.1): the geometry
// shader discards the entry or emits its children (or the converged cluster, flagged final)
// into transform-feedback buffer 0; rasterisation is discarded. The next level is drawn with
// vkCmdDrawIndirectByteCountEXT from this level's counter buffer: nothing is read back.
#version 450
#include "wyman2008/traverse.glsl"
layout(points) in;
layout(points, max_vertices = 4) out;
layout(location = 0) flat in uint v_entry[];
layout(location = 0, xfb_buffer = 0, xfb_offset = 0, xfb_stride = 4) flat out uint g_entry;

void main() {
    uvec4 outs[4];
    uint n = expand(unpack_entry(v_entry[0]), outs);
    for (uint i = 0u; i < n; ++i) {
        // Every output is rewritten before every emit.
        g_entry = pack_entry(outs[i]);
        gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
        EmitVertex();
        EndPrimitive();
    }
}
