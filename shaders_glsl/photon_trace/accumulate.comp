// Progressive accumulation of `photon-trace` (`progressive = true`,
// crates/caustics/src/techniques/photon_trace/progressive.rs): after every light's deposit, the
// running mean of the frames' estimates since the last restart (Knaus & Zwicker 2011, Eq. 8:
// c_i = c_{i-1} + (frame - c_{i-1}) / i) is updated, and the frame's buffer, which the eye and
// the receiver map read, takes it. The caustic map's every layer; with FLUX, the photons binned
// into the receiver map (power rgb, count). weight = 1 (the first frame): the mean is the frame,
// whatever the mean's memory held.
#version 450
layout(push_constant) uniform AccumulateConstants {
    float weight;   // 1 / i
    uint count;     // FLUX: texels
} constants;

vec4 mean_with(vec4 mean, vec4 frame) {
    return constants.weight >= 1.0 ? frame : mean + (frame - mean) * constants.weight;
}

#ifdef FLUX
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer FrameFlux { vec4 frame_flux[]; };
layout(std430, binding = 1) buffer MeanFlux { vec4 mean_flux[]; };

void main() {
    // The grid's rows flattened (vkcore::dispatch_grid: a large map needs more than 65535 groups).
    uint i = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) + gl_GlobalInvocationID.x;
    if (i >= constants.count) return;
    vec4 m = mean_with(mean_flux[i], frame_flux[i]);
    mean_flux[i] = m;
    frame_flux[i] = m;
}
#else
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform image2DArray caustic_map;
layout(rgba32f, binding = 1) uniform image2DArray mean_map;

void main() {
    ivec3 t = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(t, imageSize(caustic_map)))) return;
    vec4 m = mean_with(imageLoad(mean_map, t), imageLoad(caustic_map, t));
    imageStore(mean_map, t, m);
    imageStore(caustic_map, t, m);
}
#endif
