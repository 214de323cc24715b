// The material kinds of the scene's meshes, mirrored by `MATERIAL_*` in
// crates/caustics/src/gpu/structs.rs: what the mesh push constants and the light-space geometry
// buffers of adaptive caustic maps (wyman_nichols2009/light_geometry.frag) carry.
#ifndef MATERIALS_GLSL
#define MATERIALS_GLSL
#define MATERIAL_DIFFUSE 0u
#define MATERIAL_REFRACTIVE 1u
#define MATERIAL_REFLECTIVE 2u
#endif
