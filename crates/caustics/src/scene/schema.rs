//! The scene file as written: serde structs that mirror the TOML one to one. Every struct
//! rejects unknown keys; shape- and type-specific keys are optional here and checked in
//! `load.rs`, which knows the key paths for its messages. See `scenes/README.md`.

use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::fmt;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    pub camera: CameraDef,
    #[serde(default)]
    pub lights: Vec<LightDef>,
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialDef>,
    #[serde(default)]
    pub objects: Vec<ObjectDef>,
    pub receiver_map: Option<ReceiverMapDef>,
    #[serde(default)]
    pub render: RenderDef,
    #[serde(default)]
    /// `[caustics]`: the caustic technique and its parameters (each overridable on the command line).
    pub caustics: super::CausticOverrides,
    /// `[pool]`: a pool scene (Trendall & Stewart 2000), instead of objects and lights.
    pub pool: Option<super::pool::PoolDef>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDef {
    pub eye: [f32; 3],
    pub target: [f32; 3],
    pub up: Option<[f32; 3]>,
    pub fov_y: f32,
    pub resolution: [u32; 2],
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LightType {
    Point,
    Spot,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightDef {
    #[serde(rename = "type")]
    pub kind: LightType,
    pub position: [f32; 3],
    pub intensity: [f32; 3],
    pub direction: Option<[f32; 3]>,
    pub cone_angle: Option<f32>,
    pub texture: Option<String>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MaterialType {
    Diffuse,
    Refractive,
    Reflective,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDef {
    #[serde(rename = "type")]
    pub kind: MaterialType,
    pub albedo: Option<[f32; 3]>,
    pub ior: Option<Numbers>,
    pub transmission: Option<[f32; 3]>,
    pub specular: Option<[f32; 3]>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShapeType {
    Plane,
    Box,
    Room,
    Icosphere,
    Torus,
    Ring,
    Octahedron,
    Obj,
    Water,
}

impl ShapeType {
    pub fn name(self) -> &'static str {
        match self {
            ShapeType::Plane => "plane",
            ShapeType::Box => "box",
            ShapeType::Room => "room",
            ShapeType::Icosphere => "icosphere",
            ShapeType::Torus => "torus",
            ShapeType::Ring => "ring",
            ShapeType::Octahedron => "octahedron",
            ShapeType::Obj => "obj",
            ShapeType::Water => "water",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FitOrigin {
    Center,
    Bottom,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectDef {
    pub name: Option<String>,
    pub material: String,
    pub shape: ShapeType,
    // Shape parameters (which are allowed depends on `shape`).
    pub size: Option<Vec<f32>>,
    pub open_top: Option<bool>,
    pub radius: Option<f32>,
    pub subdivisions: Option<u32>,
    pub major_radius: Option<f32>,
    pub minor_radius: Option<f32>,
    pub segments: Option<Numbers>,
    pub height: Option<f32>,
    pub thickness: Option<f32>,
    pub file: Option<String>,
    pub fit_size: Option<f32>,
    pub fit_origin: Option<FitOrigin>,
    // Transform.
    pub scale: Option<Numbers>,
    pub rotate: Option<[f32; 3]>,
    pub translate: Option<[f32; 3]>,
}

impl ObjectDef {
    /// The shape-parameter keys that are present, in file order of declaration.
    pub fn present_shape_keys(&self) -> Vec<&'static str> {
        let mut keys = Vec::new();
        let mut add = |present: bool, key: &'static str| {
            if present {
                keys.push(key);
            }
        };
        add(self.size.is_some(), "size");
        add(self.open_top.is_some(), "open_top");
        add(self.radius.is_some(), "radius");
        add(self.subdivisions.is_some(), "subdivisions");
        add(self.major_radius.is_some(), "major_radius");
        add(self.minor_radius.is_some(), "minor_radius");
        add(self.segments.is_some(), "segments");
        add(self.height.is_some(), "height");
        add(self.thickness.is_some(), "thickness");
        add(self.file.is_some(), "file");
        add(self.fit_size.is_some(), "fit_size");
        add(self.fit_origin.is_some(), "fit_origin");
        keys
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReceiverMapDef {
    #[serde(default)]
    pub plane_y: f32,
    pub x_range: [f32; 2],
    pub z_range: [f32; 2],
    pub resolution: u32,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderDef {
    pub shadow_map_resolution: Option<u32>,
    pub exposure: Option<f32>,
    pub background: Option<[f32; 3]>,
}

/// A number or an array of numbers (`1.5` or `[1.49, 1.5, 1.51]`); lengths are checked by
/// the loader.
#[derive(Debug, Clone, PartialEq)]
pub struct Numbers(pub Vec<f64>);

impl<'de> Deserialize<'de> for Numbers {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Numbers;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number or an array of numbers")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Numbers, E> {
                Ok(Numbers(vec![v]))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Numbers, E> {
                Ok(Numbers(vec![v as f64]))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Numbers, E> {
                Ok(Numbers(vec![v as f64]))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Numbers, A::Error> {
                let mut out = Vec::new();
                while let Some(v) = seq.next_element::<f64>()? {
                    out.push(v);
                }
                Ok(Numbers(out))
            }
        }
        d.deserialize_any(V)
    }
}
