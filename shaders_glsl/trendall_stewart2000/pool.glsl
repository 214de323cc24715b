// Trendall & Stewart 2000: what every pool pass reads. The twin of `PoolUniforms` in
// crates/caustics/src/techniques/trendall_stewart2000/uniforms.rs (checked by its tests).
// Texel (i, j) of every grid is the water column at x_i = -half + (i + 0.5) texel, z_j likewise.

#define MAX_SOURCES 256

layout(set = 0, binding = 0) uniform PoolUniforms {
    uvec4 grid;              // n, kernel side, faithful (8-bit path), wave sources
    ivec4 kernel;            // window centre offset x, z (texels), half-width r, 0
    vec4 pool;               // side, depth, texel, half side (m)
    vec4 light;              // L_i (travel direction), L_s
    vec4 optics;             // n_i / n_t, n_i, n_t, exponent n
    vec4 medium;             // a, epsilon, albedo, time
    vec4 wave;               // A, K, omega, alpha
    vec4 wave_damping;       // beta
    vec4 basis_x;
    vec4 basis_y;
    vec4 basis_z;
    vec4 enc_height_slope;   // height (lo, span), slope (lo, span)
    vec4 enc_cos;            // cos(theta_i) (lo, span)
    vec4 enc_normal_lo;
    vec4 enc_normal_span;
    vec4 enc_gamma_n_lo;
    vec4 enc_gamma_n_span;
    vec4 enc_lt_lo;
    vec4 enc_lt_span;
    vec4 enc_direction_lo;
    vec4 enc_direction_span;
    vec4 enc_convolution_lo;
    vec4 enc_convolution_span;
    vec4 cam_right;          // xyz, tan(fov_y / 2) aspect
    vec4 cam_up;             // xyz, tan(fov_y / 2)
    vec4 cam_forward;
    vec4 eye;                // xyz, exposure
    vec4 view;               // width, height, E of flat water (physical), 0
    vec4 sky;
    vec4 sources[MAX_SOURCES]; // x, z, time since the impulse
} u;

// Sec. 3.2: an "adjusted" function f~ = (f - lo) / span in [0, 1] (clamped, as the pipeline
// clamps); decoding reads it back.
float adjust(float v, float lo, float span) { return clamp((v - lo) / span, 0.0, 1.0); }
vec4 adjust(vec4 v, vec4 lo, vec4 span) { return clamp((v - lo) / span, 0.0, 1.0); }
float unadjust(float a, float lo, float span) { return lo + a * span; }
vec4 unadjust(vec4 a, vec4 lo, vec4 span) { return lo + a * span; }

// The entry of a 256-entry colour table an adjusted value picks: the nearest (OpenGL 1.2).
int table_index(float adjusted) { return int(round(clamp(adjusted, 0.0, 1.0) * 255.0)); }

// log(1 - x) for small x without losing digits to 1 - x.
float log1m(float x) { return x < 0.01 ? -(x + x * x * (0.5 + x * (1.0 / 3.0 + 0.25 * x))) : log(1.0 - x); }
