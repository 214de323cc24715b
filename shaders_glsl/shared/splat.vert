// The point splat of every photon-splatting technique (shared/splat_points.glsl says where the
// photons come from, by define); a deposit with its own radius has its own vertex shader, in its
// paper's folder, that includes it with TEXEL_RADIUS.
#version 450
#include "shared/splat_points.glsl"
