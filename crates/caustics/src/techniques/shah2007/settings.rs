//! What Shah et al.'s techniques declare: the paper and the features the vertex-photon pass
//! needs (a leaf module: the technique enum reads it).

use super::super::value_enum::value_enum;
use vkcore::Feature;

/// The paper, as tables and `--help` cite it.
pub const PAPER: &str = "Shah, Konttinen & Pattanaik 2007, caustics mapping";

/// What the vertex-photon pass needs: it writes the photon buffer from the vertex stage.
pub const VERTEX_PHOTON_FEATURES: &[Feature] =
    &[Feature::ShaderOutputLayer, Feature::LargePoints, Feature::VertexPipelineStoresAndAtomics];

value_enum! {
    /// Where a photon refracts (`caustics.refractions`, `--refractions`).
    pub enum Refractions {
        /// Into the object and out of it, at the light-space back faces (Wyman 2005's exit
        /// estimate): causticlab's choice for every photon-buffer technique.
        Two = "two",
        /// Once, where the light meets the object, then straight on through it: the caustics
        /// mapping tutorial's path (its `psIntersectPts` refracts with `refract(lightDir, normal,
        /// g_refIndex)` and searches from there), a thin-object approximation.
        One = "one",
    }
}

value_enum! {
    /// How the final render and the receiver map turn the caustic map into light
    /// (`caustics.lookup`, `--lookup`).
    pub enum Lookup {
        /// The map's power per texel over the texel's footprint: irradiance in W/m²
        /// (`shaders_glsl/common/caustic_lookup.glsl`), causticlab's choice.
        Physical = "physical",
        /// The tutorial's `psDiffuse`: the Lambert term times (1 + pow(c, 1.3)), c the map's
        /// value; causticlab's c is the caustic irradiance over the light's unoccluded
        /// irradiance (see `docs/papers.md`).
        Tutorial = "tutorial",
    }
}
