//! Stages several papers share: photon emission into the photon buffer ([`photon_buffer`]), the
//! point splat ([`splat`]) and the compute splat beside it ([`compute_splat`]), the caustic-map
//! and photon-buffer images ([`targets`]). The caustic-map lookup of the final render is
//! `shaders_glsl/common/caustic_lookup.glsl`. Shaders: `shaders_glsl/shared/`.

pub mod compute_splat;
pub mod lists;
pub mod photon_buffer;
pub mod pipelines;
pub mod screen_space;
pub mod settings;
pub mod splat;
pub mod targets;

pub use compute_splat::{ComputeSplat, ListKind, SplatList};
pub use pipelines::CausticPipelines;
pub use settings::{Intersect, PhotonView, SplatKernel, SplatPath, DUMPS};
pub use targets::{CausticTargets, PhotonTargets};

use crate::gpu::GpuMesh;
use vkcore::{Buffer, ImageView, Sampler};

use crate::image_io::{ImageF32, Layer};

/// What every light-space caustic pass may read of the frame besides its own resources: the
/// uniforms, the scene's meshes, the samplers, the spot textures and the receiver positions.
/// The one type of inputs the photon sources, selections and deposits record with (the eye
/// view's deferred refraction and the pool have their own: they read the eye's targets).
pub struct FrameInputs<'a> {
    pub frame_uniforms: &'a Buffer,
    pub caustic_uniforms: &'a Buffer,
    pub meshes: &'a [GpuMesh],
    pub nearest: &'a Sampler,
    /// The spot lights' projected textures (one layer per light) and the linear sampler they
    /// are read with (`common/spot_texture.glsl`): they weight every photon's power.
    pub spot_textures: &'a ImageView,
    pub linear: &'a Sampler,
    /// Every light's receiver positions (layer per light: where photons land).
    pub receiver_positions: &'a ImageView,
}

/// The eye's view as the eye render made it this frame, for deposits into it (Wyman & Davis
/// 2006's eye-space techniques).
#[derive(Clone, Copy)]
pub struct EyeView<'a> {
    pub view_proj: glam::Mat4,
    pub eye: glam::Vec3,
    /// The eye's geometry buffer (first diffuse surface: world position, w = 1 on a surface;
    /// normal; albedo) and its radiance, to which the caustics are added.
    pub position: &'a ImageView,
    pub normal: &'a ImageView,
    pub albedo: &'a ImageView,
    pub background: &'a ImageView,
}

/// What every caustic pass of a light records with: the technique's pipelines, the caustic-map
/// and photon-buffer targets, and the inputs.
#[derive(Clone, Copy)]
pub struct CausticPasses<'a> {
    pub pipelines: &'a CausticPipelines,
    pub targets: &'a CausticTargets,
    pub photons: &'a PhotonTargets,
    pub inputs: &'a FrameInputs<'a>,
}

/// One light's part of a light-space dump (`--dump`), as the stage that owns the buffer read
/// it after the light's passes. One set of light-space buffers serves every light in turn, so
/// a dump is read light by light and put together by `super::stages`.
pub enum LightDump {
    /// An image of this light: its layers become `light<l>` (the unnamed one) and
    /// `light<l>.<name>`, beside the other lights' in one image of the same size.
    Image(ImageF32),
    /// Lists of records (`channels.len()` values each), named as layers under `light<l>.` (an
    /// empty name: `light<l>` itself), laid out over all lights by [`records_image`].
    Records { channels: &'static [&'static str], lists: Vec<(String, Vec<Vec<f32>>)> },
}

/// Lists of records as one image for the dumps: a record (of `channels.len()` values) per pixel
/// in row-major order, zeros after the list's end, in an image just large enough for the
/// longest list; one layer per (name, list).
pub(crate) fn records_image(lists: Vec<(String, Vec<Vec<f32>>)>, channels: &[&str]) -> ImageF32 {
    let longest = lists.iter().map(|(_, l)| l.len()).max().unwrap_or(0).max(1);
    let w = (longest as f64).sqrt().ceil() as usize;
    let h = longest.div_ceil(w);
    let nc = channels.len();
    let layers = lists
        .into_iter()
        .map(|(name, records)| {
            let mut data = vec![0.0f32; w * h * nc];
            for (i, r) in records.iter().enumerate() {
                data[i * nc..(i + 1) * nc].copy_from_slice(r);
            }
            Layer::new(Some(&name), channels, data)
        })
        .collect();
    ImageF32 { width: w as u32, height: h as u32, layers }
}
