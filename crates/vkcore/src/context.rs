//! `Context`: instance + device + queue + allocator + the barrier tracker. Everything else in
//! vkcore hangs off it. Headless: every submission is waited for before returning.

use crate::device::{choose_device, create_device, enumerate_devices, DeviceShared};
use crate::error::{Result, VkError, VkResultExt};
use crate::features::{DeviceInfo, Feature};
use crate::instance::{Instance, ValidationLog};
use crate::tracker::Tracker;
use ash::vk;
use gpu_allocator::vulkan::{Allocator, AllocatorCreateDesc};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// How to open a device.
#[derive(Debug, Clone, Default)]
pub struct ContextOptions {
    /// `--device`: an index or a name substring. None = hardware GPU if present, else lavapipe.
    pub device: Option<String>,
    /// `--validate`: Khronos validation with synchronization validation.
    pub validation: bool,
    /// Print validation messages as they arrive.
    pub echo_validation: bool,
    /// Pretend the device lacks these (`--without-feature`), to exercise error paths and fallbacks.
    pub without: Vec<Feature>,
}

impl ContextOptions {
    /// What the GPU tests open: the device `$CAUSTICLAB_TEST_DEVICE` names (default: the default
    /// device), the Khronos validation layer on with its messages echoed, and `without` hidden.
    pub fn for_tests(without: Vec<Feature>) -> ContextOptions {
        ContextOptions {
            device: std::env::var("CAUSTICLAB_TEST_DEVICE").ok(),
            validation: true,
            echo_validation: true,
            without,
        }
    }
}

pub(crate) struct Shared {
    pub device: DeviceShared,
    pub allocator: Mutex<Option<Allocator>>,
    pub tracker: Mutex<Tracker>,
    pub command_pool: Mutex<vk::CommandPool>,
    pub counters: crate::counters::AtomicCounters,
    pub pipelines: crate::shared_pipelines::SharedPipelines,
    next_id: AtomicU64,
    /// Whether frames record their graph ([`Context::record_frame_graphs`]).
    pub frame_graphs: AtomicBool,
}

impl Shared {
    /// Frees a resource's memory and forgets its barrier state (from the resources' `Drop`).
    pub fn release(&self, allocation: Option<gpu_allocator::vulkan::Allocation>, id: u64) {
        if let Some(a) = allocation {
            if let Ok(mut guard) = self.allocator.lock() {
                if let Some(alloc) = guard.as_mut() {
                    let _ = alloc.free(a);
                }
            }
        }
        if let Ok(mut t) = self.tracker.lock() {
            t.forget(id);
        }
    }

    pub fn new_id(&self) -> u64 {
        self.next_id.fetch_add(1, Ordering::Relaxed)
    }
    pub fn raw(&self) -> &ash::Device {
        &self.device.raw
    }
}

impl Drop for Shared {
    fn drop(&mut self) {
        unsafe {
            let _ = self.device.raw.device_wait_idle();
            if let Ok(pool) = self.command_pool.lock() {
                self.device.raw.destroy_command_pool(*pool, None);
            }
        }
        // The allocator must go before the device (DeviceShared's Drop destroys the device).
        if let Ok(mut a) = self.allocator.lock() {
            a.take();
        }
    }
}

/// An open device. Clone is cheap; resources keep it alive.
#[derive(Clone)]
pub struct Context {
    pub(crate) shared: Arc<Shared>,
    instance: Instance,
}

impl Context {
    pub fn new(opts: &ContextOptions) -> Result<Context> {
        let instance = Instance::new(opts.validation, opts.echo_validation)?;
        Context::open(opts, instance, None)
    }

    /// A context whose device presents to the window `window` of display `display` (the
    /// viewer): the instance gets the display's surface extensions, the device VK_KHR_swapchain
    /// and a graphics queue that can present to the surface, which is returned beside it.
    pub fn with_window(
        opts: &ContextOptions,
        display: raw_window_handle::RawDisplayHandle,
        window: raw_window_handle::RawWindowHandle,
    ) -> Result<(Context, crate::window::Surface)> {
        let extensions =
            ash_window::enumerate_required_extensions(display).call("vkEnumerateInstanceExtensionProperties")?;
        let instance = Instance::with_extensions(opts.validation, opts.echo_validation, extensions)?;
        let surface = crate::window::Surface::new(&instance, display, window)?;
        let ctx = Context::open(opts, instance, Some(&surface))?;
        Ok((ctx, surface))
    }

    fn open(opts: &ContextOptions, instance: Instance, present: Option<&crate::window::Surface>) -> Result<Context> {
        let devices = enumerate_devices(&instance)?;
        let index = match (present, opts.device.as_deref()) {
            (Some(surface), None) => crate::device::choose_presenting(&instance, &devices, surface)?,
            (_, query) => choose_device(&devices, query)?,
        };
        let chosen = &devices[index];
        crate::crash::install(&format!("`{}`, driver {}", chosen.name, crate::device::driver_label(chosen)));
        let device = create_device(&instance, index, &opts.without, present)?;
        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: instance.shared.raw.clone(),
            device: device.raw.clone(),
            physical_device: device.physical,
            debug_settings: Default::default(),
            // Acceleration-structure builds read their inputs by device address.
            buffer_device_address: device.accel.is_some(),
            allocation_sizes: Default::default(),
        })
        .map_err(|e| VkError::Alloc { name: "allocator".into(), bytes: 0, message: e.to_string() })?;
        let pool_info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(device.queue_family)
            .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
        let command_pool = unsafe { device.raw.create_command_pool(&pool_info, None) }.call("vkCreateCommandPool")?;
        Ok(Context {
            shared: Arc::new(Shared {
                device,
                allocator: Mutex::new(Some(allocator)),
                tracker: Mutex::new(Tracker::default()),
                command_pool: Mutex::new(command_pool),
                counters: Default::default(),
                pipelines: Default::default(),
                next_id: AtomicU64::new(1),
                frame_graphs: AtomicBool::new(false),
            }),
            instance,
        })
    }

    /// The chosen device's name, driver, version, features and limits.
    pub fn info(&self) -> &DeviceInfo {
        &self.shared.device.info
    }

    /// Fails with a message naming the first missing feature.
    pub fn require(&self, who: &str, features: &[Feature]) -> Result<()> {
        self.info().require(who, features)
    }

    pub fn validation_log(&self) -> Arc<ValidationLog> {
        self.instance.validation_log()
    }

    pub fn validation_enabled(&self) -> bool {
        self.instance.validation_enabled()
    }

    /// From now on, every frame records its graph: each pass with the resources it read and
    /// wrote ([`crate::FrameReport::graph`]; off by default, to keep the recording loop lean).
    pub fn record_frame_graphs(&self, on: bool) {
        self.shared.frame_graphs.store(on, Ordering::Relaxed);
    }

    /// Objects created, submits, barriers and timestamps so far (see [`crate::Counters`]).
    pub fn counters(&self) -> crate::Counters {
        self.shared.counters.snapshot()
    }

    /// How many pipelines were made (each `vkCreate*Pipelines`; a pipeline shared with a live
    /// one of equal description is not made again): a mark for [`Context::pipelines_made_since`].
    pub fn pipelines_made(&self) -> usize {
        self.shared.pipelines.made_count()
    }

    /// The names of the pipelines made since `mark` (from [`Context::pipelines_made`]), in order.
    pub fn pipelines_made_since(&self, mark: usize) -> Vec<String> {
        self.shared.pipelines.made_since(mark)
    }

    /// Device memory held through the allocator: (bytes of live allocations, bytes of the memory
    /// blocks they are carved from).
    pub fn device_memory(&self) -> (u64, u64) {
        match self.shared.allocator.lock() {
            Ok(guard) => match guard.as_ref() {
                Some(a) => {
                    let r = a.generate_report();
                    (r.total_allocated_bytes, r.total_reserved_bytes)
                }
                None => (0, 0),
            },
            Err(_) => (0, 0),
        }
    }

    /// Waits until the device is idle.
    pub fn wait_idle(&self) -> Result<()> {
        unsafe { self.shared.raw().device_wait_idle() }.call("vkDeviceWaitIdle")
    }

    /// Names a Vulkan object for validation messages and GPU debuggers.
    pub(crate) fn set_name<H: vk::Handle>(&self, handle: H, name: &str) {
        if let Some(du) = &self.shared.device.debug_utils {
            if let Ok(cname) = std::ffi::CString::new(name) {
                let info = vk::DebugUtilsObjectNameInfoEXT::default().object_handle(handle).object_name(&cname);
                unsafe {
                    let _ = du.set_debug_utils_object_name(&info);
                }
            }
        }
    }
}
