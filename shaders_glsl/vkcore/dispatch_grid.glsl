// The work-group grid of crates/vkcore/src/grid.rs (`dispatch_grid`), for dispatch arguments
// written on the GPU: (x, y) groups covering `groups` (at least one), each at most 65535, in
// balanced rows, so that fewer than y groups are idle. The shader dispatched flattens the grid
// row by row.
#ifndef VKCORE_DISPATCH_GRID_GLSL
#define VKCORE_DISPATCH_GRID_GLSL
uvec2 dispatch_grid(uint groups) {
    groups = max(groups, 1u);
    uint rows = (groups + 65534u) / 65535u;
    uint x = (groups + rows - 1u) / rows;
    return uvec2(x, (groups + x - 1u) / x);
}
#endif
