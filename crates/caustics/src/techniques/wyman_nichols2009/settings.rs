//! The settings of Wyman & Nichols 2009 as the scene's `[caustics]`, the bench configs and the
//! command line name them, and the buffers they add (a leaf module: the scene description
//! reads it).

use super::super::value_enum::value_enum;
use vkcore::Feature;

/// The paper, as tables and `--help` cite it.
pub const PAPER: &str = "Wyman & Nichols 2009, adaptive caustic maps using deferred shading";

value_enum! {
    /// How the eye render refracts (`caustics.refraction`, `--refraction`): an eye-render
    /// setting, independent of the caustic technique.
    pub enum Refraction {
        /// Wyman 2005's image-space refraction: back faces, then the refraction in the front
        /// faces' fragment shader, then a composite (Wyman & Nichols 2009 Fig. 3, top).
        Forward = "forward",
        /// Wyman & Nichols 2009 Sec. 3.1: front and back faces in one pass (a geometry shader
        /// routes each face to its layer), then one full-screen refraction pass per refractor,
        /// back to front (Sec. 3.1.1).
        Deferred = "deferred",
    }
}

impl Refraction {
    /// The eye render's buffers that only this refraction has (`--dump` names).
    pub fn dumps(self) -> &'static [&'static str] {
        match self {
            Refraction::Forward => &["refractor_back_faces", "refractor_front_faces"],
            Refraction::Deferred => &["refractor_geometry", "refraction_layers"],
        }
    }

    /// The device features it needs beyond the baseline.
    pub fn required_features(self) -> &'static [Feature] {
        match self {
            Refraction::Forward => &[],
            // The geometry shader that routes each face to the front or back layer (gl_Layer).
            Refraction::Deferred => &[Feature::GeometryShader],
        }
    }
}
