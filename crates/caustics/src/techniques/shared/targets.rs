//! Images of the caustic techniques: per-light receiver positions and caustic map layers, and the
//! photon buffer (reused light after light).

use super::settings::{PHOTON_BACK_FACES, PHOTON_BUFFER, PHOTON_FOOTPRINTS};
use crate::dump::Dump;
pub use crate::gpu::formats::{COLOR, DEPTH};
use crate::gpu::{Target, MAX_LIGHTS};
use crate::image_io::ImageF32;
use crate::scene::Scene;
use anyhow::Result;
use vkcore::{Buffer, Context, Image, ImageDesc, ImageView, Memory, ViewKind};

/// What the eye passes read: always present (1x1 when the technique is `none`).
pub struct CausticTargets {
    /// Power (W) per texel, rgb, and photon count in a; one layer per light.
    pub caustic_map: Target,
    /// World position (xyz, w = 1 if a receiver) of the first diffuse surface per texel.
    pub receiver_positions: Target,
    pub receiver_depth: Image,
    /// Caustic-map layers per light (4 for the multi-resolution map, else 1).
    pub levels: u32,
    /// Per light: (caustic-map layers view, receiver-positions layer view, depth layer view).
    pub per_light: Vec<(ImageView, ImageView, ImageView)>,
    /// `photon-trace`'s direct deposit (`deposit = "receiver-map"`): per receiver-map texel, the
    /// power (W, rgb) of the photons that landed in it and their count, which the receiver map
    /// reads; one unused texel otherwise.
    pub receiver_flux: Buffer,
}

impl CausticTargets {
    pub fn new(ctx: &Context, scene: &Scene, active: bool) -> Result<CausticTargets> {
        let m = if active { scene.caustics.caustic_map_resolution } else { 1 };
        let lights = scene.lights.len().clamp(1, MAX_LIGHTS) as u32;
        // One layer per light, or per light and level of the multi-resolution map.
        let levels = if active { scene.caustics.caustic_levels() } else { 1 };
        let caustic_map = Target::array(ctx, ImageDesc::new_2d("caustic_map", COLOR, m, m).layers(lights * levels))?;
        let receiver_positions =
            Target::array(ctx, ImageDesc::new_2d("receiver_positions", COLOR, m, m).layers(lights))?;
        let receiver_depth = Image::new(ctx, ImageDesc::new_2d("receiver depth", DEPTH, m, m).layers(lights))?;
        let per_light = (0..lights)
            .map(|l| {
                Ok((
                    caustic_map.image.view(ViewKind::D2Array, 0..1, l * levels..(l + 1) * levels)?,
                    receiver_positions.image.view(ViewKind::D2, 0..1, l..l + 1)?,
                    receiver_depth.view(ViewKind::D2, 0..1, l..l + 1)?,
                ))
            })
            .collect::<Result<Vec<_>>>()?;
        let receiver_texels = match &scene.receiver_map {
            Some(spec) if active && scene.caustics.receiver_deposit() => {
                spec.resolution as u64 * spec.resolution as u64
            }
            _ => 1,
        };
        let receiver_flux = Buffer::new(ctx, "photon_trace receiver flux", receiver_texels * 16, Memory::Gpu)?;
        Ok(CausticTargets { caustic_map, receiver_positions, receiver_depth, levels, per_light, receiver_flux })
    }
}

/// The photon buffer (Wyman & Davis 2006 Fig. 1 and 3): where each photon lands, its incident
/// direction and its power; plus the refractors' back faces seen from the light.
pub struct PhotonTargets {
    pub position: Target,
    pub direction: Target,
    pub power: Target,
    pub back_faces: Target,
    pub depth: Target,
    /// `photon-trace --differentials`: each photon's footprint vectors (`PHOTON_FOOTPRINTS`);
    /// 1 x 1 otherwise.
    pub footprint_u: Target,
    pub footprint_v: Target,
    pub width: u32,
}

impl PhotonTargets {
    /// `n` x `n` light-space photons; `photon_texels` is the photon texture's side (N for the
    /// photon buffer, ceil(sqrt(vertices)) for vertex photons).
    pub fn new(ctx: &Context, n: u32, photon_texels: u32, footprints: bool) -> Result<PhotonTargets> {
        let w = photon_texels.max(1);
        let c = |name: &str, s: u32| Target::new(ctx, ImageDesc::new_2d(name, COLOR, s, s));
        Ok(PhotonTargets {
            position: c("photon position", w)?,
            direction: c("photon direction", w)?,
            power: c("photon power", w)?,
            back_faces: c("light-space back faces", n)?,
            depth: Target::new(ctx, ImageDesc::new_2d("light-space depth", DEPTH, n, n))?,
            footprint_u: c("photon footprint u", if footprints { w } else { 1 })?,
            footprint_v: c("photon footprint v", if footprints { w } else { 1 })?,
            width: w,
        })
    }

    /// The photon buffer or its back faces (`d`) as they are now: the light that rendered
    /// them last. Layers are unprefixed (`super::super::stages` names them per light).
    pub fn dump(&self, ctx: &Context, d: &'static Dump) -> Result<ImageF32> {
        let xyzw = [0, 1, 2, 3];
        Ok(match d {
            d if d == &PHOTON_BACK_FACES => self.back_faces.as_image(vec![self.back_faces.read_layer(
                ctx,
                0,
                None,
                &["NX", "NY", "NZ", "distance"],
                &xyzw,
            )?]),
            d if d == &PHOTON_BUFFER => self.position.as_image(vec![
                self.position.read_layer(ctx, 0, Some("position"), &["X", "Y", "Z", "valid"], &xyzw)?,
                self.direction.read_layer(ctx, 0, Some("direction"), &["X", "Y", "Z", "W"], &xyzw)?,
                self.power.read_layer(ctx, 0, Some("power"), &["R", "G", "B"], &[0, 1, 2])?,
            ]),
            d if d == &PHOTON_FOOTPRINTS => self.footprint_u.as_image(vec![
                self.footprint_u.read_layer(ctx, 0, Some("u"), &["X", "Y", "Z"], &[0, 1, 2])?,
                self.footprint_v.read_layer(ctx, 0, Some("v"), &["X", "Y", "Z"], &[0, 1, 2])?,
            ]),
            other => anyhow::bail!("the photon buffer has no dump `{other}`"),
        })
    }
}
