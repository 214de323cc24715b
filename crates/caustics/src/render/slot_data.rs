//! The mesh renderer's per-frame data (`crate::gpu::frame_mode`): the uniform buffers the passes
//! bind and the moved meshes' vertices. One-shot frames update one device buffer by a pass and
//! upload moved meshes at once; a ring of frames in flight writes each slot's own host-visible
//! uniforms and copies moved meshes from the slot's staging buffer inside the frame, so that a
//! warm frame creates nothing.

use crate::gpu::frames::Slot;
use crate::gpu::{setup, FrameMode, FrameUniforms, GpuMesh, Stage};
use crate::scene::Scene;
use crate::techniques::uniforms::CausticUniforms;
use anyhow::{Context as _, Result};
use vkcore::{Access, Buffer, Context, Frame, Memory, Use};

pub struct SlotData {
    /// One device buffer (one-shot frames) or one host-written buffer per ring slot.
    frame_uniforms: Vec<Buffer>,
    caustic_uniforms: Vec<Buffer>,
    /// The slot the frame being recorded (or the last one) uses.
    slot: usize,
    /// The uniforms of the current pose, and those one-shot frames have not written yet.
    current: (FrameUniforms, CausticUniforms),
    pending: Option<(FrameUniforms, CausticUniforms)>,
    /// Throughput frames: the meshes the last pose moved, and per slot one staging buffer for
    /// every mesh's vertices (made by the first frame that moves one).
    moved: Vec<usize>,
    staging: Vec<Option<Buffer>>,
}

impl SlotData {
    pub fn new(ctx: &Context, mode: FrameMode, uniforms: (FrameUniforms, CausticUniforms)) -> Result<SlotData> {
        let (fu, cu) = uniforms;
        let (frame_uniforms, caustic_uniforms, slots) = match mode {
            FrameMode::PerPass => (
                vec![ctx.buffer_with_data("frame uniforms", bytemuck::bytes_of(&fu))?],
                vec![ctx.buffer_with_data("caustic uniforms", bytemuck::bytes_of(&cu))?],
                0,
            ),
            FrameMode::Throughput { slots } => {
                let host = |name: &str, bytes: &[u8]| -> Result<Buffer> {
                    let mut b = Buffer::new(ctx, name, bytes.len() as u64, Memory::Upload)?;
                    b.write_mapped(0, bytes)?;
                    Ok(b)
                };
                let f = (0..slots).map(|s| host(&format!("frame uniforms, slot {s}"), bytemuck::bytes_of(&fu)));
                let c = (0..slots).map(|s| host(&format!("caustic uniforms, slot {s}"), bytemuck::bytes_of(&cu)));
                (f.collect::<Result<_>>()?, c.collect::<Result<_>>()?, slots)
            }
        };
        Ok(SlotData {
            frame_uniforms,
            caustic_uniforms,
            slot: 0,
            current: uniforms,
            pending: None,
            moved: vec![],
            staging: (0..slots).map(|_| None).collect(),
        })
    }

    /// The uniform buffers of the frame being recorded.
    pub fn frame_uniforms(&self) -> &Buffer {
        &self.frame_uniforms[self.slot]
    }

    pub fn caustic_uniforms(&self) -> &Buffer {
        &self.caustic_uniforms[self.slot]
    }

    /// The uniforms of the current pose.
    pub fn current(&self) -> &(FrameUniforms, CausticUniforms) {
        &self.current
    }

    /// Whether a new pose's uniforms wait for the next one-shot frame.
    pub fn pending(&self) -> bool {
        self.pending.is_some()
    }

    /// A new pose: its uniforms, written by the next frame.
    pub fn set_uniforms(&mut self, uniforms: (FrameUniforms, CausticUniforms)) {
        self.current = uniforms;
        self.pending = Some(uniforms);
    }

    /// The splat radius of the next frames (caustic-map texels: `photon-trace`'s progressive
    /// accumulation shrinks it frame by frame), written by the next frame.
    pub fn set_splat_radius(&mut self, radius: f32) {
        self.current.1.splat[0] = radius;
        self.pending = Some(self.current);
    }

    /// Mesh `i` moved: true if the next frame copies it (throughput frames), false if the
    /// caller uploads it now.
    pub fn mesh_moved(&mut self, i: usize) -> bool {
        // Throughput frames have a staging slot per ring slot; one-shot frames none.
        let throughput = !self.staging.is_empty();
        if throughput && !self.moved.contains(&i) {
            self.moved.push(i);
        }
        throughput
    }

    /// The start of a frame: a one-shot frame writes pending uniforms by a pass; a throughput
    /// frame writes its slot's uniforms and copies the moved meshes of `scene` from its
    /// slot's staging buffer.
    pub fn record(
        &mut self,
        ctx: &Context,
        f: &mut Frame,
        slot: Option<Slot>,
        meshes: &[GpuMesh],
        scene: &Scene,
    ) -> Result<()> {
        let Some(slot) = slot else {
            self.slot = 0;
            if let Some((fu, cu)) = self.pending.take() {
                let (u, c) = (&self.frame_uniforms[0], &self.caustic_uniforms[0]);
                let uses = [Use::buffer(u, Access::TRANSFER_WRITE), Use::buffer(c, Access::TRANSFER_WRITE)];
                f.pass(&Stage::Uniforms.pass()).uses(uses).record(|cmd| {
                    cmd.update_buffer(u, 0, bytemuck::bytes_of(&fu))?;
                    cmd.update_buffer(c, 0, bytemuck::bytes_of(&cu))?;
                    Ok(())
                })?;
            }
            return Ok(());
        };
        let s = slot.index;
        self.slot = s;
        self.pending = None;
        let (fu, cu) = self.current;
        self.frame_uniforms[s].write_mapped(0, bytemuck::bytes_of(&fu))?;
        self.caustic_uniforms[s].write_mapped(0, bytemuck::bytes_of(&cu))?;
        self.record_moved_meshes(ctx, f, s, meshes, scene)
    }

    /// Copies the meshes the last pose moved from slot `s`'s staging buffer (every slot's made,
    /// each for every mesh's vertices at once, by the first frame that needs one).
    fn record_moved_meshes(
        &mut self,
        ctx: &Context,
        f: &mut Frame,
        s: usize,
        meshes: &[GpuMesh],
        scene: &Scene,
    ) -> Result<()> {
        if self.moved.is_empty() {
            return Ok(());
        }
        let total: u64 = meshes.iter().map(|m| m.vertices.size()).sum();
        for (k, staging) in self.staging.iter_mut().enumerate() {
            if staging.is_none() {
                *staging = Some(Buffer::new(ctx, &format!("moved meshes, slot {k}"), total, Memory::Upload)?);
            }
        }
        let staging = self.staging[s].as_mut().context("staging")?;
        let mut regions = vec![];
        let mut offset = 0u64;
        for (i, mesh) in meshes.iter().enumerate() {
            if self.moved.contains(&i) {
                let vertices = setup::mesh_vertices(&scene.objects[i].mesh, &mesh.thickness);
                let bytes: &[u8] = bytemuck::cast_slice(&vertices);
                staging.write_mapped(offset, bytes)?;
                regions.push((i, offset, bytes.len() as u64));
            }
            offset += mesh.vertices.size();
        }
        self.moved.clear();
        let staging = &*staging;
        let mut uses = vec![Use::buffer(staging, Access::TRANSFER_READ)];
        uses.extend(regions.iter().map(|&(i, _, _)| Use::buffer(&meshes[i].vertices, Access::TRANSFER_WRITE)));
        f.pass(&Stage::UploadMeshes.pass()).uses(uses).record(|cmd| {
            for &(i, at, bytes) in &regions {
                cmd.copy_buffer_region(staging, at, &meshes[i].vertices, 0, bytes);
            }
            Ok(())
        })?;
        Ok(())
    }
}
