//! `Cmd`: the commands a pass may record. Safe signatures over raw ash calls; resources are
//! borrowed, and frames are waited for before anything they used can be dropped.

use crate::bind::{check_binds, Bind, Named};
use crate::buffer::Buffer;
use crate::context::Context;
use crate::error::{Result, VkError};
use crate::frame::{sync, Use};
use crate::image::{aspect, Image, ImageView};
use crate::pipeline::{Binding, Pipeline, PUSH_CONSTANT_BYTES};
use crate::push::PushConstants;
use crate::query::QueryPool;
use crate::tracker::Access;
use ash::vk;
use std::sync::Arc;

/// Colour and depth targets of a rendering scope. All views must have the same extent.
pub struct Targets<'a> {
    /// (view, clear colour or None to load)
    pub color: Vec<(&'a ImageView, Option<[f32; 4]>)>,
    /// (view, clear depth or None to load)
    pub depth: Option<(&'a ImageView, Option<f32>)>,
    /// Layers rendered (layered rendering with gl_Layer); ignored with multiview.
    pub layers: u32,
    /// Multiview mask; 0 = off.
    pub view_mask: u32,
    /// Render area when there are no attachments (transform-feedback passes).
    pub extent: Option<(u32, u32)>,
}

impl<'a> Targets<'a> {
    pub fn color(view: &'a ImageView, clear: Option<[f32; 4]>) -> Self {
        Targets { color: vec![(view, clear)], depth: None, layers: 1, view_mask: 0, extent: None }
    }
    /// Several colour targets (multiple render targets).
    pub fn colors(views: Vec<(&'a ImageView, Option<[f32; 4]>)>) -> Self {
        Targets { color: views, depth: None, layers: 1, view_mask: 0, extent: None }
    }
    /// Depth only.
    pub fn depth_only(view: &'a ImageView, clear: Option<f32>) -> Self {
        Targets { color: vec![], depth: Some((view, clear)), layers: 1, view_mask: 0, extent: None }
    }
    /// No attachments at all: a rendering scope for rasterizer-discard (transform feedback) draws.
    pub fn none() -> Self {
        Targets { color: vec![], depth: None, layers: 1, view_mask: 0, extent: Some((1, 1)) }
    }
    pub fn with_depth(mut self, view: &'a ImageView, clear: Option<f32>) -> Self {
        self.depth = Some((view, clear));
        self
    }
    pub fn layered(mut self, layers: u32) -> Self {
        self.layers = layers;
        self
    }
    pub fn multiview(mut self, mask: u32) -> Self {
        self.view_mask = mask;
        self
    }
}

pub struct Cmd<'f> {
    ctx: &'f Context,
    cb: vk::CommandBuffer,
    bound: Option<Bound>,
    rendering: bool,
    /// (resource id, access) of everything the pass declared: what its descriptors may name.
    declared: Vec<(u64, Access)>,
}

/// The bound pipeline, as `bind` and `push` need it.
struct Bound {
    name: String,
    point: vk::PipelineBindPoint,
    layout: vk::PipelineLayout,
    /// The stages its layout names, which push constants must name too.
    stages: vk::ShaderStageFlags,
    bindings: Arc<[Binding]>,
}

impl<'f> Cmd<'f> {
    pub(crate) fn new(ctx: &'f Context, cb: vk::CommandBuffer, declared: Vec<(u64, Access)>) -> Self {
        Cmd { ctx, cb, bound: None, rendering: false, declared }
    }

    fn d(&self) -> &ash::Device {
        self.ctx.shared.raw()
    }

    /// The command buffer, for vkcore's own commands that no `Cmd` method records
    /// (`crate::accel`'s builds).
    pub(crate) fn raw_command_buffer(&self) -> vk::CommandBuffer {
        self.cb
    }

    pub(crate) fn begin_label(&mut self, name: &str) {
        if let (Some(du), Ok(c)) = (&self.ctx.shared.device.debug_utils, std::ffi::CString::new(name)) {
            let label = vk::DebugUtilsLabelEXT::default().label_name(&c);
            unsafe { du.cmd_begin_debug_utils_label(self.cb, &label) };
        }
    }

    pub(crate) fn end_label(&mut self) {
        if let Some(du) = &self.ctx.shared.device.debug_utils {
            unsafe { du.cmd_end_debug_utils_label(self.cb) };
        }
    }

    /// Barriers in the middle of a pass (outside rendering), e.g. between traversal levels.
    pub fn sync(&mut self, uses: &[Use]) -> Result<()> {
        if self.rendering {
            return Err(VkError::Invalid("Cmd::sync inside a rendering scope".into()));
        }
        sync(self.ctx, self.cb, uses)
    }

    /// Begins dynamic rendering into `t` and sets a full viewport and scissor.
    pub fn begin_rendering(&mut self, t: &Targets) -> Result<()> {
        let extent = t
            .color
            .first()
            .map(|c| c.0.extent)
            .or(t.depth.as_ref().map(|d| d.0.extent))
            .or(t.extent)
            .ok_or_else(|| VkError::Invalid("rendering with no targets".into()))?;
        let color: Vec<vk::RenderingAttachmentInfo> = t
            .color
            .iter()
            .map(|(v, clear)| {
                let a = vk::RenderingAttachmentInfo::default()
                    .image_view(v.raw)
                    .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
                    .store_op(vk::AttachmentStoreOp::STORE);
                match clear {
                    Some(c) => a
                        .load_op(vk::AttachmentLoadOp::CLEAR)
                        .clear_value(vk::ClearValue { color: vk::ClearColorValue { float32: *c } }),
                    None => a.load_op(vk::AttachmentLoadOp::LOAD),
                }
            })
            .collect();
        let depth = t.depth.as_ref().map(|(v, clear)| {
            let a = vk::RenderingAttachmentInfo::default()
                .image_view(v.raw)
                .image_layout(vk::ImageLayout::DEPTH_ATTACHMENT_OPTIMAL)
                .store_op(vk::AttachmentStoreOp::STORE);
            match clear {
                Some(c) => a.load_op(vk::AttachmentLoadOp::CLEAR).clear_value(vk::ClearValue {
                    depth_stencil: vk::ClearDepthStencilValue { depth: *c, stencil: 0 },
                }),
                None => a.load_op(vk::AttachmentLoadOp::LOAD),
            }
        });
        let area = vk::Rect2D {
            offset: vk::Offset2D { x: 0, y: 0 },
            extent: vk::Extent2D { width: extent.0, height: extent.1 },
        };
        let mut info = vk::RenderingInfo::default()
            .render_area(area)
            .layer_count(if t.view_mask != 0 { 1 } else { t.layers.max(1) })
            .view_mask(t.view_mask)
            .color_attachments(&color);
        if let Some(d) = depth.as_ref() {
            info = info.depth_attachment(d);
        }
        unsafe { self.d().cmd_begin_rendering(self.cb, &info) };
        self.rendering = true;
        self.viewport(0.0, 0.0, extent.0 as f32, extent.1 as f32);
        Ok(())
    }

    pub fn end_rendering(&mut self) {
        if self.rendering {
            unsafe { self.d().cmd_end_rendering(self.cb) };
            self.rendering = false;
        }
    }

    /// Viewport (y down, depth 0..1) and a matching scissor.
    pub fn viewport(&mut self, x: f32, y: f32, w: f32, h: f32) {
        let vp = vk::Viewport { x, y, width: w, height: h, min_depth: 0.0, max_depth: 1.0 };
        let sc = vk::Rect2D {
            offset: vk::Offset2D { x: x.max(0.0) as i32, y: y.max(0.0) as i32 },
            extent: vk::Extent2D { width: w.max(1.0) as u32, height: h.max(1.0) as u32 },
        };
        unsafe {
            self.d().cmd_set_viewport(self.cb, 0, &[vp]);
            self.d().cmd_set_scissor(self.cb, 0, &[sc]);
        }
    }

    /// Binds `p`. A pass built with `Pass::bind` has its pipeline bound already; this is for
    /// passes that push their descriptors themselves (`Pass::declare`) or switch pipelines.
    pub fn bind_pipeline(&mut self, p: &Pipeline) {
        let b = &p.built;
        unsafe { self.d().cmd_bind_pipeline(self.cb, b.bind_point, b.raw) };
        self.bound = Some(Bound {
            name: p.name.clone(),
            point: b.bind_point,
            layout: b.layout,
            stages: b.stages,
            bindings: b.bindings.clone(),
        });
    }

    /// Pushes descriptors for the bound pipeline, each under its shader's name for the binding,
    /// in binding order (checked: `bind.rs`). Each must have been declared by the pass
    /// (`Pass::bind` or `Pass::declare`), or its barrier is missing.
    pub fn bind(&mut self, binds: &[Named]) -> Result<()> {
        let Bound { name, point, bindings, .. } =
            self.bound.as_ref().ok_or_else(|| VkError::Invalid("bind() before bind_pipeline()".into()))?;
        check_binds(name, bindings, binds)?;
        if let Some((n, _)) = binds.iter().find(|(_, b)| !self.declared.contains(&b.to_use(*point).key())) {
            return Err(VkError::Invalid(format!(
                "binding `{n}` of pipeline `{name}`: its resource was not declared by the pass (Pass::bind or \
                 Pass::declare)"
            )));
        }
        self.push_descriptors(binds)
    }

    /// Pushes `binds` for the bound pipeline without checking them: `Pass::bind` checked them
    /// against the pipeline and declared them when the pass was described.
    pub(crate) fn push_descriptors(&mut self, binds: &[Named]) -> Result<()> {
        let Bound { point, layout, bindings, .. } =
            self.bound.as_ref().ok_or_else(|| VkError::Invalid("bind() before bind_pipeline()".into()))?;
        if binds.is_empty() {
            return Ok(());
        }
        let mut image_infos = Vec::with_capacity(binds.len());
        let mut buffer_infos = Vec::with_capacity(binds.len());
        let mut structures = vec![];
        for (_, b) in binds {
            match b {
                Bind::Sampled(v, s) => image_infos.push(
                    vk::DescriptorImageInfo::default()
                        .image_view(v.raw)
                        .sampler(s.raw)
                        .image_layout(vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL),
                ),
                Bind::Storage(v) => image_infos
                    .push(vk::DescriptorImageInfo::default().image_view(v.raw).image_layout(vk::ImageLayout::GENERAL)),
                Bind::Buffer(buf) | Bind::BufferRead(buf) | Bind::Uniform(buf) => buffer_infos
                    .push(vk::DescriptorBufferInfo::default().buffer(buf.raw).offset(0).range(vk::WHOLE_SIZE)),
                Bind::BufferRange(buf, o, s) => {
                    buffer_infos.push(vk::DescriptorBufferInfo::default().buffer(buf.raw).offset(*o).range(*s))
                }
                Bind::AccelerationStructure(a) => structures.push(a.raw),
            }
        }
        let mut structure_writes: Vec<vk::WriteDescriptorSetAccelerationStructureKHR> = structures
            .iter()
            .map(|s| {
                vk::WriteDescriptorSetAccelerationStructureKHR::default()
                    .acceleration_structures(std::slice::from_ref(s))
            })
            .collect();
        let mut structure_writes = structure_writes.iter_mut();
        let (mut ii, mut bi) = (0, 0);
        let mut writes = vec![];
        // check_binds matched binds[i] to bindings[i] (here or in Pass::bind).
        for ((_, b), binding) in binds.iter().zip(bindings.iter()) {
            let w = vk::WriteDescriptorSet::default().dst_binding(binding.binding).descriptor_type(binding.kind.vk());
            match b {
                Bind::Sampled(..) | Bind::Storage(..) => {
                    writes.push(w.image_info(std::slice::from_ref(&image_infos[ii])));
                    ii += 1;
                }
                Bind::AccelerationStructure(_) => {
                    let next =
                        structure_writes.next().ok_or_else(|| VkError::Invalid("acceleration structures".into()))?;
                    writes.push(w.descriptor_count(1).push_next(next));
                }
                _ => {
                    writes.push(w.buffer_info(std::slice::from_ref(&buffer_infos[bi])));
                    bi += 1;
                }
            }
        }
        unsafe { self.ctx.shared.device.push_descriptor.cmd_push_descriptor_set(self.cb, *point, *layout, 0, &writes) };
        Ok(())
    }

    /// Push constants (at most 128 bytes) for every stage of the bound pipeline: a struct
    /// declared with `push_constants!`, twin of the shaders' `layout(push_constant)` block.
    pub fn push<T: PushConstants>(&mut self, data: &T) -> Result<()> {
        let bytes = bytemuck::bytes_of(data);
        if bytes.len() as u32 > PUSH_CONSTANT_BYTES {
            return Err(VkError::Invalid(format!(
                "push constants of {} bytes exceed {PUSH_CONSTANT_BYTES}",
                bytes.len()
            )));
        }
        let (layout, stages) = self
            .bound
            .as_ref()
            .map(|b| (b.layout, b.stages))
            .ok_or_else(|| VkError::Invalid("push() before bind_pipeline()".into()))?;
        unsafe { self.d().cmd_push_constants(self.cb, layout, stages, 0, bytes) };
        Ok(())
    }

    /// An error unless the pass declared `b` with `access` (`Pass::uses`): what a command reads
    /// outside its descriptors must have its barrier too.
    fn declared(&self, b: &Buffer, (access, name): (Access, &str), what: &str) -> Result<()> {
        if self.declared.contains(&(b.id, access)) {
            return Ok(());
        }
        Err(VkError::Invalid(format!(
            "{what}: buffer `{}` was not declared by the pass (Pass::uses with Use::buffer(.., Access::{name}))",
            b.name()
        )))
    }

    /// Binds `b` as vertex buffer 0; the pass must declare it `Access::VERTEX_INPUT`.
    pub fn bind_vertex_buffer(&mut self, b: &Buffer, offset: u64) -> Result<()> {
        self.declared(b, (Access::VERTEX_INPUT, "VERTEX_INPUT"), "bind_vertex_buffer")?;
        unsafe { self.d().cmd_bind_vertex_buffers(self.cb, 0, &[b.raw], &[offset]) };
        Ok(())
    }

    /// Binds `b` as the index buffer (u32); the pass must declare it `Access::VERTEX_INPUT`.
    pub fn bind_index_buffer(&mut self, b: &Buffer) -> Result<()> {
        self.declared(b, (Access::VERTEX_INPUT, "VERTEX_INPUT"), "bind_index_buffer")?;
        unsafe { self.d().cmd_bind_index_buffer(self.cb, b.raw, 0, vk::IndexType::UINT32) };
        Ok(())
    }

    pub fn draw(&mut self, vertices: u32, instances: u32, first_vertex: u32, first_instance: u32) {
        unsafe { self.d().cmd_draw(self.cb, vertices, instances, first_vertex, first_instance) };
    }

    pub fn draw_indexed(&mut self, indices: u32, instances: u32, first_index: u32) {
        unsafe { self.d().cmd_draw_indexed(self.cb, indices, instances, first_index, 0, 0) };
    }

    /// One VkDrawIndirectCommand at `offset`; the pass must declare `args` `Access::INDIRECT`.
    pub fn draw_indirect(&mut self, args: &Buffer, offset: u64) -> Result<()> {
        self.declared(args, (Access::INDIRECT, "INDIRECT"), "draw_indirect")?;
        unsafe { self.d().cmd_draw_indirect(self.cb, args.raw, offset, 1, 16) };
        Ok(())
    }

    pub fn dispatch(&mut self, x: u32, y: u32, z: u32) {
        unsafe { self.d().cmd_dispatch(self.cb, x, y, z) };
    }

    /// One VkDispatchIndirectCommand at `offset`; the pass must declare `args` `Access::INDIRECT`.
    pub fn dispatch_indirect(&mut self, args: &Buffer, offset: u64) -> Result<()> {
        self.declared(args, (Access::INDIRECT, "INDIRECT"), "dispatch_indirect")?;
        unsafe { self.d().cmd_dispatch_indirect(self.cb, args.raw, offset) };
        Ok(())
    }

    /// vkCmdFillBuffer over the whole buffer (outside rendering).
    pub fn fill_buffer(&mut self, b: &Buffer, value: u32) {
        unsafe { self.d().cmd_fill_buffer(self.cb, b.raw, 0, vk::WHOLE_SIZE, value) };
    }

    /// vkCmdUpdateBuffer: writes up to 65536 bytes (a multiple of 4) at `offset`, outside rendering.
    pub fn update_buffer(&mut self, b: &Buffer, offset: u64, data: &[u8]) -> Result<()> {
        if data.is_empty()
            || !data.len().is_multiple_of(4)
            || data.len() > 65536
            || offset + data.len() as u64 > b.size()
        {
            return Err(VkError::Invalid(format!(
                "update_buffer: {} bytes at {offset} into `{}`",
                data.len(),
                b.name()
            )));
        }
        unsafe { self.d().cmd_update_buffer(self.cb, b.raw, offset, data) };
        Ok(())
    }

    pub fn copy_buffer(&mut self, src: &Buffer, dst: &Buffer, bytes: u64) {
        let region = vk::BufferCopy { src_offset: 0, dst_offset: 0, size: bytes };
        unsafe { self.d().cmd_copy_buffer(self.cb, src.raw, dst.raw, &[region]) };
    }

    /// Copies `bytes` from `src` at `src_offset` into `dst` at `dst_offset`.
    pub fn copy_buffer_region(&mut self, src: &Buffer, src_offset: u64, dst: &Buffer, dst_offset: u64, bytes: u64) {
        let region = vk::BufferCopy { src_offset, dst_offset, size: bytes };
        unsafe { self.d().cmd_copy_buffer(self.cb, src.raw, dst.raw, &[region]) };
    }

    fn image_region(image: &Image, mip: u32, layer: u32) -> vk::BufferImageCopy {
        let (w, h) = image.mip_extent(mip);
        vk::BufferImageCopy {
            buffer_offset: 0,
            buffer_row_length: 0,
            buffer_image_height: 0,
            image_subresource: vk::ImageSubresourceLayers {
                aspect_mask: aspect(image.desc.format),
                mip_level: mip,
                base_array_layer: layer,
                layer_count: 1,
            },
            image_offset: vk::Offset3D::default(),
            image_extent: vk::Extent3D { width: w, height: h, depth: 1 },
        }
    }

    /// Copies one mip/layer of `image` (in TRANSFER_SRC layout, see `Access::TRANSFER_READ`) into `dst`.
    pub fn copy_image_to_buffer(&mut self, image: &Image, mip: u32, layer: u32, dst: &Buffer) {
        let r = Self::image_region(image, mip, layer);
        unsafe {
            self.d().cmd_copy_image_to_buffer(self.cb, image.raw, vk::ImageLayout::TRANSFER_SRC_OPTIMAL, dst.raw, &[r])
        };
    }

    /// Blits mip 0 / layer 0 of `src` (TRANSFER_SRC layout) onto mip 0 / layer 0 of `dst`
    /// (TRANSFER_DST layout), same extent, converting the texel format (e.g. 16-bit to 32-bit float).
    pub fn blit_converting(&mut self, src: &Image, dst: &Image) {
        let (w, h) = src.mip_extent(0);
        let sub = |i: &Image| vk::ImageSubresourceLayers {
            aspect_mask: aspect(i.desc.format),
            mip_level: 0,
            base_array_layer: 0,
            layer_count: 1,
        };
        let corners = [vk::Offset3D::default(), vk::Offset3D { x: w as i32, y: h as i32, z: 1 }];
        let region = vk::ImageBlit2::default()
            .src_subresource(sub(src))
            .src_offsets(corners)
            .dst_subresource(sub(dst))
            .dst_offsets(corners);
        let regions = [region];
        let info = vk::BlitImageInfo2::default()
            .src_image(src.raw)
            .src_image_layout(vk::ImageLayout::TRANSFER_SRC_OPTIMAL)
            .dst_image(dst.raw)
            .dst_image_layout(vk::ImageLayout::TRANSFER_DST_OPTIMAL)
            .regions(&regions)
            .filter(vk::Filter::NEAREST);
        unsafe { self.d().cmd_blit_image2(self.cb, &info) };
    }

    /// Copies `src` into one mip/layer of `image` (in TRANSFER_DST layout).
    pub fn copy_buffer_to_image(&mut self, src: &Buffer, image: &Image, mip: u32, layer: u32) {
        let r = Self::image_region(image, mip, layer);
        unsafe {
            self.d().cmd_copy_buffer_to_image(self.cb, src.raw, image.raw, vk::ImageLayout::TRANSFER_DST_OPTIMAL, &[r])
        };
    }

    /// Clears every subresource of `view` (in TRANSFER_DST layout) to `color`.
    pub fn clear_color(&mut self, view: &ImageView, color: [f32; 4]) {
        let range = vk::ImageSubresourceRange {
            aspect_mask: vk::ImageAspectFlags::COLOR,
            base_mip_level: view.mips.start,
            level_count: view.mips.end - view.mips.start,
            base_array_layer: view.layers.start,
            layer_count: view.layers.end - view.layers.start,
        };
        let c = vk::ClearColorValue { float32: color };
        unsafe {
            self.d().cmd_clear_color_image(self.cb, view.image, vk::ImageLayout::TRANSFER_DST_OPTIMAL, &c, &[range])
        };
    }

    fn xfb(&self) -> Result<&ash::ext::transform_feedback::Device> {
        self.ctx.shared.device.xfb.as_ref().ok_or_else(|| VkError::MissingFeature {
            who: "transform feedback".into(),
            feature: crate::Feature::TransformFeedback.name(),
            vulkan_name: crate::Feature::TransformFeedback.vulkan_name(),
            device: self.ctx.info().name.clone(),
        })
    }

    /// Binds transform-feedback buffers 0.. to whole `buffers`; the pass must declare each
    /// `Access::XFB_WRITE`.
    pub fn bind_xfb_buffers(&mut self, buffers: &[&Buffer]) -> Result<()> {
        for b in buffers {
            self.declared(b, (Access::XFB_WRITE, "XFB_WRITE"), "bind_xfb_buffers")?;
        }
        let raws: Vec<vk::Buffer> = buffers.iter().map(|b| b.raw).collect();
        let offsets = vec![0u64; buffers.len()];
        let sizes: Vec<u64> = buffers.iter().map(|b| b.size()).collect();
        let x = self.xfb()?;
        unsafe {
            (x.fp().cmd_bind_transform_feedback_buffers_ext)(
                self.cb,
                0,
                raws.len() as u32,
                raws.as_ptr(),
                offsets.as_ptr(),
                sizes.as_ptr(),
            )
        };
        Ok(())
    }

    /// Begins transform feedback; with `counters`, writing resumes at the byte counts stored
    /// there (one u32 per xfb buffer at offset 0), otherwise at offset 0.
    /// The pass must declare each counter `Access::XFB_COUNTER`.
    pub fn begin_xfb(&mut self, counters: &[&Buffer], resume: bool) -> Result<()> {
        for b in counters {
            self.declared(b, (Access::XFB_COUNTER, "XFB_COUNTER"), "begin_xfb")?;
        }
        let raws: Vec<vk::Buffer> = counters.iter().map(|b| b.raw).collect();
        let offsets = vec![0u64; counters.len()];
        let x = self.xfb()?;
        unsafe {
            if resume {
                (x.fp().cmd_begin_transform_feedback_ext)(
                    self.cb,
                    0,
                    raws.len() as u32,
                    raws.as_ptr(),
                    offsets.as_ptr(),
                )
            } else {
                (x.fp().cmd_begin_transform_feedback_ext)(self.cb, 0, 0, std::ptr::null(), std::ptr::null())
            }
        };
        Ok(())
    }

    /// Ends transform feedback, storing each buffer's byte count into `counters`; the pass must
    /// declare each `Access::XFB_COUNTER`.
    pub fn end_xfb(&mut self, counters: &[&Buffer]) -> Result<()> {
        for b in counters {
            self.declared(b, (Access::XFB_COUNTER, "XFB_COUNTER"), "end_xfb")?;
        }
        let raws: Vec<vk::Buffer> = counters.iter().map(|b| b.raw).collect();
        let offsets = vec![0u64; counters.len()];
        let x = self.xfb()?;
        unsafe {
            (x.fp().cmd_end_transform_feedback_ext)(self.cb, 0, raws.len() as u32, raws.as_ptr(), offsets.as_ptr())
        };
        Ok(())
    }

    /// vkCmdDrawIndirectByteCountEXT: draws `counter`'s byte count / `stride` vertices, so the
    /// output of one transform-feedback pass feeds the next without a CPU readback.
    /// The pass must declare `counter` `Access::INDIRECT`.
    pub fn draw_indirect_byte_count(&mut self, instances: u32, counter: &Buffer, stride: u32) -> Result<()> {
        self.declared(counter, (Access::INDIRECT, "INDIRECT"), "draw_indirect_byte_count")?;
        self.ctx.require("vkCmdDrawIndirectByteCountEXT", &[crate::Feature::TransformFeedbackDraw])?;
        let x = self.xfb()?;
        unsafe { (x.fp().cmd_draw_indirect_byte_count_ext)(self.cb, instances, 0, counter.raw, 0, 0, stride) };
        Ok(())
    }

    /// Begins query `index` of `pool` (transform-feedback stream 0 for xfb pools).
    pub fn begin_query(&mut self, pool: &QueryPool, index: u32) -> Result<()> {
        if pool.is_xfb() {
            let x = self.xfb()?;
            unsafe {
                (x.fp().cmd_begin_query_indexed_ext)(self.cb, pool.raw, index, vk::QueryControlFlags::empty(), 0)
            };
        } else {
            unsafe { self.d().cmd_begin_query(self.cb, pool.raw, index, vk::QueryControlFlags::empty()) };
        }
        Ok(())
    }

    pub fn end_query(&mut self, pool: &QueryPool, index: u32) -> Result<()> {
        if pool.is_xfb() {
            let x = self.xfb()?;
            unsafe { (x.fp().cmd_end_query_indexed_ext)(self.cb, pool.raw, index, 0) };
        } else {
            unsafe { self.d().cmd_end_query(self.cb, pool.raw, index) };
        }
        Ok(())
    }
}

impl Drop for Cmd<'_> {
    fn drop(&mut self) {
        // A pass that returned early must not leave rendering open.
        self.end_rendering();
    }
}
