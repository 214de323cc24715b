// The push constants of every mesh draw, mirrored by `MeshConstants` in
// crates/caustics/src/gpu/push.rs. Only mesh shaders include this; other passes declare their
// own push-constant block.
#ifndef MESH_CONSTANTS_GLSL
#define MESH_CONSTANTS_GLSL

#include "common/materials.glsl"

layout(push_constant) uniform MeshConstants {
    vec4 colour;          // diffuse albedo / transmission colour / specular colour
    vec4 ior;             // rgb index of refraction (refractive)
    uint material;        // MATERIAL_*
    uint light;           // the light a pass from a light (or the shadow map) renders for
    uint first_photon;    // vertex photons: this mesh's first photon
    uint object;          // the mesh's index in the scene (light-space geometry buffers)
} mesh;

#endif
