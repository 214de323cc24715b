//! Work-group grids for one-dimensional work larger than a dispatch's x limit.
//!
//! Every device allows at least 65535 work groups along each axis
//! (`maxComputeWorkGroupCount`), so work of more groups is dispatched as y rows of x groups and
//! flattened by the shader (`gl_GlobalInvocationID.y * gl_NumWorkGroups.x * local size + x`).
//! The rows are balanced: rows of 65535 would leave up to a whole row idle (65536 groups as
//! 65535 x 2 runs 131070), and an idle group is not free: on lavapipe it costs about what a
//! working one does. `shaders_glsl/vkcore/dispatch_grid.glsl` is the same rule for arguments
//! written on the GPU.

/// The most work groups along one axis that every Vulkan device accepts.
pub const MAX_GROUPS_PER_AXIS: u32 = 65535;

/// (x, y) work groups covering `groups` (at least one), each within
/// [`MAX_GROUPS_PER_AXIS`], with fewer than y groups idle.
pub fn dispatch_grid(groups: u32) -> (u32, u32) {
    let groups = groups.max(1);
    let rows = groups.div_ceil(MAX_GROUPS_PER_AXIS);
    let x = groups.div_ceil(rows);
    (x, groups.div_ceil(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_covers_the_groups_within_the_limit_with_fewer_idle_groups_than_rows() {
        let samples = [0u32, 1, 2, 65534, 65535, 65536, 65537, 131070, 131071, 262144, 4_000_000, u32::MAX / 64];
        for groups in samples.into_iter().chain((0..2000).map(|i| i * 7919 + 1)) {
            let (x, y) = dispatch_grid(groups);
            let want = groups.max(1) as u64;
            assert!(
                (1..=MAX_GROUPS_PER_AXIS).contains(&x) && (1..=MAX_GROUPS_PER_AXIS).contains(&y),
                "{groups}: {x} x {y}"
            );
            let total = x as u64 * y as u64;
            assert!(total >= want, "{groups}: {x} x {y} misses groups");
            assert!(total - want < y as u64, "{groups}: {x} x {y} leaves {} groups idle", total - want);
        }
        // The case that showed it: 65536 groups (2048² photons of 64) ran as 65535 x 2.
        assert_eq!(dispatch_grid(65536), (32768, 2));
    }
}
