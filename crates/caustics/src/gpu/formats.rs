//! Image formats of the render targets.

use vkcore::Format;

/// Colour targets and intermediate buffers: RGBA, 32-bit float.
pub const COLOR: Format = Format::R32G32B32A32_SFLOAT;
/// Distances (shadow maps).
pub const DISTANCE: Format = Format::R32_SFLOAT;
/// Depth buffers.
pub const DEPTH: Format = Format::D32_SFLOAT;
