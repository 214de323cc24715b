//! causticlab's techniques, one module per paper, plus the scene description and CPU references.

pub mod bvh;
pub mod caustic_map;
pub mod error;
pub mod image_io;
pub mod render;
pub mod scene;
pub mod reference;
pub mod compare;

pub use error::InputError;
