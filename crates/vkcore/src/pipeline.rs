//! Graphics pipelines (vertex + optional geometry + optional fragment; points with gl_PointSize,
//! additive blending, layered targets with per-primitive gl_Layer, multiview, rasterizer discard
//! for transform-feedback-only passes) and compute pipelines. Descriptors are push descriptors
//! in set 0, laid out as the shaders declare them (SPIR-V reflection, `reflect.rs`): a pipeline
//! knows each binding's name and kind, and a pass binds by those names (`bind.rs`); 128 bytes
//! of push constants for every stage.

use crate::context::{Context, Shared};
use crate::error::{Result, VkError, VkResultExt};
use crate::shader::{Spirv, Stage};
use crate::shared_pipelines::Key;
use ash::vk;
use std::sync::Arc;

/// Size of the push-constant block every pipeline gets.
pub const PUSH_CONSTANT_BYTES: u32 = 128;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BindingKind {
    /// `sampler2D` / `sampler2DArray` / `samplerCube` (combined image sampler).
    SampledImage,
    /// `image2D` etc.
    StorageImage,
    /// `buffer { ... }`.
    StorageBuffer,
    /// `uniform { ... }`.
    UniformBuffer,
    /// `accelerationStructureEXT` (GL_EXT_ray_query).
    AccelerationStructure,
}

/// One descriptor binding of a pipeline, as its shaders declare it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Binding {
    /// `layout(binding = N)`.
    pub binding: u32,
    /// The shader's name for it (see [`crate::ReflectedBinding::name`]).
    pub name: String,
    pub kind: BindingKind,
}

impl BindingKind {
    pub(crate) fn vk(self) -> vk::DescriptorType {
        match self {
            BindingKind::SampledImage => vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
            BindingKind::StorageImage => vk::DescriptorType::STORAGE_IMAGE,
            BindingKind::StorageBuffer => vk::DescriptorType::STORAGE_BUFFER,
            BindingKind::UniformBuffer => vk::DescriptorType::UNIFORM_BUFFER,
            BindingKind::AccelerationStructure => vk::DescriptorType::ACCELERATION_STRUCTURE_KHR,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Topology {
    Points,
    Lines,
    Triangles,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Cull {
    None,
    Back,
    Front,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Blend {
    Replace,
    /// dst += src on every channel (splatting photons).
    Additive,
}

/// One vertex attribute of a tightly specified vertex buffer (binding 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct VertexAttribute {
    pub location: u32,
    pub format: vk::Format,
    pub offset: u32,
}

#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct VertexLayout {
    pub stride: u32,
    pub attributes: Vec<VertexAttribute>,
}

#[derive(Debug, Clone)]
pub struct GraphicsDesc {
    pub name: String,
    pub vertex: Spirv,
    pub geometry: Option<Spirv>,
    pub fragment: Option<Spirv>,
    pub vertex_layout: Option<VertexLayout>,
    pub topology: Topology,
    pub cull: Cull,
    pub color_formats: Vec<vk::Format>,
    pub blend: Blend,
    pub depth_format: Option<vk::Format>,
    pub depth_test: bool,
    pub depth_write: bool,
    /// No rasterization (transform-feedback-only passes).
    pub rasterizer_discard: bool,
    /// Multiview mask (0 = off): one draw renders into every layer whose bit is set.
    pub view_mask: u32,
}

impl GraphicsDesc {
    pub fn new(name: &str, vertex: Spirv, fragment: Option<Spirv>) -> Self {
        GraphicsDesc {
            name: name.into(),
            vertex,
            geometry: None,
            fragment,
            vertex_layout: None,
            topology: Topology::Triangles,
            cull: Cull::None,
            color_formats: vec![],
            blend: Blend::Replace,
            depth_format: None,
            depth_test: false,
            depth_write: false,
            rasterizer_discard: false,
            view_mask: 0,
        }
    }
}

/// A pipeline of either kind with its layout. Pipelines of equal descriptions share one Vulkan
/// pipeline (`shared_pipelines.rs`).
pub struct Pipeline {
    pub(crate) built: Arc<Built>,
    pub name: String,
}

/// The Vulkan objects of a pipeline, destroyed with the last `Pipeline` that shares them.
pub(crate) struct Built {
    shared: Arc<Shared>,
    pub raw: vk::Pipeline,
    pub layout: vk::PipelineLayout,
    set_layout: vk::DescriptorSetLayout,
    pub bind_point: vk::PipelineBindPoint,
    /// The stages its layout's descriptors and push constants name: its own shaders'.
    pub stages: vk::ShaderStageFlags,
    /// Shared with every `Cmd` that binds the pipeline (no copy per pass).
    pub bindings: Arc<[Binding]>,
}

impl Drop for Built {
    fn drop(&mut self) {
        let d = self.shared.raw();
        unsafe {
            d.destroy_pipeline(self.raw, None);
            d.destroy_pipeline_layout(self.layout, None);
            d.destroy_descriptor_set_layout(self.set_layout, None);
        }
    }
}

fn stage_flags(s: Stage) -> vk::ShaderStageFlags {
    match s {
        Stage::Vertex => vk::ShaderStageFlags::VERTEX,
        Stage::Geometry => vk::ShaderStageFlags::GEOMETRY,
        Stage::Fragment => vk::ShaderStageFlags::FRAGMENT,
        Stage::Compute => vk::ShaderStageFlags::COMPUTE,
    }
}

/// The stages a pipeline's layout names: its own shaders' stages, no others. A layout that named
/// every stage made a graphics pass push constants for the compute stage too, which lavapipe
/// (Mesa 22.3.6 and 25.0.7 seen) answers by dereferencing a null compute shader at the next
/// statistics query (docs/mesa_lavapipe_statistics_crash.md). With its own stages, a push
/// names only stages whose pipeline is bound, on every driver.
fn layout_stages(stages: &[Stage]) -> vk::ShaderStageFlags {
    stages.iter().fold(vk::ShaderStageFlags::empty(), |all, s| all | stage_flags(*s))
}

fn make_layout(
    ctx: &Context,
    bindings: &[Binding],
    stages: vk::ShaderStageFlags,
) -> Result<(vk::DescriptorSetLayout, vk::PipelineLayout)> {
    let b: Vec<vk::DescriptorSetLayoutBinding> = bindings
        .iter()
        .map(|b| {
            vk::DescriptorSetLayoutBinding::default()
                .binding(b.binding)
                .descriptor_type(b.kind.vk())
                .descriptor_count(1)
                .stage_flags(stages)
        })
        .collect();
    let info = vk::DescriptorSetLayoutCreateInfo::default()
        .flags(vk::DescriptorSetLayoutCreateFlags::PUSH_DESCRIPTOR_KHR)
        .bindings(&b);
    let d = ctx.shared.raw();
    let set_layout = unsafe { d.create_descriptor_set_layout(&info, None) }.call("vkCreateDescriptorSetLayout")?;
    ctx.shared.counters.object(2); // the set layout and the pipeline layout
    let ranges = [vk::PushConstantRange { stage_flags: stages, offset: 0, size: PUSH_CONSTANT_BYTES }];
    let layouts = [set_layout];
    let info = vk::PipelineLayoutCreateInfo::default().set_layouts(&layouts).push_constant_ranges(&ranges);
    match unsafe { d.create_pipeline_layout(&info, None) } {
        Ok(l) => Ok((set_layout, l)),
        Err(e) => {
            unsafe { d.destroy_descriptor_set_layout(set_layout, None) };
            Err(VkError::Call { call: "vkCreatePipelineLayout", result: e })
        }
    }
}

/// The descriptor bindings of a pipeline's stages, merged, in binding order. Stages that
/// declare one binding must agree on its name and kind.
pub(crate) fn reflect_bindings(name: &str, stages: &[&Spirv]) -> Result<Vec<Binding>> {
    let mut out: Vec<Binding> = vec![];
    for s in stages {
        let list = s
            .descriptor_bindings()
            .map_err(|e| VkError::Invalid(format!("pipeline `{name}`, {:?} shader: {e}", s.stage)))?;
        for b in list {
            match out.iter().find(|o| o.binding == b.binding) {
                Some(o) if (o.name.as_str(), o.kind) != (b.name.as_str(), b.kind) => {
                    return Err(VkError::Invalid(format!(
                        "pipeline `{name}`: binding {} is `{}` ({:?}) in one stage and `{}` ({:?}) in the {:?} shader",
                        b.binding, o.name, o.kind, b.name, b.kind, s.stage
                    )))
                }
                Some(_) => {}
                None => out.push(Binding { binding: b.binding, name: b.name, kind: b.kind }),
            }
        }
    }
    out.sort_by_key(|b| b.binding);
    Ok(out)
}

struct Modules<'a> {
    device: &'a ash::Device,
    list: Vec<vk::ShaderModule>,
}

impl Modules<'_> {
    fn add(&mut self, spirv: &Spirv) -> Result<vk::ShaderModule> {
        let info = vk::ShaderModuleCreateInfo::default().code(&spirv.words);
        let m = unsafe { self.device.create_shader_module(&info, None) }.call("vkCreateShaderModule")?;
        self.list.push(m);
        Ok(m)
    }
}

impl Drop for Modules<'_> {
    fn drop(&mut self) {
        for m in self.list.drain(..) {
            unsafe { self.device.destroy_shader_module(m, None) };
        }
    }
}

impl Pipeline {
    /// The descriptor bindings its shaders declare, in binding order: what a pass binds, by name.
    pub fn bindings(&self) -> &[Binding] {
        &self.built.bindings
    }

    /// Whether its shaders declare a binding of this name (for a binding that a shader variant
    /// leaves out, e.g. under a define).
    pub fn declares(&self, name: &str) -> bool {
        self.built.bindings.iter().any(|b| b.name == name)
    }

    /// Whether `self` and `other` are one Vulkan pipeline (equal descriptions, both alive).
    pub fn shares(&self, other: &Pipeline) -> bool {
        Arc::ptr_eq(&self.built, &other.built)
    }

    pub fn graphics(ctx: &Context, desc: &GraphicsDesc) -> Result<Pipeline> {
        if desc.geometry.is_some() {
            ctx.require(&format!("pipeline `{}` (geometry shader)", desc.name), &[crate::Feature::GeometryShader])?;
        }
        let stages: Vec<&Spirv> =
            [Some(&desc.vertex), desc.geometry.as_ref(), desc.fragment.as_ref()].into_iter().flatten().collect();
        // Every field, named: a field added to `GraphicsDesc` fails to compile here until the
        // key says whether it makes a different pipeline.
        let GraphicsDesc {
            name,
            vertex: _,
            geometry: _,
            fragment: _,
            vertex_layout,
            topology,
            cull,
            color_formats,
            blend,
            depth_format,
            depth_test,
            depth_write,
            rasterizer_discard,
            view_mask,
        } = desc;
        let key = Key {
            name: name.clone(),
            stages: stages.iter().map(|s| (s.stage, s.words.clone())).collect(),
            state: Some((
                vertex_layout.clone(),
                *topology,
                *cull,
                color_formats.clone(),
                *blend,
                *depth_format,
                *depth_test,
                *depth_write,
                *rasterizer_discard,
                *view_mask,
            )),
        };
        let built = ctx.shared.pipelines.get_or_make(key, || {
            let bindings = reflect_bindings(&desc.name, &stages)?;
            let layout_stages = layout_stages(&stages.iter().map(|s| s.stage).collect::<Vec<_>>());
            built(ctx, &desc.name, bindings, vk::PipelineBindPoint::GRAPHICS, layout_stages, |layout| {
                Self::build_graphics(ctx, desc, layout)
            })
        })?;
        Ok(Pipeline { built, name: desc.name.clone() })
    }

    fn build_graphics(ctx: &Context, desc: &GraphicsDesc, layout: vk::PipelineLayout) -> Result<vk::Pipeline> {
        let d = ctx.shared.raw();
        let mut modules = Modules { device: d, list: vec![] };
        let mut stages = vec![];
        for s in [Some(&desc.vertex), desc.geometry.as_ref(), desc.fragment.as_ref()].into_iter().flatten() {
            let m = modules.add(s)?;
            stages
                .push(vk::PipelineShaderStageCreateInfo::default().stage(stage_flags(s.stage)).module(m).name(c"main"));
        }
        let (vb, va) = match &desc.vertex_layout {
            Some(l) => (
                vec![vk::VertexInputBindingDescription {
                    binding: 0,
                    stride: l.stride,
                    input_rate: vk::VertexInputRate::VERTEX,
                }],
                l.attributes
                    .iter()
                    .map(|a| vk::VertexInputAttributeDescription {
                        location: a.location,
                        binding: 0,
                        format: a.format,
                        offset: a.offset,
                    })
                    .collect(),
            ),
            None => (vec![], vec![]),
        };
        let vertex_input = vk::PipelineVertexInputStateCreateInfo::default()
            .vertex_binding_descriptions(&vb)
            .vertex_attribute_descriptions(&va);
        let topology = match desc.topology {
            Topology::Points => vk::PrimitiveTopology::POINT_LIST,
            Topology::Lines => vk::PrimitiveTopology::LINE_LIST,
            Topology::Triangles => vk::PrimitiveTopology::TRIANGLE_LIST,
        };
        let input_assembly = vk::PipelineInputAssemblyStateCreateInfo::default().topology(topology);
        let viewport = vk::PipelineViewportStateCreateInfo::default().viewport_count(1).scissor_count(1);
        let cull = match desc.cull {
            Cull::None => vk::CullModeFlags::NONE,
            Cull::Back => vk::CullModeFlags::BACK,
            Cull::Front => vk::CullModeFlags::FRONT,
        };
        let raster = vk::PipelineRasterizationStateCreateInfo::default()
            .polygon_mode(vk::PolygonMode::FILL)
            .cull_mode(cull)
            .front_face(vk::FrontFace::COUNTER_CLOCKWISE)
            .line_width(1.0)
            .rasterizer_discard_enable(desc.rasterizer_discard);
        let multisample =
            vk::PipelineMultisampleStateCreateInfo::default().rasterization_samples(vk::SampleCountFlags::TYPE_1);
        let depth = vk::PipelineDepthStencilStateCreateInfo::default()
            .depth_test_enable(desc.depth_test)
            .depth_write_enable(desc.depth_write)
            .depth_compare_op(vk::CompareOp::LESS_OR_EQUAL);
        let attachment = match desc.blend {
            Blend::Replace => {
                vk::PipelineColorBlendAttachmentState::default().color_write_mask(vk::ColorComponentFlags::RGBA)
            }
            Blend::Additive => vk::PipelineColorBlendAttachmentState::default()
                .blend_enable(true)
                .src_color_blend_factor(vk::BlendFactor::ONE)
                .dst_color_blend_factor(vk::BlendFactor::ONE)
                .color_blend_op(vk::BlendOp::ADD)
                .src_alpha_blend_factor(vk::BlendFactor::ONE)
                .dst_alpha_blend_factor(vk::BlendFactor::ONE)
                .alpha_blend_op(vk::BlendOp::ADD)
                .color_write_mask(vk::ColorComponentFlags::RGBA),
        };
        let attachments = vec![attachment; desc.color_formats.len()];
        let blend = vk::PipelineColorBlendStateCreateInfo::default().attachments(&attachments);
        let dynamic_states = [vk::DynamicState::VIEWPORT, vk::DynamicState::SCISSOR];
        let dynamic = vk::PipelineDynamicStateCreateInfo::default().dynamic_states(&dynamic_states);
        let mut rendering = vk::PipelineRenderingCreateInfo::default()
            .color_attachment_formats(&desc.color_formats)
            .depth_attachment_format(desc.depth_format.unwrap_or(vk::Format::UNDEFINED))
            .view_mask(desc.view_mask);
        let info = vk::GraphicsPipelineCreateInfo::default()
            .stages(&stages)
            .vertex_input_state(&vertex_input)
            .input_assembly_state(&input_assembly)
            .viewport_state(&viewport)
            .rasterization_state(&raster)
            .multisample_state(&multisample)
            .depth_stencil_state(&depth)
            .color_blend_state(&blend)
            .dynamic_state(&dynamic)
            .layout(layout)
            .push_next(&mut rendering);
        let pipelines = unsafe { d.create_graphics_pipelines(vk::PipelineCache::null(), &[info], None) }
            .map_err(|(_, e)| VkError::Call { call: "vkCreateGraphicsPipelines", result: e })?;
        Ok(pipelines[0])
    }

    /// A compute pipeline of `shader`, its descriptor set laid out as the shader declares it.
    pub fn compute(ctx: &Context, name: &str, shader: &Spirv) -> Result<Pipeline> {
        let key = Key { name: name.into(), stages: vec![(shader.stage, shader.words.clone())], state: None };
        let built = ctx.shared.pipelines.get_or_make(key, || {
            let bindings = reflect_bindings(name, &[shader])?;
            built(ctx, name, bindings, vk::PipelineBindPoint::COMPUTE, vk::ShaderStageFlags::COMPUTE, |layout| {
                let d = ctx.shared.raw();
                let mut modules = Modules { device: d, list: vec![] };
                let m = modules.add(shader)?;
                let stage = vk::PipelineShaderStageCreateInfo::default()
                    .stage(vk::ShaderStageFlags::COMPUTE)
                    .module(m)
                    .name(c"main");
                let info = vk::ComputePipelineCreateInfo::default().stage(stage).layout(layout);
                let p = unsafe { d.create_compute_pipelines(vk::PipelineCache::null(), &[info], None) }
                    .map_err(|(_, e)| VkError::Call { call: "vkCreateComputePipelines", result: e })?;
                Ok(p[0])
            })
        })?;
        Ok(Pipeline { built, name: name.into() })
    }
}

/// A pipeline's Vulkan objects: the layout of `bindings`, then the pipeline `build` makes with
/// it (the layout destroyed again if that fails).
fn built(
    ctx: &Context,
    name: &str,
    bindings: Vec<Binding>,
    bind_point: vk::PipelineBindPoint,
    stages: vk::ShaderStageFlags,
    build: impl FnOnce(vk::PipelineLayout) -> Result<vk::Pipeline>,
) -> Result<Built> {
    let (set_layout, layout) = make_layout(ctx, &bindings, stages)?;
    match build(layout) {
        Ok(raw) => {
            ctx.shared.counters.object(2); // its modules (counted as one) and the pipeline
            ctx.set_name(raw, name);
            Ok(Built {
                shared: ctx.shared.clone(),
                raw,
                layout,
                set_layout,
                bind_point,
                stages,
                bindings: bindings.into(),
            })
        }
        Err(e) => {
            let d = ctx.shared.raw();
            unsafe {
                d.destroy_pipeline_layout(layout, None);
                d.destroy_descriptor_set_layout(set_layout, None);
            }
            Err(e)
        }
    }
}
