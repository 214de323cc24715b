//! causticlab's techniques, one module per paper, plus the scene description and CPU references.

pub mod animation;
pub mod bvh;
pub mod caustic_map;
pub mod compare;
pub mod error;
pub mod image_io;
pub mod reference;
pub mod render;
pub mod scene;

pub use error::InputError;
