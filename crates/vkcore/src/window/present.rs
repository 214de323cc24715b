//! The presenter: each call copies an image the last frame rendered (tracked like every other
//! image, so its barrier comes from the tracker) into the next swapchain image, draws an egui
//! panel over it with `egui-ash-renderer`, and presents. Two presents in flight, each with its
//! command buffer, fence and acquire semaphore; the swapchain is remade when the window's size
//! changes or the driver says it is out of date.

use super::surface::Surface;
use super::swapchain::Swapchain;
use crate::context::Context;
use crate::error::{Result, VkError, VkResultExt};
use crate::frame::{sync, Use};
use crate::image::Image;
use crate::tracker::Access;
use ash::vk;
use egui_ash_renderer::{allocator::DefaultAllocator, DynamicRendering, Options, RenderMode, Renderer};

/// Presents in flight.
const SLOTS: usize = 2;

#[derive(Debug, Clone, Copy, Default)]
pub struct PresentOptions {
    /// Wait for the display's refresh (FIFO); off by default in the viewer, so that the frame
    /// rate shown is the renderer's.
    pub vsync: bool,
}

/// What egui drew this frame (`egui::FullOutput`, tessellated).
pub struct Overlay<'a> {
    /// Textures to upload before drawing and to free once drawn.
    pub textures: &'a egui::TexturesDelta,
    pub primitives: &'a [egui::ClippedPrimitive],
    pub pixels_per_point: f32,
}

/// Whether a present showed the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Presented {
    Shown,
    /// The window has no area, or the swapchain was out of date (remade for the next call).
    Skipped,
}

struct Slot {
    cb: vk::CommandBuffer,
    acquired: vk::Semaphore,
    fence: vk::Fence,
}

pub struct Presenter {
    ctx: Context,
    swapchain: Option<Swapchain>,
    surface: Surface,
    /// Remake the swapchain before the next present.
    stale: bool,
    size: (u32, u32),
    opts: PresentOptions,
    pool: vk::CommandPool,
    slots: Vec<Slot>,
    next: usize,
    presents: u64,
    egui: Option<Renderer<DefaultAllocator>>,
    /// The swapchain format the egui renderer draws into.
    egui_format: Option<vk::Format>,
    /// egui textures to free once no present in flight can use them: (present count, id).
    to_free: Vec<(u64, egui::TextureId)>,
    /// Texture changes of presents skipped before they could upload them (in order).
    unapplied: Vec<(egui::TextureId, egui::epaint::ImageDelta)>,
}

impl Presenter {
    /// A presenter for `surface` (from `Context::with_window`), whose window is `size` pixels.
    pub fn new(ctx: &Context, surface: Surface, size: (u32, u32), opts: PresentOptions) -> Result<Presenter> {
        let dev = ctx.shared.raw();
        let pool_info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(ctx.shared.device.queue_family)
            .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
        let pool = unsafe { dev.create_command_pool(&pool_info, None) }.call("vkCreateCommandPool")?;
        let mut p = Presenter {
            ctx: ctx.clone(),
            swapchain: None,
            surface,
            stale: true,
            size,
            opts,
            pool,
            slots: vec![],
            next: 0,
            presents: 0,
            egui: None,
            egui_format: None,
            to_free: vec![],
            unapplied: vec![],
        };
        let alloc = vk::CommandBufferAllocateInfo::default()
            .command_pool(pool)
            .level(vk::CommandBufferLevel::PRIMARY)
            .command_buffer_count(SLOTS as u32);
        let cbs = unsafe { dev.allocate_command_buffers(&alloc) }.call("vkAllocateCommandBuffers")?;
        for cb in cbs {
            let acquired =
                unsafe { dev.create_semaphore(&vk::SemaphoreCreateInfo::default(), None) }.call("vkCreateSemaphore")?;
            let signaled = vk::FenceCreateInfo::default().flags(vk::FenceCreateFlags::SIGNALED);
            let fence = match unsafe { dev.create_fence(&signaled, None) } {
                Ok(f) => f,
                Err(e) => {
                    unsafe { dev.destroy_semaphore(acquired, None) };
                    return Err(VkError::Call { call: "vkCreateFence", result: e });
                }
            };
            p.slots.push(Slot { cb, acquired, fence });
        }
        Ok(p)
    }

    /// The window's new size in pixels: the swapchain is remade before the next present.
    pub fn resize(&mut self, size: (u32, u32)) {
        if size != self.size {
            self.size = size;
            self.stale = true;
        }
    }

    /// The swapchain's size (None while there is none, e.g. minimized).
    pub fn extent(&self) -> Option<(u32, u32)> {
        self.swapchain.as_ref().map(|s| (s.extent.width, s.extent.height))
    }

    fn remake(&mut self) -> Result<()> {
        let old = self.swapchain.as_ref().map(|s| s.raw).unwrap_or_default();
        let new = Swapchain::new(&self.ctx, &self.surface, self.size, self.opts.vsync, old)?;
        // The old one goes once the new exists (its Drop waits for the device).
        self.swapchain = new;
        self.stale = false;
        let format = self.swapchain.as_ref().map(|s| s.format.format);
        // A new egui renderer has none of egui's textures, which egui sends once: only a new
        // format makes one (a minimized window keeps it).
        if let (Some(sc), true) = (&self.swapchain, format.is_some() && format != self.egui_format) {
            self.egui = None;
            self.egui_format = format;
            let shared = &self.ctx.shared;
            let renderer = Renderer::with_default_allocator(
                &shared.device.instance.raw,
                shared.device.physical,
                shared.raw().clone(),
                RenderMode::DynamicRendering(DynamicRendering {
                    color_attachment_format: sc.format.format,
                    depth_attachment_format: None,
                    stencil_attachment_format: None,
                }),
                Options {
                    in_flight_frames: SLOTS,
                    enable_depth_test: false,
                    enable_depth_write: false,
                    srgb_framebuffer: sc.is_srgb(),
                },
            )
            .map_err(|e| VkError::Invalid(format!("the egui renderer: {e}")))?;
            self.egui = Some(renderer);
        }
        Ok(())
    }

    /// Copies `image` (8-bit RGBA holding sRGB-encoded values, written by an earlier frame on
    /// this context's queue) into the next swapchain image, scaled to it when the sizes differ,
    /// draws `overlay` over it and presents.
    pub fn present(&mut self, image: &Image, overlay: &Overlay) -> Result<Presented> {
        if self.stale || self.swapchain.is_none() {
            self.remake()?;
        }
        // The device outlives this call through the context's shared state, not a copy of its
        // function table.
        let shared = self.ctx.shared.clone();
        let dev = shared.raw();
        let queue = self.ctx.shared.device.queue;
        let slot = &self.slots[self.next];
        unsafe { dev.wait_for_fences(&[slot.fence], true, u64::MAX) }.call("vkWaitForFences")?;
        let pending = overlay.textures.set.iter().flat_map(|(id, ds)| ds.iter().map(|d| (*id, d.clone())));
        self.unapplied.extend(pending);
        // egui frees these once this frame is drawn: after the presents in flight now and this one.
        let last_user = self.presents + 1;
        self.to_free.extend(overlay.textures.free.iter().map(|id| (last_user, *id)));
        let (Some(sc), Some(egui)) = (self.swapchain.as_ref(), self.egui.as_mut()) else {
            return Ok(Presented::Skipped);
        };
        // Every present up to `presents - SLOTS` has finished: their textures may go.
        let done = self.presents.saturating_sub(SLOTS as u64);
        let free: Vec<egui::TextureId> = self.to_free.iter().filter(|(n, _)| *n <= done).map(|(_, id)| *id).collect();
        for id in &free {
            egui.free_texture(*id).map_err(|e| VkError::Invalid(format!("freeing an egui texture: {e}")))?;
        }
        self.to_free.retain(|(n, _)| *n > done);
        if !self.unapplied.is_empty() {
            // The other present in flight may still sample the textures these change.
            let fences: Vec<vk::Fence> = self.slots.iter().map(|s| s.fence).collect();
            unsafe { dev.wait_for_fences(&fences, true, u64::MAX) }.call("vkWaitForFences")?;
        }
        for (id, delta) in self.unapplied.drain(..) {
            egui.set_texture(queue, self.pool, id, &delta)
                .map_err(|e| VkError::Invalid(format!("uploading an egui texture: {e}")))?;
        }
        let index = match unsafe { sc.loader.acquire_next_image(sc.raw, u64::MAX, slot.acquired, vk::Fence::null()) } {
            Ok((index, suboptimal)) => {
                self.stale |= suboptimal;
                index
            }
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => {
                self.stale = true;
                return Ok(Presented::Skipped);
            }
            Err(result) => return Err(VkError::Call { call: "vkAcquireNextImageKHR", result }),
        };
        unsafe { dev.reset_fences(&[slot.fence]) }.call("vkResetFences")?;
        let cb = slot.cb;
        let target = sc.images[index as usize];
        let extent = sc.extent;
        unsafe {
            dev.reset_command_buffer(cb, vk::CommandBufferResetFlags::empty()).call("vkResetCommandBuffer")?;
            let begin = vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
            dev.begin_command_buffer(cb, &begin).call("vkBeginCommandBuffer")?;
        }
        sync(&self.ctx, cb, &[Use::image(image, 0..1, 0..1, Access::TRANSFER_READ)])?;
        let to_transfer = transition(
            target,
            (vk::PipelineStageFlags2::ALL_COMMANDS, vk::AccessFlags2::NONE, vk::ImageLayout::UNDEFINED),
            (
                vk::PipelineStageFlags2::ALL_TRANSFER,
                vk::AccessFlags2::TRANSFER_WRITE,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            ),
        );
        let (w, h) = (image.desc.width, image.desc.height);
        let layers = vk::ImageSubresourceLayers {
            aspect_mask: vk::ImageAspectFlags::COLOR,
            mip_level: 0,
            base_array_layer: 0,
            layer_count: 1,
        };
        let blit = vk::ImageBlit {
            src_subresource: layers,
            src_offsets: [vk::Offset3D::default(), vk::Offset3D { x: w as i32, y: h as i32, z: 1 }],
            dst_subresource: layers,
            dst_offsets: [
                vk::Offset3D::default(),
                vk::Offset3D { x: extent.width as i32, y: extent.height as i32, z: 1 },
            ],
        };
        let filter = if (w, h) == (extent.width, extent.height) { vk::Filter::NEAREST } else { vk::Filter::LINEAR };
        let color_attachment = vk::AccessFlags2::COLOR_ATTACHMENT_READ | vk::AccessFlags2::COLOR_ATTACHMENT_WRITE;
        let to_color = transition(
            target,
            (
                vk::PipelineStageFlags2::ALL_TRANSFER,
                vk::AccessFlags2::TRANSFER_WRITE,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            ),
            (
                vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
                color_attachment,
                vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
            ),
        );
        let to_present = transition(
            target,
            (
                vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT,
                vk::AccessFlags2::COLOR_ATTACHMENT_WRITE,
                vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
            ),
            (vk::PipelineStageFlags2::NONE, vk::AccessFlags2::NONE, vk::ImageLayout::PRESENT_SRC_KHR),
        );
        let attachment = [vk::RenderingAttachmentInfo::default()
            .image_view(sc.views[index as usize])
            .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
            .load_op(vk::AttachmentLoadOp::LOAD)
            .store_op(vk::AttachmentStoreOp::STORE)];
        let rendering = vk::RenderingInfo::default()
            .render_area(vk::Rect2D { offset: vk::Offset2D::default(), extent })
            .layer_count(1)
            .color_attachments(&attachment);
        unsafe {
            dev.cmd_pipeline_barrier2(cb, &vk::DependencyInfo::default().image_memory_barriers(&[to_transfer]));
            dev.cmd_blit_image(
                cb,
                image.raw,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                target,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &[blit],
                filter,
            );
            dev.cmd_pipeline_barrier2(cb, &vk::DependencyInfo::default().image_memory_barriers(&[to_color]));
            dev.cmd_begin_rendering(cb, &rendering);
        }
        let drawn = egui.cmd_draw(cb, extent, overlay.pixels_per_point, overlay.primitives);
        unsafe {
            dev.cmd_end_rendering(cb);
            dev.cmd_pipeline_barrier2(cb, &vk::DependencyInfo::default().image_memory_barriers(&[to_present]));
            dev.end_command_buffer(cb).call("vkEndCommandBuffer")?;
        }
        drawn.map_err(|e| VkError::Invalid(format!("drawing the egui panel: {e}")))?;
        let waits = [vk::SemaphoreSubmitInfo::default()
            .semaphore(slot.acquired)
            .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)];
        let ready = sc.ready[index as usize];
        let signals =
            [vk::SemaphoreSubmitInfo::default().semaphore(ready).stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)];
        let cbs = [vk::CommandBufferSubmitInfo::default().command_buffer(cb)];
        let submit = vk::SubmitInfo2::default()
            .wait_semaphore_infos(&waits)
            .command_buffer_infos(&cbs)
            .signal_semaphore_infos(&signals);
        unsafe { dev.queue_submit2(queue, &[submit], slot.fence) }.call("vkQueueSubmit2")?;
        self.ctx.shared.counters.submit();
        let wait = [ready];
        let swapchains = [sc.raw];
        let indices = [index];
        let info = vk::PresentInfoKHR::default().wait_semaphores(&wait).swapchains(&swapchains).image_indices(&indices);
        match unsafe { sc.loader.queue_present(queue, &info) } {
            Ok(suboptimal) => self.stale |= suboptimal,
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => self.stale = true,
            Err(result) => return Err(VkError::Call { call: "vkQueuePresentKHR", result }),
        }
        self.presents += 1;
        self.next = (self.next + 1) % SLOTS;
        Ok(Presented::Shown)
    }
}

/// (stage, access, layout) on one side of a barrier.
type Side = (vk::PipelineStageFlags2, vk::AccessFlags2, vk::ImageLayout);

/// The barrier that moves the swapchain image `image` (one colour layer, one level) from `from`
/// to `to`.
fn transition(image: vk::Image, from: Side, to: Side) -> vk::ImageMemoryBarrier2<'static> {
    vk::ImageMemoryBarrier2::default()
        .src_stage_mask(from.0)
        .src_access_mask(from.1)
        .old_layout(from.2)
        .dst_stage_mask(to.0)
        .dst_access_mask(to.1)
        .new_layout(to.2)
        .image(image)
        .subresource_range(vk::ImageSubresourceRange {
            aspect_mask: vk::ImageAspectFlags::COLOR,
            base_mip_level: 0,
            level_count: 1,
            base_array_layer: 0,
            layer_count: 1,
        })
}

impl Drop for Presenter {
    fn drop(&mut self) {
        let dev = self.ctx.shared.raw();
        unsafe {
            let _ = dev.device_wait_idle();
        }
        // egui's buffers and textures, then the swapchain, before the surface (a field).
        self.egui = None;
        self.swapchain = None;
        unsafe {
            for s in &self.slots {
                dev.destroy_semaphore(s.acquired, None);
                dev.destroy_fence(s.fence, None);
            }
            dev.destroy_command_pool(self.pool, None);
        }
    }
}
