//! The swapchain of a window's surface: its images, a view of each (egui draws into it) and a
//! semaphore per image that the presenting submission signals and `vkQueuePresentKHR` waits on.

use super::surface::Surface;
use crate::context::Context;
use crate::error::{Result, VkError, VkResultExt};
use ash::{khr, vk};

pub(crate) struct Swapchain {
    ctx: Context,
    pub loader: khr::swapchain::Device,
    pub raw: vk::SwapchainKHR,
    pub images: Vec<vk::Image>,
    pub views: Vec<vk::ImageView>,
    /// Per image: the presenting submission is done with it (present waits on it).
    pub ready: Vec<vk::Semaphore>,
    pub format: vk::SurfaceFormatKHR,
    pub extent: vk::Extent2D,
}

/// 8-bit UNORM first: the presented image holds sRGB-encoded values already (the tone map
/// encodes them), which a blit must copy as they are.
fn choose_format(formats: &[vk::SurfaceFormatKHR]) -> Option<vk::SurfaceFormatKHR> {
    let wanted = [vk::Format::B8G8R8A8_UNORM, vk::Format::R8G8B8A8_UNORM];
    wanted
        .iter()
        .find_map(|w| formats.iter().find(|f| f.format == *w && f.color_space == vk::ColorSpaceKHR::SRGB_NONLINEAR))
        .or_else(|| formats.first())
        .copied()
}

/// Without vsync: IMMEDIATE, else MAILBOX, else FIFO (always there); with vsync: FIFO.
fn choose_present_mode(modes: &[vk::PresentModeKHR], vsync: bool) -> vk::PresentModeKHR {
    if vsync {
        return vk::PresentModeKHR::FIFO;
    }
    [vk::PresentModeKHR::IMMEDIATE, vk::PresentModeKHR::MAILBOX]
        .into_iter()
        .find(|m| modes.contains(m))
        .unwrap_or(vk::PresentModeKHR::FIFO)
}

impl Swapchain {
    /// A swapchain of `size` pixels (the surface's own extent where it says one); None while
    /// the window has no area (minimized). `old` is retired by the new one.
    pub fn new(
        ctx: &Context,
        surface: &Surface,
        size: (u32, u32),
        vsync: bool,
        old: vk::SwapchainKHR,
    ) -> Result<Option<Swapchain>> {
        let pd = ctx.shared.device.physical;
        let caps = unsafe { surface.loader.get_physical_device_surface_capabilities(pd, surface.raw) }
            .call("vkGetPhysicalDeviceSurfaceCapabilitiesKHR")?;
        let extent = if caps.current_extent.width != u32::MAX {
            caps.current_extent
        } else {
            vk::Extent2D {
                width: size.0.clamp(caps.min_image_extent.width, caps.max_image_extent.width),
                height: size.1.clamp(caps.min_image_extent.height, caps.max_image_extent.height),
            }
        };
        if extent.width == 0 || extent.height == 0 {
            return Ok(None);
        }
        if !caps
            .supported_usage_flags
            .contains(vk::ImageUsageFlags::TRANSFER_DST | vk::ImageUsageFlags::COLOR_ATTACHMENT)
        {
            return Err(VkError::Invalid(format!(
                "the window's swapchain images cannot be blitted to and drawn into (usage {:?})",
                caps.supported_usage_flags
            )));
        }
        let formats = unsafe { surface.loader.get_physical_device_surface_formats(pd, surface.raw) }
            .call("vkGetPhysicalDeviceSurfaceFormatsKHR")?;
        let format = choose_format(&formats)
            .ok_or_else(|| VkError::Invalid("the window's surface offers no image format".into()))?;
        let modes = unsafe { surface.loader.get_physical_device_surface_present_modes(pd, surface.raw) }
            .call("vkGetPhysicalDeviceSurfacePresentModesKHR")?;
        let mut count = caps.min_image_count + 1;
        if caps.max_image_count > 0 {
            count = count.min(caps.max_image_count);
        }
        let alpha = [vk::CompositeAlphaFlagsKHR::OPAQUE, vk::CompositeAlphaFlagsKHR::INHERIT]
            .into_iter()
            .find(|a| caps.supported_composite_alpha.contains(*a))
            .unwrap_or(vk::CompositeAlphaFlagsKHR::OPAQUE);
        let info = vk::SwapchainCreateInfoKHR::default()
            .surface(surface.raw)
            .min_image_count(count)
            .image_format(format.format)
            .image_color_space(format.color_space)
            .image_extent(extent)
            .image_array_layers(1)
            .image_usage(vk::ImageUsageFlags::TRANSFER_DST | vk::ImageUsageFlags::COLOR_ATTACHMENT)
            .image_sharing_mode(vk::SharingMode::EXCLUSIVE)
            .pre_transform(caps.current_transform)
            .composite_alpha(alpha)
            .present_mode(choose_present_mode(&modes, vsync))
            .clipped(true)
            .old_swapchain(old);
        let dev = ctx.shared.raw();
        let loader = khr::swapchain::Device::new(&ctx.shared.device.instance.raw, dev);
        let raw = unsafe { loader.create_swapchain(&info, None) }.call("vkCreateSwapchainKHR")?;
        let mut sc =
            Swapchain { ctx: ctx.clone(), loader, raw, images: vec![], views: vec![], ready: vec![], format, extent };
        sc.images = unsafe { sc.loader.get_swapchain_images(raw) }.call("vkGetSwapchainImagesKHR")?;
        for (i, &image) in sc.images.iter().enumerate() {
            let view = vk::ImageViewCreateInfo::default()
                .image(image)
                .view_type(vk::ImageViewType::TYPE_2D)
                .format(format.format)
                .subresource_range(vk::ImageSubresourceRange {
                    aspect_mask: vk::ImageAspectFlags::COLOR,
                    base_mip_level: 0,
                    level_count: 1,
                    base_array_layer: 0,
                    layer_count: 1,
                });
            sc.views.push(unsafe { dev.create_image_view(&view, None) }.call("vkCreateImageView")?);
            let semaphore =
                unsafe { dev.create_semaphore(&vk::SemaphoreCreateInfo::default(), None) }.call("vkCreateSemaphore")?;
            sc.ready.push(semaphore);
            ctx.set_name(image, &format!("swapchain image {i}"));
        }
        Ok(Some(sc))
    }

    /// Whether the format stores sRGB-encoded values itself (egui must then output linear).
    pub fn is_srgb(&self) -> bool {
        matches!(self.format.format, vk::Format::B8G8R8A8_SRGB | vk::Format::R8G8B8A8_SRGB)
    }
}

impl Drop for Swapchain {
    fn drop(&mut self) {
        let dev = self.ctx.shared.raw();
        unsafe {
            let _ = dev.device_wait_idle();
            for &v in &self.views {
                dev.destroy_image_view(v, None);
            }
            for &s in &self.ready {
                dev.destroy_semaphore(s, None);
            }
            self.loader.destroy_swapchain(self.raw, None);
        }
    }
}
