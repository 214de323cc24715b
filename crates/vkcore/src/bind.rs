//! Descriptors: what a pass binds, in binding order. Each kind also says how the pass touches
//! its resource, so a pass names a resource once and gets both the push descriptor and the
//! barrier from it.

use crate::buffer::Buffer;
use crate::error::{Result, VkError};
use crate::frame::Use;
use crate::image::{ImageView, Sampler};
use crate::pipeline::BindingKind;
use crate::tracker::Access;
use ash::vk;

/// One descriptor to push, in binding order. Each kind also says how the pass touches the
/// resource, so a pass names it once.
#[derive(Clone, Copy)]
pub enum Bind<'a> {
    /// A sampled image: read by any shader stage.
    Sampled(&'a ImageView, &'a Sampler),
    /// A storage image: read and written.
    Storage(&'a ImageView),
    /// A storage buffer: read and written.
    Buffer(&'a Buffer),
    /// Part of a storage buffer (offset, bytes): read and written (the barrier covers all of it).
    BufferRange(&'a Buffer, u64, u64),
    /// A storage buffer that is only read.
    BufferRead(&'a Buffer),
    /// A uniform buffer.
    Uniform(&'a Buffer),
}

impl<'a> Bind<'a> {
    /// How a pipeline at `point` touches this descriptor's resource: uniforms and sampled images
    /// are read, storage images and buffers read and written by compute or by the graphics
    /// stages, `BufferRead` only read.
    pub(crate) fn access(&self, point: vk::PipelineBindPoint) -> Access {
        let read_write = if point == vk::PipelineBindPoint::COMPUTE {
            Access::COMPUTE_READ_WRITE
        } else {
            Access::GRAPHICS_READ_WRITE
        };
        match self {
            Bind::Sampled(..) => Access::SHADER_READ,
            Bind::Uniform(_) => Access::UNIFORM_READ,
            Bind::BufferRead(_) => Access::STORAGE_READ,
            Bind::Storage(_) | Bind::Buffer(_) | Bind::BufferRange(..) => read_write,
        }
    }

    /// The barrier declaration of this descriptor for a pipeline at `point`.
    pub(crate) fn to_use(self, point: vk::PipelineBindPoint) -> Use<'a> {
        let access = self.access(point);
        match self {
            Bind::Sampled(v, _) | Bind::Storage(v) => Use::view(v, access),
            Bind::Buffer(b) | Bind::BufferRange(b, ..) | Bind::BufferRead(b) | Bind::Uniform(b) => {
                Use::buffer(b, access)
            }
        }
    }
}

/// Checks that `binds` fit `kinds`, a pipeline's bindings, one by one.
pub(crate) fn check_binds(kinds: &[BindingKind], binds: &[Bind]) -> Result<()> {
    if binds.len() != kinds.len() {
        return Err(VkError::Invalid(format!("pipeline declares {} bindings, {} given", kinds.len(), binds.len())));
    }
    for (i, (b, kind)) in binds.iter().zip(kinds).enumerate() {
        let ok = matches!(
            (b, kind),
            (Bind::Sampled(..), BindingKind::SampledImage)
                | (Bind::Storage(..), BindingKind::StorageImage)
                | (Bind::Buffer(..) | Bind::BufferRange(..) | Bind::BufferRead(..), BindingKind::StorageBuffer)
                | (Bind::Uniform(..), BindingKind::UniformBuffer)
        );
        if !ok {
            return Err(VkError::Invalid(format!("binding {i}: descriptor does not match the pipeline's {kind:?}")));
        }
    }
    Ok(())
}
