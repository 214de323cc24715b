//! Physical-device discovery (`causticlab devices`), device choice (`--device`), and the logical
//! device with every feature this project uses that the hardware has.

use crate::error::{Result, VkError, VkResultExt};
use crate::features::{device_type_name, DeviceInfo, Feature};
use crate::instance::{Instance, InstanceShared};
use ash::{ext, khr, vk};
use std::ffi::CStr;
use std::sync::Arc;

/// Everything the project reads off a physical device.
pub(crate) fn query_device(instance: &ash::Instance, pd: vk::PhysicalDevice, index: usize) -> DeviceInfo {
    unsafe {
        let ext_props = instance.enumerate_device_extension_properties(pd).unwrap_or_default();
        let has_ext = |name: &CStr| ext_props.iter().any(|e| e.extension_name_as_c_str().ok() == Some(name));
        let has_xfb = has_ext(ext::transform_feedback::NAME);
        let has_atomic_float = has_ext(ext::shader_atomic_float::NAME);
        // Acceleration structures need deferred host operations enabled beside them.
        let has_accel = has_ext(khr::acceleration_structure::NAME) && has_ext(khr::deferred_host_operations::NAME);
        let has_ray_query = has_ext(khr::ray_query::NAME);
        let has_rt_pipeline = has_ext(khr::ray_tracing_pipeline::NAME);

        // The Vulkan 1.1-1.3 feature and driver structs may only be chained on 1.3 devices here
        // (older ones are listed, never used).
        let modern = instance.get_physical_device_properties(pd).api_version >= vk::API_VERSION_1_3;
        let mut f11 = vk::PhysicalDeviceVulkan11Features::default();
        let mut f12 = vk::PhysicalDeviceVulkan12Features::default();
        let mut f13 = vk::PhysicalDeviceVulkan13Features::default();
        let mut xfb = vk::PhysicalDeviceTransformFeedbackFeaturesEXT::default();
        let mut af = vk::PhysicalDeviceShaderAtomicFloatFeaturesEXT::default();
        let mut accel = vk::PhysicalDeviceAccelerationStructureFeaturesKHR::default();
        let mut rq = vk::PhysicalDeviceRayQueryFeaturesKHR::default();
        let mut rtp = vk::PhysicalDeviceRayTracingPipelineFeaturesKHR::default();
        let mut f2 = vk::PhysicalDeviceFeatures2::default();
        if modern {
            f2 = f2.push_next(&mut f11).push_next(&mut f12).push_next(&mut f13);
        }
        if has_xfb {
            f2 = f2.push_next(&mut xfb);
        }
        if has_atomic_float {
            f2 = f2.push_next(&mut af);
        }
        if modern && has_accel {
            f2 = f2.push_next(&mut accel);
        }
        if modern && has_ray_query {
            f2 = f2.push_next(&mut rq);
        }
        if modern && has_rt_pipeline {
            f2 = f2.push_next(&mut rtp);
        }
        instance.get_physical_device_features2(pd, &mut f2);
        let f = f2.features;

        let mut driver = vk::PhysicalDeviceDriverProperties::default();
        let mut xfb_props = vk::PhysicalDeviceTransformFeedbackPropertiesEXT::default();
        let mut p2 = vk::PhysicalDeviceProperties2::default();
        if modern {
            p2 = p2.push_next(&mut driver);
        }
        if has_xfb {
            p2 = p2.push_next(&mut xfb_props);
        }
        instance.get_physical_device_properties2(pd, &mut p2);
        let props = p2.properties;
        let limits = props.limits;

        let families = instance.get_physical_device_queue_family_properties(pd);
        let timestamp_valid_bits =
            graphics_family(&families).map(|i| families[i as usize].timestamp_valid_bits).unwrap_or(0);
        let mem = instance.get_physical_device_memory_properties(pd);
        let device_local_bytes = mem.memory_heaps[..mem.memory_heap_count as usize]
            .iter()
            .filter(|h| h.flags.contains(vk::MemoryHeapFlags::DEVICE_LOCAL))
            .map(|h| h.size)
            .max()
            .unwrap_or(0);

        let yes = |b: vk::Bool32| b == vk::TRUE;
        let quirks = driver_quirks(&driver);
        let broken = |f: Feature| quirks.iter().any(|(q, _)| *q == f);
        let mut supported = vec![];
        let mut add = |cond: bool, feat: Feature| {
            if cond {
                supported.push(feat)
            }
        };
        add(yes(f.geometry_shader), Feature::GeometryShader);
        add(has_xfb && yes(xfb.transform_feedback), Feature::TransformFeedback);
        add(has_xfb && yes(xfb_props.transform_feedback_draw), Feature::TransformFeedbackDraw);
        add(has_xfb && yes(xfb_props.transform_feedback_queries), Feature::TransformFeedbackQueries);
        add(yes(f12.shader_output_layer), Feature::ShaderOutputLayer);
        add(yes(f11.multiview) && !broken(Feature::Multiview), Feature::Multiview);
        add(yes(f11.multiview_geometry_shader) && !broken(Feature::Multiview), Feature::MultiviewGeometryShader);
        add(has_atomic_float && yes(af.shader_buffer_float32_atomic_add), Feature::BufferFloat32AtomicAdd);
        add(has_atomic_float && yes(af.shader_image_float32_atomic_add), Feature::ImageFloat32AtomicAdd);
        add(
            yes(f.pipeline_statistics_query) && !broken(Feature::PipelineStatisticsQuery),
            Feature::PipelineStatisticsQuery,
        );
        add(yes(f.large_points), Feature::LargePoints);
        add(timestamp_valid_bits > 0, Feature::Timestamps);
        add(has_ext(khr::push_descriptor::NAME), Feature::PushDescriptor);
        add(yes(f.fragment_stores_and_atomics), Feature::FragmentStoresAndAtomics);
        add(yes(f.vertex_pipeline_stores_and_atomics), Feature::VertexPipelineStoresAndAtomics);
        let accel_ok = has_accel && yes(accel.acceleration_structure) && yes(f12.buffer_device_address);
        add(accel_ok, Feature::AccelerationStructure);
        add(accel_ok && has_ray_query && yes(rq.ray_query), Feature::RayQuery);
        add(accel_ok && has_rt_pipeline && yes(rtp.ray_tracing_pipeline), Feature::RayTracingPipeline);

        // What every technique relies on; vkCreateDevice would fail without them.
        let baseline = [
            (yes(f.multi_draw_indirect), "multiDrawIndirect"),
            (yes(f.draw_indirect_first_instance), "drawIndirectFirstInstance"),
            (yes(f.shader_storage_image_write_without_format), "shaderStorageImageWriteWithoutFormat"),
            (yes(f11.shader_draw_parameters), "shaderDrawParameters"),
            (yes(f12.host_query_reset), "hostQueryReset"),
            (yes(f12.scalar_block_layout), "scalarBlockLayout"),
            (yes(f12.draw_indirect_count), "drawIndirectCount"),
            (yes(f13.dynamic_rendering), "dynamicRendering"),
            (yes(f13.synchronization2), "synchronization2"),
            (yes(f13.maintenance4), "maintenance4"),
        ];
        let baseline_missing = baseline.iter().filter(|(ok, _)| !ok).map(|(_, n)| *n).collect();
        let v = props.api_version;
        DeviceInfo {
            index,
            name: props.device_name_as_c_str().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
            device_type: device_type_name(props.device_type).to_string(),
            is_software: props.device_type == vk::PhysicalDeviceType::CPU,
            api_version: format!(
                "{}.{}.{}",
                vk::api_version_major(v),
                vk::api_version_minor(v),
                vk::api_version_patch(v)
            ),
            api_major_minor: (vk::api_version_major(v), vk::api_version_minor(v)),
            driver_name: driver.driver_name_as_c_str().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
            driver_info: driver.driver_info_as_c_str().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
            driver_version: props.driver_version,
            vendor_id: props.vendor_id,
            device_id: props.device_id,
            supported,
            baseline_missing,
            quirks: quirks.iter().map(|(f, why)| format!("{}: {why}", f.name())).collect(),
            timestamp_valid_bits,
            timestamp_period_ns: limits.timestamp_period,
            point_size_range: limits.point_size_range,
            point_size_granularity: limits.point_size_granularity,
            max_image_dimension_2d: limits.max_image_dimension2_d,
            max_image_array_layers: limits.max_image_array_layers,
            max_framebuffer_layers: limits.max_framebuffer_layers,
            max_geometry_output_vertices: limits.max_geometry_output_vertices,
            max_geometry_total_output_components: limits.max_geometry_total_output_components,
            max_transform_feedback_buffer_size: if has_xfb { xfb_props.max_transform_feedback_buffer_size } else { 0 },
            max_transform_feedback_buffers: if has_xfb { xfb_props.max_transform_feedback_buffers } else { 0 },
            max_compute_work_group_count: limits.max_compute_work_group_count,
            max_storage_buffer_range: limits.max_storage_buffer_range,
            device_local_bytes,
        }
    }
}

/// Features a driver reports but gets wrong, found by this project's GPU tests; they are
/// treated as absent (and `causticlab devices` says why).
///
/// Pipeline statistics are not among them: the crash once listed here for lavapipe before Mesa
/// 23 ("a statistics query brackets some compute dispatches") is the one Mesa 25's lavapipe
/// showed on every mesh scene, a null compute shader read by `vkCmdBeginQuery` after a graphics
/// pass had pushed constants for the compute stage. Pipelines now name their own stages only
/// (`pipeline::layout_stages`), which no lavapipe crashes on (docs/mesa_lavapipe_statistics_crash.md).
fn driver_quirks(driver: &vk::PhysicalDeviceDriverProperties) -> Vec<(Feature, &'static str)> {
    let mesa_major = driver
        .driver_info_as_c_str()
        .ok()
        .and_then(|s| s.to_str().ok()?.strip_prefix("Mesa ")?.split('.').next()?.parse::<u32>().ok());
    let old_lavapipe = driver.driver_id == vk::DriverId::MESA_LLVMPIPE && mesa_major.is_none_or(|m| m < 23);
    if !old_lavapipe {
        return vec![];
    }
    vec![(
        Feature::Multiview,
        "lavapipe before Mesa 23 renders every view into layer 0 with dynamic rendering (tests/rendering.rs)",
    )]
}

pub(crate) fn graphics_family(families: &[vk::QueueFamilyProperties]) -> Option<u32> {
    families
        .iter()
        .position(|f| f.queue_flags.contains(vk::QueueFlags::GRAPHICS | vk::QueueFlags::COMPUTE))
        .map(|i| i as u32)
}

/// Lists every physical device the loader sees, in enumeration order.
pub fn enumerate_devices(instance: &Instance) -> Result<Vec<DeviceInfo>> {
    let raw = &instance.shared.raw;
    let pds = unsafe { raw.enumerate_physical_devices() }.call("vkEnumeratePhysicalDevices")?;
    Ok(pds.iter().enumerate().map(|(i, pd)| query_device(raw, *pd, i)).collect())
}

/// Picks a device: `query` is an index, or a case-insensitive substring of the device's name
/// or of its driver (`causticlab devices`' "driver" line: the driver's name and version, e.g.
/// "Mesa 25" or "mesa 22.3", which tells two lavapipes apart, both named "llvmpipe (LLVM ...)");
/// without one, the first hardware GPU, else the first software device (lavapipe). A query that
/// matches devices of different names or drivers is refused, naming them (identical devices,
/// such as a node's GPUs of one model, give the first).
pub fn choose_device(devices: &[DeviceInfo], query: Option<&str>) -> Result<usize> {
    let list = |ds: &mut dyn Iterator<Item = &DeviceInfo>| {
        ds.map(|d| format!("[{}] {} ({})", d.index, d.name, driver_label(d))).collect::<Vec<_>>().join(", ")
    };
    let available = || list(&mut devices.iter());
    let usable: Vec<&DeviceInfo> = devices.iter().filter(|d| d.api_major_minor >= (1, 3)).collect();
    match query {
        Some(q) => {
            let found = if let Ok(i) = q.trim().parse::<usize>() {
                devices.iter().find(|d| d.index == i)
            } else {
                let ql = q.to_lowercase();
                let matches: Vec<&DeviceInfo> = devices
                    .iter()
                    .filter(|d| d.name.to_lowercase().contains(&ql) || driver_label(d).to_lowercase().contains(&ql))
                    .collect();
                let same = |a: &&DeviceInfo, b: &&DeviceInfo| (&a.name, &a.driver_info) == (&b.name, &b.driver_info);
                if matches.iter().any(|d| !same(d, &matches[0])) {
                    return Err(VkError::AmbiguousDevice {
                        query: q.to_string(),
                        count: matches.len(),
                        matches: list(&mut matches.iter().copied()),
                    });
                }
                matches.first().copied()
            };
            let d = found.ok_or_else(|| VkError::NoDevice { query: q.to_string(), available: available() })?;
            if d.api_major_minor < (1, 3) {
                return Err(VkError::Invalid(format!(
                    "device `{}` supports Vulkan {} but causticlab needs 1.3 (dynamic rendering, synchronization2)",
                    d.name, d.api_version
                )));
            }
            Ok(d.index)
        }
        None => usable
            .iter()
            .find(|d| !d.is_software)
            .or_else(|| usable.first())
            .map(|d| d.index)
            .ok_or_else(|| VkError::NoDevice { query: "(any Vulkan 1.3 device)".into(), available: available() }),
    }
}

/// The driver as `causticlab devices` and `--device` name it: "llvmpipe Mesa 25.0.7 (LLVM 15.0.6)".
pub fn driver_label(d: &DeviceInfo) -> String {
    format!("{} {}", d.driver_name, d.driver_info).trim().to_string()
}

/// With no `--device` and a window: the device [`choose_device`] prefers if its graphics queue
/// can present to `surface`, else the first Vulkan 1.3 device whose can (a GPU whose driver
/// cannot reach the window's display, e.g. under Xvfb, leaves it to lavapipe).
pub(crate) fn choose_presenting(
    instance: &Instance,
    devices: &[DeviceInfo],
    surface: &crate::window::Surface,
) -> Result<usize> {
    let preferred = choose_device(devices, None)?;
    let raw = &instance.shared.raw;
    let pds = unsafe { raw.enumerate_physical_devices() }.call("vkEnumeratePhysicalDevices")?;
    let presents = |i: usize| -> Result<bool> {
        let Some(&pd) = pds.get(i) else { return Ok(false) };
        let families = unsafe { raw.get_physical_device_queue_family_properties(pd) };
        match graphics_family(&families) {
            Some(f) => surface.supports(pd, f),
            None => Ok(false),
        }
    };
    if presents(preferred)? {
        return Ok(preferred);
    }
    for d in devices.iter().filter(|d| d.api_major_minor >= (1, 3)) {
        if presents(d.index)? {
            return Ok(d.index);
        }
    }
    // None can: creating the preferred one names the problem.
    Ok(preferred)
}

/// The logical device and the extension loaders the rest of vkcore calls through.
pub(crate) struct DeviceShared {
    /// Keeps the instance alive until the device is destroyed.
    #[allow(dead_code)]
    pub instance: Arc<InstanceShared>,
    pub physical: vk::PhysicalDevice,
    pub raw: ash::Device,
    pub queue: vk::Queue,
    pub queue_family: u32,
    pub push_descriptor: khr::push_descriptor::Device,
    pub xfb: Option<ext::transform_feedback::Device>,
    /// VK_KHR_acceleration_structure, where the device has it and ray queries (`crate::accel`).
    pub accel: Option<khr::acceleration_structure::Device>,
    pub debug_utils: Option<ext::debug_utils::Device>,
    pub info: DeviceInfo,
}

impl Drop for DeviceShared {
    fn drop(&mut self) {
        unsafe {
            let _ = self.raw.device_wait_idle();
            self.raw.destroy_device(None);
        }
    }
}

/// Creates the logical device on physical device `index`, enabling every feature the project
/// uses that the device has; `without` masks features as if the driver lacked them (tests and
/// `--without-feature`). With `present` (a window's surface), the device must also present to
/// it from its graphics queue and have VK_KHR_swapchain, which is enabled.
pub(crate) fn create_device(
    instance: &Instance,
    index: usize,
    without: &[Feature],
    present: Option<&crate::window::Surface>,
) -> Result<DeviceShared> {
    let raw_inst = &instance.shared.raw;
    let pds = unsafe { raw_inst.enumerate_physical_devices() }.call("vkEnumeratePhysicalDevices")?;
    let pd = *pds.get(index).ok_or_else(|| VkError::Invalid(format!("no device with index {index}")))?;
    let mut info = query_device(raw_inst, pd, index);
    info.supported.retain(|f| !without.contains(f));
    if without.contains(&Feature::Multiview) {
        info.supported.retain(|f| *f != Feature::MultiviewGeometryShader);
    }
    if without.contains(&Feature::AccelerationStructure) {
        info.supported.retain(|f| ![Feature::RayQuery, Feature::RayTracingPipeline].contains(f));
    }
    if let Some(missing) = info.baseline_missing.first() {
        return Err(VkError::Invalid(format!(
            "device `{}` lacks {missing} (and {} other baseline features causticlab needs: {:?})",
            info.name,
            info.baseline_missing.len() - 1,
            info.baseline_missing
        )));
    }
    if !info.has(Feature::PushDescriptor) {
        return Err(VkError::MissingFeature {
            who: "vkcore (descriptor binding)".into(),
            feature: Feature::PushDescriptor.name(),
            vulkan_name: Feature::PushDescriptor.vulkan_name(),
            device: info.name.clone(),
        });
    }
    let families = unsafe { raw_inst.get_physical_device_queue_family_properties(pd) };
    let queue_family = graphics_family(&families)
        .ok_or_else(|| VkError::Invalid(format!("device `{}` has no graphics+compute queue", info.name)))?;
    let has = |f| info.has(f);
    if let Some(surface) = present {
        if !surface.supports(pd, queue_family)? {
            return Err(VkError::Invalid(format!(
                "device `{}` cannot present to this window from its graphics queue (choose another with --device)",
                info.name
            )));
        }
        let available = unsafe { raw_inst.enumerate_device_extension_properties(pd) }
            .call("vkEnumerateDeviceExtensionProperties")?;
        if !available.iter().any(|e| e.extension_name_as_c_str().ok() == Some(khr::swapchain::NAME)) {
            return Err(VkError::Invalid(format!(
                "device `{}` lacks VK_KHR_swapchain (needed to show a window)",
                info.name
            )));
        }
    }

    let features = vk::PhysicalDeviceFeatures::default()
        .geometry_shader(has(Feature::GeometryShader))
        .pipeline_statistics_query(has(Feature::PipelineStatisticsQuery))
        .large_points(has(Feature::LargePoints))
        .fragment_stores_and_atomics(has(Feature::FragmentStoresAndAtomics))
        .vertex_pipeline_stores_and_atomics(has(Feature::VertexPipelineStoresAndAtomics))
        .shader_storage_image_write_without_format(true)
        .multi_draw_indirect(true)
        .draw_indirect_first_instance(true);
    let mut f11 = vk::PhysicalDeviceVulkan11Features::default()
        .multiview(has(Feature::Multiview))
        .multiview_geometry_shader(has(Feature::MultiviewGeometryShader))
        .shader_draw_parameters(true);
    let mut f12 = vk::PhysicalDeviceVulkan12Features::default()
        .shader_output_layer(has(Feature::ShaderOutputLayer))
        .host_query_reset(true)
        .scalar_block_layout(true)
        .draw_indirect_count(true)
        .buffer_device_address(has(Feature::AccelerationStructure));
    let mut f13 =
        vk::PhysicalDeviceVulkan13Features::default().dynamic_rendering(true).synchronization2(true).maintenance4(true);
    let mut xfb =
        vk::PhysicalDeviceTransformFeedbackFeaturesEXT::default().transform_feedback(has(Feature::TransformFeedback));
    let mut af = vk::PhysicalDeviceShaderAtomicFloatFeaturesEXT::default()
        .shader_buffer_float32_atomics(has(Feature::BufferFloat32AtomicAdd))
        .shader_buffer_float32_atomic_add(has(Feature::BufferFloat32AtomicAdd))
        .shader_image_float32_atomics(has(Feature::ImageFloat32AtomicAdd))
        .shader_image_float32_atomic_add(has(Feature::ImageFloat32AtomicAdd));

    let mut accel = vk::PhysicalDeviceAccelerationStructureFeaturesKHR::default().acceleration_structure(true);
    let mut rq = vk::PhysicalDeviceRayQueryFeaturesKHR::default().ray_query(true);
    // Ray queries are what this project traces with; acceleration structures alone serve nothing.
    let ray_query = has(Feature::AccelerationStructure) && has(Feature::RayQuery);

    let mut exts = vec![khr::push_descriptor::NAME.as_ptr()];
    if ray_query {
        exts.extend([
            khr::acceleration_structure::NAME.as_ptr(),
            khr::deferred_host_operations::NAME.as_ptr(),
            khr::ray_query::NAME.as_ptr(),
        ]);
    }
    if has(Feature::TransformFeedback) {
        exts.push(ext::transform_feedback::NAME.as_ptr());
    }
    let want_af = has(Feature::BufferFloat32AtomicAdd) || has(Feature::ImageFloat32AtomicAdd);
    if want_af {
        exts.push(ext::shader_atomic_float::NAME.as_ptr());
    }
    if present.is_some() {
        exts.push(khr::swapchain::NAME.as_ptr());
    }
    let priorities = [1.0f32];
    let queues = [vk::DeviceQueueCreateInfo::default().queue_family_index(queue_family).queue_priorities(&priorities)];
    let mut create = vk::DeviceCreateInfo::default()
        .queue_create_infos(&queues)
        .enabled_extension_names(&exts)
        .enabled_features(&features)
        .push_next(&mut f11)
        .push_next(&mut f12)
        .push_next(&mut f13);
    if has(Feature::TransformFeedback) {
        create = create.push_next(&mut xfb);
    }
    if want_af {
        create = create.push_next(&mut af);
    }
    if ray_query {
        create = create.push_next(&mut accel).push_next(&mut rq);
    }
    let raw = unsafe { raw_inst.create_device(pd, &create, None) }.call("vkCreateDevice")?;
    let queue = unsafe { raw.get_device_queue(queue_family, 0) };
    let push_descriptor = khr::push_descriptor::Device::new(raw_inst, &raw);
    let xfb = has(Feature::TransformFeedback).then(|| ext::transform_feedback::Device::new(raw_inst, &raw));
    let accel = ray_query.then(|| khr::acceleration_structure::Device::new(raw_inst, &raw));
    let debug_utils = instance.shared.debug_utils.as_ref().map(|_| ext::debug_utils::Device::new(raw_inst, &raw));
    Ok(DeviceShared {
        instance: instance.shared.clone(),
        physical: pd,
        raw,
        queue,
        queue_family,
        push_descriptor,
        xfb,
        accel,
        debug_utils,
        info,
    })
}

#[cfg(test)]
mod tests {
    use super::choose_device;
    use crate::features::DeviceInfo;

    fn device(index: usize, name: &str, driver_info: &str, software: bool, api: (u32, u32)) -> DeviceInfo {
        DeviceInfo {
            index,
            name: name.into(),
            device_type: String::new(),
            is_software: software,
            api_version: format!("{}.{}.0", api.0, api.1),
            driver_name: if software { "llvmpipe" } else { "NVIDIA" }.into(),
            driver_info: driver_info.into(),
            driver_version: 0,
            vendor_id: 0,
            device_id: 0,
            supported: vec![],
            baseline_missing: vec![],
            quirks: vec![],
            timestamp_valid_bits: 64,
            timestamp_period_ns: 1.0,
            point_size_range: [1.0, 1.0],
            point_size_granularity: 1.0,
            max_image_dimension_2d: 0,
            max_image_array_layers: 0,
            max_framebuffer_layers: 0,
            max_geometry_output_vertices: 0,
            max_geometry_total_output_components: 0,
            max_transform_feedback_buffer_size: 0,
            max_transform_feedback_buffers: 0,
            max_compute_work_group_count: [0; 3],
            max_storage_buffer_range: 0,
            device_local_bytes: 0,
            api_major_minor: api,
        }
    }

    const LLVMPIPE: &str = "llvmpipe (LLVM 15.0.6, 256 bits)";

    /// Two lavapipes share a name: the driver's version tells them apart, the name alone is
    /// refused naming both, and an index still picks either.
    #[test]
    fn two_lavapipes_are_told_apart_by_their_driver() {
        let ds = [
            device(0, LLVMPIPE, "Mesa 25.0.7-2~bpo12+1 (LLVM 15.0.6)", true, (1, 4)),
            device(1, LLVMPIPE, "Mesa 22.3.6 (LLVM 15.0.6)", true, (1, 3)),
        ];
        assert_eq!(choose_device(&ds, Some("Mesa 25")).unwrap(), 0);
        assert_eq!(choose_device(&ds, Some("mesa 22.3")).unwrap(), 1);
        assert_eq!(choose_device(&ds, Some("1")).unwrap(), 1);
        let e = choose_device(&ds, Some("llvmpipe")).unwrap_err();
        assert!(matches!(e, crate::VkError::AmbiguousDevice { count: 2, .. }), "{e}");
        let e = e.to_string();
        assert!(e.contains("matches 2 different devices") && e.contains("[0]") && e.contains("Mesa 22.3.6"), "{e}");
        let e = choose_device(&ds, Some("Mesa 24")).unwrap_err().to_string();
        assert!(e.contains("no Vulkan device matches `Mesa 24`") && e.contains("Mesa 25.0.7"), "{e}");
    }

    /// A node's identical GPUs are one choice (the first), not an ambiguity; a hardware GPU is
    /// the default over lavapipe, and a device below Vulkan 1.3 is refused by name.
    #[test]
    fn identical_devices_give_the_first_and_the_default_prefers_hardware() {
        let ds = [
            device(0, LLVMPIPE, "Mesa 22.3.6 (LLVM 15.0.6)", true, (1, 3)),
            device(1, "NVIDIA H100 80GB HBM3", "570.86", false, (1, 4)),
            device(2, "NVIDIA H100 80GB HBM3", "570.86", false, (1, 4)),
            device(3, "Old GPU", "1.0", false, (1, 2)),
        ];
        assert_eq!(choose_device(&ds, Some("h100")).unwrap(), 1);
        assert_eq!(choose_device(&ds, None).unwrap(), 1);
        assert_eq!(choose_device(&ds[..1], None).unwrap(), 0);
        let e = choose_device(&ds, Some("old")).unwrap_err().to_string();
        assert!(e.contains("needs 1.3"), "{e}");
    }
}
