//! A window's `VkSurfaceKHR` (made by `Context::with_window`), destroyed before the instance.

use crate::error::{Result, VkResultExt};
use crate::instance::Instance;
use ash::{khr, vk};
use raw_window_handle::{RawDisplayHandle, RawWindowHandle};

pub struct Surface {
    /// Keeps the instance alive until the surface is destroyed.
    #[allow(dead_code)]
    instance: Instance,
    pub(crate) loader: khr::surface::Instance,
    pub(crate) raw: vk::SurfaceKHR,
}

impl Surface {
    pub(crate) fn new(instance: &Instance, display: RawDisplayHandle, window: RawWindowHandle) -> Result<Surface> {
        let s = &instance.shared;
        let raw = unsafe { ash_window::create_surface(&s.entry, &s.raw, display, window, None) }
            .call("vkCreateSurfaceKHR")?;
        let loader = khr::surface::Instance::new(&s.entry, &s.raw);
        Ok(Surface { instance: instance.clone(), loader, raw })
    }

    /// Whether queue family `family` of `pd` can present to this surface.
    pub(crate) fn supports(&self, pd: vk::PhysicalDevice, family: u32) -> Result<bool> {
        unsafe { self.loader.get_physical_device_surface_support(pd, family, self.raw) }
            .call("vkGetPhysicalDeviceSurfaceSupportKHR")
    }
}

impl Drop for Surface {
    fn drop(&mut self) {
        unsafe { self.loader.destroy_surface(self.raw, None) };
    }
}
