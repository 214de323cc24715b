//! vkcore: the only crate in causticlab that says `unsafe` or calls `ash`. Small RAII modules:
//! an instance with counted validation messages, device choice with the features this project
//! uses, gpu-allocator buffers and images, runtime GLSL, pipelines, frames of passes with
//! automatic barriers and timestamps, transform feedback and compute stream compaction, and a
//! window's swapchain with an egui panel (`window`, the viewer's).

mod accel;
mod bind;
mod buffer;
pub mod compaction;
mod context;
mod counters;
mod crash;
mod device;
mod error;
mod features;
mod frame;
mod grid;
mod image;
mod instance;
mod marker;
mod pass;
mod pipeline;
mod profiler;
mod push;
mod query;
mod recorder;
mod reflect;
mod ring;
mod shader;
mod shared_pipelines;
mod tracker;
mod transfer;
pub mod window;

pub use accel::{AccelerationStructure, TlasInstance};
pub use ash::vk::Format;
pub use bind::{Bind, Named};
pub use buffer::{Buffer, Memory};
pub use compaction::{
    AppendCounter, CompactConstants, CompactStream, CompactionPath, Compactor, Finalize, Source, StepInput,
};

pub use context::{Context, ContextOptions};
pub use counters::Counters;
pub use crash::TEST_SEGFAULT_ENV;
pub use device::{choose_device, driver_label, enumerate_devices};
pub use error::{Result, VkError};
pub use features::{DeviceInfo, Feature};
pub use frame::{Frame, FrameOptions, PassNode, Use};
pub use grid::{dispatch_grid, MAX_GROUPS_PER_AXIS};
pub use image::{texel_size, Filter, Image, ImageDesc, ImageView, Sampler, ViewKind};
pub use instance::{Instance, ValidationLog};
pub use pass::Pass;
pub use pipeline::{
    Binding, BindingKind, Blend, Cull, GraphicsDesc, Pipeline, Topology, VertexAttribute, VertexLayout,
    PUSH_CONSTANT_BYTES,
};
pub use profiler::{FrameReport, PassSummary, PassTiming, PipelineStats, Profiler, MAX_PASSES};
pub use push::{check_push_constants, PushConstants};
pub use query::QueryPool;
pub use recorder::{Cmd, Targets};
pub use reflect::{ReflectedBinding, ReflectedMember};
pub use ring::{FrameRing, RingOptions, Timing};
pub use shader::{ShaderCompiler, Spirv, Stage};
pub use tracker::Access;
pub use window::{Overlay, PresentOptions, Presented, Presenter, Surface};
