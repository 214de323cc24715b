//! The caustic techniques' uniforms (twin of `shaders_glsl/common/caustics.glsl`) and the two
//! light-space frusta per light: the photon buffer's, tight around the specular objects, and
//! the caustic map's, wide enough to hold where the photons land.

use super::shared::{Intersect, PhotonView, SplatKernel};
use crate::gpu::setup::perspective;
use crate::gpu::MAX_LIGHTS;
use crate::scene::{Light, LightKind, MaterialKind, Scene};
use crate::techniques::shah2007::settings::{Lookup, Refractions};
use crate::techniques::wyman2008::settings::VaryingRadius;
use crate::techniques::wyman_davis2006::{self, settings::Reflection};
use crate::techniques::CausticSettings;
use anyhow::Result;
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable, Debug)]
pub struct CausticLightUniforms {
    pub photon_view_proj: [f32; 16],
    pub caustic_view_proj: [f32; 16],
    pub photon_plane: [f32; 4],
    pub caustic_plane: [f32; 4],
    pub axis: [f32; 4],
    pub position: [f32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable, Debug)]
pub struct CausticUniforms {
    pub settings: [u32; 4],
    pub splat: [f32; 4],
    /// x: the y of the plane mirrored photons land on (`reflection = plane`).
    pub background_plane: [f32; 4],
    pub lights: [CausticLightUniforms; MAX_LIGHTS],
}

pub const FLAG_FRESNEL: u32 = 1;
pub const FLAG_WD_DEPTH_SEARCH: u32 = 2;
pub const FLAG_BEAM_AREA: u32 = 4;
pub const FLAG_EYE_SPACE: u32 = 8;
pub const FLAG_REFLECTION_PLANE: u32 = 16;
pub const FLAG_ONE_REFRACTION: u32 = 32;
pub const FLAG_TUTORIAL_LOOKUP: u32 = 64;
pub const FLAG_RECEIVER_FLUX: u32 = 128;

const _: () = assert!(std::mem::size_of::<CausticLightUniforms>() == 2 * 64 + 4 * 16);
const _: () = assert!(std::mem::size_of::<CausticUniforms>() == 48 + MAX_LIGHTS * 192);

/// Bounding sphere of every refractive or reflective object (None if there are none).
pub fn specular_bounds(scene: &Scene) -> Option<(Vec3, f32)> {
    let specular: Vec<_> =
        scene.objects.iter().filter(|o| !matches!(scene.material_of(o).kind, MaterialKind::Diffuse { .. })).collect();
    if specular.is_empty() {
        return None;
    }
    let (lo, hi) = specular
        .iter()
        .map(|o| o.mesh.bounds())
        .fold((Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)), |(a, b), (l, h)| (a.min(l), b.max(h)));
    let centre = 0.5 * (lo + hi);
    let radius =
        specular.iter().flat_map(|o| o.mesh.positions.iter()).map(|p| p.distance(centre)).fold(0.0f32, f32::max);
    Some((centre, radius.max(1e-4)))
}

/// Half-angle (radians) a frustum along `axis` from `light` needs to contain `p`.
fn angle_to(light: Vec3, axis: Vec3, p: Vec3) -> f32 {
    (p - light).normalize_or_zero().dot(axis).clamp(-1.0, 1.0).acos()
}

/// The photon buffer's axis and half field of view (radians) for `light`, by
/// `settings.photon_view` (see [`PhotonView`]), with the specular objects' bounding sphere.
pub fn photon_view(settings: &CausticSettings, light: &Light, centre: Vec3, radius: f32) -> (Vec3, f32) {
    let to_centre = (centre - light.position).normalize_or(Vec3::NEG_Y);
    match settings.photon_view {
        PhotonView::Fitted => {
            let d = light.position.distance(centre);
            (to_centre, ((radius / d).asin() * 1.02).min(1.5))
        }
        PhotonView::FixedFov => {
            let axis = match &light.kind {
                LightKind::Spot { direction, .. } => *direction,
                LightKind::Point => to_centre,
            };
            (axis, 0.5 * settings.photon_fov.to_radians())
        }
        PhotonView::ShadowMap => {
            // The cube face whose direction is nearest the direction to the objects.
            let face = [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z]
                .into_iter()
                .max_by(|a, b| a.dot(to_centre).total_cmp(&b.dot(to_centre)))
                .unwrap_or(Vec3::NEG_Y);
            (face, std::f32::consts::FRAC_PI_4)
        }
    }
}

/// Uniforms for `settings` on `scene`. With technique `none`, zero lights have caustics.
pub fn caustic_uniforms(scene: &Scene, settings: &CausticSettings) -> Result<CausticUniforms> {
    let mut u = CausticUniforms {
        settings: [0; 4],
        splat: [0.0; 4],
        background_plane: [wyman_davis2006::reflection::background_plane(scene), 0.0, 0.0, 0.0],
        lights: [CausticLightUniforms::zeroed(); MAX_LIGHTS],
    };
    let flags = if settings.fresnel { FLAG_FRESNEL } else { 0 }
        | if settings.intersect() == Intersect::WdDepthSearch { FLAG_WD_DEPTH_SEARCH } else { 0 }
        | if settings.varying_radius == VaryingRadius::BeamArea { FLAG_BEAM_AREA } else { 0 }
        | if settings.eye_space() { FLAG_EYE_SPACE } else { 0 }
        | if settings.reflection == Reflection::Plane { FLAG_REFLECTION_PLANE } else { 0 }
        | if settings.refractions == Refractions::One { FLAG_ONE_REFRACTION } else { 0 }
        | if settings.lookup == Lookup::Tutorial { FLAG_TUTORIAL_LOOKUP } else { 0 }
        | if settings.receiver_deposit() { FLAG_RECEIVER_FLUX } else { 0 };
    u.settings = [0, settings.photons, settings.iterations, flags];
    u.splat = [
        settings.splat_radius,
        if settings.splat_kernel == SplatKernel::Box { 1.0 } else { 0.0 },
        settings.back_face_iterations as f32,
        // Splat sizes (Wyman 2008 Sec. 3.3, Fig. 7).
        settings.splat.uniform(settings.technique),
    ];
    let Some((centre, radius)) = specular_bounds(scene) else { return Ok(u) };
    if !settings.technique.has_caustics() {
        return Ok(u);
    }
    let (lo, hi) = scene.bounds();
    let diag = (hi - lo).length();
    for (l, light) in scene.lights.iter().take(MAX_LIGHTS).enumerate() {
        let d = light.position.distance(centre);
        if d <= radius * 1.01 {
            return Err(crate::input_error!(
                "{}: light {l} at {} is inside the bounding sphere of the specular objects (centre {}, radius {radius}); the light-space caustic techniques need the light outside it",
                scene.path.display(),
                point(light.position),
                point(centre)
            )
            .into());
        }
        let (axis, photon_half) = photon_view(settings, light, centre, radius);
        // The caustic map holds wherever photons may land: the receiver map if there is one
        // (or the rectangle that stands for it, `Scene::caustic_frame`), else three times the
        // photon cone, capped at 80 degrees.
        let mut caustic_half = photon_half * 1.2;
        match scene.framing_rectangle() {
            Some(r) => {
                for x in r.x_range {
                    for z in r.z_range {
                        caustic_half =
                            caustic_half.max(angle_to(light.position, axis, Vec3::new(x, r.plane_y, z)) * 1.05);
                    }
                }
            }
            None => caustic_half = caustic_half.max(3.0 * photon_half),
        }
        let caustic_half = caustic_half.min(80f32.to_radians());
        let up = if axis.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y };
        // (The fitted view looks at the centre itself: the same matrix, bit for bit, as before
        // the photon view could be chosen.)
        let target = if settings.photon_view == PhotonView::Fitted { centre } else { light.position + axis };
        let view = Mat4::look_at_rh(light.position, target, up);
        let far = d + diag;
        // The specular objects' nearest depth along the axis, halved (any view holds them in front).
        let photon_near = ((centre - light.position).dot(axis) - radius).max(far * 1e-3) * 0.5;
        let caustic_near = (far * 1e-4).max(1e-3);
        let photon_proj = perspective(2.0 * photon_half, 1.0, photon_near, far);
        let caustic_proj = perspective(2.0 * caustic_half, 1.0, caustic_near, far);
        let n = settings.photons as f32;
        let m = settings.caustic_map_resolution as f32;
        let (tp, tc) = (photon_half.tan(), caustic_half.tan());
        u.lights[l] = CausticLightUniforms {
            photon_view_proj: (photon_proj * view).to_cols_array(),
            caustic_view_proj: (caustic_proj * view).to_cols_array(),
            photon_plane: [tp, n, (2.0 * tp / n).powi(2), 0.0],
            caustic_plane: [tc, m, (2.0 * tc / m).powi(2), 0.0],
            axis: axis.extend(0.0).to_array(),
            position: light.position.extend(1.0).to_array(),
        };
    }
    u.settings[0] = scene.lights.len().min(MAX_LIGHTS) as u32;
    Ok(u)
}

/// A point as a scene file writes it, `[x, y, z]`, for messages.
fn point(p: glam::Vec3) -> String {
    format!("[{}, {}, {}]", p.x, p.y, p.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The solid angles of all texels of a square frustum add up to the frustum's solid angle
    /// (4 asin(sin^2 a) for a square pyramid of half-angle a): the texel formula the shaders use
    /// (cos^3 law) must integrate exactly.
    #[test]
    fn texel_solid_angles_sum_to_the_frustum() {
        for (half_deg, n) in [(10.0f64, 64usize), (45.0, 128), (70.0, 256)] {
            let t = half_deg.to_radians().tan();
            let s = 2.0 * t / n as f64;
            let mut sum = 0.0;
            for j in 0..n {
                for i in 0..n {
                    let x = (-1.0 + (i as f64 + 0.5) * 2.0 / n as f64) * t;
                    let y = (-1.0 + (j as f64 + 0.5) * 2.0 / n as f64) * t;
                    sum += s * s / (1.0 + x * x + y * y).powf(1.5);
                }
            }
            // Solid angle of a rectangular pyramid with half-extents (t, t) at unit distance.
            let exact = 4.0 * (t * t / (1.0 + 2.0 * t * t).sqrt()).atan();
            assert!((sum - exact).abs() / exact < 2e-3, "half {half_deg}: {sum} vs {exact}");
        }
    }

    fn light(position: Vec3, kind: LightKind) -> Light {
        Light { position, intensity: Vec3::ONE, kind }
    }

    /// The axis and half-angle of each photon view, against what each view promises.
    #[test]
    fn photon_views() {
        let (centre, radius) = (Vec3::new(2.0, 1.0, 0.0), 0.5);
        let point = light(Vec3::new(0.0, 5.0, 0.0), LightKind::Point);
        let spot_dir = Vec3::new(0.0, -1.0, 0.2).normalize();
        let spot = light(
            Vec3::new(0.0, 5.0, 0.0),
            LightKind::Spot { direction: spot_dir, cone_angle_deg: 40.0, texture: None },
        );
        let mut s = CausticSettings::default();
        let to_centre = (centre - point.position).normalize();
        // Fitted: along the direction to the objects, just wider than their bounding sphere.
        let (axis, half) = photon_view(&s, &point, centre, radius);
        let subtended = (radius / centre.distance(point.position)).asin();
        assert!(axis.distance(to_centre) < 1e-6 && half > subtended && half < subtended * 1.05);
        // Fixed field of view: half the angle, about the spot's axis or towards the objects.
        s.photon_view = PhotonView::FixedFov;
        s.photon_fov = 60.0;
        let (axis, half) = photon_view(&s, &spot, centre, radius);
        assert!(axis.distance(spot_dir) < 1e-6 && (half - 30f32.to_radians()).abs() < 1e-6);
        let (axis, _) = photon_view(&s, &point, centre, radius);
        assert!(axis.distance(to_centre) < 1e-6);
        // Shadow-map face: (2, -4, 0) from the light leans most to -Y; from the side, +X.
        s.photon_view = PhotonView::ShadowMap;
        assert_eq!(photon_view(&s, &point, centre, radius), (Vec3::NEG_Y, std::f32::consts::FRAC_PI_4));
        let side = light(Vec3::new(-6.0, 1.5, 0.5), LightKind::Point);
        assert_eq!(photon_view(&s, &side, centre, radius).0, Vec3::X);
    }

    #[test]
    fn glsl_mirror_agrees() {
        let src =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shaders_glsl/common/caustics.glsl"))
                .unwrap();
        let names: Vec<&str> =
            ["photon_view_proj", "caustic_view_proj", "photon_plane", "caustic_plane", "axis", "position"].to_vec();
        let body = &src[src.find("struct CausticLight {").unwrap()..];
        let body = &body[..body.find('}').unwrap()];
        let found: Vec<&str> = body
            .lines()
            .filter_map(|l| l.split("//").next()?.trim().strip_suffix(';'))
            .map(|l| l.split_whitespace().nth(1).unwrap())
            .collect();
        assert_eq!(found, names);
        assert!(src.contains(&format!("#define CAUSTIC_FRESNEL {FLAG_FRESNEL}u")));
        assert!(src.contains(&format!("#define CAUSTIC_WD_DEPTH_SEARCH {FLAG_WD_DEPTH_SEARCH}u")));
        assert!(src.contains(&format!("#define CAUSTIC_BEAM_AREA {FLAG_BEAM_AREA}u")));
        assert!(src.contains(&format!("#define CAUSTIC_EYE_SPACE {FLAG_EYE_SPACE}u")));
        assert!(src.contains(&format!("#define CAUSTIC_REFLECTION_PLANE {FLAG_REFLECTION_PLANE}u")));
        assert!(src.contains(&format!("#define CAUSTIC_ONE_REFRACTION {FLAG_ONE_REFRACTION}u")));
        assert!(src.contains(&format!("#define CAUSTIC_TUTORIAL_LOOKUP {FLAG_TUTORIAL_LOOKUP}u")));
        assert!(src.contains(&format!("#define CAUSTIC_RECEIVER_FLUX {FLAG_RECEIVER_FLUX}u")));
    }
}
