//! RAII images, views and samplers. Views remember which mips and layers they cover, so a pass
//! that declares access through a view gets barriers on exactly those subresources.

use crate::context::{Context, Shared};
use crate::error::{Result, VkError, VkResultExt};
use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;
use std::ops::Range;
use std::sync::Arc;

#[derive(Debug, Clone)]
pub struct ImageDesc {
    pub name: String,
    pub format: vk::Format,
    pub width: u32,
    pub height: u32,
    pub mip_levels: u32,
    pub array_layers: u32,
    /// Create as cube-compatible (array_layers a multiple of 6).
    pub cube: bool,
}

impl ImageDesc {
    pub fn new_2d(name: &str, format: vk::Format, width: u32, height: u32) -> Self {
        ImageDesc { name: name.into(), format, width, height, mip_levels: 1, array_layers: 1, cube: false }
    }
    pub fn layers(mut self, n: u32) -> Self {
        self.array_layers = n;
        self
    }
    pub fn mips(mut self, n: u32) -> Self {
        self.mip_levels = n;
        self
    }
    pub fn cube(mut self) -> Self {
        self.cube = true;
        self
    }
}

pub(crate) fn is_depth(format: vk::Format) -> bool {
    matches!(
        format,
        vk::Format::D32_SFLOAT | vk::Format::D16_UNORM | vk::Format::D24_UNORM_S8_UINT | vk::Format::D32_SFLOAT_S8_UINT
    )
}

pub(crate) fn aspect(format: vk::Format) -> vk::ImageAspectFlags {
    if is_depth(format) {
        vk::ImageAspectFlags::DEPTH
    } else {
        vk::ImageAspectFlags::COLOR
    }
}

/// Bytes per texel of the formats this project reads back.
pub fn texel_size(format: vk::Format) -> Option<u32> {
    use vk::Format as F;
    Some(match format {
        F::R8G8B8A8_UNORM | F::R8G8B8A8_SRGB | F::R32_SFLOAT | F::R32_UINT | F::D32_SFLOAT | F::R16G16_SFLOAT => 4,
        F::R16_SFLOAT => 2,
        F::R32G32_SFLOAT | F::R16G16B16A16_SFLOAT => 8,
        F::R32G32B32A32_SFLOAT | F::R32G32B32A32_UINT => 16,
        _ => return None,
    })
}

pub struct Image {
    pub(crate) shared: Arc<Shared>,
    pub(crate) raw: vk::Image,
    allocation: Option<Allocation>,
    pub(crate) id: u64,
    pub desc: ImageDesc,
}

impl Image {
    pub fn new(ctx: &Context, desc: ImageDesc) -> Result<Image> {
        let info = ctx.info();
        let max = info.max_image_dimension_2d;
        if desc.width == 0 || desc.height == 0 || desc.width > max || desc.height > max {
            return Err(VkError::Invalid(format!(
                "image `{}`: size {}x{} is outside 1..={max} (this device's maxImageDimension2D)",
                desc.name, desc.width, desc.height
            )));
        }
        if desc.array_layers == 0 || desc.array_layers > info.max_image_array_layers {
            return Err(VkError::Invalid(format!(
                "image `{}`: {} layers is outside 1..={}",
                desc.name, desc.array_layers, info.max_image_array_layers
            )));
        }
        let full_mips = 32 - desc.width.max(desc.height).leading_zeros();
        if desc.mip_levels == 0 || desc.mip_levels > full_mips {
            return Err(VkError::Invalid(format!(
                "image `{}`: {} mip levels is outside 1..={full_mips}",
                desc.name, desc.mip_levels
            )));
        }
        let usage = if is_depth(desc.format) {
            vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT
                | vk::ImageUsageFlags::SAMPLED
                | vk::ImageUsageFlags::TRANSFER_SRC
        } else {
            let mut u = vk::ImageUsageFlags::SAMPLED
                | vk::ImageUsageFlags::COLOR_ATTACHMENT
                | vk::ImageUsageFlags::TRANSFER_SRC
                | vk::ImageUsageFlags::TRANSFER_DST;
            if desc.format != vk::Format::R8G8B8A8_SRGB {
                u |= vk::ImageUsageFlags::STORAGE;
            }
            u
        };
        let flags = if desc.cube { vk::ImageCreateFlags::CUBE_COMPATIBLE } else { vk::ImageCreateFlags::empty() };
        let create = vk::ImageCreateInfo::default()
            .flags(flags)
            .image_type(vk::ImageType::TYPE_2D)
            .format(desc.format)
            .extent(vk::Extent3D { width: desc.width, height: desc.height, depth: 1 })
            .mip_levels(desc.mip_levels)
            .array_layers(desc.array_layers)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(usage)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        let dev = ctx.shared.raw();
        let raw = unsafe { dev.create_image(&create, None) }.call("vkCreateImage")?;
        let requirements = unsafe { dev.get_image_memory_requirements(raw) };
        let allocation = {
            let mut guard =
                ctx.shared.allocator.lock().map_err(|_| VkError::Invalid("allocator lock poisoned".into()))?;
            let alloc = guard.as_mut().ok_or_else(|| VkError::Invalid("allocator gone".into()))?;
            alloc.allocate(&AllocationCreateDesc {
                name: &desc.name,
                requirements,
                location: MemoryLocation::GpuOnly,
                linear: false,
                allocation_scheme: AllocationScheme::GpuAllocatorManaged,
            })
        };
        let allocation = match allocation {
            Ok(a) => a,
            Err(e) => {
                unsafe { dev.destroy_image(raw, None) };
                return Err(VkError::Alloc {
                    name: desc.name.clone(),
                    bytes: requirements.size,
                    message: e.to_string(),
                });
            }
        };
        if let Err(e) = unsafe { dev.bind_image_memory(raw, allocation.memory(), allocation.offset()) } {
            unsafe { dev.destroy_image(raw, None) };
            return Err(VkError::Call { call: "vkBindImageMemory", result: e });
        }
        ctx.set_name(raw, &desc.name);
        ctx.shared.counters.object(2); // the image and its memory
        let id = ctx.shared.new_id();
        if let Ok(mut t) = ctx.shared.tracker.lock() {
            t.register(id, (desc.mip_levels * desc.array_layers) as usize);
        }
        Ok(Image { shared: ctx.shared.clone(), raw, allocation: Some(allocation), id, desc })
    }

    /// Width and height of mip level `mip`.
    pub fn mip_extent(&self, mip: u32) -> (u32, u32) {
        ((self.desc.width >> mip).max(1), (self.desc.height >> mip).max(1))
    }

    /// A view of mips `mips` and layers `layers`, as a 2D, 2D-array or cube view.
    pub fn view(&self, kind: ViewKind, mips: Range<u32>, layers: Range<u32>) -> Result<ImageView> {
        if mips.start >= mips.end
            || mips.end > self.desc.mip_levels
            || layers.start >= layers.end
            || layers.end > self.desc.array_layers
        {
            return Err(VkError::Invalid(format!(
                "view of `{}`: mips {:?} / layers {:?} outside the image ({} mips, {} layers)",
                self.desc.name, mips, layers, self.desc.mip_levels, self.desc.array_layers
            )));
        }
        let view_type = match kind {
            ViewKind::D2 => vk::ImageViewType::TYPE_2D,
            ViewKind::D2Array => vk::ImageViewType::TYPE_2D_ARRAY,
            ViewKind::Cube => vk::ImageViewType::CUBE,
        };
        let range = vk::ImageSubresourceRange {
            aspect_mask: aspect(self.desc.format),
            base_mip_level: mips.start,
            level_count: mips.end - mips.start,
            base_array_layer: layers.start,
            layer_count: layers.end - layers.start,
        };
        let info = vk::ImageViewCreateInfo::default()
            .image(self.raw)
            .view_type(view_type)
            .format(self.desc.format)
            .subresource_range(range);
        let raw = unsafe { self.shared.raw().create_image_view(&info, None) }.call("vkCreateImageView")?;
        self.shared.counters.object(1);
        Ok(ImageView {
            shared: self.shared.clone(),
            raw,
            image: self.raw,
            image_id: self.id,
            image_name: self.desc.name.as_str().into(),
            mips,
            layers,
            total_layers: self.desc.array_layers,
            format: self.desc.format,
            extent: self.mip_extent(range.base_mip_level),
        })
    }

    /// A view of the whole image: 2D for one layer, 2D array otherwise.
    pub fn full_view(&self) -> Result<ImageView> {
        let kind = if self.desc.array_layers == 1 { ViewKind::D2 } else { ViewKind::D2Array };
        self.view(kind, 0..self.desc.mip_levels, 0..self.desc.array_layers)
    }
}

impl Drop for Image {
    fn drop(&mut self) {
        unsafe { self.shared.raw().destroy_image(self.raw, None) };
        self.shared.release(self.allocation.take(), self.id);
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViewKind {
    D2,
    D2Array,
    Cube,
}

/// A view of some mips and layers of an image. Must not outlive its image.
pub struct ImageView {
    shared: Arc<Shared>,
    pub(crate) raw: vk::ImageView,
    pub(crate) image: vk::Image,
    pub(crate) image_id: u64,
    /// The image's name (its `ImageDesc::name`), for the frame graph.
    pub(crate) image_name: std::sync::Arc<str>,
    pub mips: Range<u32>,
    pub layers: Range<u32>,
    pub(crate) total_layers: u32,
    pub format: vk::Format,
    /// Extent of the view's first mip.
    pub extent: (u32, u32),
}

impl Drop for ImageView {
    fn drop(&mut self) {
        unsafe { self.shared.raw().destroy_image_view(self.raw, None) };
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Filter {
    Nearest,
    Linear,
}

pub struct Sampler {
    shared: Arc<Shared>,
    pub(crate) raw: vk::Sampler,
}

impl Sampler {
    /// Clamp-to-edge sampler with the given filter (mipmaps nearest).
    pub fn new(ctx: &Context, filter: Filter) -> Result<Sampler> {
        let f = match filter {
            Filter::Nearest => vk::Filter::NEAREST,
            Filter::Linear => vk::Filter::LINEAR,
        };
        let info = vk::SamplerCreateInfo::default()
            .mag_filter(f)
            .min_filter(f)
            .mipmap_mode(vk::SamplerMipmapMode::NEAREST)
            .address_mode_u(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .address_mode_v(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .address_mode_w(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .max_lod(vk::LOD_CLAMP_NONE);
        let raw = unsafe { ctx.shared.raw().create_sampler(&info, None) }.call("vkCreateSampler")?;
        ctx.shared.counters.object(1);
        Ok(Sampler { shared: ctx.shared.clone(), raw })
    }
}

impl Drop for Sampler {
    fn drop(&mut self) {
        unsafe { self.shared.raw().destroy_sampler(self.raw, None) };
    }
}
