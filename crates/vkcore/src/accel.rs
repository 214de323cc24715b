//! Acceleration structures (VK_KHR_acceleration_structure) for ray queries: a bottom level over
//! a mesh's triangles, built once and compacted (or, to be refitted to moved vertices later, built
//! updatable and not compacted), and a top level over instances of them, each
//! with its transform and a custom index the shader reads back
//! (`rayQueryGetIntersectionInstanceCustomIndexEXT`). Every build is its own one-shot submission
//! that ends in a barrier making the structure visible to every later command, so a pass that
//! binds one ([`crate::Bind::AccelerationStructure`]) needs no barrier of its own. Only on a
//! device with [`Feature::AccelerationStructure`] and [`Feature::RayQuery`] (the device enables
//! them with buffer device addresses); elsewhere a build is an error naming the feature.

use crate::buffer::{Buffer, Memory};
use crate::context::{Context, Shared};
use crate::error::{Result, VkError, VkResultExt};
use crate::features::Feature;
use crate::frame::FrameOptions;
use ash::vk;
use std::sync::Arc;

/// One instance of a bottom-level structure in a top-level one.
pub struct TlasInstance<'a> {
    pub blas: &'a AccelerationStructure,
    /// Object to world, the top three rows of a 4x4 matrix, row-major.
    pub transform: [[f32; 4]; 3],
    /// What `rayQueryGetIntersectionInstanceCustomIndexEXT` returns (24 bits).
    pub custom_index: u32,
}

/// A built acceleration structure and the buffer that holds it.
pub struct AccelerationStructure {
    shared: Arc<Shared>,
    pub(crate) raw: vk::AccelerationStructureKHR,
    buffer: Buffer,
    address: vk::DeviceAddress,
    name: String,
    /// A bottom level built to be refitted: its vertex count and its indices, which a refit must
    /// keep (Vulkan: an update's primitives are the build's, only their vertices move).
    updatable: Option<(usize, Vec<u32>)>,
}

/// Scratch memory and build inputs are addressed at this alignment, the largest
/// `minAccelerationStructureScratchOffsetAlignment` drivers report.
const ALIGN: u64 = 256;

impl AccelerationStructure {
    /// A bottom-level structure over the triangles `indices` (three per triangle) of `positions`,
    /// opaque and two-sided (ray queries see both faces), compacted after its build.
    pub fn triangles(ctx: &Context, name: &str, positions: &[[f32; 3]], indices: &[u32]) -> Result<Self> {
        let built = triangles_build(ctx, name, positions, indices, Flags::Compactable(true))?;
        built.expect("a new structure").compacted(ctx)
    }

    /// The same, built to be refitted ([`AccelerationStructure::refit`]) and so not compacted.
    pub fn triangles_updatable(ctx: &Context, name: &str, positions: &[[f32; 3]], indices: &[u32]) -> Result<Self> {
        let mut built = triangles_build(ctx, name, positions, indices, Flags::Updatable)?.expect("a new structure");
        built.updatable = Some((positions.len(), indices.to_vec()));
        Ok(built)
    }

    /// Refits this bottom level, built by [`AccelerationStructure::triangles_updatable`], in place
    /// to moved vertices of the same triangles (`VK_BUILD_ACCELERATION_STRUCTURE_MODE_UPDATE_KHR`):
    /// the tree's topology stays the first build's, its boxes grow to the moved triangles. The
    /// vertex count and every index must be the build's (an error naming the structure).
    pub fn refit(&mut self, ctx: &Context, positions: &[[f32; 3]], indices: &[u32]) -> Result<()> {
        match &self.updatable {
            Some((vertices, built)) if *vertices == positions.len() && built.as_slice() == indices => {}
            Some((vertices, built)) => {
                return Err(VkError::Invalid(format!(
                "acceleration structure `{}`: a refit keeps the triangles ({} over {vertices} vertices), got {} over \
                     {}{}",
                self.name,
                built.len() / 3,
                indices.len() / 3,
                positions.len(),
                if built.len() == indices.len() && *vertices == positions.len() { " with other indices" } else { "" }
            )))
            }
            None => {
                return Err(VkError::Invalid(format!(
                    "acceleration structure `{}` was not built to be refitted (triangles_updatable)",
                    self.name
                )))
            }
        }
        let name = self.name.clone();
        triangles_build(ctx, &name, positions, indices, Flags::Refit(self))?;
        Ok(())
    }

    /// A top-level structure over `instances`.
    pub fn instances(ctx: &Context, name: &str, instances: &[TlasInstance]) -> Result<Self> {
        let accel = loader(ctx, name)?;
        let records: Vec<vk::AccelerationStructureInstanceKHR> = instances
            .iter()
            .map(|i| vk::AccelerationStructureInstanceKHR {
                transform: vk::TransformMatrixKHR { matrix: bytemuck::cast(i.transform) },
                instance_custom_index_and_mask: vk::Packed24_8::new(i.custom_index, 0xff),
                instance_shader_binding_table_record_offset_and_flags: vk::Packed24_8::new(
                    0,
                    vk::GeometryInstanceFlagsKHR::TRIANGLE_FACING_CULL_DISABLE.as_raw() as u8,
                ),
                acceleration_structure_reference: vk::AccelerationStructureReferenceKHR {
                    device_handle: i.blas.address,
                },
            })
            .collect();
        // SAFETY: VkAccelerationStructureInstanceKHR is plain data, 64 bytes without padding.
        let bytes = unsafe {
            std::slice::from_raw_parts(
                records.as_ptr() as *const u8,
                records.len() * std::mem::size_of::<vk::AccelerationStructureInstanceKHR>(),
            )
        };
        let buffer = host_buffer(ctx, &format!("{name} instances"), bytes)?;
        let data = vk::AccelerationStructureGeometryInstancesDataKHR::default()
            .array_of_pointers(false)
            .data(vk::DeviceOrHostAddressConstKHR { device_address: address(ctx, &buffer) });
        let geometry = vk::AccelerationStructureGeometryKHR::default()
            .geometry_type(vk::GeometryTypeKHR::INSTANCES)
            .geometry(vk::AccelerationStructureGeometryDataKHR { instances: data })
            .flags(vk::GeometryFlagsKHR::OPAQUE);
        let count = instances.len() as u32;
        let built = build(
            ctx,
            accel,
            name,
            vk::AccelerationStructureTypeKHR::TOP_LEVEL,
            geometry,
            count,
            Flags::Compactable(false),
        );
        drop(buffer);
        Ok(built?.expect("a new structure"))
    }

    /// Bytes the structure occupies (after compaction, for a bottom level).
    pub fn size(&self) -> u64 {
        self.buffer.size()
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    pub(crate) fn buffer(&self) -> &Buffer {
        &self.buffer
    }

    /// A copy of this structure in a buffer of its compacted size.
    fn compacted(self, ctx: &Context) -> Result<Self> {
        let accel = loader(ctx, &self.name)?;
        let d = ctx.shared.raw();
        let info = vk::QueryPoolCreateInfo::default()
            .query_type(vk::QueryType::ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR)
            .query_count(1);
        let pool = unsafe { d.create_query_pool(&info, None) }.call("vkCreateQueryPool(compacted size)")?;
        let size = (|| {
            unsafe { d.reset_query_pool(pool, 0, 1) };
            one_shot(ctx, &format!("compacted size of {}", self.name), |cb| unsafe {
                accel.cmd_write_acceleration_structures_properties(
                    cb,
                    &[self.raw],
                    vk::QueryType::ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR,
                    pool,
                    0,
                )
            })?;
            let mut size = [0u64];
            unsafe {
                d.get_query_pool_results(pool, 0, &mut size, vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT)
            }
            .call("vkGetQueryPoolResults(compacted size)")?;
            Ok::<u64, VkError>(size[0])
        })();
        unsafe { d.destroy_query_pool(pool, None) };
        let size = size?;
        if size == 0 || size >= self.buffer.size() {
            return Ok(self);
        }
        let ty = vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL;
        let compact = create(ctx, accel, &self.name, ty, size)?;
        let copy = vk::CopyAccelerationStructureInfoKHR::default()
            .src(self.raw)
            .dst(compact.raw)
            .mode(vk::CopyAccelerationStructureModeKHR::COMPACT);
        one_shot(ctx, &format!("compact {}", self.name), |cb| unsafe {
            accel.cmd_copy_acceleration_structure(cb, &copy)
        })?;
        Ok(compact)
    }
}

impl Drop for AccelerationStructure {
    fn drop(&mut self) {
        if let Some(accel) = &self.shared.device.accel {
            unsafe { accel.destroy_acceleration_structure(self.raw, None) };
        }
    }
}

fn loader<'c>(ctx: &'c Context, name: &str) -> Result<&'c ash::khr::acceleration_structure::Device> {
    ctx.require(&format!("acceleration structure `{name}`"), &[Feature::AccelerationStructure, Feature::RayQuery])?;
    ctx.shared.device.accel.as_ref().ok_or_else(|| VkError::MissingFeature {
        who: format!("acceleration structure `{name}`"),
        feature: Feature::AccelerationStructure.name(),
        vulkan_name: Feature::AccelerationStructure.vulkan_name(),
        device: ctx.info().name.clone(),
    })
}

/// A host-visible buffer holding `data`, read by a build (its writes are visible at submit).
/// Its data starts at [`address`], the buffer's own address aligned up.
fn host_buffer(ctx: &Context, name: &str, data: &[u8]) -> Result<Buffer> {
    let mut b = Buffer::new(ctx, name, data.len() as u64 + ALIGN, Memory::Upload)?;
    let start = raw_address(ctx, &b);
    b.write_mapped(aligned(start) - start, data)?;
    Ok(b)
}

/// `b`'s device address aligned up to [`ALIGN`] (buffers are made [`ALIGN`] bytes longer).
fn address(ctx: &Context, b: &Buffer) -> vk::DeviceAddress {
    aligned(raw_address(ctx, b))
}

fn raw_address(ctx: &Context, b: &Buffer) -> vk::DeviceAddress {
    unsafe { ctx.shared.raw().get_buffer_device_address(&vk::BufferDeviceAddressInfo::default().buffer(b.raw)) }
}

fn aligned(a: vk::DeviceAddress) -> vk::DeviceAddress {
    a.div_ceil(ALIGN) * ALIGN
}

/// A structure of `size` bytes in a buffer of its own.
fn create(
    ctx: &Context,
    accel: &ash::khr::acceleration_structure::Device,
    name: &str,
    ty: vk::AccelerationStructureTypeKHR,
    size: u64,
) -> Result<AccelerationStructure> {
    let buffer = Buffer::new(ctx, name, size, Memory::Gpu)?;
    let info = vk::AccelerationStructureCreateInfoKHR::default().buffer(buffer.raw).size(size).ty(ty);
    let raw = unsafe { accel.create_acceleration_structure(&info, None) }.call("vkCreateAccelerationStructureKHR")?;
    ctx.set_name(raw, name);
    let address = unsafe {
        accel.get_acceleration_structure_device_address(
            &vk::AccelerationStructureDeviceAddressInfoKHR::default().acceleration_structure(raw),
        )
    };
    Ok(AccelerationStructure { shared: ctx.shared.clone(), raw, buffer, address, name: name.into(), updatable: None })
}

/// A bottom level over the triangles `indices` (three per triangle) of `positions`, opaque and
/// two-sided, built as `how` says (`None` for a refit, which writes over its structure).
fn triangles_build(
    ctx: &Context,
    name: &str,
    positions: &[[f32; 3]],
    indices: &[u32],
    how: Flags,
) -> Result<Option<AccelerationStructure>> {
    let accel = loader(ctx, name)?;
    if !indices.len().is_multiple_of(3) || indices.iter().any(|&i| i as usize >= positions.len()) {
        return Err(VkError::Invalid(format!(
            "acceleration structure `{name}`: {} indices into {} vertices",
            indices.len(),
            positions.len()
        )));
    }
    let vertices = host_buffer(ctx, &format!("{name} vertices"), bytemuck::cast_slice(positions))?;
    let index_buffer = host_buffer(ctx, &format!("{name} indices"), bytemuck::cast_slice(indices))?;
    let triangles = vk::AccelerationStructureGeometryTrianglesDataKHR::default()
        .vertex_format(vk::Format::R32G32B32_SFLOAT)
        .vertex_data(vk::DeviceOrHostAddressConstKHR { device_address: address(ctx, &vertices) })
        .vertex_stride(12)
        .max_vertex(positions.len().saturating_sub(1) as u32)
        .index_type(vk::IndexType::UINT32)
        .index_data(vk::DeviceOrHostAddressConstKHR { device_address: address(ctx, &index_buffer) });
    let geometry = vk::AccelerationStructureGeometryKHR::default()
        .geometry_type(vk::GeometryTypeKHR::TRIANGLES)
        .geometry(vk::AccelerationStructureGeometryDataKHR { triangles })
        .flags(vk::GeometryFlagsKHR::OPAQUE);
    let count = (indices.len() / 3) as u32;
    let built = build(ctx, accel, name, vk::AccelerationStructureTypeKHR::BOTTOM_LEVEL, geometry, count, how)?;
    drop((vertices, index_buffer));
    Ok(built)
}

/// How [`build`] builds: a new structure, compactable or not, updatable, or an update (refit) of
/// an updatable one in place.
enum Flags<'a> {
    Compactable(bool),
    Updatable,
    Refit(&'a AccelerationStructure),
}

/// Builds a structure of `ty` over `count` primitives of `geometry` as `how` says and waits for
/// it; a refit writes over the structure it updates (returned as `None`).
fn build(
    ctx: &Context,
    accel: &ash::khr::acceleration_structure::Device,
    name: &str,
    ty: vk::AccelerationStructureTypeKHR,
    geometry: vk::AccelerationStructureGeometryKHR,
    count: u32,
    how: Flags,
) -> Result<Option<AccelerationStructure>> {
    let mut flags = vk::BuildAccelerationStructureFlagsKHR::PREFER_FAST_TRACE;
    match how {
        Flags::Compactable(true) => flags |= vk::BuildAccelerationStructureFlagsKHR::ALLOW_COMPACTION,
        Flags::Compactable(false) => {}
        Flags::Updatable | Flags::Refit(_) => flags |= vk::BuildAccelerationStructureFlagsKHR::ALLOW_UPDATE,
    }
    // A refit updates its structure in place: it is both source and destination.
    let refit = match how {
        Flags::Refit(existing) => Some(existing.raw),
        _ => None,
    };
    let mode = if refit.is_some() {
        vk::BuildAccelerationStructureModeKHR::UPDATE
    } else {
        vk::BuildAccelerationStructureModeKHR::BUILD
    };
    let geometries = [geometry];
    let mut info =
        vk::AccelerationStructureBuildGeometryInfoKHR::default().ty(ty).flags(flags).mode(mode).geometries(&geometries);
    let mut sizes = vk::AccelerationStructureBuildSizesInfoKHR::default();
    unsafe {
        accel.get_acceleration_structure_build_sizes(
            vk::AccelerationStructureBuildTypeKHR::DEVICE,
            &info,
            &[count],
            &mut sizes,
        )
    };
    let built = match refit {
        Some(_) => None,
        None => Some(create(ctx, accel, name, ty, sizes.acceleration_structure_size)?),
    };
    let target = refit.or(built.as_ref().map(|b| b.raw)).expect("a structure to write");
    let scratch_size = if refit.is_some() { sizes.update_scratch_size } else { sizes.build_scratch_size };
    let scratch = Buffer::new(ctx, &format!("{name} scratch"), scratch_size + ALIGN, Memory::Gpu)?;
    info = info
        .dst_acceleration_structure(target)
        .scratch_data(vk::DeviceOrHostAddressKHR { device_address: address(ctx, &scratch) });
    if let Some(existing) = refit {
        info = info.src_acceleration_structure(existing);
    }
    let range = vk::AccelerationStructureBuildRangeInfoKHR::default().primitive_count(count);
    let what = if refit.is_some() { "refit" } else { "build" };
    one_shot(ctx, &format!("{what} {name}"), |cb| unsafe {
        accel.cmd_build_acceleration_structures(cb, std::slice::from_ref(&info), &[std::slice::from_ref(&range)])
    })?;
    match refit {
        Some(_) => ctx.shared.counters.acceleration_structure_refit(),
        None => ctx.shared.counters.acceleration_structure(ty == vk::AccelerationStructureTypeKHR::TOP_LEVEL),
    }
    drop(scratch);
    Ok(built)
}

/// Records `record` alone in a frame, then a barrier that makes the structures it wrote visible
/// to every later command, submits and waits.
fn one_shot(ctx: &Context, what: &str, record: impl FnOnce(vk::CommandBuffer)) -> Result<()> {
    let mut f = ctx.frame(FrameOptions { timestamps: false, pipeline_statistics: false, ..Default::default() })?;
    let mut record = Some(record);
    f.pass(what).record(|cmd| {
        let cb = cmd.raw_command_buffer();
        if let Some(r) = record.take() {
            r(cb);
        }
        let barrier = vk::MemoryBarrier2::default()
            .src_stage_mask(vk::PipelineStageFlags2::ACCELERATION_STRUCTURE_BUILD_KHR)
            .src_access_mask(vk::AccessFlags2::ACCELERATION_STRUCTURE_WRITE_KHR)
            .dst_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
            .dst_access_mask(
                vk::AccessFlags2::ACCELERATION_STRUCTURE_READ_KHR | vk::AccessFlags2::ACCELERATION_STRUCTURE_WRITE_KHR,
            );
        let dep = vk::DependencyInfo::default().memory_barriers(std::slice::from_ref(&barrier));
        unsafe { ctx.shared.raw().cmd_pipeline_barrier2(cb, &dep) };
        Ok(())
    })?;
    f.submit()?;
    Ok(())
}
