//! Records the caustic passes of one frame, light after light: receiver positions (Shah step 1),
//! the refractor's back faces from the light, the photon buffer (or vertex photons), and the
//! splat into the light's caustic-map layer.

use super::compute_splat::{self, ComputeSplat};
use super::hierarchy::{Hierarchy, Inputs as HierarchyInputs};
use super::photon_copy::PhotonCopy;
use super::pipelines::CausticPipelines;
use super::targets::{CausticTargets, PhotonTargets};
use crate::render::gpu::{MATERIAL_DIFFUSE, MATERIAL_REFRACTIVE};
use crate::render::setup::{mesh_uses, GpuMesh};
use anyhow::Result;
use vkcore::{Access, Bind, Buffer, Frame, Sampler, Targets, Use};

pub struct CausticInputs<'a> {
    pub frame_uniforms: &'a Buffer,
    pub caustic_uniforms: &'a Buffer,
    pub meshes: &'a [GpuMesh],
    /// Per mesh: a third of each vertex's triangle areas (vertex photons only).
    pub vertex_areas: &'a [Option<Buffer>],
    /// 0..instance_vertices, for instanced photon fetch.
    pub splat_vertices: &'a Buffer,
    /// Vertices per instance of the instanced fetch (Wyman 2008 Sec. 4).
    pub instance_vertices: u32,
    pub nearest: &'a Sampler,
}

/// What one frame records beyond the splat.
#[derive(Clone, Copy, Default)]
pub struct CausticFrame<'a> {
    /// Render the receiver positions, back faces and photon buffer again. False reuses the
    /// previous frame's photons: static lighting in Wyman & Davis 2006 Table 1, where "the
    /// photon buffer does not need rerendering" and only the splat and eye passes run.
    pub reuse_photons: bool,
    /// Copy the photon buffer into a vertex array and splat from it (Wyman 2008 Table 1).
    pub copy: Option<&'a PhotonCopy>,
    /// Traverse the photon hierarchy and splat its final list (Wyman 2008 Sec. 3.1-3.2).
    pub hierarchy: Option<&'a Hierarchy>,
    /// Splat with a compute shader instead of points (`splat_path = compute`).
    pub compute_splat: Option<&'a ComputeSplat>,
}

impl<'a> CausticInputs<'a> {
    /// What the hierarchy's passes (and the `splats` dump) read of these.
    pub fn hierarchy(&self) -> HierarchyInputs<'a> {
        HierarchyInputs {
            frame_uniforms: self.frame_uniforms,
            caustic_uniforms: self.caustic_uniforms,
            nearest: self.nearest,
        }
    }
}

/// Light `l`'s light-space work before its splat: receiver positions, back faces, the photon
/// buffer, and the copy or the hierarchy's build and traversal that read it. One set of these
/// buffers serves every light, light after light; `Renderer::dumps` records this alone to read a
/// light's back.
pub fn record_light_space(
    f: &mut Frame,
    p: &CausticPipelines,
    ct: &CausticTargets,
    pt: &PhotonTargets,
    inp: &CausticInputs,
    l: u32,
    frame: CausticFrame,
) -> Result<()> {
    record_photons(f, p, ct, pt, inp, l)?;
    // The copied vertex arrays and the traversal's list stay valid as long as the photon
    // buffer does.
    if let Some(copy) = frame.copy {
        copy.record(f, pt, l)?;
    }
    if let Some(h) = frame.hierarchy {
        h.record_traversal(f, &inp.hierarchy(), pt, l)?;
    }
    Ok(())
}

pub fn record_caustics(
    f: &mut Frame,
    p: &CausticPipelines,
    ct: &CausticTargets,
    pt: &PhotonTargets,
    inp: &CausticInputs,
    lights: u32,
    frame: CausticFrame,
) -> Result<()> {
    for l in 0..lights {
        if !frame.reuse_photons {
            record_light_space(f, p, ct, pt, inp, l, frame)?;
        }
        let cmap = &ct.per_light[l as usize].0;
        let splat_inputs = compute_splat::Inputs {
            frame_uniforms: inp.frame_uniforms,
            caustic_uniforms: inp.caustic_uniforms,
            nearest: inp.nearest,
        };
        match (frame.hierarchy, frame.compute_splat) {
            (Some(h), None) => h.record_splat(f, &inp.hierarchy(), pt, cmap, ct.levels, l)?,
            (Some(h), Some(cs)) => cs.record(f, &splat_inputs, pt, &h.final_list(), cmap, l)?,
            (None, Some(cs)) => cs.record(f, &splat_inputs, pt, &compute_splat::Photons::Dense, cmap, l)?,
            (None, None) => record_splat(f, p, ct, pt, inp, l, frame.copy)?,
        }
    }
    Ok(())
}

fn ubo_uses<'a>(inp: &CausticInputs<'a>) -> [Use<'a>; 2] {
    [Use::buffer(inp.frame_uniforms, Access::UNIFORM_READ), Use::buffer(inp.caustic_uniforms, Access::UNIFORM_READ)]
}

/// Receiver positions, the refractors' back faces and the photon buffer (or vertex photons)
/// of light `l`.
fn record_photons(
    f: &mut Frame,
    p: &CausticPipelines,
    ct: &CausticTargets,
    pt: &PhotonTargets,
    inp: &CausticInputs,
    l: u32,
) -> Result<()> {
    let ubos = || ubo_uses(inp);
    let ubo_binds = || [Bind::Uniform(inp.frame_uniforms), Bind::Uniform(inp.caustic_uniforms)];
    {
        let (_, rpos, rdepth) = &ct.per_light[l as usize];
        let mut uses = Vec::from(ubos());
        uses.extend([Use::view(rpos, Access::COLOR_ATTACHMENT), Use::view(rdepth, Access::DEPTH_ATTACHMENT)]);
        uses.extend(mesh_uses(inp.meshes));
        f.pass(&format!("receiver_positions.light{l}"), &uses, |cmd| {
            cmd.begin_rendering(&Targets::color(rpos, Some([0.0; 4])).with_depth(rdepth, Some(1.0)))?;
            cmd.bind_pipeline(&p.receiver_positions);
            cmd.bind(&ubo_binds())?;
            for m in inp.meshes.iter().filter(|m| m.kind() == MATERIAL_DIFFUSE) {
                m.draw(cmd, 1, l)?;
            }
            cmd.end_rendering();
            Ok(())
        })?;

        let mut uses = Vec::from(ubos());
        uses.extend([
            Use::view(&pt.back_faces.view, Access::COLOR_ATTACHMENT),
            Use::view(&pt.depth.view, Access::DEPTH_ATTACHMENT),
        ]);
        uses.extend(mesh_uses(inp.meshes));
        f.pass(&format!("photon_back_faces.light{l}"), &uses, |cmd| {
            cmd.begin_rendering(
                &Targets::color(&pt.back_faces.view, Some([0.0; 4])).with_depth(&pt.depth.view, Some(1.0)),
            )?;
            cmd.bind_pipeline(&p.back_faces);
            cmd.bind(&ubo_binds())?;
            for m in inp.meshes.iter().filter(|m| m.kind() == MATERIAL_REFRACTIVE) {
                m.draw(cmd, 1, l)?;
            }
            cmd.end_rendering();
            Ok(())
        })?;

        let photons = [&pt.position, &pt.direction, &pt.power];
        // What tracing a photon reads (photons/trace.glsl, bindings 0-3).
        let trace_binds = || {
            vec![
                Bind::Uniform(inp.frame_uniforms),
                Bind::Uniform(inp.caustic_uniforms),
                Bind::Sampled(&pt.back_faces.view, inp.nearest),
                Bind::Sampled(&ct.receiver_positions.view, inp.nearest),
            ]
        };
        let mut uses = Vec::from(ubos());
        uses.extend([
            Use::view(&pt.back_faces.view, Access::SHADER_READ),
            Use::view(&ct.receiver_positions.view, Access::SHADER_READ),
        ]);
        uses.extend(mesh_uses(inp.meshes));
        let specular = || inp.meshes.iter().filter(|m| m.kind() != MATERIAL_DIFFUSE);
        if let Some(vp) = &p.vertex_photons {
            let clear: Vec<Use> = photons.iter().map(|t| Use::view(&t.view, Access::TRANSFER_WRITE)).collect();
            f.pass(&format!("vertex_photons.clear.light{l}"), &clear, |cmd| {
                for t in photons {
                    cmd.clear_color(&t.view, [0.0; 4]);
                }
                Ok(())
            })?;
            uses.extend(photons.iter().map(|t| Use::view(&t.view, Access::GRAPHICS_READ_WRITE)));
            uses.extend(inp.vertex_areas.iter().flatten().map(|b| Use::buffer(b, Access::STORAGE_READ)));
            f.pass(&format!("vertex_photons.light{l}"), &uses, |cmd| {
                cmd.begin_rendering(&Targets::none())?;
                cmd.bind_pipeline(vp);
                let mut first = 0u32;
                for (m, areas) in inp.meshes.iter().zip(inp.vertex_areas) {
                    let (true, Some(areas)) = (m.kind() != MATERIAL_DIFFUSE, areas) else { continue };
                    let mut binds = trace_binds();
                    binds.extend(photons.map(|t| Bind::Storage(&t.view)));
                    binds.push(Bind::Buffer(areas));
                    cmd.bind(&binds)?;
                    let mut c = m.constants;
                    c.info[1] = l;
                    c.info[3] = first;
                    cmd.push(&c)?;
                    cmd.bind_vertex_buffer(&m.vertices, 0);
                    let vertices = (m.vertices.size() / 28) as u32;
                    cmd.draw(vertices, 1, 0, 0);
                    first += vertices;
                }
                cmd.end_rendering();
                Ok(())
            })?;
        } else {
            uses.extend(photons.iter().map(|t| Use::view(&t.view, Access::COLOR_ATTACHMENT)));
            uses.push(Use::view(&pt.depth.view, Access::DEPTH_ATTACHMENT));
            f.pass(&format!("photon_buffer.light{l}"), &uses, |cmd| {
                let targets = Targets::colors(photons.iter().map(|t| (&t.view, Some([0.0; 4]))).collect());
                cmd.begin_rendering(&targets.with_depth(&pt.depth.view, Some(1.0)))?;
                cmd.bind_pipeline(&p.photon_buffer);
                cmd.bind(&trace_binds())?;
                for m in specular() {
                    m.draw(cmd, 1, l)?;
                }
                cmd.end_rendering();
                Ok(())
            })?;
        }
    }
    Ok(())
}

/// Splats light `l`'s photons into its caustic-map layer: instanced fetch from the photon
/// texture (Wyman 2008 Sec. 4), or one vertex per photon from the copied vertex array.
fn record_splat(
    f: &mut Frame,
    p: &CausticPipelines,
    ct: &CausticTargets,
    pt: &PhotonTargets,
    inp: &CausticInputs,
    l: u32,
    copy: Option<&PhotonCopy>,
) -> Result<()> {
    let (cmap, _, _) = &ct.per_light[l as usize];
    let mut uses = Vec::from(ubo_uses(inp));
    uses.push(Use::view(cmap, Access::COLOR_ATTACHMENT));
    if let (Some(copy), Some(pipeline)) = (copy, &p.splat_vertex_array) {
        uses.push(Use::buffer(&copy.positions, Access::VERTEX_INPUT));
        uses.push(Use::buffer(&copy.powers, Access::STORAGE_READ));
        f.pass(&format!("splat.light{l}"), &uses, |cmd| {
            cmd.begin_rendering(&Targets::color(cmap, Some([0.0; 4])))?;
            cmd.bind_pipeline(pipeline);
            cmd.bind(&[
                Bind::Uniform(inp.frame_uniforms),
                Bind::Uniform(inp.caustic_uniforms),
                Bind::Buffer(&copy.powers),
            ])?;
            let c = crate::render::gpu::ObjectConstants { info: [0, l, 0, 0], ..Default::default() };
            cmd.push(&c)?;
            cmd.bind_vertex_buffer(&copy.positions, 0);
            cmd.draw(copy.vertices(), 1, 0, 0);
            cmd.end_rendering();
            Ok(())
        })?;
        return Ok(());
    }
    uses.extend([Use::view(&pt.position.view, Access::SHADER_READ), Use::view(&pt.power.view, Access::SHADER_READ)]);
    uses.push(Use::buffer(inp.splat_vertices, Access::VERTEX_INPUT));
    {
        f.pass(&format!("splat.light{l}"), &uses, |cmd| {
            cmd.begin_rendering(&Targets::color(cmap, Some([0.0; 4])))?;
            cmd.bind_pipeline(&p.splat);
            cmd.bind(&[
                Bind::Uniform(inp.frame_uniforms),
                Bind::Uniform(inp.caustic_uniforms),
                Bind::Sampled(&pt.position.view, inp.nearest),
                Bind::Sampled(&pt.power.view, inp.nearest),
            ])?;
            let c =
                crate::render::gpu::ObjectConstants { info: [0, l, inp.instance_vertices, 0], ..Default::default() };
            cmd.push(&c)?;
            cmd.bind_vertex_buffer(inp.splat_vertices, 0);
            let total = pt.width * pt.width;
            // Wyman 2008 Sec. 4: one small vertex buffer drawn instanced; the vertex shader
            // finds its photon from gl_InstanceIndex and the vertex's index.
            cmd.draw(inp.instance_vertices, total.div_ceil(inp.instance_vertices), 0, 0);
            cmd.end_rendering();
            Ok(())
        })?;
    }
    Ok(())
}

/// With technique `none`: clears the (1x1) caustic map and receiver positions the eye passes bind.
pub fn record_cleared(f: &mut Frame, ct: &CausticTargets) -> Result<()> {
    let uses = [
        Use::view(&ct.caustic_map.view, Access::TRANSFER_WRITE),
        Use::view(&ct.receiver_positions.view, Access::TRANSFER_WRITE),
    ];
    f.pass("caustics.clear", &uses, |cmd| {
        cmd.clear_color(&ct.caustic_map.view, [0.0; 4]);
        cmd.clear_color(&ct.receiver_positions.view, [0.0; 4]);
        Ok(())
    })?;
    Ok(())
}
