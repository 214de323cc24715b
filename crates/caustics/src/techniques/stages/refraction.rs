//! The eye's refraction (`caustics.refraction`): `forward`, Wyman 2005's image-space refraction,
//! which the eye render records with its own targets (`crate::render`), or `deferred`, Wyman &
//! Nichols 2009's deferred and multi-layer deferred refraction (Sec. 3.1, 3.1.1), whose passes
//! and buffers this stage owns. Not a caustic stage: what the eye sees through the refractors.

use crate::dump::Dump;
use crate::gpu::Target;
use crate::image_io::ImageF32;
use crate::scene::Scene;
/// What deferred refraction reads and writes of the eye render.
pub use crate::techniques::wyman_nichols2009::deferred_refraction::Inputs as RefractionInputs;
use crate::techniques::wyman_nichols2009::deferred_refraction::{self, DeferredRefraction};
pub use crate::techniques::wyman_nichols2009::deferred_refraction::{
    DEFERRED_REFRACTION_DUMPS, REFRACTION_LAYERS, REFRACTOR_GEOMETRY,
};
use crate::techniques::Refraction;
use anyhow::Result;
use vkcore::{Context, Frame, ShaderCompiler};

/// The eye's refraction: deferred refraction's passes and the specular objects' order, or
/// nothing (forward refraction).
pub struct EyeRefraction {
    deferred: Option<DeferredRefraction>,
    /// The specular objects, farthest from the eye first (Sec. 3.1.1).
    order: Vec<usize>,
}

impl EyeRefraction {
    pub fn new(ctx: &Context, sh: &ShaderCompiler, scene: &Scene) -> Result<EyeRefraction> {
        let order = deferred_refraction::back_to_front(scene);
        let deferred = match scene.caustics.refraction {
            Refraction::Forward => None,
            Refraction::Deferred => {
                let (w, h) = (scene.camera.width, scene.camera.height);
                Some(DeferredRefraction::new(ctx, sh, order.len(), w, h)?)
            }
        };
        Ok(EyeRefraction { deferred, order })
    }

    /// Sorts the specular objects again for a new pose (the same objects: `crate::animation`).
    pub fn set_pose(&mut self, scene: &Scene) {
        self.order = deferred_refraction::back_to_front(scene);
    }

    /// Records deferred refraction's passes; false (nothing recorded) with forward refraction,
    /// which the eye render records itself.
    pub fn record_deferred(&self, f: &mut Frame, inp: &RefractionInputs) -> Result<bool> {
        let Some(deferred) = &self.deferred else { return Ok(false) };
        deferred.record(f, inp, &self.order)?;
        Ok(true)
    }

    /// The last frame's buffer `d` where this stage owns it (deferred refraction's), else None.
    pub fn dump(&self, ctx: &Context, final_image: &Target, d: &'static Dump) -> Result<Option<ImageF32>> {
        match &self.deferred {
            Some(deferred) => deferred.dump(ctx, final_image, d),
            None => Ok(None),
        }
    }
}
