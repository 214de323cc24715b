//! The views the eye-space techniques draw their photons into (Wyman & Davis 2006 Sec. 3.2):
//! the eye's, and for the receiver map an orthographic view straight down on the receiver plane
//! (`receiver_view.comp`), so that eye-space variants are checked against the same exact
//! reference as the light-space ones. A view holds its eye-space photon buffer (power and count
//! per pixel, history layers for the temporal filter), the photons' directions, and the caustic
//! irradiance it resolves to.

use super::push::ImageSpaceConstants;
use crate::gpu::formats::COLOR;
use crate::gpu::Target;
use crate::scene::Scene;
use crate::techniques::shared::CausticPasses;
use anyhow::Result;
use glam::{Mat4, Vec3, Vec4};
use vkcore::{Bind, Context, ImageDesc, ImageView, Named, Pipeline, ViewKind};

/// What the photons' points and quads read first (`photons.vert`, `quads.vert`): the uniforms,
/// the photon buffer and the view's geometry (world position and normal), the normals only
/// where `pipeline` declares them (light space, `LIGHT_SPACE`, reads none).
pub fn photon_view_binds<'a>(
    c: &CausticPasses<'a>,
    pipeline: &Pipeline,
    geometry: (&'a ImageView, &'a ImageView),
) -> Vec<Named<'a>> {
    let (pt, inp) = (c.photons, c.inputs);
    let mut binds = vec![
        ("frame", Bind::Uniform(inp.frame_uniforms)),
        ("caustics", Bind::Uniform(inp.caustic_uniforms)),
        ("photon_position", Bind::Sampled(&pt.position.view, inp.nearest)),
        ("photon_direction", Bind::Sampled(&pt.direction.view, inp.nearest)),
        ("photon_power", Bind::Sampled(&pt.power.view, inp.nearest)),
        ("view_position", Bind::Sampled(geometry.0, inp.nearest)),
    ];
    if pipeline.declares("view_normal") {
        binds.push(("view_normal", Bind::Sampled(geometry.1, inp.nearest)));
    }
    binds
}

/// Photons, directions and caustic irradiance of one view.
pub struct ViewBuffers {
    /// rgb power (W), a: photons; one layer per history frame (per light and frame in light space).
    pub photons: Target,
    /// Each history layer as a 2D view (a colour attachment).
    pub layers: Vec<ImageView>,
    /// xyz: sum of m * (-direction), w: sum of m * cos(direct), m the mean power (this frame).
    pub directions: Target,
    /// rgb caustic irradiance (W/m^2), a: photons in the neighbourhood (eye space only).
    pub caustic: Option<Target>,
    /// Screen-space photon mapping's photons over their kernel's support (rgb W/m^2, a:
    /// photons; `techniques::shared::screen_space`), None for the others.
    pub normalized: Option<Target>,
    pub width: u32,
    pub height: u32,
}

impl ViewBuffers {
    pub fn new(ctx: &Context, name: &str, (w, h): (u32, u32), layers: u32, caustic: bool) -> Result<ViewBuffers> {
        let photons = Target::array(ctx, ImageDesc::new_2d(&format!("{name} photons"), COLOR, w, h).layers(layers))?;
        let views =
            (0..layers).map(|k| Ok(photons.image.view(ViewKind::D2, 0..1, k..k + 1)?)).collect::<Result<_>>()?;
        let caustic = match caustic {
            true => Some(Target::array(ctx, ImageDesc::new_2d(&format!("{name} caustic"), COLOR, w, h))?),
            false => None,
        };
        Ok(ViewBuffers {
            photons,
            layers: views,
            directions: Target::color(ctx, &format!("{name} photon directions"), w, h)?,
            caustic,
            normalized: None,
            width: w,
            height: h,
        })
    }

    /// With `filtered`, the scratch image of screen-space photon mapping's filter.
    pub fn filtered(mut self, ctx: &Context, name: &str, filtered: bool) -> Result<ViewBuffers> {
        if filtered {
            let name = format!("{name} normalized photons");
            self.normalized = Some(Target::color(ctx, &name, self.width, self.height)?);
        }
        Ok(self)
    }
}

/// The orthographic view straight down on the receiver plane: (x0..x1, z0..z1) to NDC, row 0
/// at z0 (the receiver map's texel (i, j) is pixel (i, j)).
pub fn receiver_view_proj(scene: &Scene) -> Option<Mat4> {
    let r = scene.receiver_map.as_ref()?;
    let ([x0, x1], [z0, z1]) = (r.x_range, r.z_range);
    let (sx, sz) = (2.0 / (x1 - x0), 2.0 / (z1 - z0));
    Some(Mat4::from_cols(
        Vec4::new(sx, 0.0, 0.0, 0.0),
        Vec4::ZERO,
        Vec4::new(0.0, sz, 0.0, 0.0),
        Vec4::new(-1.0 - x0 * sx, -1.0 - z0 * sz, 0.5, 1.0),
    ))
}

/// The push constants of a pass in the eye's view (`ortho`: false) or the receiver view; the
/// pass sets its own light, slot and gather fields.
pub fn view_constants(view_proj: Mat4, eye: Vec3, tolerance: [f32; 2], ortho: bool) -> ImageSpaceConstants {
    ImageSpaceConstants {
        view_proj: view_proj.to_cols_array(),
        tolerance: [tolerance[0], tolerance[1], 0.0, 0.0],
        eye: eye.extend(if ortho { 1.0 } else { 0.0 }).to_array(),
        ..Default::default()
    }
}

/// How far from the surface a pixel sees a photon may land and still be on it: in the eye's
/// view 2% of the distance to the eye (as the caustic-map lookup's test), in the receiver view
/// one and a half texels.
pub fn tolerance(scene: &Scene, ortho: bool) -> [f32; 2] {
    match (ortho, &scene.receiver_map) {
        (true, Some(r)) => {
            let texel =
                ((r.x_range[1] - r.x_range[0]).abs()).max((r.z_range[1] - r.z_range[0]).abs()) / r.resolution as f32;
            [0.0, 1.5 * texel]
        }
        _ => [0.02, 1e-3],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_receiver_view_puts_texel_centres_on_pixel_centres() {
        let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/sphere_oblique.toml"));
        let scene = Scene::load(path).expect("shipped scene");
        let r = scene.receiver_map.clone().expect("a receiver map");
        let m = receiver_view_proj(&scene).expect("a view");
        let n = r.resolution as f32;
        for (i, j) in [(0u32, 0u32), (17, 200), (255, 255)] {
            let x = r.x_range[0] + (i as f32 + 0.5) * (r.x_range[1] - r.x_range[0]) / n;
            let z = r.z_range[0] + (j as f32 + 0.5) * (r.z_range[1] - r.z_range[0]) / n;
            let clip = m * Vec4::new(x, r.plane_y + 0.3, z, 1.0);
            let px = (clip.x / clip.w * 0.5 + 0.5) * n;
            let py = (clip.y / clip.w * 0.5 + 0.5) * n;
            assert!((px - (i as f32 + 0.5)).abs() < 1e-3 && (py - (j as f32 + 0.5)).abs() < 1e-3, "{i},{j}: {px},{py}");
        }
    }
}
