// Adaptive traversal, transform-feedback path (Wyman & Nichols 2009 Sec. 4, "transform feedback
// and geometry shader extensions"): each kernel is a geometry shader over one point per element
// of its input stream, emitting into transform-feedback buffer 0 (rasterisation is discarded);
// the next kernel is drawn with vkCmdDrawIndirectByteCountEXT from that buffer's counter, so
// nothing is read back. The kernels (wyman_nichols2009/adaptive.glsl does the work):
// - SUBDIVIDE: clusters -> the four children of each cluster that touches the refractor;
// - EMIT: clusters of the last level -> their photons that landed (the maximal traversal
//   metric's last step; with SUBDIVIDE, "a single stream kernel per traversal step", Sec. 4.1);
// - the maximal caustic map error metric's three kernels per step (Sec. 4.1): HITS, "one that
//   computes photon hit positions" (clusters -> a cluster's hits); CONVERGED, "one that
//   identifies converged photons and outputs a separate stream" (hits -> the one photon of a
//   converged cluster, and at the last level the photons that landed of the others); REFINE,
//   "one that identifies unconverged photons and subdivides them" (hits -> children).
#version 450
#include "wyman_nichols2009/adaptive.glsl"
layout(points) in;
#if defined(HITS)
layout(points, max_vertices = 1) out;
#else
layout(points, max_vertices = 4) out;
#endif

#ifdef FROM_HITS
layout(location = 0) flat in uint v_index[];
layout(std430, binding = 9) readonly buffer Hits { ClusterHits hits[]; };
#else
layout(location = 0) flat in uint v_cluster[];
#endif

#if defined(SUBDIVIDE) || defined(REFINE)
layout(location = 0, xfb_buffer = 0, xfb_offset = 0, xfb_stride = 4) flat out uint g_cluster;
void refine(uvec3 c) {
    for (uint i = 0u; i < 4u; ++i) {
        // Every output is rewritten before every emit.
        g_cluster = pack_cell(uvec3(photon_of(c, i), c.z + 1u));
        gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
        EmitVertex();
        EndPrimitive();
    }
}
#elif defined(HITS)
layout(location = 0, xfb_buffer = 0, xfb_offset = 0, xfb_stride = 144) flat out uvec4 g_hits[9];
#else
layout(location = 0, xfb_buffer = 0, xfb_offset = 0, xfb_stride = 32) flat out uvec4 g_photon[2];
void emit(AdaptivePhoton p) {
    g_photon[0] = photon_word0(p);
    g_photon[1] = photon_word1(p);
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
    EmitVertex();
    EndPrimitive();
}
#endif

void main() {
#ifdef FROM_HITS
    ClusterHits h = hits[v_index[0]];
    uvec3 c = unpack_cell(h.header.x);
    bool converged = constants.converge != 0u && converges(h.photons, h.header.y, h.header.z != 0u);
#if defined(CONVERGED)
    if (converged) {
        emit(merged(c, h.photons));
    } else if (c.z == constants.finest) {
        AdaptivePhoton p[4] = h.photons;
        with_footprints(c, p, h.header.y);
        for (uint k = 0u; k < 4u; ++k) {
            if ((h.header.y & (1u << k)) != 0u) emit(p[k]);
        }
    }
#else   // REFINE
    if (!converged && c.z < constants.finest) refine(c);
#endif
#else
    uvec3 c = unpack_cell(v_cluster[0]);
    vec2 cover = footprint_coverage(c);
    if (cover.x < 0.5) return;          // misses the refractor: discarded
#if defined(SUBDIVIDE)
    refine(c);
#elif defined(EMIT)
    AdaptivePhoton p[4];
    uint landed = cluster_photons(c, p);
    with_footprints(c, p, landed);
    for (uint k = 0u; k < 4u; ++k) {
        if ((landed & (1u << k)) != 0u) emit(p[k]);
    }
#else   // HITS
    AdaptivePhoton p[4];
    uint landed = cluster_photons(c, p);
    g_hits[0] = uvec4(v_cluster[0], landed, cover.y > 0.5 ? 1u : 0u, 0u);
    for (int k = 0; k < 4; ++k) {
        g_hits[1 + 2 * k] = photon_word0(p[k]);
        g_hits[2 + 2 * k] = photon_word1(p[k]);
    }
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
    EmitVertex();
    EndPrimitive();
#endif
#endif
}
