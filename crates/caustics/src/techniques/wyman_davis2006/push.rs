//! Push constants of Wyman & Davis 2006's image-space passes: eye-space points, caustic quads
//! and gathers. The twin of a GLSL `layout(push_constant)` block of the same name and members
//! (`crate::gpu::push`); the tests compare them through the SPIR-V of every shader that
//! declares one.

use vkcore::push_constants;

push_constants! {
    /// Wyman & Davis 2006's eye-space points, caustic quads and gathers
    /// (`shaders_glsl/wyman_davis2006/image_space.glsl`).
    pub struct ImageSpaceConstants {
        /// World to the view's clip space (the eye's, or the orthographic receiver view).
        pub view_proj: [f32; 16],
        /// A photon is on a pixel's surface within x * (distance to the eye) + y metres.
        pub tolerance: [f32; 4],
        /// xyz: the eye; w: 1 for an orthographic view.
        pub eye: [f32; 4],
        pub light: u32,
        /// The equation lighting the photons: 9, 10, 11 (points, gathers) or 3, 4 (quads).
        pub lighting: u32,
        /// The history layer this frame writes (temporal filter).
        pub slot: u32,
        /// History layers that hold a frame (1..=4).
        pub frames: u32,
        /// The gather's half-width (3: 7x7; 0: points).
        pub radius: u32,
        /// Neighbourhoods with fewer photons are discarded.
        pub min_photons: u32,
        /// The photon buffer's side N.
        pub photon_side: u32,
        /// The view's first history layer.
        pub history_base: u32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::push::check;

    #[test]
    fn image_space_constants() {
        let light: &[(&str, &str)] = &[("LIGHT_SPACE", "1")];
        check::<ImageSpaceConstants>(&[
            ("wyman_davis2006/photons.vert", &[]),
            ("wyman_davis2006/photons.frag", &[]),
            ("wyman_davis2006/photons.vert", light),
            ("wyman_davis2006/photons.frag", light),
            ("wyman_davis2006/quads.vert", &[]),
            ("wyman_davis2006/quads.frag", &[]),
            ("wyman_davis2006/quads.vert", light),
            ("wyman_davis2006/quads.frag", light),
            ("wyman_davis2006/gather.comp", &[]),
            ("wyman_davis2006/gather.comp", light),
        ]);
    }
}
