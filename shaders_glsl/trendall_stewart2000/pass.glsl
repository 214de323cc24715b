// What every fragment pass of Sec. 4.2 shares: the uniforms, and the grid texel (i, j) the
// fragment stands for (the passes draw one triangle over the n x n target).
#include "pool.glsl"

ivec2 grid_texel() { return ivec2(gl_FragCoord.xy); }
