// Adaptive traversal, transform-feedback path, stage 1: one point per element of the previous
// kernel's stream, drawn with vkCmdDrawIndirectByteCountEXT (wyman_nichols2009/adaptive_step.geom):
// a packed cluster fetched as a vertex attribute, or (FROM_HITS) the index of a cluster's hits,
// which the geometry shader reads from their buffer.
#version 450
#ifdef FROM_HITS
layout(location = 0) flat out uint v_index;
#else
layout(location = 0) in uint a_cluster;
layout(location = 0) flat out uint v_cluster;
#endif

void main() {
#ifdef FROM_HITS
    v_index = uint(gl_VertexIndex);
#else
    v_cluster = a_cluster;
#endif
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
    gl_PointSize = 1.0;
}
