// Tracing one photon from the light through a specular surface of the mesh being drawn, shared
// by the photon buffer (a photon per light-space texel: Wyman & Davis 2006 Sec. 3.1, Shah's
// refractive vertex grid) and the vertex-photon pass (a photon per mesh vertex: Shah's original
// first pass). The tracing itself is shared/trace_surface.glsl.
// Needs bindings 0-4 (shared/trace_surface.glsl).
#ifndef TRACE_GLSL
#define TRACE_GLSL
#include "shared/trace_surface.glsl"
#include "common/mesh_constants.glsl"

// The material of the mesh being drawn.
SpecularMaterial mesh_material() {
    return SpecularMaterial(mesh.material, mesh.colour.rgb, dot(mesh.ior.rgb, vec3(1.0 / 3.0)));
}

// Photon through the surface point p1 (normal n1, thickness d_n) with solid angle `omega`.
Photon trace_photon(uint l, vec3 p1, vec3 n1, float d_n, float omega) {
    return trace_photon_through(l, p1, n1, d_n, omega, mesh_material());
}
#endif
