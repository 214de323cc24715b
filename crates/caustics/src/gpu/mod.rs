//! What every pass shares on the GPU, below both the eye render (`crate::render`) and the
//! caustic techniques (`crate::techniques`): the scene's meshes and uniforms (twins of
//! `shaders_glsl/common/`), render targets, their formats, pipelines over meshes, and the frame
//! modes both record in.

pub mod formats;
pub mod frame_mode;
pub mod frames;
pub mod mesh_pipeline;
pub mod pass_name;
pub mod push;
pub mod setup;
pub mod structs;
pub mod target;

pub use frame_mode::{FrameMode, FrameStep};
pub use pass_name::{BatchPart, PassName, Stage};
pub use push::*;
pub use setup::{mesh_uses, GpuMesh};
pub use structs::*;
pub use target::Target;
