//! Records the caustic passes of one frame, light after light: the light-space work (receiver
//! positions, the refractors' back faces, the photon buffer or vertex photons, and the copy or
//! the hierarchy that read it; or the adaptive traversal's geometry buffers and photons), then
//! the splat into the light's caustic-map layer, by the
//! technique's path (points, the hierarchy's list, or the compute splat).

use super::shah2007::VertexPhotons;
use super::shared::compute_splat::{self, ComputeSplat};
use super::shared::{photon_buffer, splat};
use super::wyman2008::photon_copy::PhotonCopy;
use super::wyman2008::Hierarchy;
use super::wyman_davis2006::{EyeView, ImageSpace};
use super::wyman_nichols2009::adaptive::{self, AdaptiveCaustics, Part};
use super::wyman_nichols2009::DeferredPhotons;
use anyhow::Result;
use vkcore::Frame;

pub use super::shared::splat::record_cleared;
pub use super::shared::{CausticPasses, FrameInputs};

/// What one frame records beyond the splat.
#[derive(Clone, Copy, Default)]
pub struct CausticFrame<'a> {
    /// Render the receiver positions, back faces and photon buffer again. False reuses the
    /// previous frame's photons: static lighting in Wyman & Davis 2006 Table 1, where "the
    /// photon buffer does not need rerendering" and only the splat and eye passes run.
    pub reuse_photons: bool,
    /// Copy the photon buffer into a vertex array and splat from it (Wyman 2008 Table 1).
    pub copy: Option<&'a PhotonCopy>,
    /// Trace a photon per vertex instead of the photon buffer (Shah's first pass).
    pub vertex_photons: Option<&'a VertexPhotons>,
    /// Traverse the photon hierarchy and splat its final list (Wyman 2008 Sec. 3.1-3.2).
    pub hierarchy: Option<&'a Hierarchy>,
    /// Create photons adaptively from geometry buffers and splat them (Wyman & Nichols 2009
    /// Sec. 3.2), instead of a photon buffer.
    pub adaptive: Option<&'a AdaptiveCaustics>,
    /// Create the photon buffer by deferred shading (`photon_refraction = deferred`, Wyman &
    /// Nichols 2009 Sec. 3.2, 3.1.1) instead of rasterizing the specular objects.
    pub deferred_photons: Option<&'a DeferredPhotons>,
    /// Splat with a compute shader instead of points (`splat_path = compute`).
    pub compute_splat: Option<&'a ComputeSplat>,
    /// Wyman & Davis 2006's eye-space points, quads or gathers instead of a splat, with the
    /// eye's view where they render into it.
    pub image_space: Option<(&'a ImageSpace, Option<EyeView<'a>>)>,
}

/// Light `l`'s light-space work before its splat: receiver positions, back faces, the photon
/// buffer, and the copy or the hierarchy's build and traversal that read it. One set of these
/// buffers serves every light, light after light; `Renderer::dumps` records this alone to read a
/// light's back.
pub fn record_light_space(f: &mut Frame, c: &CausticPasses, l: u32, frame: CausticFrame) -> Result<()> {
    let (pt, inp) = (c.photons, c.inputs);
    if let Some(a) = frame.adaptive {
        // No photon buffer and no back-face pass: the geometry buffers hold the back faces.
        photon_buffer::record_receiver_positions(f, c, l)?;
        return a.record_traversal(f, c.inputs, l, None);
    }
    match (frame.vertex_photons, frame.deferred_photons) {
        (Some(vp), _) => {
            photon_buffer::record_light_views(f, c, l)?;
            vp.record(f, c, l)?
        }
        // Wyman & Nichols 2009 Sec. 3.2: the geometry buffers hold the back faces.
        (None, Some(dp)) => {
            photon_buffer::record_receiver_positions(f, c, l)?;
            dp.record(f, c, l)?
        }
        (None, None) => {
            photon_buffer::record_light_views(f, c, l)?;
            photon_buffer::record_photon_buffer(f, c, l)?
        }
    }
    // The copied vertex arrays and the traversal's list stay valid as long as the photon
    // buffer does.
    if let Some(copy) = frame.copy {
        copy.record(f, pt, l)?;
    }
    if let Some(h) = frame.hierarchy {
        h.record_traversal(f, inp, pt, l)?;
    }
    Ok(())
}

/// One part of light `l`'s batched adaptive traversal alone, without its splat: the
/// breadth-first levels, or one batch after them (`Renderer::dumps` reads each batch's lists
/// so; a frame's traversal leaves only the last batch's).
pub fn record_adaptive_part(f: &mut Frame, c: &CausticPasses, a: &AdaptiveCaustics, l: u32, part: Part) -> Result<()> {
    match part {
        Part::Breadth => {
            photon_buffer::record_receiver_positions(f, c, l)?;
            a.record_breadth(f, c.inputs, l, None)?;
        }
        Part::Batch(b) => a.record_batch(f, c.inputs, l, b, None)?,
    }
    Ok(())
}

pub fn record_caustics(f: &mut Frame, c: &CausticPasses, lights: u32, frame: CausticFrame) -> Result<()> {
    let (ct, pt, inp) = (c.targets, c.photons, c.inputs);
    for l in 0..lights {
        if let Some(a) = frame.adaptive {
            // Adaptive caustic maps splat batch after batch inside their traversal (Sec. 4.3).
            let cmap = &ct.per_light[l as usize].0;
            let splat = adaptive::Splat {
                inputs: inp,
                compute: frame.compute_splat,
                photon_targets: pt,
                cmap,
                layers: ct.levels,
            };
            if frame.reuse_photons && !a.plan().batched() {
                a.record_splat_batch(f, &splat, l, crate::gpu::BatchPart::Whole, true, true)?;
            } else {
                photon_buffer::record_receiver_positions(f, c, l)?;
                a.record_traversal(f, c.inputs, l, Some(&splat))?;
            }
            continue;
        }
        if !frame.reuse_photons {
            record_light_space(f, c, l, frame)?;
        }
        if let Some((is, eye)) = frame.image_space {
            is.record_light(f, c, l, eye, frame.reuse_photons)?;
            continue;
        }
        let cmap = &ct.per_light[l as usize].0;
        match (frame.hierarchy, frame.compute_splat, frame.copy) {
            (Some(h), None, _) => h.record_splat(f, inp, pt, cmap, ct.levels, l)?,
            (Some(h), Some(cs), _) => cs.record(f, inp, pt, &h.final_list(), cmap, l)?,
            (None, Some(cs), _) => cs.record(f, inp, pt, &compute_splat::Photons::Dense, cmap, l)?,
            (None, None, Some(copy)) => copy.record_splat(f, inp, cmap, l)?,
            (None, None, None) => splat::record_splat(f, c, l)?,
        }
    }
    if let Some((is, eye)) = frame.image_space {
        is.record_after_lights(f, c, eye, frame.reuse_photons)?;
    }
    Ok(())
}
