//! Screen-space photon mapping (Kim 2019, "Caustics using screen-space photon mapping", Ray
//! Tracing Gems ch. 30): photons drawn into a view's pixels, then their density estimated on the
//! view's geometry buffer by an edge-aware filter (`shaders_glsl/shared/screen_space_filter.comp`,
//! which states the kernel and the edge tests). Two passes per light: each photon pixel's power
//! divided by its kernel's support (so the filter keeps the photons' power exactly), then the
//! gather. `photon-trace --deposit screen-space` deposits its exact photons this way into
//! Wyman & Davis 2006's eye-space views, the eye's and the receiver view (the instrument the
//! receiver map reads), beside `wd-eye-points`, its 2006 ancestor (each pixel its own photons).
//!
//! Each photon pixel's kernel grows, as photon mapping's k nearest photons, to the least radius
//! whose joined pixels hold [`PHOTONS_PER_KERNEL`] photons, at most [`MAX_RADIUS`] pixels. The
//! constants are ours (Kim's chapter tunes its filter per scene): a depth edge where a pixel
//! lies more than 1% of its distance to the eye (plus 1 mm) off the other's tangent plane, a
//! crease past 25 degrees.

use crate::gpu::Stage;
use anyhow::Result;
use vkcore::{push_constants, Bind, Context, Frame, ImageView, Pipeline, Sampler, ShaderCompiler};

/// The largest kernel radius in pixels (`MAX_RADIUS` in the shader bounds it).
pub const MAX_RADIUS: u32 = 6;
/// The photons a kernel's radius is grown to hold.
pub const PHOTONS_PER_KERNEL: f32 = 16.0;
/// The depth-edge test's tolerance in the eye's view: 1% of the distance to the eye, plus 1 mm.
pub const EYE_TOLERANCE: [f32; 2] = [0.01, 1e-3];
/// The crease test: normals more than 25 degrees apart are not joined.
pub const CREASE_DEGREES: f32 = 25.0;

push_constants! {
    /// The edge-aware filter's (`shaders_glsl/shared/screen_space_filter.comp`).
    pub struct ScreenSpaceConstants {
        /// xyz: the view's eye; w: 1 for an orthographic view.
        pub eye: [f32; 4],
        /// x: of the distance to the eye, y: metres (the depth-edge test).
        pub tolerance: [f32; 4],
        /// The largest kernel radius in pixels.
        pub max_radius: u32,
        /// The photon layer this light's photons were drawn into.
        pub slot: u32,
        /// Lights after the first add to the view's caustic.
        pub light: u32,
        /// The crease test's least cosine between normals.
        pub cos_normal: f32,
        /// The photons a kernel's radius is grown to hold.
        pub photons_per_kernel: f32,
    }
}

/// A view as the filter reads and writes it.
pub struct FilterView<'a> {
    /// The pass's name after the stage (`eye`, `receiver`).
    pub view: &'a str,
    /// The view's photons (a 2D array: rgb power, a: photons), its geometry buffer (world
    /// position with w = 1 on a surface; normal), the photons over their support (a scratch
    /// image of the view's size) and the caustic irradiance it writes.
    pub photons: &'a ImageView,
    pub position: &'a ImageView,
    pub normal: &'a ImageView,
    pub normalized: &'a ImageView,
    pub caustic: &'a ImageView,
    pub size: (u32, u32),
    /// xyz: the view's eye; w: 1 for an orthographic view (no distance to the eye), as the
    /// view's other passes have it (`ImageSpaceConstants::eye`).
    pub eye: [f32; 4],
    /// The depth-edge tolerance (x: of the distance to the eye, y: metres).
    pub tolerance: [f32; 2],
}

/// The filter's two pipelines.
pub struct ScreenSpaceFilter {
    normalize: Pipeline,
    gather: Pipeline,
}

impl ScreenSpaceFilter {
    pub fn new(ctx: &Context, sh: &ShaderCompiler) -> Result<ScreenSpaceFilter> {
        let file = "shared/screen_space_filter.comp";
        Ok(ScreenSpaceFilter {
            normalize: Pipeline::compute(ctx, "screen_space.normalize", &sh.compile(file, &[("NORMALIZE", "1")])?)?,
            gather: Pipeline::compute(ctx, "screen_space.filter", &sh.compile(file, &[])?)?,
        })
    }

    /// Light `l`'s photons (drawn into layer `slot` of `v.photons`) filtered into `v.caustic`
    /// (the lights after the first add to it).
    pub fn record(&self, f: &mut Frame, nearest: &Sampler, v: &FilterView, l: u32, slot: u32) -> Result<()> {
        let k = ScreenSpaceConstants {
            eye: v.eye,
            tolerance: [v.tolerance[0], v.tolerance[1], 0.0, 0.0],
            max_radius: MAX_RADIUS,
            slot,
            light: l,
            cos_normal: CREASE_DEGREES.to_radians().cos(),
            photons_per_kernel: PHOTONS_PER_KERNEL,
        };
        let groups = (v.size.0.div_ceil(8), v.size.1.div_ceil(8));
        let geometry = [
            ("photons", Bind::Sampled(v.photons, nearest)),
            ("view_position", Bind::Sampled(v.position, nearest)),
            ("view_normal", Bind::Sampled(v.normal, nearest)),
        ];
        let mut binds = geometry.to_vec();
        binds.push(("normalized", Bind::Storage(v.normalized)));
        let name = Stage::ScreenSpaceNormalize.pass().view(v.view).light(l);
        f.pass(&name).bind(&self.normalize, binds).record(|cmd| {
            cmd.push(&k)?;
            cmd.dispatch(groups.0, groups.1, 1);
            Ok(())
        })?;
        let mut binds = geometry.to_vec();
        binds.push(("normalized", Bind::Sampled(v.normalized, nearest)));
        binds.push(("gathered", Bind::Storage(v.caustic)));
        let name = Stage::ScreenSpaceFilter.pass().view(v.view).light(l);
        f.pass(&name).bind(&self.gather, binds).record(|cmd| {
            cmd.push(&k)?;
            cmd.dispatch(groups.0, groups.1, 1);
            Ok(())
        })?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::push::check;

    #[test]
    fn screen_space_constants() {
        check::<ScreenSpaceConstants>(&[
            ("shared/screen_space_filter.comp", &[("NORMALIZE", "1")]),
            ("shared/screen_space_filter.comp", &[]),
        ]);
    }
}
