//! Push constants of adaptive caustic maps' passes (Wyman & Nichols 2009 Sec. 3.2-4.2): the
//! coverage pyramid, the traversal's kernels, its batches and counts. Each is the twin of a
//! GLSL `layout(push_constant)` block of the same name and members (`crate::gpu::push`); the
//! tests compare them through the SPIR-V of every shader that declares one.

use vkcore::push_constants;

push_constants! {
    /// One level of the coverage pyramid of adaptive caustic maps' geometry buffers
    /// (`wyman_nichols2009/coverage.comp`).
    pub struct CoverageConstants {
        /// m: 0 from the geometry buffers, else from level m - 1.
        pub level: u32,
    }
}

push_constants! {
    /// One kernel of a step of the adaptive traversal (`wyman_nichols2009/adaptive.glsl`).
    pub struct AdaptiveConstants {
        pub light: u32,
        /// k: the step's photons lie on the (64 2^k)² grid.
        pub level: u32,
        /// L: the last level (64 2^L photons per side).
        pub finest: u32,
        /// 1 when the step tests convergence (max-error metric, from the 512² level on).
        pub converge: u32,
    }
}

push_constants! {
    /// A batch's input of the adaptive traversal (`wyman_nichols2009/adaptive_batch.comp`).
    pub struct BatchConstants {
        /// The batch's first cluster of level B.
        pub first: u32,
        /// Clusters per batch.
        pub size: u32,
        /// 1 on the transform-feedback path (byte counts).
        pub xfb: u32,
    }
}

push_constants! {
    /// The adaptive traversal's per-level counts (`wyman_nichols2009/adaptive_counts.comp`).
    pub struct CountConstants {
        /// The next level's slot (u32::MAX: none).
        pub cluster_slot: u32,
        pub photon_slot: u32,
        /// 1 on the transform-feedback path (byte counts).
        pub xfb: u32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::push::check;

    #[test]
    fn adaptive_constants() {
        let mut variants: Vec<(&str, &[(&str, &str)])> = vec![("wyman_nichols2009/adaptive_traverse.comp", &[])];
        let kernels: [&[(&str, &str)]; 5] = [
            &[("SUBDIVIDE", "1")],
            &[("EMIT", "1")],
            &[("HITS", "1")],
            &[("FROM_HITS", "1"), ("CONVERGED", "1")],
            &[("FROM_HITS", "1"), ("REFINE", "1")],
        ];
        variants.extend(kernels.iter().map(|d| ("wyman_nichols2009/adaptive_step.geom", *d)));
        check::<AdaptiveConstants>(&variants);
        check::<CoverageConstants>(&[("wyman_nichols2009/coverage.comp", &[])]);
        check::<BatchConstants>(&[("wyman_nichols2009/adaptive_batch.comp", &[])]);
        check::<CountConstants>(&[("wyman_nichols2009/adaptive_counts.comp", &[])]);
    }
}
