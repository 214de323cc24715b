// Stream compaction, transform-feedback path, stage 2: the geometry shader keeps or discards
// each point; kept points are captured into xfb buffer 0 in order of arrival (Wyman 2008
// Sec. 3.1 traverses its photon hierarchy the same way). KEEP_EXPR is a define over `v`.
#version 450
layout(points) in;
layout(points, max_vertices = 1) out;

layout(location = 0) flat in uvec4 v_value[];
layout(location = 0, xfb_buffer = 0, xfb_offset = 0, xfb_stride = 16) flat out uvec4 g_value;

bool keep(uvec4 v) { return KEEP_EXPR; }

void main() {
    uvec4 v = v_value[0];
    if (keep(v)) {
        // Every output is written before every emit.
        g_value = v;
        gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
        EmitVertex();
        EndPrimitive();
    }
}
