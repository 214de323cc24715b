//! The settings of Wyman & Nichols 2009 as the scene's `[caustics]`, the bench configs and the
//! command line name them, and the buffers they add (a leaf module: the scene description
//! reads it): the eye's refraction (Sec. 3.1) and the adaptive caustic maps' metric and
//! geometry-buffer resolution (Sec. 3.2).

use super::super::settings::{Bad, CausticSettings};
use super::super::shared::settings::TraversalPath;
use super::super::technique::Technique;
use super::super::value_enum::value_enum;
use super::adaptive::batches;
use crate::dump::{layer, layer_when, Dump, Format, Space};
use vkcore::Feature;

/// The paper, as tables and `--help` cite it.
pub const PAPER: &str = "Wyman & Nichols 2009, adaptive caustic maps using deferred shading";

value_enum! {
    /// How the eye render refracts (`caustics.refraction`, `--refraction`): an eye-render
    /// setting, independent of the caustic technique.
    pub enum Refraction {
        /// Wyman 2005's image-space refraction: back faces, then the refraction in the front
        /// faces' fragment shader, then a composite (Wyman & Nichols 2009 Fig. 3, top).
        Forward = "forward",
        /// Wyman & Nichols 2009 Sec. 3.1: front and back faces in one pass (a geometry shader
        /// routes each face to its layer), then one full-screen refraction pass per refractor,
        /// back to front (Sec. 3.1.1).
        Deferred = "deferred",
    }
}

value_enum! {
    /// How a photon-buffer technique makes its dense photon buffer (`caustics.photon_refraction`,
    /// `--photon-refraction`): a caustics setting, independent of the eye's [`Refraction`].
    pub enum PhotonRefraction {
        /// The specular objects' front faces rasterized from the light, each fragment a photon
        /// refracted out through the back faces by Wyman 2005's estimate (Wyman & Davis 2006).
        Forward = "forward",
        /// Wyman & Nichols 2009's deferred caustic maps (Fig. 10): light-space geometry buffers
        /// of the specular objects (front and back faces in one pass), then one full-screen pass
        /// makes a photon per texel; with several specular objects, each photon through each in
        /// turn (Sec. 3.1.1, `deferred_photon_layers.glsl`).
        Deferred = "deferred",
    }
}

impl Refraction {
    /// The device features it needs beyond the baseline.
    pub fn required_features(self) -> &'static [Feature] {
        match self {
            Refraction::Forward => &[],
            // The geometry shader that routes each face to the front or back layer (gl_Layer).
            Refraction::Deferred => &[Feature::GeometryShader],
        }
    }
}

impl PhotonRefraction {
    /// The features the photon buffer made this way needs.
    pub fn required_features(self) -> &'static [Feature] {
        match self {
            PhotonRefraction::Forward => &[],
            // The light-space geometry buffers' pass routes each face to its layer (gl_Layer).
            PhotonRefraction::Deferred => &[Feature::GeometryShader],
        }
    }
}

/// The light-space geometry buffers deferred photons (Sec. 3.1.1, Fig. 10) are created from.
pub static PHOTON_GEOMETRY_BUFFERS: Dump = Dump::new(
    "photon_geometry_buffers",
    module_path!(),
    Space::LightInTurn,
    Format::Image,
    &[
        layer("light<l>.front.position", FRONT_POSITION),
        layer("light<l>.front.normal", FRONT_NORMAL),
        layer("light<l>.front.material", MATERIAL),
        layer("light<l>.back.position", BACK_POSITION),
        layer("light<l>.back.normal", BACK_NORMAL),
        layer_when("light<l>.refractor<k>.front.position", FRONT_POSITION, SEVERAL),
        layer_when("light<l>.refractor<k>.front.normal", FRONT_NORMAL, SEVERAL),
        layer_when("light<l>.refractor<k>.front.material", MATERIAL, SEVERAL),
        layer_when("light<l>.refractor<k>.back.position", BACK_POSITION, SEVERAL),
        layer_when("light<l>.refractor<k>.back.normal", BACK_NORMAL, SEVERAL),
    ],
);

/// The channels of the light-space geometry buffers' layers (Sec. 3.2, 3.1.1): the front
/// surface's position and Wyman 2005 thickness, normal and object index + 1, transmission or
/// mirror colour and mean index of refraction; the back surface's position, normal and distance.
pub const FRONT_POSITION: &[&str] = &["X", "Y", "Z", "thickness"];
pub const FRONT_NORMAL: &[&str] = &["NX", "NY", "NZ", "object"];
pub const MATERIAL: &[&str] = &["R", "G", "B", "ior"];
pub const BACK_POSITION: &[&str] = &["X", "Y", "Z", "distance"];
pub const BACK_NORMAL: &[&str] = &["NX", "NY", "NZ", "distance"];
const SEVERAL: &str = "with several specular objects";
/// The buffers only deferred photons have (`photon_refraction = "deferred"`).
pub static DEFERRED_PHOTONS_DUMPS: &[&Dump] = &[&PHOTON_GEOMETRY_BUFFERS];

/// The most batches a traversal may be asked for (`photon_batches`); one frame records fewer
/// (see `adaptive::batches::plan`).
pub const MAX_BATCHES: u32 = 256;

/// The light-space geometry buffers and their coverage pyramid (Sec. 3.2).
pub static ADAPTIVE_GEOMETRY: Dump = Dump::new(
    "adaptive_geometry",
    module_path!(),
    Space::LightInTurn,
    Format::Image,
    &[
        layer("light<l>.front.position", FRONT_POSITION),
        layer("light<l>.front.normal", FRONT_NORMAL),
        layer("light<l>.front.material", MATERIAL),
        layer("light<l>.back.position", BACK_POSITION),
        layer("light<l>.back.normal", BACK_NORMAL),
        layer("light<l>.coverage.level<m>", &["any", "all"]),
        layer_when("light<l>.refractor<k>.front.position", FRONT_POSITION, SEVERAL),
        layer_when("light<l>.refractor<k>.front.normal", FRONT_NORMAL, SEVERAL),
        layer_when("light<l>.refractor<k>.front.material", MATERIAL, SEVERAL),
        layer_when("light<l>.refractor<k>.back.position", BACK_POSITION, SEVERAL),
        layer_when("light<l>.refractor<k>.back.normal", BACK_NORMAL, SEVERAL),
    ],
);
/// The traversal's lists and its photons.
pub static ADAPTIVE_LISTS: Dump = Dump::new(
    "adaptive_lists",
    module_path!(),
    Space::LightInTurn,
    Format::Records,
    &[
        layer("light<l>.clusters<k>", &LIST_CHANNELS),
        layer_when("light<l>.photons", &LIST_CHANNELS, "unbatched"),
        layer_when("light<l>.breadth.photons", &LIST_CHANNELS, BATCHED),
        layer_when("light<l>.batch<b>.clusters<k>", &LIST_CHANNELS, BATCHED),
        layer_when("light<l>.batch<b>.photons", &LIST_CHANNELS, BATCHED),
    ],
);
const BATCHED: &str = "batched (`photon_memory_limit` or `photon_batches`)";
/// A record of the traversal's lists in `adaptive_lists`: a cell's x, y and level, where its
/// photon lands, its power, its splat footprint, and `valid` for a record (the rest is padding).
pub const LIST_CHANNELS: [&str; 11] = ["x", "y", "level", "X", "Y", "Z", "R", "G", "B", "footprint", "valid"];
/// The buffers only technique `adaptive` has.
pub static ADAPTIVE_DUMPS: &[&Dump] = &[&ADAPTIVE_GEOMETRY, &ADAPTIVE_LISTS];

/// Sec. 3.2: "We used a 64² grid for this coarse sampling": the photons per side of level 0.
pub const TOP_PHOTONS: u32 = 64;

/// The deepest level the packed cells address (x, y < 2^14: 16384² photons, the paper's
/// deepest traversal, Fig. 8).
pub const MAX_LEVEL: u32 = 8;

/// Sec. 4.2: "We begin checking for convergence once we reach the 512² subdivision level."
pub const CONVERGENCE_FROM_PHOTONS: u32 = 512;

/// Sec. 3.2: "sampling the refractor positions and normals at a quarter the final caustic map's
/// resolution provided a good speed-quality tradeoff".
pub const DEFAULT_GBUFFER_SCALE: f32 = 0.25;

value_enum! {
    /// When the adaptive traversal stops refining a cluster (Sec. 3.2.1-3.2.2;
    /// `caustics.metric`, `--metric`).
    pub enum Metric {
        /// Sec. 3.2.1: refine every cluster that touches the refractor down to the last level,
        /// where its photons are emitted (one kernel per traversal step).
        MaxTraversal = "max-traversal",
        /// Sec. 3.2.2: also emit a cluster whose four photons land in one caustic-map texel as one
        /// photon with their summed power, tested from the 512² level on (Sec. 4.2); the last
        /// level caps the traversal (three kernels per step on the xfb path, Sec. 4.1).
        MaxError = "max-error",
    }
}

/// The last level L of the adaptive traversal for `photons` per side: 64 × 2^L = photons, or
/// None when `photons` is no such size.
pub fn finest_level(photons: u32) -> Option<u32> {
    let ratio = photons / TOP_PHOTONS;
    (photons.is_multiple_of(TOP_PHOTONS) && ratio.is_power_of_two() && ratio.trailing_zeros() <= MAX_LEVEL)
        .then(|| ratio.trailing_zeros())
}

/// Whether the step at level `level` (photons on the (64 × 2^level)² grid) tests convergence
/// under `metric`.
pub fn tests_convergence(metric: Metric, level: u32) -> bool {
    metric == Metric::MaxError && (TOP_PHOTONS << level) >= CONVERGENCE_FROM_PHOTONS
}

/// The range checks of technique `adaptive`'s own keys (`CausticSettings::validate` calls it):
/// the geometry buffers' scale, the photon grid, its memory limit and batches.
pub fn validate_ranges(s: &CausticSettings, bad: Bad) -> anyhow::Result<()> {
    let most = s.most_photons();
    if !(s.gbuffer_scale > 0.0 && s.gbuffer_scale <= 4.0) {
        bad(
            "gbuffer_scale",
            format!(
                "must be a fraction of the caustic-map resolution in (0, 4] (the paper's 0.25), got {}",
                s.gbuffer_scale
            ),
        )?;
    }
    // Only adaptive caustic maps make geometry buffers at this side (`gbuffer_side`).
    if s.technique == Technique::Adaptive && !(16..=8192).contains(&s.gbuffer_side()) {
        bad(
            "gbuffer_scale",
            format!(
                "{} × caustic_map_resolution {} gives geometry buffers {} texels wide; they must be 16 to 8192",
                s.gbuffer_scale,
                s.caustic_map_resolution,
                s.gbuffer_side()
            ),
        )?;
    }
    if let Some(level) = s.max_level {
        let deepest = finest_level(most).unwrap_or(0);
        if level > deepest {
            bad("max_level", format!("must be between 0 and {deepest} (64² to {most}² photons), got {level}"))?;
        }
    }
    if s.photon_memory_limit > 1 << 20 {
        bad(
            "photon_memory_limit",
            format!("must be at most 1048576 MiB (0: no limit), got {}", s.photon_memory_limit),
        )?;
    }
    if !(1..=MAX_BATCHES).contains(&s.photon_batches) {
        bad("photon_batches", format!("must be between 1 and {} batches, got {}", MAX_BATCHES, s.photon_batches))?;
    }
    if s.technique == Technique::Adaptive {
        validate_adaptive(s, bad)?;
    }
    Ok(())
}

/// Technique `adaptive`'s photon grid: 64 × 2^L per side (Wyman & Nichols 2009 Sec. 3.2),
/// agreeing with `max_level` when it is set.
fn validate_adaptive(s: &CausticSettings, bad: Bad) -> anyhow::Result<()> {
    let Some(level) = finest_level(s.photons) else {
        return bad(
            "photons",
            format!(
                "technique `adaptive` refines a 64² grid of photons by halving its cells, so photons must be \
                 64 × 2^L (64, 128, 256, ..., 4096; up to 16384 with a photon_memory_limit), got {}",
                s.photons
            ),
        );
    };
    if s.photon_memory_limit > 0 || s.photon_batches > 1 {
        let xfb = s.path == TraversalPath::Xfb;
        let limit = (s.photon_memory_limit > 0).then(|| s.photon_memory_limit as u64 * 1024 * 1024);
        if let Err(e) = batches::plan(level, s.metric, xfb, limit, s.photon_batches, 1) {
            let key = if s.photon_memory_limit > 0 { "photon_memory_limit" } else { "photon_batches" };
            bad(key, e)?;
        }
    }
    match s.max_level {
        Some(max) if max != level => bad(
            "max_level",
            format!(
                "{max} means {}² photons, but photons is {} (level {level}); set one of them, or both to agree",
                TOP_PHOTONS << max.min(MAX_LEVEL),
                s.photons
            ),
        ),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_of_photon_grids() {
        assert_eq!(finest_level(64), Some(0));
        assert_eq!(finest_level(256), Some(2));
        assert_eq!(finest_level(16384), Some(8));
        for bad in [0, 32, 100, 192, 320, 32768] {
            assert_eq!(finest_level(bad), None, "{bad}");
        }
        assert!(!tests_convergence(Metric::MaxError, 2) && tests_convergence(Metric::MaxError, 3));
        assert!(!tests_convergence(Metric::MaxTraversal, 5));
    }
}
