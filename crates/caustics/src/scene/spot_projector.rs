//! A spot light's cone and projected texture as one emission function, shared by the renderer
//! (which uploads the same resampled texels and samples them in `spot_emission`,
//! `shaders_glsl/common/spot_texture.glsl`, for the direct light and every photon) and the exact
//! CPU reference (which samples them here the same way): the texture shapes the direct light
//! and the photons alike, as Wyman & Nichols 2009's elephant under a textured spotlight
//! (Fig. 12).
//!
//! The texture is resampled (nearest) to [`SIZE`]² texels; a direction `d` inside the cone maps
//! to `uv = (d·u, d·v) / (d·dir) · ½ + ½`, with `u`, `v` the cone's side axes over
//! tan(half-angle), and is filtered bilinearly with clamp-to-edge, as the renderer's linear
//! sampler does.

use super::{Light, LightKind};
use anyhow::{Context as _, Result};
use glam::{DVec3, Vec3};

/// The side of the resampled texture.
pub const SIZE: u32 = 256;

/// A spot light's emission per direction (RGB factor on its intensity).
#[derive(Debug, Clone)]
pub struct SpotProjector {
    pub direction: Vec3,
    /// The cone's side axes, over tan(half-angle): `uv = (d·u, d·v) / (d·dir)` in [-1, 1].
    pub u: Vec3,
    pub v: Vec3,
    pub cos_cone: f32,
    /// SIZE² RGBA texels, row 0 first; None when the spot has no texture (white).
    pub texels: Option<Vec<f32>>,
}

impl SpotProjector {
    /// The projector of `light`; None for a point light.
    pub fn of(light: &Light) -> Result<Option<SpotProjector>> {
        let LightKind::Spot { direction, cone_angle_deg, texture } = &light.kind else { return Ok(None) };
        let (u, v, cos_cone) = cone_axes(*direction, *cone_angle_deg);
        let texels = match texture {
            Some(path) => Some(resample(path)?),
            None => None,
        };
        Ok(Some(SpotProjector { direction: *direction, u, v, cos_cone, texels }))
    }

    /// The RGB factor on the light's intensity towards unit direction `d`: 0 outside the cone,
    /// the texture's colour inside it (1 without a texture).
    pub fn emission(&self, d: DVec3) -> [f64; 3] {
        let c = d.dot(self.direction.as_dvec3());
        if c < self.cos_cone as f64 {
            return [0.0; 3];
        }
        let Some(texels) = &self.texels else { return [1.0; 3] };
        let uv = [d.dot(self.u.as_dvec3()) / c * 0.5 + 0.5, d.dot(self.v.as_dvec3()) / c * 0.5 + 0.5];
        bilinear(texels, uv)
    }
}

/// A spot cone's side axes over tan(half-angle) (`u`, `v`: `uv = (d·u, d·v) / (d·dir)` in
/// [-1, 1] across the cone) and the cosine of its half-angle.
pub fn cone_axes(direction: Vec3, cone_angle_deg: f32) -> (Vec3, Vec3, f32) {
    let half = cone_angle_deg.to_radians();
    let helper = if direction.y.abs() > 0.9 { Vec3::Z } else { Vec3::Y };
    let right = direction.cross(helper).normalize();
    let up = right.cross(direction).normalize();
    let t = half.tan().max(1e-4);
    (right / t, up / t, half.cos())
}

/// The PNG at `path` resampled (nearest) to SIZE² RGBA (linear values).
pub fn resample(path: &std::path::Path) -> Result<Vec<f32>> {
    let n = SIZE as usize;
    let (w, h, rgba) =
        crate::image_io::read_png_rgba(path).with_context(|| format!("spot-light texture {}", path.display()))?;
    let mut out = vec![0.0f32; n * n * 4];
    for y in 0..n {
        for x in 0..n {
            let sx = (x * w as usize / n).min(w as usize - 1);
            let sy = (y * h as usize / n).min(h as usize - 1);
            out[(y * n + x) * 4..(y * n + x) * 4 + 4].copy_from_slice(&rgba[(sy * w as usize + sx) * 4..][..4]);
        }
    }
    Ok(out)
}

/// Bilinear filtering of SIZE² RGBA `texels` at `uv` (texel centres at (i + ½) / SIZE),
/// clamped to the edge.
fn bilinear(texels: &[f32], uv: [f64; 2]) -> [f64; 3] {
    let n = SIZE as i64;
    let (x, y) = (uv[0] * n as f64 - 0.5, uv[1] * n as f64 - 0.5);
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let at = |i: i64, j: i64, c: usize| texels[((j.clamp(0, n - 1) * n + i.clamp(0, n - 1)) * 4) as usize + c] as f64;
    let (i, j) = (x0 as i64, y0 as i64);
    std::array::from_fn(|c| {
        let top = at(i, j, c) * (1.0 - fx) + at(i + 1, j, c) * fx;
        let bottom = at(i, j + 1, c) * (1.0 - fx) + at(i + 1, j + 1, c) * fx;
        top * (1.0 - fy) + bottom * fy
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spot(texels: Option<Vec<f32>>) -> SpotProjector {
        let light = Light {
            position: Vec3::ZERO,
            intensity: Vec3::ONE,
            kind: LightKind::Spot { direction: Vec3::NEG_Y, cone_angle_deg: 30.0, texture: None },
        };
        SpotProjector { texels, ..SpotProjector::of(&light).expect("spot").expect("a projector") }
    }

    #[test]
    fn the_cone_cuts_and_the_axis_reads_the_texture_centre() {
        let n = SIZE as usize;
        // Left half red, right half blue (in u).
        let texels: Vec<f32> =
            (0..n * n).flat_map(|k| if k % n < n / 2 { [1.0, 0.0, 0.0, 1.0] } else { [0.0, 0.0, 1.0, 1.0] }).collect();
        let s = spot(Some(texels));
        assert_eq!(s.emission(DVec3::X), [0.0; 3], "outside the cone");
        assert_eq!(spot(None).emission(DVec3::NEG_Y), [1.0; 3], "no texture: white");
        // Straight down: between the two halves, bilinear gives half of each.
        let axis = s.emission(DVec3::NEG_Y);
        assert!((axis[0] - 0.5).abs() < 1e-9 && (axis[2] - 0.5).abs() < 1e-9, "{axis:?}");
        // 20 degrees off the axis towards ±u: fully one colour.
        let side = |sign: f64| {
            let u = s.u.as_dvec3().normalize() * sign;
            (DVec3::NEG_Y * 20f64.to_radians().cos() + u * 20f64.to_radians().sin()).normalize()
        };
        assert_eq!(s.emission(side(-1.0)), [1.0, 0.0, 0.0]);
        assert_eq!(s.emission(side(1.0)), [0.0, 0.0, 1.0]);
    }
}
