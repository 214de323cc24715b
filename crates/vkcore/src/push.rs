//! Push constants: one named `#[repr(C)]` struct per pass, declared with [`push_constants!`],
//! whose GLSL twin is a `layout(push_constant)` block of the same name and members.
//! [`check_push_constants`] compares the two through SPIR-V reflection.

use crate::shader::Spirv;

/// A push-constant struct: its name and each member's (name, byte offset), in declaration
/// order. Implemented by [`push_constants!`].
pub trait PushConstants: bytemuck::Pod {
    const NAME: &'static str;
    const MEMBERS: &'static [(&'static str, usize)];
}

/// Declares a `#[repr(C)]` push-constant struct (Pod, Default) and its [`PushConstants`]
/// table, taken from the declaration itself:
///
/// ```
/// use vkcore::PushConstants;
/// vkcore::push_constants! {
///     /// The point splat's.
///     pub struct SplatConstants {
///         pub light: u32,
///         pub vertices_per_instance: u32,
///     }
/// }
/// assert_eq!(SplatConstants::NAME, "SplatConstants");
/// assert_eq!(SplatConstants::MEMBERS, &[("light", 0), ("vertices_per_instance", 4)]);
/// ```
#[macro_export]
macro_rules! push_constants {
    ($(#[$meta:meta])* $vis:vis struct $name:ident {
        $($(#[$field_meta:meta])* $field_vis:vis $field:ident : $ty:ty),* $(,)?
    }) => {
        $(#[$meta])*
        #[repr(C)]
        #[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
        $vis struct $name {
            $($(#[$field_meta])* $field_vis $field: $ty),*
        }
        impl $crate::PushConstants for $name {
            const NAME: &'static str = stringify!($name);
            const MEMBERS: &'static [(&'static str, usize)] =
                &[$((stringify!($field), ::std::mem::offset_of!($name, $field))),*];
        }
    };
}

/// Checks that `spirv`'s push-constant block is `T`'s twin: the same name, and the same
/// members in the same order at the same offsets.
pub fn check_push_constants<T: PushConstants>(spirv: &Spirv) -> Result<(), String> {
    let block = spirv.push_constant_block();
    let glsl = spirv.push_constant_members();
    let rust: Vec<(String, u32)> = T::MEMBERS.iter().map(|(n, o)| (n.to_string(), *o as u32)).collect();
    if block.as_deref() != Some(T::NAME) || glsl != rust {
        return Err(format!(
            "{}: push-constant block {:?} with {glsl:?}; the Rust struct {} has {rust:?}",
            spirv.file,
            block,
            T::NAME
        ));
    }
    Ok(())
}
