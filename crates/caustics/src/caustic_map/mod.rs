//! Caustic maps: Shah et al.'s caustics mapping (refractive vertex grid, rayGeo, point splats)
//! and the Wyman & Davis 2006 photon buffer, splatted into a physically scaled light-space
//! caustic map (one array layer per light). Techniques:
//! - `shah`: a photon per light-space texel of the specular objects, Shah's iterative
//!   ray/receiver intersection, point splats;
//! - `shah-vertex`: a photon per vertex of the specular meshes (Shah's original first pass);
//! - `wd-points`: the Wyman & Davis photon buffer splatted as points, with their search of the
//!   light's render of the first diffuse surface;
//! - `hcm`: Wyman 2008's hierarchical caustic maps over the `wd-points` photon buffer: only
//!   valid photons (or clusters of converging ones) are splatted (see [`hierarchy`]).
//!
//! Each technique splats as points (the papers' path) or, with `splat_path = compute`, with a
//! compute shader that gives the same map (see [`compute_splat`]).
//!
//! Every technique writes power (W) into caustic-map texels; `common/caustic_lookup.glsl` turns
//! that into irradiance with the texel's area on the receiver (Wyman & Davis 2006, Eq. 5-8).

pub mod compute_splat;
pub mod gpu;
pub mod hierarchy;
mod passes;
pub mod photon_copy;
mod pipelines;
pub mod splat_footprints;
mod targets;

pub use compute_splat::ComputeSplat;
pub use passes::{record_caustics, record_cleared, record_light_space, CausticFrame, CausticInputs};
pub use photon_copy::{CopyType, PhotonCopy, COPY_TYPES};
pub use pipelines::CausticPipelines;
pub use targets::{CausticTargets, PhotonTargets};

use crate::image_io::{ImageF32, Layer};
use crate::scene::CausticSettings;

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

/// Photons the technique emits per light (for tables; hardware independent).
pub fn photons_per_light(settings: &CausticSettings, specular_vertices: u32) -> u64 {
    match settings.technique.as_str() {
        "none" => 0,
        "shah-vertex" => specular_vertices as u64,
        _ => settings.photons as u64 * settings.photons as u64,
    }
}
