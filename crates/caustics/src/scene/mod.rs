//! Scene description: a TOML file (format in `scenes/README.md`) turned into world-space
//! triangle meshes, materials, lights, a camera and the caustic receiver map.
//!
//! All problems with the user's input come back as `anyhow::Error` wrapping
//! [`crate::error::InputError`], whose message names the file and the key.

pub mod load;
pub mod mesh;
pub mod obj;
mod object;
mod overrides;
mod parse;
pub mod procedural;
pub mod schema;
pub mod search_path;

pub use glam::Vec3;
pub use load::{MAX_RESOLUTION, MAX_SUBDIVISIONS};
pub use mesh::Mesh;
pub use overrides::CausticOverrides;
pub use parse::parse_toml;
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
    pub render: RenderSettings,
    pub caustics: CausticSettings,
}

/// Caustic technique names `--technique` and `caustics.technique` accept.
pub const TECHNIQUES: &[&str] = &["none", "shah", "shah-vertex", "wd-points", "hcm"];
/// Traversal paths of `hcm` (`caustics.path`, `--path`): geometry shader + transform feedback
/// (the paper's) or compute append.
pub const HIERARCHY_PATHS: &[&str] = &["xfb", "compute"];
/// Converging-photon clustering of `hcm` (`caustics.cluster`, `--cluster`, Wyman 2008 Sec. 3.2):
/// never, at the last hierarchy level only, or at every level.
pub const CLUSTER_MODES: &[&str] = &["none", "last", "all"];
/// Splat sizes of `hcm` (`caustics.splat`, `--splat`, Wyman 2008 Sec. 3.3): the fixed
/// `splat_radius`, a radius from the photon's neighbours in one caustic map (the paper's slow
/// baseline), or that radius with each splat in the layer of a multi-resolution caustic map
/// i = trunc(log2(max(1, D/5))) for a diameter of D texels (drawn D/2^i wide there).
pub const SPLAT_MODES: &[&str] = &["fixed", "varying-single", "varying-multires"];
/// How varying splats (`caustics.varying_radius`, `--varying-radius`) find their radius from the
/// photon's neighbours in the photon buffer (Wyman 2008 Sec. 3.3): the largest distance to its
/// four adjacent photons (the approximation the paper used, for robustness), or Eq. 1-2, the
/// area of the quadrilaterals it forms with its adjacent photons over its unoccluded beam's.
pub const VARYING_RADII: &[&str] = &["max-distance", "beam-area"];
/// How photons are splatted into the caustic map (`caustics.splat_path`, `--splat-path`): points
/// drawn by the graphics pipeline (the papers') or a compute shader adding each splat with float
/// atomics (photons/splat.comp); both give the same map.
pub const SPLAT_PATHS: &[&str] = &["raster", "compute"];
/// Ray/receiver intersection variants (`caustics.intersect`, `--intersect`).
pub const INTERSECTS: &[&str] = &["shah-iterative", "wd-depth-search"];
/// Splat kernels (`caustics.splat_kernel`, `--splat-kernel`).
pub const SPLAT_KERNELS: &[&str] = &["gaussian", "box"];

/// `[caustics]`: which technique renders caustics and with what parameters.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CausticSettings {
    /// One of [`TECHNIQUES`]; default `none`.
    pub technique: String,
    /// Photon buffer resolution N (N x N photons per light), 64..=4096; default 512.
    pub photons: u32,
    /// Splat radius in caustic-map texels, (0, 32]; default 1.5.
    pub splat_radius: f32,
    /// One of [`SPLAT_KERNELS`]; default `gaussian`.
    pub splat_kernel: String,
    /// Caustic map (and receiver positions) resolution, 16..=8192; default 1024.
    pub caustic_map_resolution: u32,
    /// rayGeo iterations (Shah) or bisection refinements (Wyman & Davis), 1..=64; default 4.
    pub iterations: u32,
    /// Fresnel transmittance at both interfaces; default true.
    pub fresnel: bool,
    /// Refinements of the photon's exit point against the light-space back faces, 0..=16;
    /// 0 is Wyman 2005's estimate alone (the papers), default 4 (see photons/trace.glsl).
    pub back_face_iterations: u32,
    /// One of [`INTERSECTS`]; None = the technique's own (see [`CausticSettings::intersect`]).
    pub intersect: Option<String>,
    /// `hcm` only: one of [`HIERARCHY_PATHS`]; default `xfb`.
    pub path: String,
    /// `hcm` only: one of [`CLUSTER_MODES`]; default `none`.
    pub cluster: String,
    /// `hcm` only: one of [`SPLAT_MODES`]; default `fixed`.
    pub splat: String,
    /// `hcm` with varying splats only: one of [`VARYING_RADII`]; default `max-distance`.
    pub varying_radius: String,
    /// One of [`SPLAT_PATHS`]; default `raster`.
    pub splat_path: String,
    /// Vertices per instance of the instanced photon fetch (Wyman 2008 Sec. 4: "a smaller
    /// buffer of size 1024, 2048, or 4096" drawn instanced); a power of two, 64..=65536;
    /// default 1024. Not used by the copy path or by `hcm`'s splatted lists.
    pub instance_vertices: u32,
}

impl Default for CausticSettings {
    fn default() -> Self {
        CausticSettings {
            technique: "none".into(),
            photons: 512,
            splat_radius: 1.5,
            splat_kernel: "gaussian".into(),
            caustic_map_resolution: 1024,
            iterations: 4,
            fresnel: true,
            back_face_iterations: 4,
            intersect: None,
            path: "xfb".into(),
            cluster: "none".into(),
            splat: "fixed".into(),
            varying_radius: "max-distance".into(),
            splat_path: "raster".into(),
            instance_vertices: 1024,
        }
    }
}

impl CausticSettings {
    /// Caustic-map layers per light: 4 for the multi-resolution map (levels 0-3, Wyman 2008
    /// Sec. 3.3), else 1.
    pub fn caustic_levels(&self) -> u32 {
        if self.technique == "hcm" && self.splat == "varying-multires" {
            4
        } else {
            1
        }
    }

    /// The ray/receiver intersection in effect: the one asked for, else the technique's own
    /// (Wyman & Davis' depth search for `wd-points`, Shah's rayGeo otherwise).
    pub fn intersect(&self) -> &str {
        match (&self.intersect, self.technique.as_str()) {
            (Some(i), _) => i,
            (None, "wd-points" | "hcm") => "wd-depth-search",
            (None, _) => "shah-iterative",
        }
    }

    /// Checks that the settings belong together, once they are final (a scene's `[caustics]`
    /// may set `hcm`'s keys and leave the technique to the command line): the hierarchy's
    /// settings mean nothing to the other techniques, so setting one there is a mistake (and
    /// would be recorded in timings.json as if it had been applied). `origin` and `key` as for
    /// [`CausticSettings::validate`].
    pub fn validate_combination(&self, origin: &str, key: &str) -> anyhow::Result<()> {
        let bad = |k: &str, msg: String| -> anyhow::Result<()> {
            Err(crate::input_error!("{origin}: key `{key}{k}` (or flag --{}): {msg}", k.replace('_', "-")).into())
        };
        let d = CausticSettings::default();
        let hcm_only =
            [("path", &self.path, &d.path), ("cluster", &self.cluster, &d.cluster), ("splat", &self.splat, &d.splat)];
        for (k, v, default) in hcm_only {
            if self.technique != "hcm" && v != default {
                bad(k, format!("`{v}` is a setting of technique hcm, not of `{}`", self.technique))?;
            }
        }
        if self.varying_radius != d.varying_radius && (self.technique != "hcm" || self.splat == "fixed") {
            let what = "sizes varying splats (technique hcm with splat varying-single or varying-multires)";
            bad("varying_radius", format!("`{}` {what}", self.varying_radius))?;
        }
        Ok(())
    }

    /// Checks ranges and names; `origin` says where the values came from (a file or the command
    /// line) and `key` prefixes key names, e.g. `caustics.`.
    pub fn validate(&self, origin: &str, key: &str) -> anyhow::Result<()> {
        let bad = |k: &str, msg: String| -> anyhow::Result<()> {
            // On the command line the key is a flag: `--splat-radius`, not `--splat_radius`.
            let k = if key == "--" { k.replace('_', "-") } else { k.to_string() };
            Err(crate::input_error!("{origin}: key `{key}{k}`: {msg}").into())
        };
        let one_of = |k: &str, v: &str, list: &[&str]| -> anyhow::Result<()> {
            if list.contains(&v) {
                Ok(())
            } else {
                bad(k, format!("unknown value `{v}`; expected one of {}", list.join(", ")))
            }
        };
        one_of("technique", &self.technique, TECHNIQUES)?;
        one_of("splat_kernel", &self.splat_kernel, SPLAT_KERNELS)?;
        one_of("path", &self.path, HIERARCHY_PATHS)?;
        one_of("cluster", &self.cluster, CLUSTER_MODES)?;
        one_of("splat", &self.splat, SPLAT_MODES)?;
        one_of("varying_radius", &self.varying_radius, VARYING_RADII)?;
        one_of("splat_path", &self.splat_path, SPLAT_PATHS)?;
        if let Some(i) = &self.intersect {
            one_of("intersect", i, INTERSECTS)?;
        }
        if !(64..=4096).contains(&self.photons) {
            bad("photons", format!("must be between 64 and 4096 (photons per side), got {}", self.photons))?;
        }
        if !(self.splat_radius > 0.0 && self.splat_radius <= 32.0) {
            bad("splat_radius", format!("must be in (0, 32] caustic-map texels, got {}", self.splat_radius))?;
        }
        if !(16..=8192).contains(&self.caustic_map_resolution) {
            bad("caustic_map_resolution", format!("must be between 16 and 8192, got {}", self.caustic_map_resolution))?;
        }
        if self.back_face_iterations > 16 {
            bad("back_face_iterations", format!("must be between 0 and 16, got {}", self.back_face_iterations))?;
        }
        if !(64..=65536).contains(&self.instance_vertices) || !self.instance_vertices.is_power_of_two() {
            bad(
                "instance_vertices",
                format!("must be a power of two between 64 and 65536, got {}", self.instance_vertices),
            )?;
        }
        if !(1..=64).contains(&self.iterations) {
            bad("iterations", format!("must be between 1 and 64, got {}", self.iterations))?;
        }
        Ok(())
    }
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
