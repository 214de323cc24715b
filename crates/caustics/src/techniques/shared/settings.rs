//! The shared stages' settings and dumps, as the scene's `[caustics]`, the bench configs and the
//! command line name them (a leaf module: the scene description reads it).

use super::super::value_enum::value_enum;
use crate::dump::{layer, layer_when, Dump, Format, Space};
use vkcore::{CompactionPath, Feature};

/// The receivers' world positions from the light (Shah's positions texture).
pub static RECEIVER_POSITIONS: Dump = Dump::new(
    "receiver_positions",
    module_path!(),
    Space::LightLayers,
    Format::Image,
    &[layer("light<l>", &["X", "Y", "Z", "hit"])],
);
/// The refractors' back faces from the light.
pub static PHOTON_BACK_FACES: Dump = Dump::new(
    "photon_back_faces",
    module_path!(),
    Space::LightInTurn,
    Format::Image,
    &[layer("light<l>", &["NX", "NY", "NZ", "distance"])],
);
/// Where each photon lands, its direction and power.
pub static PHOTON_BUFFER: Dump = Dump::new(
    "photon_buffer",
    module_path!(),
    Space::LightInTurn,
    Format::Image,
    &[
        layer("light<l>.position", &["X", "Y", "Z", "valid"]),
        layer("light<l>.direction", &["X", "Y", "Z", "W"]),
        layer("light<l>.power", &["R", "G", "B"]),
    ],
);
/// `photon-trace --differentials`: each photon's footprint on the surface it landed on, the
/// derivatives of its position with respect to the emission square's two coordinates times the
/// stratum's side (world units): the parallelogram its power covers.
pub static PHOTON_FOOTPRINTS: Dump = Dump::new(
    "photon_footprints",
    module_path!(),
    Space::LightInTurn,
    Format::Image,
    &[layer("light<l>.u", &["X", "Y", "Z"]), layer("light<l>.v", &["X", "Y", "Z"])],
);
/// The caustic map the photons are splatted into.
pub static CAUSTIC_MAP: Dump = Dump::new(
    "caustic_map",
    module_path!(),
    Space::LightLayers,
    Format::Image,
    &[
        layer_when("light<l>", CAUSTIC_MAP_CHANNELS, "with one level"),
        layer_when("light<l>_level<i>", CAUSTIC_MAP_CHANNELS, "with `--splat varying-multires` or `interpolated`"),
    ],
);
const CAUSTIC_MAP_CHANNELS: &[&str] = &["R", "G", "B", "photons"];
/// The buffers every light-space caustic technique has.
pub static DUMPS: &[&Dump] = &[&RECEIVER_POSITIONS, &PHOTON_BACK_FACES, &PHOTON_BUFFER, &CAUSTIC_MAP];

value_enum! {
    /// The splat kernel (`caustics.splat_kernel`, `--splat-kernel`).
    pub enum SplatKernel {
        /// A Gaussian falling to its tail at the splat radius (Shah et al., Wyman & Davis 2006).
        Gaussian = "gaussian",
        /// Constant over the splat's disc.
        Box = "box",
    }
}

/// Features the compute splat (`splat_path = "compute"`) needs: float atomics in
/// shared/splat.comp.
pub const COMPUTE_SPLAT_FEATURES: &[Feature] = &[Feature::BufferFloat32AtomicAdd];

value_enum! {
    /// How photons are splatted into the caustic map (`caustics.splat_path`, `--splat-path`).
    pub enum SplatPath {
        /// Points drawn by the graphics pipeline with additive blending (the papers').
        Raster = "raster",
        /// A compute shader adding each splat with float atomics (`shared/splat.comp`).
        Compute = "compute",
    }
}

value_enum! {
    /// Where a refracted photon meets the receivers (`caustics.intersect`, `--intersect`).
    pub enum Intersect {
        /// Shah et al.'s iterative image-space estimate, rayGeo (`shah2007/ray_geo.glsl`).
        ShahIterative = "shah-iterative",
        /// Wyman & Davis 2006: a march through the light's depth, refined by bisection
        /// (`wyman_davis2006/depth_search.glsl`).
        WdDepthSearch = "wd-depth-search",
    }
}

value_enum! {
    /// The light's view of the specular objects that the photon buffer is rendered in
    /// (`caustics.photon_view`, `--photon-view`).
    pub enum PhotonView {
        /// A frustum fitted to the specular objects' bounding sphere: most texels are photons.
        Fitted = "fitted",
        /// A square frustum of `photon_fov` degrees about the light's direction (a spot's axis; a
        /// point light's direction to the specular objects): Wyman & Davis 2006 Table 1 emits
        /// "in a 90 degree field-of-view", and Wyman 2008 Sec. 3.1 does not fit the view to the
        /// object ("tight bounds are not desirable"), so most texels miss it.
        FixedFov = "fixed-fov",
        /// The face of the light's cube shadow map (90 degrees, axis-aligned) that the direction
        /// to the specular objects passes through; parts of an object in other faces get no photons.
        ShadowMap = "shadow-map",
    }
}

value_enum! {
    /// How a compacted traversal runs (`caustics.path`, `--path`): Wyman 2008 Sec. 3.1's
    /// hierarchy and Wyman & Nichols 2009's adaptive photon hierarchy both step through
    /// levels, keeping only the nodes that go on.
    pub enum TraversalPath {
        /// A geometry shader per level writes transform-feedback buffers (the papers' path).
        Xfb = "xfb",
        /// A compute kernel per level appends with an atomic counter.
        Compute = "compute",
    }
}

impl TraversalPath {
    /// The stream-compaction path of `vkcore` that implements it.
    pub fn compaction(self) -> CompactionPath {
        match self {
            TraversalPath::Xfb => CompactionPath::TransformFeedback,
            TraversalPath::Compute => CompactionPath::Compute,
        }
    }

    /// The device features the path needs.
    pub fn features(self) -> &'static [Feature] {
        match self {
            TraversalPath::Xfb => {
                &[Feature::GeometryShader, Feature::TransformFeedback, Feature::TransformFeedbackDraw]
            }
            TraversalPath::Compute => &[],
        }
    }
}
