//! The device features this project uses, queried once per physical device, and the check that
//! turns "a technique needs X" into a clear error instead of a driver crash.

use crate::error::VkError;
use ash::vk;

/// A capability some technique needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Feature {
    GeometryShader,
    TransformFeedback,
    TransformFeedbackDraw,
    TransformFeedbackQueries,
    ShaderOutputLayer,
    Multiview,
    MultiviewGeometryShader,
    BufferFloat32AtomicAdd,
    ImageFloat32AtomicAdd,
    PipelineStatisticsQuery,
    LargePoints,
    Timestamps,
    PushDescriptor,
    FragmentStoresAndAtomics,
    VertexPipelineStoresAndAtomics,
    /// Acceleration structures (with the buffer device addresses their builds read).
    AccelerationStructure,
    /// `rayQueryEXT` in any shader stage.
    RayQuery,
    /// Ray-generation, hit and miss shaders (listed; no pipeline of this project uses them yet).
    RayTracingPipeline,
}

impl Feature {
    pub const ALL: [Feature; 18] = [
        Feature::GeometryShader,
        Feature::TransformFeedback,
        Feature::TransformFeedbackDraw,
        Feature::TransformFeedbackQueries,
        Feature::ShaderOutputLayer,
        Feature::Multiview,
        Feature::MultiviewGeometryShader,
        Feature::BufferFloat32AtomicAdd,
        Feature::ImageFloat32AtomicAdd,
        Feature::PipelineStatisticsQuery,
        Feature::LargePoints,
        Feature::Timestamps,
        Feature::PushDescriptor,
        Feature::FragmentStoresAndAtomics,
        Feature::VertexPipelineStoresAndAtomics,
        Feature::AccelerationStructure,
        Feature::RayQuery,
        Feature::RayTracingPipeline,
    ];

    /// The name used on the command line (`--without-feature`) and in `causticlab devices`.
    pub fn name(self) -> &'static str {
        match self {
            Feature::GeometryShader => "geometry_shader",
            Feature::TransformFeedback => "transform_feedback",
            Feature::TransformFeedbackDraw => "transform_feedback_draw",
            Feature::TransformFeedbackQueries => "transform_feedback_queries",
            Feature::ShaderOutputLayer => "shader_output_layer",
            Feature::Multiview => "multiview",
            Feature::MultiviewGeometryShader => "multiview_geometry_shader",
            Feature::BufferFloat32AtomicAdd => "buffer_float32_atomic_add",
            Feature::ImageFloat32AtomicAdd => "image_float32_atomic_add",
            Feature::PipelineStatisticsQuery => "pipeline_statistics_query",
            Feature::LargePoints => "large_points",
            Feature::Timestamps => "timestamps",
            Feature::PushDescriptor => "push_descriptor",
            Feature::FragmentStoresAndAtomics => "fragment_stores_and_atomics",
            Feature::VertexPipelineStoresAndAtomics => "vertex_pipeline_stores_and_atomics",
            Feature::AccelerationStructure => "acceleration_structure",
            Feature::RayQuery => "ray_query",
            Feature::RayTracingPipeline => "ray_tracing_pipeline",
        }
    }

    /// Where the Vulkan spec defines it.
    pub fn vulkan_name(self) -> &'static str {
        match self {
            Feature::GeometryShader => "VkPhysicalDeviceFeatures::geometryShader",
            Feature::TransformFeedback => "VK_EXT_transform_feedback: transformFeedback",
            Feature::TransformFeedbackDraw => {
                "VK_EXT_transform_feedback: transformFeedbackDraw (vkCmdDrawIndirectByteCountEXT)"
            }
            Feature::TransformFeedbackQueries => "VK_EXT_transform_feedback: transformFeedbackQueries",
            Feature::ShaderOutputLayer => "VkPhysicalDeviceVulkan12Features::shaderOutputLayer",
            Feature::Multiview => "VkPhysicalDeviceVulkan11Features::multiview",
            Feature::MultiviewGeometryShader => "VkPhysicalDeviceVulkan11Features::multiviewGeometryShader",
            Feature::BufferFloat32AtomicAdd => "VK_EXT_shader_atomic_float: shaderBufferFloat32AtomicAdd",
            Feature::ImageFloat32AtomicAdd => "VK_EXT_shader_atomic_float: shaderImageFloat32AtomicAdd",
            Feature::PipelineStatisticsQuery => "VkPhysicalDeviceFeatures::pipelineStatisticsQuery",
            Feature::LargePoints => "VkPhysicalDeviceFeatures::largePoints",
            Feature::Timestamps => "VkQueueFamilyProperties::timestampValidBits > 0",
            Feature::PushDescriptor => "VK_KHR_push_descriptor",
            Feature::FragmentStoresAndAtomics => "VkPhysicalDeviceFeatures::fragmentStoresAndAtomics",
            Feature::VertexPipelineStoresAndAtomics => "VkPhysicalDeviceFeatures::vertexPipelineStoresAndAtomics",
            Feature::AccelerationStructure => {
                "VK_KHR_acceleration_structure: accelerationStructure (with VkPhysicalDeviceVulkan12Features::bufferDeviceAddress)"
            }
            Feature::RayQuery => "VK_KHR_ray_query: rayQuery",
            Feature::RayTracingPipeline => "VK_KHR_ray_tracing_pipeline: rayTracingPipeline",
        }
    }

    pub fn parse(name: &str) -> Option<Feature> {
        Feature::ALL.into_iter().find(|f| f.name() == name)
    }
}

/// What a physical device reports, for `causticlab devices` and for recording beside timings.
#[derive(Debug, Clone)]
pub struct DeviceInfo {
    pub index: usize,
    pub name: String,
    pub device_type: String,
    pub is_software: bool,
    pub api_version: String,
    pub driver_name: String,
    pub driver_info: String,
    pub driver_version: u32,
    pub vendor_id: u32,
    pub device_id: u32,
    pub supported: Vec<Feature>,
    /// Baseline features every technique relies on that this device lacks (it cannot be used).
    pub baseline_missing: Vec<&'static str>,
    /// Features the driver reports but this project treats as absent, with the reason.
    pub quirks: Vec<String>,
    pub timestamp_valid_bits: u32,
    pub timestamp_period_ns: f32,
    pub point_size_range: [f32; 2],
    pub point_size_granularity: f32,
    pub max_image_dimension_2d: u32,
    pub max_image_array_layers: u32,
    pub max_framebuffer_layers: u32,
    pub max_geometry_output_vertices: u32,
    pub max_geometry_total_output_components: u32,
    pub max_transform_feedback_buffer_size: u64,
    pub max_transform_feedback_buffers: u32,
    pub max_compute_work_group_count: [u32; 3],
    pub max_storage_buffer_range: u32,
    pub device_local_bytes: u64,
    pub api_major_minor: (u32, u32),
}

impl DeviceInfo {
    pub fn has(&self, f: Feature) -> bool {
        self.supported.contains(&f)
    }

    /// `Ok` when every feature is present, else an error naming the first missing one.
    pub fn require(&self, who: &str, features: &[Feature]) -> Result<(), VkError> {
        match features.iter().find(|f| !self.has(**f)) {
            None => Ok(()),
            Some(f) => Err(VkError::MissingFeature {
                who: who.to_string(),
                feature: f.name(),
                vulkan_name: f.vulkan_name(),
                device: self.name.clone(),
            }),
        }
    }

    /// A short, filesystem-safe name for results folders, e.g. `lavapipe-llvmpipe-llvm-15`.
    pub fn slug(&self) -> String {
        let raw = format!("{}-{}", self.driver_name, self.name);
        let mut s = String::new();
        for c in raw.to_lowercase().chars() {
            if c.is_ascii_alphanumeric() {
                s.push(c);
            } else if !s.ends_with('-') {
                s.push('-');
            }
        }
        s.trim_matches('-').chars().take(48).collect()
    }
}

pub(crate) fn device_type_name(t: vk::PhysicalDeviceType) -> &'static str {
    match t {
        vk::PhysicalDeviceType::DISCRETE_GPU => "discrete GPU",
        vk::PhysicalDeviceType::INTEGRATED_GPU => "integrated GPU",
        vk::PhysicalDeviceType::VIRTUAL_GPU => "virtual GPU",
        vk::PhysicalDeviceType::CPU => "CPU (software)",
        _ => "other",
    }
}
