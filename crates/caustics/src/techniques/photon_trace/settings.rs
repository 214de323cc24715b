//! What the GPU photon tracer declares (a leaf module: the technique enum reads it).

/// The technique's source, as tables and `--help` cite it.
pub const PAPER: &str = "beyond the papers: exact photon tracing through a BVH (compute)";

/// Its light-space buffers: the receiver positions the caustic-map lookup tests against, the
/// traced photons (the photon buffer's layout) and the caustic map they are splatted into.
pub const DUMPS: &[&str] = &["receiver_positions", "photon_buffer", "caustic_map"];

/// The most specular interactions `max_bounces` may allow.
pub const MAX_BOUNCES: u32 = 64;

/// The deepest BVH the shader's traversal stack (`BVH_STACK` in `photon_trace/bvh.glsl`) holds.
pub const MAX_BVH_DEPTH: u32 = 60;
