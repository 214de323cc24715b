//! Reading a scene file: TOML parsing (errors mapped to key paths), validation, and building
//! world-space meshes.

use super::schema::{self, LightType, MaterialType, Numbers};
use super::{
    Camera, Light, LightKind, Material, MaterialKind, ModelSearchPath, ReceiverMapSpec, RenderSettings, Scene,
};
use crate::input_error;
use glam::Vec3;
use std::fmt::Display;
use std::path::{Path, PathBuf};

/// Largest resolution accepted for images and maps.
pub const MAX_RESOLUTION: u32 = 16384;
/// Largest icosphere subdivision level (7 gives 327 680 triangles).
pub const MAX_SUBDIVISIONS: u32 = 7;
/// The largest coordinate (and half the largest size) a scene may give, in metres.
pub const MAX_COORDINATE: f32 = 1e6;

/// Formats errors as `<file>: key `<key>`: <message>`.
pub(super) struct Ctx<'a> {
    pub(super) file: &'a Path,
}

impl Ctx<'_> {
    pub(super) fn err(&self, key: &str, msg: impl Display) -> anyhow::Error {
        anyhow::Error::new(input_error!("{}: key `{key}`: {msg}", self.file.display()))
    }

    /// The file `name` relative to the scene file's folder (key `key`); an error saying that
    /// the `what` is not found unless it is a file.
    pub(super) fn beside(&self, key: &str, name: &str, what: &str) -> anyhow::Result<PathBuf> {
        let path = self.file.parent().unwrap_or(Path::new("")).join(name);
        if !path.is_file() {
            return Err(self.err(key, format!("{what} {} not found", path.display())));
        }
        Ok(path)
    }

    pub(super) fn finite(&self, key: &str, v: f32) -> anyhow::Result<f32> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(key, format!("must be a finite number, got {v}")))
        }
    }

    pub(super) fn positive(&self, key: &str, v: f32) -> anyhow::Result<f32> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(key, format!("must be a finite number > 0, got {v}")))
        }
    }

    /// Three numbers within ±[`MAX_COORDINATE`]: beyond it, lengths overflow f32 (a direction
    /// of 3e38 normalises to zero) and nothing renders.
    pub(super) fn vec3(&self, key: &str, v: [f32; 3]) -> anyhow::Result<Vec3> {
        if v.iter().all(|x| x.is_finite() && x.abs() <= MAX_COORDINATE) {
            Ok(Vec3::from_array(v))
        } else {
            Err(self.err(key, format!("must be 3 finite numbers within ±{MAX_COORDINATE:e}, got {v:?}")))
        }
    }

    /// A colour with every channel in `0..=max`.
    pub(super) fn colour(&self, key: &str, v: [f32; 3], max: f32) -> anyhow::Result<Vec3> {
        if v.iter().all(|x| x.is_finite() && (0.0..=max).contains(x)) {
            Ok(Vec3::from_array(v))
        } else if max.is_finite() {
            Err(self.err(key, format!("each channel must be between 0 and {max}, got {v:?}")))
        } else {
            Err(self.err(key, format!("each channel must be finite and >= 0, got {v:?}")))
        }
    }

    pub(super) fn resolution(&self, key: &str, v: u32) -> anyhow::Result<u32> {
        if (1..=MAX_RESOLUTION).contains(&v) {
            Ok(v)
        } else {
            Err(self.err(key, format!("must be between 1 and {MAX_RESOLUTION}, got {v}")))
        }
    }

    /// An integer-valued `Numbers` entry of exactly `n` values, each in `lo..=hi`.
    pub(super) fn counts(&self, key: &str, v: &Numbers, n: usize, lo: u32, hi: u32) -> anyhow::Result<Vec<u32>> {
        let what = if n == 1 { "an integer".to_string() } else { format!("{n} integers") };
        let ok = v.0.len() == n && v.0.iter().all(|x| x.fract() == 0.0 && *x >= lo as f64 && *x <= hi as f64);
        if ok {
            Ok(v.0.iter().map(|&x| x as u32).collect())
        } else {
            Err(self.err(key, format!("must be {what} between {lo} and {hi}, got {:?}", v.0)))
        }
    }
}

/// Reads, validates and builds the scene at `path`.
pub fn load_scene(path: &Path, search: &ModelSearchPath) -> anyhow::Result<Scene> {
    let ctx = Ctx { file: path };
    let text = std::fs::read_to_string(path)
        .map_err(|e| anyhow::Error::new(input_error!("{}: cannot read the scene file: {e}", path.display())))?;
    let def = super::parse::parse(path, &text)?;
    build(&ctx, def, search)
}

fn build(ctx: &Ctx, def: schema::SceneFile, search: &ModelSearchPath) -> anyhow::Result<Scene> {
    let camera = build_camera(ctx, &def.camera)?;
    let pool = match &def.pool {
        Some(p) => {
            super::pool::check_pool_scene(ctx, &def)?;
            Some(super::pool::build_pool(ctx, p)?)
        }
        None => None,
    };
    if def.lights.is_empty() && pool.is_none() {
        return Err(ctx.err("lights", "the scene has no lights; add at least one [[lights]] table"));
    }
    let lights = def
        .lights
        .iter()
        .enumerate()
        .map(|(i, l)| build_light(ctx, &format!("lights[{i}]"), l))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let materials =
        def.materials.iter().map(|(name, m)| build_material(ctx, name, m)).collect::<anyhow::Result<Vec<_>>>()?;
    if def.objects.is_empty() && pool.is_none() {
        return Err(ctx.err("objects", "the scene has no objects; add at least one [[objects]] table"));
    }
    let objects = def
        .objects
        .iter()
        .enumerate()
        .map(|(i, o)| super::object::build_object(ctx, i, o, &materials, search))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let receiver_map = def.receiver_map.as_ref().map(|r| build_receiver(ctx, r)).transpose()?;
    let r = &def.render;
    let render = RenderSettings {
        shadow_map_resolution: ctx
            .resolution("render.shadow_map_resolution", r.shadow_map_resolution.unwrap_or(1024))?,
        exposure: ctx.positive("render.exposure", r.exposure.unwrap_or(1.0))?,
        background: ctx.colour("render.background", r.background.unwrap_or([0.0; 3]), f32::INFINITY)?,
    };
    let mut caustics = super::CausticSettings::default();
    def.caustics.apply(&mut caustics);
    caustics.validate(&ctx.file.display().to_string(), "caustics.")?;
    Ok(Scene {
        path: ctx.file.to_path_buf(),
        camera,
        lights,
        materials,
        objects,
        receiver_map,
        caustic_frame: None,
        render,
        caustics,
        pool,
    })
}

fn build_camera(ctx: &Ctx, c: &schema::CameraDef) -> anyhow::Result<Camera> {
    let eye = ctx.vec3("camera.eye", c.eye)?;
    let target = ctx.vec3("camera.target", c.target)?;
    let up = ctx.vec3("camera.up", c.up.unwrap_or([0.0, 1.0, 0.0]))?;
    let view = target - eye;
    if view.length() <= 1e-6 * eye.length().max(1.0) {
        return Err(ctx.err("camera.target", "must differ from camera.eye"));
    }
    if up.length() == 0.0 || view.normalize().cross(up.normalize()).length() < 1e-4 {
        return Err(ctx.err("camera.up", format!("must be non-zero and not parallel to the view direction, got {up}")));
    }
    let fov = ctx.finite("camera.fov_y", c.fov_y)?;
    if !(fov > 0.0 && fov < 180.0) {
        return Err(ctx.err("camera.fov_y", format!("must be between 0 and 180 degrees (exclusive), got {fov}")));
    }
    Ok(Camera {
        eye,
        target,
        up: up.normalize(),
        fov_y_deg: fov,
        width: ctx.resolution("camera.resolution", c.resolution[0])?,
        height: ctx.resolution("camera.resolution", c.resolution[1])?,
    })
}

fn build_light(ctx: &Ctx, key: &str, l: &schema::LightDef) -> anyhow::Result<Light> {
    let position = ctx.vec3(&format!("{key}.position"), l.position)?;
    let intensity = ctx.colour(&format!("{key}.intensity"), l.intensity, f32::INFINITY)?;
    let kind = match l.kind {
        LightType::Point => {
            for (present, k) in [
                (l.direction.is_some(), "direction"),
                (l.cone_angle.is_some(), "cone_angle"),
                (l.texture.is_some(), "texture"),
            ] {
                if present {
                    return Err(ctx.err(&format!("{key}.{k}"), "only allowed for type = \"spot\""));
                }
            }
            LightKind::Point
        }
        LightType::Spot => {
            let dkey = format!("{key}.direction");
            let d = l.direction.ok_or_else(|| ctx.err(&dkey, "required for a spot light"))?;
            let d = ctx.vec3(&dkey, d)?;
            if d.length() == 0.0 {
                return Err(ctx.err(&dkey, "must be non-zero"));
            }
            let akey = format!("{key}.cone_angle");
            let a = l.cone_angle.ok_or_else(|| ctx.err(&akey, "required for a spot light"))?;
            if !(a.is_finite() && a > 0.0 && a <= 90.0) {
                return Err(ctx.err(&akey, format!("half-angle must be > 0 and <= 90 degrees, got {a}")));
            }
            let texture = match &l.texture {
                None => None,
                Some(t) => Some(ctx.beside(&format!("{key}.texture"), t, "texture file")?),
            };
            LightKind::Spot { direction: d.normalize(), cone_angle_deg: a, texture }
        }
    };
    Ok(Light { position, intensity, kind })
}

fn build_material(ctx: &Ctx, name: &str, m: &schema::MaterialDef) -> anyhow::Result<Material> {
    let key = format!("materials.{name}");
    let k = |s: &str| format!("{key}.{s}");
    let allowed: &[&str] = match m.kind {
        MaterialType::Diffuse => &["albedo"],
        MaterialType::Refractive => &["ior", "transmission"],
        MaterialType::Reflective => &["specular"],
    };
    for (present, field) in [
        (m.albedo.is_some(), "albedo"),
        (m.ior.is_some(), "ior"),
        (m.transmission.is_some(), "transmission"),
        (m.specular.is_some(), "specular"),
    ] {
        if present && !allowed.contains(&field) {
            return Err(
                ctx.err(&k(field), format!("not a key of this material type (allowed: {})", allowed.join(", ")))
            );
        }
    }
    let required =
        |v: Option<[f32; 3]>, field: &str| v.ok_or_else(|| ctx.err(&k(field), "required for this material type"));
    let kind = match m.kind {
        MaterialType::Diffuse => {
            MaterialKind::Diffuse { albedo: ctx.colour(&k("albedo"), required(m.albedo, "albedo")?, 1.0)? }
        }
        MaterialType::Reflective => {
            MaterialKind::Reflective { specular: ctx.colour(&k("specular"), required(m.specular, "specular")?, 1.0)? }
        }
        MaterialType::Refractive => {
            let ior = m.ior.as_ref().ok_or_else(|| ctx.err(&k("ior"), "required for a refractive material"))?;
            let ior = match ior.0.as_slice() {
                &[x] => [x; 3],
                &[r, g, b] => [r, g, b],
                other => {
                    return Err(ctx.err(&k("ior"), format!("must be a number or [r, g, b], got {} values", other.len())))
                }
            };
            if !ior.iter().all(|x| (1.0..=4.0).contains(x)) {
                return Err(ctx.err(&k("ior"), format!("each value must be between 1.0 and 4.0, got {ior:?}")));
            }
            let ior = Vec3::new(ior[0] as f32, ior[1] as f32, ior[2] as f32);
            let transmission = ctx.colour(&k("transmission"), m.transmission.unwrap_or([1.0; 3]), 1.0)?;
            MaterialKind::Refractive { ior, transmission }
        }
    };
    Ok(Material { name: name.to_string(), kind })
}

fn build_receiver(ctx: &Ctx, r: &schema::ReceiverMapDef) -> anyhow::Result<ReceiverMapSpec> {
    let range = |key: &str, v: [f32; 2]| -> anyhow::Result<[f32; 2]> {
        if v.iter().all(|x| x.is_finite() && x.abs() <= MAX_COORDINATE) && v[0] < v[1] {
            Ok(v)
        } else {
            Err(ctx.err(key, format!("must be [min, max] with min < max, within ±{MAX_COORDINATE:e}, got {v:?}")))
        }
    };
    Ok(ReceiverMapSpec {
        plane_y: ctx.finite("receiver_map.plane_y", r.plane_y)?,
        x_range: range("receiver_map.x_range", r.x_range)?,
        z_range: range("receiver_map.z_range", r.z_range)?,
        resolution: ctx.resolution("receiver_map.resolution", r.resolution)?,
    })
}
