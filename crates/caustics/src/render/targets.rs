//! Images of the eye render and the views passes use.

use crate::gpu::formats::{COLOR, DEPTH, DISTANCE};
use crate::gpu::setup::SPOT_TEXTURE_SIZE;
pub use crate::gpu::Target;
use crate::scene::Scene;
use anyhow::Result;
use vkcore::{Context, Image, ImageDesc, ImageView, ViewKind};

/// Shadow maps of every light: distances in layers 6l..6l+6, plus per-light layer views.
pub struct ShadowMaps {
    pub distance: Target,
    /// Kept alive for the per-light depth views.
    #[allow(dead_code)]
    pub depth: Image,
    /// Per light: (distance view, depth view) over its six layers.
    pub per_light: Vec<(ImageView, ImageView)>,
    pub lights: u32,
}

pub struct EyeTargets {
    pub shadow: ShadowMaps,
    pub spot_textures: Target,
    pub background: Target,
    pub position: Target,
    pub normal: Target,
    /// rgb diffuse albedo, a = 1 where a surface was hit (eye-space caustics shade with it).
    pub albedo: Target,
    pub depth: Target,
    pub back_faces: Target,
    pub back_depth: Target,
    pub surface: Target,
    pub final_image: Target,
    /// (E/E0, E and mean E0, caustic E) over the receiver grid.
    pub receiver: Option<(Target, Target, Target)>,
    /// What the receiver map binds for the receiver view's caustics when there are none (1x1).
    pub no_receiver_view: Target,
}

impl EyeTargets {
    /// The eye-sized images below: COLOR (background, position, normal, albedo, back faces,
    /// surface, final) and DEPTH (depth, back-face depth), counted by `memory.rs`.
    pub const COLOR_IMAGES: u64 = 7;
    pub const DEPTH_IMAGES: u64 = 2;

    pub fn new(ctx: &Context, scene: &Scene) -> Result<EyeTargets> {
        let (w, h) = (scene.camera.width, scene.camera.height);
        let lights = scene.lights.len().clamp(1, crate::gpu::MAX_LIGHTS) as u32;
        let res = scene.render.shadow_map_resolution;
        let distance = Target::array(ctx, ImageDesc::new_2d("shadow_map", DISTANCE, res, res).layers(6 * lights))?;
        let depth = Image::new(ctx, ImageDesc::new_2d("shadow_map depth", DEPTH, res, res).layers(6 * lights))?;
        let per_light = (0..lights)
            .map(|l| {
                let layers = 6 * l..6 * l + 6;
                Ok((
                    distance.image.view(ViewKind::D2Array, 0..1, layers.clone())?,
                    depth.view(ViewKind::D2Array, 0..1, layers)?,
                ))
            })
            .collect::<Result<Vec<_>>>()?;
        let receiver = match &scene.receiver_map {
            Some(r) => Some((
                Target::color(ctx, "receiver E/E0", r.resolution, r.resolution)?,
                Target::color(ctx, "receiver E", r.resolution, r.resolution)?,
                Target::color(ctx, "receiver caustic E", r.resolution, r.resolution)?,
            )),
            None => None,
        };
        Ok(EyeTargets {
            shadow: ShadowMaps { distance, depth, per_light, lights },
            spot_textures: Target::array(
                ctx,
                ImageDesc::new_2d("spot textures", COLOR, SPOT_TEXTURE_SIZE, SPOT_TEXTURE_SIZE).layers(lights),
            )?,
            background: Target::color(ctx, "background radiance", w, h)?,
            position: Target::color(ctx, "eye position", w, h)?,
            normal: Target::color(ctx, "eye normal", w, h)?,
            albedo: Target::color(ctx, "eye albedo", w, h)?,
            depth: Target::depth(ctx, "eye depth", w, h)?,
            back_faces: Target::color(ctx, "refractor back faces", w, h)?,
            back_depth: Target::depth(ctx, "refractor back-face depth", w, h)?,
            surface: Target::color(ctx, "refractor front faces", w, h)?,
            final_image: Target::color(ctx, "final", w, h)?,
            receiver,
            no_receiver_view: Target::array(ctx, ImageDesc::new_2d("no receiver view", COLOR, 1, 1))?,
        })
    }
}
