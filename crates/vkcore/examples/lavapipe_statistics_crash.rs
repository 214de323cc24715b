//! The smallest command buffer that crashes lavapipe (Mesa 22.3.6 and 25.0.7 seen; the write-up
//! is docs/mesa_lavapipe_statistics_crash.md): push constants for a range whose stages include
//! COMPUTE, with no compute pipeline bound, then begin a pipeline-statistics query that counts
//! compute-shader invocations. No pipeline, no draw, no dispatch is needed.
//!
//! ```sh
//! cargo run -p vkcore --example lavapipe_statistics_crash            # the default device
//! cargo run -p vkcore --example lavapipe_statistics_crash -- vertex  # the same, VERTEX only
//! ```
//!
//! With `vertex` the push names only VERTEX and the driver survives: the stage flags are the
//! trigger. Raw ash on purpose (no vkcore), so it can be read as the C it would be upstream.

use ash::vk;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mode = std::env::args().nth(1).unwrap_or_default();
    let compute_in_push = mode != "vertex";
    // SAFETY: each call follows the Vulkan spec's valid usage, which the validation layer
    // accepts (VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation reports nothing before the crash).
    unsafe {
        let entry = ash::Entry::load()?;
        let app = vk::ApplicationInfo::default().api_version(vk::API_VERSION_1_3);
        let instance = entry.create_instance(&vk::InstanceCreateInfo::default().application_info(&app), None)?;
        let pd = *instance.enumerate_physical_devices()?.first().ok_or("no Vulkan device")?;
        let mut driver = vk::PhysicalDeviceDriverProperties::default();
        let mut props = vk::PhysicalDeviceProperties2::default().push_next(&mut driver);
        instance.get_physical_device_properties2(pd, &mut props);
        println!(
            "device: {} ({} {})",
            props.properties.device_name_as_c_str()?.to_string_lossy(),
            driver.driver_name_as_c_str()?.to_string_lossy(),
            driver.driver_info_as_c_str()?.to_string_lossy()
        );

        let family = instance
            .get_physical_device_queue_family_properties(pd)
            .iter()
            .position(|f| f.queue_flags.contains(vk::QueueFlags::GRAPHICS | vk::QueueFlags::COMPUTE))
            .ok_or("no graphics+compute queue")? as u32;
        let priorities = [1.0];
        let queues = [vk::DeviceQueueCreateInfo::default().queue_family_index(family).queue_priorities(&priorities)];
        let features = vk::PhysicalDeviceFeatures::default().pipeline_statistics_query(true);
        let device = instance.create_device(
            pd,
            &vk::DeviceCreateInfo::default().queue_create_infos(&queues).enabled_features(&features),
            None,
        )?;

        // A layout with one push-constant range for the vertex and compute stages.
        let stages = vk::ShaderStageFlags::VERTEX | vk::ShaderStageFlags::COMPUTE;
        let ranges = [vk::PushConstantRange { stage_flags: stages, offset: 0, size: 4 }];
        let layout = device
            .create_pipeline_layout(&vk::PipelineLayoutCreateInfo::default().push_constant_ranges(&ranges), None)?;
        let pool = device.create_query_pool(
            &vk::QueryPoolCreateInfo::default()
                .query_type(vk::QueryType::PIPELINE_STATISTICS)
                .query_count(1)
                .pipeline_statistics(vk::QueryPipelineStatisticFlags::COMPUTE_SHADER_INVOCATIONS),
            None,
        )?;
        let cmd_pool =
            device.create_command_pool(&vk::CommandPoolCreateInfo::default().queue_family_index(family), None)?;
        let cb = device.allocate_command_buffers(
            &vk::CommandBufferAllocateInfo::default().command_pool(cmd_pool).command_buffer_count(1),
        )?[0];

        device.begin_command_buffer(cb, &vk::CommandBufferBeginInfo::default())?;
        device.cmd_reset_query_pool(cb, pool, 0, 1);
        // The push names COMPUTE (as the range must: the stages of every range it overlaps).
        // lavapipe marks the compute stage's inline uniforms dirty...
        let push_stages = if compute_in_push { stages } else { vk::ShaderStageFlags::VERTEX };
        let push_layout = if compute_in_push {
            layout
        } else {
            let vertex_only = [vk::PushConstantRange { stage_flags: push_stages, offset: 0, size: 4 }];
            device.create_pipeline_layout(
                &vk::PipelineLayoutCreateInfo::default().push_constant_ranges(&vertex_only),
                None,
            )?
        };
        if mode != "none" {
            device.cmd_push_constants(cb, push_layout, push_stages, 0, &1u32.to_le_bytes());
        }
        // ...and vkCmdBeginQuery, for a pool counting compute invocations, emits the compute
        // state, reading `shaders[MESA_SHADER_COMPUTE]->inlines.can_inline` of no shader.
        device.cmd_begin_query(cb, pool, 0, vk::QueryControlFlags::empty());
        device.cmd_end_query(cb, pool, 0);
        device.end_command_buffer(cb)?;

        let queue = device.get_device_queue(family, 0);
        let cbs = [cb];
        let fence = device.create_fence(&vk::FenceCreateInfo::default(), None)?;
        println!("submitting (push stages {push_stages:?})");
        device.queue_submit(queue, &[vk::SubmitInfo::default().command_buffers(&cbs)], fence)?;
        device.wait_for_fences(&[fence], true, u64::MAX)?;
        println!("no crash: the driver survived");

        device.destroy_fence(fence, None);
        device.destroy_command_pool(cmd_pool, None);
        device.destroy_query_pool(pool, None);
        if push_layout != layout {
            device.destroy_pipeline_layout(push_layout, None);
        }
        device.destroy_pipeline_layout(layout, None);
        device.destroy_device(None);
        instance.destroy_instance(None);
    }
    Ok(())
}
