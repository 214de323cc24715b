//! Descriptors: what a pass binds, each under the name its shader gives the binding, in
//! binding order: `("photon_power", Bind::Sampled(&view, &sampler))`. The names are checked
//! against the pipeline's shaders (SPIR-V reflection), so a swapped, missing or extra binding
//! is an error naming both sides rather than a wrong image. Each kind also says how the pass
//! touches its resource, so a pass names a resource once and gets both the push descriptor
//! and the barrier from it.

use crate::buffer::Buffer;
use crate::error::{Result, VkError};
use crate::frame::Use;
use crate::image::{ImageView, Sampler};
use crate::pipeline::{Binding, BindingKind};
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
    /// A top-level acceleration structure, read by ray queries (`accelerationStructureEXT`).
    AccelerationStructure(&'a crate::AccelerationStructure),
}

/// A descriptor under the name its shader gives the binding.
pub type Named<'a> = (&'static str, Bind<'a>);

impl<'a> Bind<'a> {
    /// The descriptor kind this fills.
    pub(crate) fn kind(&self) -> BindingKind {
        match self {
            Bind::Sampled(..) => BindingKind::SampledImage,
            Bind::Storage(_) => BindingKind::StorageImage,
            Bind::Buffer(_) | Bind::BufferRange(..) | Bind::BufferRead(_) => BindingKind::StorageBuffer,
            Bind::Uniform(_) => BindingKind::UniformBuffer,
            Bind::AccelerationStructure(_) => BindingKind::AccelerationStructure,
        }
    }

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
            Bind::AccelerationStructure(_) => Access::ACCELERATION_STRUCTURE_READ,
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
            // Built by its own submission, which ended in a barrier to every later command.
            Bind::AccelerationStructure(a) => Use::buffer(a.buffer(), access),
        }
    }
}

/// Checks that `binds` are `pipeline`'s bindings, by name, in binding order, each of its kind;
/// the error names the pipeline, the shader's binding and what the pass gave in its place.
pub(crate) fn check_binds(pipeline: &str, bindings: &[Binding], binds: &[Named]) -> Result<()> {
    let given: Vec<(&str, BindingKind)> = binds.iter().map(|(n, b)| (*n, b.kind())).collect();
    check_names(pipeline, bindings, &given)
}

/// [`check_binds`] on the names and kinds alone.
fn check_names(pipeline: &str, bindings: &[Binding], binds: &[(&str, BindingKind)]) -> Result<()> {
    let fail = |what: String| Err(VkError::Invalid(format!("pipeline `{pipeline}`: {what}")));
    let declared = |name: &str| bindings.iter().find(|b| b.name == name);
    for (i, &(name, kind)) in binds.iter().enumerate() {
        let Some(want) = bindings.get(i) else {
            return match declared(name) {
                Some(b) => fail(format!("`{name}` (binding {}) is given twice", b.binding)),
                None => fail(format!(
                    "the pass gives `{name}`, which its shaders do not declare (they declare {})",
                    list(bindings)
                )),
            };
        };
        if want.name != name {
            let elsewhere = match declared(name) {
                Some(b) => format!("; `{name}` is binding {}", b.binding),
                None => "; the shaders declare no such binding".to_string(),
            };
            return fail(format!(
                "binding {} is `{}` in the shaders, the pass gives `{name}` in its place{elsewhere}",
                want.binding, want.name
            ));
        }
        if kind != want.kind {
            return fail(format!(
                "binding {} `{name}` is a {:?} in the shaders, the pass gives a {:?}",
                want.binding, want.kind, kind
            ));
        }
    }
    if let Some(missing) = bindings.get(binds.len()) {
        return fail(format!("binding {} `{}` ({:?}) is not given", missing.binding, missing.name, missing.kind));
    }
    Ok(())
}

/// `a` (0), `b` (1), ... for error messages.
fn list(bindings: &[Binding]) -> String {
    if bindings.is_empty() {
        return "none".into();
    }
    bindings.iter().map(|b| format!("`{}` ({})", b.name, b.binding)).collect::<Vec<_>>().join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bindings() -> Vec<Binding> {
        [
            (0, "frame", BindingKind::UniformBuffer),
            (2, "photon_position", BindingKind::SampledImage),
            (3, "photon_power", BindingKind::SampledImage),
        ]
        .map(|(binding, name, kind)| Binding { binding, name: name.into(), kind })
        .to_vec()
    }

    fn check(given: &[(&str, BindingKind)]) -> Result<()> {
        check_names("p", &bindings(), given)
    }

    #[test]
    fn names_in_binding_order_pass() {
        use BindingKind::*;
        check(&[("frame", UniformBuffer), ("photon_position", SampledImage), ("photon_power", SampledImage)]).unwrap();
    }

    #[test]
    fn swapped_same_kind_bindings_name_both() {
        use BindingKind::*;
        let e = check(&[("frame", UniformBuffer), ("photon_power", SampledImage), ("photon_position", SampledImage)])
            .unwrap_err()
            .to_string();
        assert!(e.contains("pipeline `p`") && e.contains("binding 2 is `photon_position`"), "{e}");
        assert!(e.contains("gives `photon_power`") && e.contains("`photon_power` is binding 3"), "{e}");
    }

    #[test]
    fn missing_extra_unknown_and_wrong_kind_are_named() {
        use BindingKind::*;
        let e = check(&[("frame", UniformBuffer), ("photon_position", SampledImage)]).unwrap_err().to_string();
        assert!(e.contains("binding 3 `photon_power`") && e.contains("not given"), "{e}");
        let e = check(&[
            ("frame", UniformBuffer),
            ("photon_position", SampledImage),
            ("photon_power", SampledImage),
            ("x", StorageImage),
        ])
        .unwrap_err()
        .to_string();
        assert!(e.contains("`x`") && e.contains("do not declare") && e.contains("`photon_power` (3)"), "{e}");
        let e = check(&[("frame", UniformBuffer), ("photon_positon", SampledImage)]).unwrap_err().to_string();
        assert!(e.contains("`photon_position` in the shaders") && e.contains("no such binding"), "{e}");
        let e = check(&[("frame", StorageBuffer)]).unwrap_err().to_string();
        assert!(e.contains("binding 0 `frame` is a UniformBuffer") && e.contains("StorageBuffer"), "{e}");
    }
}
