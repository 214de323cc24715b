//! Each specular object's own light-space geometry buffers, through which a photon is followed
//! after the object it meets first (Wyman & Nichols 2009 Sec. 3.1.1 applied to photons, Sec. 5
//! and Fig. 13: "caustics from more than two refractive interfaces, using multi-layered deferred
//! refraction when rendering photons"). Deferred photons and adaptive caustic maps both hold
//! one, and their shaders read it through `deferred_photon_layers.glsl` (three sampled arrays
//! per object: position, normal, material). With one specular object there are none: the
//! buffers of all objects together hold it.

use super::geometry_buffers::{LightGeometryBuffers, Uniforms};
use crate::gpu::{GpuMesh, Stage, MATERIAL_DIFFUSE};
use crate::image_io::ImageF32;
use anyhow::Result;
use vkcore::{Context, Frame, Named, Sampler, ShaderCompiler};

/// The most specular objects the multi-layer trace follows a photon through
/// (`deferred_photon_layers.glsl` declares this many buffers at most).
pub const MAX_REFRACTORS: usize = 4;

/// Each object's three bindings, as `deferred_photon_layers.glsl`'s `LAYER_BINDINGS(k)` names them.
const LAYER_NAMES: [[&str; 3]; MAX_REFRACTORS] = [
    ["layer0_position", "layer0_normal", "layer0_material"],
    ["layer1_position", "layer1_normal", "layer1_material"],
    ["layer2_position", "layer2_normal", "layer2_material"],
    ["layer3_position", "layer3_normal", "layer3_material"],
];

/// The indices of the specular meshes (the scene's specular objects), in the scene's order.
pub fn specular_objects(meshes: &[GpuMesh]) -> Vec<usize> {
    (0..meshes.len()).filter(|&i| meshes[i].kind() != MATERIAL_DIFFUSE).collect()
}

pub struct RefractorLayers {
    /// Each specular object's index among the meshes and its buffers, in the scene's order.
    layers: Vec<(usize, LightGeometryBuffers)>,
}

impl RefractorLayers {
    /// Buffers of `side`² texels for each of the `specular` meshes when there are several.
    pub fn new(ctx: &Context, sh: &ShaderCompiler, side: u32, specular: &[usize]) -> Result<RefractorLayers> {
        let layered = if specular.len() > 1 { specular } else { &[] };
        let layers =
            layered.iter().map(|&i| Ok((i, LightGeometryBuffers::new(ctx, sh, side)?))).collect::<Result<_>>()?;
        Ok(RefractorLayers { layers })
    }

    /// The shaders' `REFRACTORS` define: the objects followed through, 1 without layers.
    pub fn refractors_define(&self) -> String {
        self.layers.len().max(1).to_string()
    }

    /// The layers' bindings, after a shader's own (`LAYER_BINDING`), under
    /// `deferred_photon_layers.glsl`'s names: `layer<k>_position`, `_normal`, `_material`.
    pub fn binds<'a>(&'a self, nearest: &'a Sampler) -> Vec<Named<'a>> {
        self.layers
            .iter()
            .zip(LAYER_NAMES)
            .flat_map(|((_, b), names)| names.into_iter().zip(b.surface_binds(nearest)))
            .collect()
    }

    /// Records light `l`'s buffers of each object alone, passes `<name>.refractor<k>.light<l>`.
    pub fn record(&self, f: &mut Frame, u: &Uniforms, meshes: &[GpuMesh], stage: Stage, l: u32) -> Result<()> {
        for (k, (object, b)) in self.layers.iter().enumerate() {
            b.record_surfaces(f, u, meshes, &[*object], stage.pass().refractor(k), l)?;
        }
        Ok(())
    }

    /// Adds each object's surfaces to `img` (of side `p`), its layers prefixed `refractor<k>.`
    /// (k in the scene's order of its specular objects).
    pub fn dump_into(&self, ctx: &Context, img: &mut ImageF32, p: u32) -> Result<()> {
        for (k, (_, b)) in self.layers.iter().enumerate() {
            for mut layer in b.dump_surfaces(ctx, p)?.layers {
                layer.name = layer.name.map(|n| format!("refractor{k}.{n}"));
                img.layers.push(layer);
            }
        }
        Ok(())
    }
}
