//! RAII buffers backed by gpu-allocator. A buffer frees its memory and forgets its barrier
//! state when dropped.

use crate::context::{Context, Shared};
use crate::error::{Result, VkError, VkResultExt};
use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// Where a buffer lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Memory {
    /// Device-local; filled by uploads or shaders.
    Gpu,
    /// Host-visible, for uploads.
    Upload,
    /// Host-visible, for readbacks.
    Readback,
}

pub struct Buffer {
    pub(crate) shared: Arc<Shared>,
    pub(crate) raw: vk::Buffer,
    allocation: Option<Allocation>,
    pub(crate) id: u64,
    size: u64,
    name: String,
}

/// Every usage a buffer in this project may need; cheap to over-declare.
fn all_usages() -> vk::BufferUsageFlags {
    vk::BufferUsageFlags::STORAGE_BUFFER
        | vk::BufferUsageFlags::UNIFORM_BUFFER
        | vk::BufferUsageFlags::VERTEX_BUFFER
        | vk::BufferUsageFlags::INDEX_BUFFER
        | vk::BufferUsageFlags::INDIRECT_BUFFER
        | vk::BufferUsageFlags::TRANSFER_SRC
        | vk::BufferUsageFlags::TRANSFER_DST
}

impl Buffer {
    /// Creates a buffer of `size` bytes (rounded up to 16). Device buffers may be vertex, index,
    /// storage, uniform, indirect and transform-feedback buffers.
    pub fn new(ctx: &Context, name: &str, size: u64, memory: Memory) -> Result<Buffer> {
        let size = size.max(16).div_ceil(16) * 16;
        let mut usage = all_usages();
        if ctx.shared.device.accel.is_some() {
            usage |= vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS
                | vk::BufferUsageFlags::ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_KHR
                | vk::BufferUsageFlags::ACCELERATION_STRUCTURE_STORAGE_KHR;
        }
        if ctx.shared.device.xfb.is_some() {
            usage |= vk::BufferUsageFlags::TRANSFORM_FEEDBACK_BUFFER_EXT
                | vk::BufferUsageFlags::TRANSFORM_FEEDBACK_COUNTER_BUFFER_EXT;
        }
        let info = vk::BufferCreateInfo::default().size(size).usage(usage).sharing_mode(vk::SharingMode::EXCLUSIVE);
        let dev = ctx.shared.raw();
        let raw = unsafe { dev.create_buffer(&info, None) }.call("vkCreateBuffer")?;
        let requirements = unsafe { dev.get_buffer_memory_requirements(raw) };
        let location = match memory {
            Memory::Gpu => MemoryLocation::GpuOnly,
            Memory::Upload => MemoryLocation::CpuToGpu,
            Memory::Readback => MemoryLocation::GpuToCpu,
        };
        let allocation = {
            let mut guard =
                ctx.shared.allocator.lock().map_err(|_| VkError::Invalid("allocator lock poisoned".into()))?;
            let alloc = guard.as_mut().ok_or_else(|| VkError::Invalid("allocator gone".into()))?;
            alloc.allocate(&AllocationCreateDesc {
                name,
                requirements,
                location,
                linear: true,
                allocation_scheme: AllocationScheme::GpuAllocatorManaged,
            })
        };
        let allocation = match allocation {
            Ok(a) => a,
            Err(e) => {
                unsafe { dev.destroy_buffer(raw, None) };
                return Err(VkError::Alloc { name: name.into(), bytes: size, message: e.to_string() });
            }
        };
        if let Err(e) = unsafe { dev.bind_buffer_memory(raw, allocation.memory(), allocation.offset()) } {
            unsafe { dev.destroy_buffer(raw, None) };
            return Err(VkError::Call { call: "vkBindBufferMemory", result: e });
        }
        ctx.set_name(raw, name);
        ctx.shared.counters.object(2); // the buffer and its memory
        let id = ctx.shared.new_id();
        if let Ok(mut t) = ctx.shared.tracker.lock() {
            t.register(id, 1);
        }
        Ok(Buffer { shared: ctx.shared.clone(), raw, allocation: Some(allocation), id, size, name: name.into() })
    }

    pub fn size(&self) -> u64 {
        self.size
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    /// Host-visible bytes (Upload/Readback buffers only).
    pub fn mapped(&self) -> Option<&[u8]> {
        self.allocation.as_ref().and_then(|a| a.mapped_slice())
    }

    /// Writes `data` at `offset` into a host-visible buffer.
    pub fn write_mapped(&mut self, offset: u64, data: &[u8]) -> Result<()> {
        let name = self.name.clone();
        let slice = self
            .allocation
            .as_mut()
            .and_then(|a| a.mapped_slice_mut())
            .ok_or_else(|| VkError::Invalid(format!("buffer `{name}` is not host-visible")))?;
        let end = offset as usize + data.len();
        if end > slice.len() {
            return Err(VkError::Invalid(format!(
                "write of {} bytes at {offset} overflows buffer `{name}`",
                data.len()
            )));
        }
        slice[offset as usize..end].copy_from_slice(data);
        Ok(())
    }
}

impl Drop for Buffer {
    fn drop(&mut self) {
        unsafe { self.shared.raw().destroy_buffer(self.raw, None) };
        self.shared.release(self.allocation.take(), self.id);
    }
}
