//! What the GPU photon tracer declares (a leaf module: the technique enum reads it).

use super::super::settings::{Bad, CausticSettings};
use super::super::shared::settings as shared;
use super::super::value_enum::value_enum;
use crate::dump::Dump;
use vkcore::Feature;

/// The technique's source, as tables and `--help` cite it.
pub const PAPER: &str = "beyond the papers: exact photon tracing through a BVH (compute)";

/// Its light-space buffers: the receiver positions the caustic-map lookup tests against, the
/// traced photons (the photon buffer's layout) and the caustic map they are splatted into.
pub static DUMPS: &[&Dump] = &[&shared::RECEIVER_POSITIONS, &shared::PHOTON_BUFFER, &shared::CAUSTIC_MAP];

/// Progressive accumulation's default alpha (`progressive_alpha`): Knaus & Zwicker 2011's for
/// surfaces (Sec. 4.3), the error's fastest fall, N^-2/3 (`super::progressive`).
pub const DEFAULT_ALPHA: f32 = 2.0 / 3.0;

/// The most specular interactions `max_bounces` may allow.
pub const MAX_BOUNCES: u32 = 64;

/// The deepest BVH the shader's traversal stack (`BVH_STACK` in `photon_trace/bvh.glsl`) holds.
pub const MAX_BVH_DEPTH: u32 = 60;

/// What `deposit = "receiver-map"` needs: float atomic adds into the receiver map's buffer.
pub const RECEIVER_DEPOSIT_FEATURES: &[Feature] = &[Feature::BufferFloat32AtomicAdd];

value_enum! {
    /// Where the traced photons' light reaches the receiver map (`caustics.deposit`, `--deposit`).
    pub enum Deposit {
        /// Through the caustic map, as every technique's: the photons splatted, the receiver map
        /// looked up in it (`common/caustic_lookup.glsl`).
        CausticMap = "caustic-map",
        /// Also straight into the receiver map: each photon that lands on the receiver rectangle
        /// adds its power to its texel, as the CPU reference bins it; the receiver map's caustic
        /// term is that power over the texel's area (the final image still reads the caustic map).
        ReceiverMap = "receiver-map",
        /// Into the eye's view instead of a caustic map: screen-space photon mapping (Kim 2019),
        /// each photon drawn into the pixel that sees where it landed, then an edge-aware filter
        /// on the eye's geometry buffer (`techniques::shared::screen_space`); the receiver map
        /// from the same filter in the orthographic receiver view, as `wd-eye-points`'.
        ScreenSpace = "screen-space",
    }
}

/// What `trace = "ray-query"` needs: acceleration structures and ray queries.
pub const RAY_QUERY_FEATURES: &[Feature] = &[Feature::AccelerationStructure, Feature::RayQuery];

value_enum! {
    /// How the tracer finds the surface a photon meets next (`caustics.trace`, `--trace`).
    pub enum Trace {
        /// Its own traversal of the CPU reference's BVH in the compute shader
        /// (`photon_trace/bvh.glsl`): every Vulkan device.
        Compute = "compute",
        /// `rayQueryEXT` against the Vulkan acceleration structures (GL_EXT_ray_query: a BLAS
        /// per object, one TLAS), the driver's traversal (ray-tracing hardware where the device
        /// has it); needs VK_KHR_acceleration_structure and VK_KHR_ray_query.
        RayQuery = "ray-query",
    }
}

value_enum! {
    /// How `trace = "ray-query"`'s acceleration structures follow an object that moves
    /// (`caustics.moving_objects`, `--moving-objects`).
    pub enum MovingObjects {
        /// An object moved rigidly since its bottom level was built (every vertex and normal
        /// where one rotation and translation put them) keeps that bottom level and its instance
        /// in the top level gets the motion as its transform; any other motion rebuilds its
        /// bottom level. The top level is rebuilt on every pose that moves an object.
        Transform = "transform",
        /// Every moved object's bottom level is rebuilt from its moved vertices (what a deforming
        /// mesh costs), its instance's transform the identity.
        Rebuild = "rebuild",
        /// Every object's bottom level is built updatable (not compacted) and, when the object
        /// moves, refitted in place to its moved vertices: the first build's tree with its boxes
        /// grown to them, the cheap update of a deforming mesh.
        Refit = "refit",
    }
}

/// What `s`'s `trace` and `deposit` need of the device, each with what needs it.
pub fn required_features(s: &CausticSettings) -> Vec<(&'static str, &'static [Feature])> {
    let mut needs = vec![];
    if s.trace == Trace::RayQuery {
        needs.push(("trace `ray-query` (technique photon-trace)", RAY_QUERY_FEATURES));
    }
    if s.deposit == Deposit::ReceiverMap {
        needs.push(("deposit `receiver-map` (float atomics in photon_trace/trace.comp)", RECEIVER_DEPOSIT_FEATURES));
    }
    if s.differentials {
        needs
            .push(("differentials (float atomics in photon_trace/differential_splat.comp)", RECEIVER_DEPOSIT_FEATURES));
    }
    needs
}

/// The range check of technique `photon-trace`'s own key (`CausticSettings::validate` calls it).
pub fn validate_ranges(s: &CausticSettings, bad: Bad) -> anyhow::Result<()> {
    if !(1..=MAX_BOUNCES).contains(&s.max_bounces) {
        bad("max_bounces", format!("must be between 1 and {MAX_BOUNCES}, got {}", s.max_bounces))?;
    }
    if s.moving_objects != MovingObjects::Transform && s.trace != Trace::RayQuery {
        bad(
            "moving_objects",
            format!(
                "`{}` is how trace = \"ray-query\"'s acceleration structures follow a moving object; trace `{}` \
                 builds its BVH once and refuses moving objects",
                s.moving_objects, s.trace
            ),
        )?;
    }
    // The keys that shape the fixed splat, each with whether it is set (not its default).
    let defaults = CausticSettings::default();
    let fixed_splat = [
        ("splat_radius", s.splat_radius != defaults.splat_radius),
        ("splat_kernel", s.splat_kernel != defaults.splat_kernel),
    ];
    let first_set = |keys: &[(&'static str, bool)]| keys.iter().find(|(_, set)| *set).map(|(key, _)| *key);
    if s.deposit == Deposit::ScreenSpace {
        let [radius, kernel] = fixed_splat;
        let caustic_map_keys = [
            ("progressive", s.progressive),
            ("differentials", s.differentials),
            radius,
            kernel,
            ("splat_path", s.splat_path != defaults.splat_path),
        ];
        if let Some(key) = first_set(&caustic_map_keys) {
            bad(
                key,
                "shapes the caustic map, and deposit = \"screen-space\" deposits the photons into the eye's view \
                 instead: drop the key or choose another deposit"
                    .into(),
            )?;
        }
    }
    if s.differentials && s.progressive {
        bad(
            "differentials",
            "photon differentials size each photon's splat by its footprint, which progressive accumulation's \
             shrinking radius does not reach: set one of differentials and progressive"
                .into(),
        )?;
    }
    if let Some(key) = first_set(&fixed_splat).filter(|_| s.differentials) {
        bad(
            key,
            "sizes the fixed splat; photon differentials (differentials = true) splat each photon as the Gaussian its \
             footprint spans"
                .to_string(),
        )?;
    }
    if !(s.progressive_alpha > 0.0 && s.progressive_alpha <= 1.0) {
        bad(
            "progressive_alpha",
            format!("must be in (0, 1] (Knaus & Zwicker 2011's alpha), got {}", s.progressive_alpha),
        )?;
    }
    if !s.progressive && (s.progressive_alpha - DEFAULT_ALPHA).abs() > 1e-4 {
        bad("progressive_alpha", "is the radius rule of progressive accumulation; set progressive = true".into())?;
    }
    Ok(())
}
