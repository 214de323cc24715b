//! [`Technique`]: the closed set of caustic techniques, and what each declares (its paper, the
//! device features it needs, its dumps, its photons). It reads only the papers' leaf settings
//! modules, so the scene description can name a technique without depending on the passes.

use super::settings::CausticSettings;
use super::shared::settings::Intersect;
use super::wyman_davis2006::settings::Space;
use super::{photon_trace, shah2007, trendall_stewart2000, value_enum, wyman2008, wyman_davis2006, wyman_nichols2009};
use vkcore::Feature;

value_enum::value_enum! {
    /// The caustic techniques (`caustics.technique`, `--technique`, a bench `[[technique]]`'s
    /// `technique`).
    pub enum Technique {
        /// No caustics: the eye render alone.
        None = "none",
        /// Shah et al.'s caustics mapping: a photon per light-space texel, rayGeo, point splats.
        Shah = "shah",
        /// Shah et al.'s original first pass: a photon per vertex of the specular meshes.
        ShahVertex = "shah-vertex",
        /// Wyman & Davis 2006: the photon buffer splatted as points into a light-space caustic map.
        WdPoints = "wd-points",
        /// Wyman & Davis 2006 Sec. 3.2, Fig. 4: the photons drawn as points into the eye's view.
        WdEyePoints = "wd-eye-points",
        /// Wyman & Davis 2006 Sec. 3.2.1: caustic quads between adjacent photons (--space eye|light).
        WdQuads = "wd-quads",
        /// Wyman & Davis 2006 Sec. 3.2.2: the 7x7 image-space gather (--space eye|light).
        WdGather = "wd-gather",
        /// Wyman 2008: hierarchical caustic maps over the photon buffer.
        Hcm = "hcm",
        /// Wyman & Nichols 2009: adaptive caustic maps, photons created by deferred shading from
        /// light-space geometry buffers while traversing a virtual photon hierarchy.
        Adaptive = "adaptive",
        /// Trendall & Stewart 2000: pool caustics as three convolutions (pool scenes only).
        PoolConvolution = "pool-convolution",
        /// Beyond the papers: photons traced exactly through a BVH of the scene by a compute
        /// shader, splatted into the caustic map.
        PhotonTrace = "photon-trace",
    }
}

impl Technique {
    /// The paper (and its sections) the technique reproduces.
    pub fn paper(self) -> &'static str {
        match self {
            Technique::None => "Wyman 2005 image-space refraction (no caustics)",
            Technique::Shah | Technique::ShahVertex => shah2007::settings::PAPER,
            Technique::WdPoints | Technique::WdEyePoints | Technique::WdQuads | Technique::WdGather => {
                wyman_davis2006::settings::PAPER
            }
            Technique::Hcm => wyman2008::settings::PAPER,
            Technique::Adaptive => wyman_nichols2009::settings::PAPER,
            Technique::PoolConvolution => trendall_stewart2000::settings::PAPER,
            Technique::PhotonTrace => photon_trace::settings::PAPER,
        }
    }

    /// Whether the technique renders caustics at all.
    pub fn has_caustics(self) -> bool {
        self != Technique::None
    }

    /// Whether its photons are the texels of a light-space photon buffer (rendered in the
    /// `photon_view`), as opposed to the specular meshes' vertices, photons created adaptively
    /// from geometry buffers (`adaptive`) or no photons at all.
    pub fn has_photon_buffer(self) -> bool {
        match self {
            Technique::Shah
            | Technique::WdPoints
            | Technique::WdEyePoints
            | Technique::WdQuads
            | Technique::WdGather
            | Technique::Hcm => true,
            Technique::PhotonTrace
            | Technique::None
            | Technique::ShahVertex
            | Technique::Adaptive
            | Technique::PoolConvolution => false,
        }
    }

    /// Whether its photons end in a photon buffer (position, direction, power per texel) that
    /// the `photon_buffer` dump reads: the light-space photon buffer's techniques and
    /// `photon-trace`, which traces its photons into the same layout.
    pub fn writes_photon_buffer(self) -> bool {
        self.has_photon_buffer() || self == Technique::PhotonTrace
    }

    /// Whether the technique renders the scene's meshes (every technique but `pool-convolution`,
    /// which renders pool scenes: a `[pool]` table instead of objects and lights).
    pub fn renders_meshes(self) -> bool {
        self != Technique::PoolConvolution
    }

    /// The ray/receiver intersection the technique's paper uses.
    pub fn default_intersect(self) -> Intersect {
        match self {
            Technique::WdPoints
            | Technique::WdEyePoints
            | Technique::WdQuads
            | Technique::WdGather
            | Technique::Hcm
            | Technique::Adaptive => Intersect::WdDepthSearch,
            // photon-trace intersects the scene's triangles exactly, never a light-space map.
            Technique::None
            | Technique::Shah
            | Technique::ShahVertex
            | Technique::PoolConvolution
            | Technique::PhotonTrace => Intersect::ShahIterative,
        }
    }

    /// Whether its photons come from the photon buffer (one per light-space texel), which the
    /// Wyman 2008 Table 1 copy path can copy into a vertex array.
    pub fn splats_the_photon_buffer(self) -> bool {
        matches!(self, Technique::Shah | Technique::WdPoints)
    }

    /// The device features the technique needs (its settings may need more: see
    /// `crate::render::check_device`).
    pub fn required_features(self) -> &'static [Feature] {
        match self {
            Technique::None => &[Feature::ShaderOutputLayer],
            // Splats are points wider than one pixel.
            Technique::Shah | Technique::WdPoints | Technique::Hcm | Technique::PhotonTrace => {
                &[Feature::ShaderOutputLayer, Feature::LargePoints]
            }
            Technique::ShahVertex => shah2007::settings::VERTEX_PHOTON_FEATURES,
            // The splats, and the geometry shader that routes each face to the front or back
            // geometry buffer (Wyman & Nichols 2009 Sec. 3.2).
            Technique::Adaptive => &[Feature::ShaderOutputLayer, Feature::LargePoints, Feature::GeometryShader],
            // Points of one pixel and triangles.
            Technique::WdEyePoints | Technique::WdQuads | Technique::WdGather => &[Feature::ShaderOutputLayer],
            // Fragment passes into RGBA8 or RGBA32F targets and compute passes: core Vulkan.
            Technique::PoolConvolution => &[],
        }
    }

    /// The intermediate buffers the technique can add to the eye render's (`--dump`), under any
    /// of its settings (see [`CausticSettings::dumps`] for those of one render).
    pub fn dumps(self) -> Vec<&'static crate::dump::Dump> {
        let mut all = CausticSettings { technique: self, ..Default::default() }.dumps();
        if self.has_photon_buffer() {
            // With photon_refraction `deferred`.
            all.push(&super::wyman_nichols2009::settings::PHOTON_GEOMETRY_BUFFERS);
        }
        if self == Technique::PhotonTrace {
            // With `differentials`; with `deposit = "screen-space"`.
            all.push(&super::shared::settings::PHOTON_FOOTPRINTS);
            all.push(&super::wyman_davis2006::settings::EYE_CAUSTIC);
        }
        if matches!(self, Technique::WdQuads | Technique::WdGather) {
            let light = CausticSettings { technique: self, space: Space::Light, ..Default::default() }.dumps();
            all.extend(light.into_iter().filter(|d| !all.contains(d)).collect::<Vec<_>>());
        }
        all
    }

    /// Photons the technique emits per light (for tables; hardware independent).
    pub fn photons_per_light(self, settings: &CausticSettings, specular_vertices: u32) -> u64 {
        match self {
            Technique::None | Technique::PoolConvolution => 0,
            Technique::ShahVertex => specular_vertices as u64,
            Technique::Shah
            | Technique::WdPoints
            | Technique::WdEyePoints
            | Technique::WdQuads
            | Technique::WdGather
            | Technique::Hcm
            | Technique::PhotonTrace
            // Adaptive: the photon grid's, those of the dense buffer it stands in for.
            | Technique::Adaptive => settings.photons as u64 * settings.photons as u64,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_technique_has_a_name_a_paper_and_features() {
        for t in Technique::ALL {
            assert_eq!(Technique::parse(t.name()), Some(*t));
            assert!(!t.paper().is_empty());
            assert_eq!(t.required_features().contains(&Feature::ShaderOutputLayer), t.renders_meshes(), "{t}");
            assert_eq!(t.has_caustics(), !t.dumps().is_empty(), "{t}");
        }
    }
}
