//! causticlab's techniques, one module per paper, plus the scene description and CPU references.

pub mod error;
pub mod scene;
pub mod bvh;
pub mod image_io;
pub mod render;

pub use error::InputError;
