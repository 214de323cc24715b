//! Scene description: a TOML file (format in `scenes/README.md`) turned into world-space
//! triangle meshes, materials, lights, a camera and the caustic receiver map.
//!
//! All problems with the user's input come back as `anyhow::Error` wrapping
//! [`crate::error::InputError`], whose message names the file and the key.

pub mod load;
pub mod mesh;
pub mod models;
pub mod obj;
mod object;
mod parse;
pub mod pool;
pub mod procedural;
pub mod schema;
pub mod search_path;
pub mod spot_projector;
pub mod water;
pub mod water_surface;

pub use crate::techniques::settings::{CausticOverrides, CausticSettings};
pub use glam::Vec3;
pub use load::{MAX_RESOLUTION, MAX_SUBDIVISIONS};
pub use mesh::Mesh;
pub use parse::parse_toml;
pub use pool::{Impulse, PoolSpec, Wave};
pub use search_path::ModelSearchPath;

use std::path::{Path, PathBuf};

/// A loaded, validated scene. Every mesh is in world space.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The `.toml` file it was read from.
    pub path: PathBuf,
    pub camera: Camera,
    pub lights: Vec<Light>,
    /// Referenced by index from [`Object::material`]; sorted by name.
    pub materials: Vec<Material>,
    pub objects: Vec<Object>,
    pub receiver_map: Option<ReceiverMapSpec>,
    /// The receiver rectangle that frames the light-space caustic map where the receiver map
    /// itself is left out (a bench's throughput frames drop the instrument, not the framing:
    /// `techniques::uniforms`); None: the receiver map's, if any. Never read from a file.
    pub caustic_frame: Option<ReceiverMapSpec>,
    pub render: RenderSettings,
    pub caustics: CausticSettings,
    /// `[pool]`: a pool scene (Trendall & Stewart 2000) has this instead of objects and lights.
    pub pool: Option<PoolSpec>,
}

/// A pinhole camera. `up` is normalised (not necessarily orthogonal to the view direction).
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    pub eye: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    /// Full vertical field of view in degrees.
    pub fov_y_deg: f32,
    pub width: u32,
    pub height: u32,
}

impl Camera {
    /// Width / height.
    pub fn aspect(&self) -> f32 {
        self.width as f32 / self.height as f32
    }
}

#[derive(Debug, Clone, PartialEq)]
pub enum LightKind {
    Point,
    Spot {
        /// Normalised.
        direction: Vec3,
        /// Half-angle of the cone in degrees, in (0, 90].
        cone_angle_deg: f32,
        /// Resolved path of a PNG projected through the cone.
        texture: Option<PathBuf>,
    },
}

#[derive(Debug, Clone, PartialEq)]
pub struct Light {
    pub position: Vec3,
    /// Radiant intensity per RGB channel, W/sr.
    pub intensity: Vec3,
    pub kind: LightKind,
}

#[derive(Debug, Clone, PartialEq)]
pub enum MaterialKind {
    Diffuse {
        albedo: Vec3,
    },
    /// Per-channel index of refraction (a scalar in the file is expanded to all three) and
    /// transmitted colour.
    Refractive {
        ior: Vec3,
        transmission: Vec3,
    },
    Reflective {
        specular: Vec3,
    },
}

#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    pub name: String,
    pub kind: MaterialKind,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    pub name: String,
    /// World space: fit, scale, rotate and translate applied; normals transformed by the
    /// inverse-transpose and renormalised.
    pub mesh: Mesh,
    /// Index into [`Scene::materials`].
    pub material: usize,
    /// The model file of a `shape = "obj"` object, by its checksum ([`models`]).
    pub model: Option<models::ModelFile>,
}

/// The horizontal rectangle on which caustic maps are gathered: `resolution` × `resolution`
/// texels covering `x_range` × `z_range` at height `plane_y`.
#[derive(Debug, Clone, PartialEq)]
pub struct ReceiverMapSpec {
    pub plane_y: f32,
    pub x_range: [f32; 2],
    pub z_range: [f32; 2],
    pub resolution: u32,
}

#[derive(Debug, Clone, PartialEq)]
pub struct RenderSettings {
    /// Default 1024.
    pub shadow_map_resolution: u32,
    /// Multiplier applied before display. Default 1.0.
    pub exposure: f32,
    /// Radiance of rays that leave the scene. Default black.
    pub background: Vec3,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self { shadow_map_resolution: 1024, exposure: 1.0, background: Vec3::ZERO }
    }
}

impl Scene {
    /// The receiver rectangle that frames the light-space caustic map: the receiver map's, or
    /// the `caustic_frame` that stands for it where the receiver map is left out.
    pub fn framing_rectangle(&self) -> Option<&ReceiverMapSpec> {
        self.receiver_map.as_ref().or(self.caustic_frame.as_ref())
    }

    /// The model files its objects were loaded from, each once.
    pub fn models(&self) -> Vec<models::ModelFile> {
        let mut out: Vec<models::ModelFile> = self.objects.iter().filter_map(|o| o.model.clone()).collect();
        out.sort();
        out.dedup();
        out
    }

    /// Loads `path`, looking for OBJ files on [`ModelSearchPath::for_scene`].
    pub fn load(path: &Path) -> anyhow::Result<Scene> {
        Self::load_with_search_path(path, &ModelSearchPath::for_scene(path))
    }

    pub fn load_with_search_path(path: &Path, search: &ModelSearchPath) -> anyhow::Result<Scene> {
        load::load_scene(path, search)
    }

    /// Total triangles over all objects.
    pub fn triangle_count(&self) -> usize {
        self.objects.iter().map(|o| o.mesh.triangle_count()).sum()
    }

    /// The material of `object`.
    pub fn material_of(&self, object: &Object) -> &Material {
        &self.materials[object.material]
    }

    /// World-space bounds of all objects.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.objects
            .iter()
            .map(|o| o.mesh.bounds())
            .fold((Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)), |(lo, hi), (a, b)| {
                (lo.min(a), hi.max(b))
            })
    }
}

#[cfg(test)]
mod tests;
