//! The settings only `hcm` has (Wyman 2008 Sec. 3.1-3.3), as the scene's `[caustics]`, the
//! bench configs and the command line name them, and the technique's dumps (a leaf module: the
//! scene description reads it).

/// Layers of the multi-resolution caustic map (Wyman 2008 Sec. 3.3, Eq. 3): a splat of
/// diameter D goes to layer trunc(log2(max(1, D/5))), the last layer taking the rest
/// (`MULTIRES_LEVELS` in `shaders_glsl/common/caustics.glsl`).
pub const MULTIRES_LEVELS: u32 = 4;

use super::super::technique::Technique;
use super::super::value_enum::value_enum;
use crate::dump::{layer, Dump, Format, Space};

/// The paper, as tables and `--help` cite it.
pub const PAPER: &str = "Wyman 2008, hierarchical caustic maps";

/// The photon hierarchy's levels (Sec. 3.1).
pub static HIERARCHY: Dump = Dump::new(
    "hierarchy",
    module_path!(),
    Space::LightInTurn,
    Format::Image,
    &[
        layer("light<l>.level<k>.power", &["R", "G", "B", "count"]),
        layer("light<l>.level<k>.position", &["X", "Y", "Z"]),
        layer("light<l>.level<k>.texels", &["min_x", "min_y", "max_x", "max_y"]),
    ],
);
/// The traversal's lists, level by level.
pub static HIERARCHY_LISTS: Dump = Dump::new(
    "hierarchy_lists",
    module_path!(),
    Space::LightInTurn,
    Format::Records,
    &[layer("light<l>.list<k>", &LIST_CHANNELS)],
);
/// A traversal list's entry in `hierarchy_lists`: a node's x, y and level, whether it is a
/// finished cluster (`final`), and `valid` for an entry (the rest is padding).
pub const LIST_CHANNELS: [&str; 5] = ["x", "y", "level", "final", "valid"];
/// Each splat of the final list as drawn (Sec. 3.3).
pub static SPLATS: Dump =
    Dump::new("splats", module_path!(), Space::LightInTurn, Format::Records, &[layer("light<l>", &SPLAT_CHANNELS)]);
/// A splat as drawn, in `splats`: centre and radius in base caustic-map texels, the layer, the
/// power, the photon count, and whether it was drawn.
pub const SPLAT_CHANNELS: [&str; 9] = ["x", "y", "radius", "layer", "R", "G", "B", "photons", "splatted"];
/// The buffers only `hcm` has.
pub static DUMPS: &[&Dump] = &[&HIERARCHY, &HIERARCHY_LISTS, &SPLATS];

value_enum! {
    /// Converging-photon clustering (Sec. 3.2; `caustics.cluster`, `--cluster`).
    pub enum Cluster {
        /// Never: every valid photon is splatted.
        None = "none",
        /// Convergence tested only at the last level above the photon buffer.
        Last = "last",
        /// Convergence tested at every level.
        All = "all",
    }
}

impl Cluster {
    /// Whether the traversal step at hierarchy level `level` tests for convergence.
    pub fn tests(self, level: u32) -> bool {
        match self {
            Cluster::None => false,
            Cluster::Last => level == 1,
            Cluster::All => true,
        }
    }
}

value_enum! {
    /// Splat sizes (Sec. 3.3 and Fig. 7; `caustics.splat`, `--splat`).
    pub enum SplatMode {
        /// Every splat `splat_radius` wide.
        Fixed = "fixed",
        /// A radius from the photon's neighbours, in one caustic map (the paper's slow baseline).
        VaryingSingle = "varying-single",
        /// That radius, each splat in layer i = trunc(log2(max(1, D/5))) of a multi-resolution map.
        VaryingMultires = "varying-multires",
        /// shah, wd-points: a radius from a per-photon thin-lens model (Fig. 7's second column,
        /// Wyman & Dachsbacher's), in one caustic map.
        ThinLens = "thin-lens",
        /// hcm: every splat at four radii, `splat_radius` times 1, 2, 4 and 8, each into its own
        /// full-resolution layer; the lookup interpolates between the layers by the local photon
        /// density (Fig. 7's third column, Wyman & Dachsbacher's multiple splat sizes).
        Interpolated = "interpolated",
    }
}

/// Layers of the interpolated splats' map (`splat = interpolated`): radii `splat_radius` 2^i,
/// i < 4 (`INTERPOLATED_LEVELS` in `shaders_glsl/common/caustics.glsl`).
pub const INTERPOLATED_LEVELS: u32 = 4;

/// What a splat mode needs of the other settings, each with the reason an error gives
/// (`CausticSettings::validate_combination` checks them, `stages::check_photon_copy` the last).
#[derive(Debug, Clone, Copy, Default)]
pub struct SplatNeeds {
    /// Whose splats it sizes (when `technique` is not among [`SplatMode::sizes_splats_of`]'s).
    pub sizes: &'static str,
    /// The point splat: it has no compute splat (`splat_path = "compute"`).
    pub points: Option<&'static str>,
    /// `photon_view = "fitted"`.
    pub fitted_view: Option<&'static str>,
    /// `photon_refraction = "forward"`: the photon buffer's own light-space back faces.
    pub forward_photons: Option<&'static str>,
    /// The photon buffer itself, not its copy into a vertex array (`photon_copy`).
    pub own_points: Option<&'static str>,
}

impl SplatMode {
    /// Whether `technique`'s splats can be sized so: the hierarchy's and the adaptive photons'
    /// by their neighbours (Sec. 3.3), the photon buffer's points by the thin lens.
    pub fn sizes_splats_of(self, technique: Technique) -> bool {
        match self {
            SplatMode::Fixed => true,
            SplatMode::VaryingSingle | SplatMode::VaryingMultires => {
                matches!(technique, Technique::Hcm | Technique::Adaptive)
            }
            SplatMode::ThinLens => matches!(technique, Technique::Shah | Technique::WdPoints),
            SplatMode::Interpolated => technique == Technique::Hcm,
        }
    }

    /// What this mode needs of the other settings.
    pub fn needs(self) -> SplatNeeds {
        match self {
            SplatMode::Fixed => SplatNeeds::default(),
            SplatMode::VaryingSingle | SplatMode::VaryingMultires => {
                SplatNeeds { sizes: "sizes the splats of technique hcm or adaptive", ..SplatNeeds::default() }
            }
            SplatMode::ThinLens => SplatNeeds {
                sizes: "sizes the photon buffer's point splats (technique shah or wd-points)",
                points: Some("sizes point splats; it has no compute splat"),
                fitted_view: Some(
                    "its lens's axis is the fitted view's, from the light through the specular objects' centre",
                ),
                forward_photons: Some(
                    "its lens is the light-space back faces, which deferred photons keep in their geometry buffers",
                ),
                own_points: Some("sizes the photon buffer's own points, not a copy of them into a vertex array"),
            },
            SplatMode::Interpolated => SplatNeeds {
                sizes: "splats the hierarchy's final list at four radii (technique hcm)",
                points: Some("draws each of its four radii as point splats; it has no compute splat"),
                ..SplatNeeds::default()
            },
        }
    }

    /// The caustic uniforms' `splat.w` for `technique` (`common/caustics.glsl` SPLAT_*): 0 fixed,
    /// 1 varying in one map (by the neighbours or the thin lens), 2 varying in the
    /// multi-resolution map, 3 interpolated; fixed where the mode does not size `technique`'s
    /// splats.
    pub fn uniform(self, technique: Technique) -> f32 {
        match self {
            _ if !self.sizes_splats_of(technique) => 0.0,
            SplatMode::Fixed => 0.0,
            SplatMode::VaryingSingle | SplatMode::ThinLens => 1.0,
            SplatMode::VaryingMultires => 2.0,
            SplatMode::Interpolated => 3.0,
        }
    }

    /// The widest point a splat of this mode draws, in pixels, with `splat_radius` for fixed
    /// splats: 2 ceil(r) + 2 (`shared/splat_photon.glsl`). Varying splats reach r < 40 texels in
    /// one map (wider ones are dropped; thin-lens splats are kept under it) and r < 5 in their
    /// layer of the multi-resolution map. Interpolated splats draw `splat_radius` 2^3 at most.
    pub fn largest_point(self, splat_radius: f32) -> f32 {
        match self {
            SplatMode::Fixed => 2.0 * splat_radius.ceil() + 2.0,
            SplatMode::Interpolated => 2.0 * (splat_radius * (1 << (INTERPOLATED_LEVELS - 1)) as f32).ceil() + 2.0,
            SplatMode::VaryingSingle | SplatMode::ThinLens => 82.0,
            SplatMode::VaryingMultires => 12.0,
        }
    }
}

value_enum! {
    /// How varying splats find their radius from the neighbouring photons (Sec. 3.3;
    /// `caustics.varying_radius`, `--varying-radius`).
    pub enum VaryingRadius {
        /// The largest distance to the four adjacent photons (the paper's approximation).
        MaxDistance = "max-distance",
        /// Eq. 1-2: the quadrilaterals' area over the unoccluded beam's.
        BeamArea = "beam-area",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clustering_levels() {
        assert!(!Cluster::None.tests(1));
        assert!(Cluster::Last.tests(1) && !Cluster::Last.tests(2));
        assert!(Cluster::All.tests(1) && Cluster::All.tests(5));
    }

    #[test]
    fn names_round_trip() {
        for p in crate::techniques::shared::settings::TraversalPath::ALL {
            assert_eq!(crate::techniques::shared::settings::TraversalPath::parse(p.name()), Some(*p));
        }
        assert_eq!("varying-multires".parse::<SplatMode>(), Ok(SplatMode::VaryingMultires));
        assert!("lsat".parse::<Cluster>().unwrap_err().contains("none, last, all"));
    }
}
