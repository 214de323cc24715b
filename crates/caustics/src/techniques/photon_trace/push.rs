//! Push constants of the GPU photon tracer's pass: the twin of a GLSL `layout(push_constant)`
//! block of the same name and members (`crate::gpu::push`); the tests compare them through the
//! SPIR-V of every shader that declares one.

use vkcore::push_constants;

push_constants! {
    /// The GPU photon tracer (`photon_trace/trace.comp`).
    pub struct PhotonTraceConstants {
        /// xyz centre, w radius: the specular objects' bounding sphere.
        pub sphere: [f32; 4],
        pub light: u32,
        pub seed: u32,
        pub max_bounces: u32,
        /// `PHOTON_TRACE_*`.
        pub flags: u32,
        /// Ray offset against self-intersection (world units).
        pub eps: f32,
        /// How far from the receiver plane a photon still lands on it (the reference's).
        pub receiver_tolerance: f32,
    }
}

push_constants! {
    /// The splat of photon differentials (`photon_trace/differential_splat.comp`).
    pub struct DifferentialSplatConstants {
        pub photon_texels: u32,
        pub light: u32,
        /// The clamp of the kernel's standard deviations, caustic-map texels.
        pub min_sigma: f32,
        pub max_sigma: f32,
    }
}

push_constants! {
    /// Progressive accumulation's running means (`photon_trace/accumulate.comp`).
    pub struct AccumulateConstants {
        /// The frame's share of the mean, 1/i (1: the mean is the frame).
        pub weight: f32,
        /// FLUX: the receiver-map binning's texels.
        pub count: u32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::push::check;

    #[test]
    fn photon_trace_constants() {
        check::<PhotonTraceConstants>(&[
            ("photon_trace/trace.comp", &[]),
            ("photon_trace/trace.comp", &[("RECEIVER_DEPOSIT", "1")]),
            ("photon_trace/trace.comp", &[("DIFFERENTIALS", "1")]),
        ]);
    }

    #[test]
    fn differential_splat_constants() {
        check::<DifferentialSplatConstants>(&[("photon_trace/differential_splat.comp", &[])]);
    }

    #[test]
    fn accumulate_constants() {
        check::<AccumulateConstants>(&[
            ("photon_trace/accumulate.comp", &[]),
            ("photon_trace/accumulate.comp", &[("FLUX", "1")]),
        ]);
    }
}
