//! causticlab's techniques, one module per paper (`techniques`), the eye render that shows them
//! (`render`), what both share on the GPU (`gpu`), the scene description and CPU references.

#![forbid(unsafe_code)]

pub mod animation;
pub mod bvh;
pub mod compare;
pub mod diff;
pub mod dump;
pub mod error;
pub mod error_png;
pub mod final_reference;
pub mod flip;
pub mod gpu;
pub mod image_io;
pub mod reference;
pub mod render;
pub mod scene;
pub mod scratch;
pub mod techniques;
pub mod workers;

pub use error::InputError;
