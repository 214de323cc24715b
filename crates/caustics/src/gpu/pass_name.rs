//! Every pass's name, built in one place: a [`Stage`] (`photon_buffer`, `hierarchy.traverse`),
//! then, as the pass has them, its view, level, layer or refractor, its batch and its light:
//! `hierarchy.traverse.level3.light0`, `adaptive.counts.level2.batch1.light0`,
//! `wd.gather.eye.light1`. The timings (`timings.json`, the bench's JSON) carry these names, and
//! bench configs select passes by glob over them (`passes = ["hierarchy.*", "splat.*"]`); a
//! test (`crates/bench/tests/pass_names.rs`) checks that every pattern of every shipped config
//! matches a name built here.

use std::fmt;

macro_rules! stages {
    ($($(#[$doc:meta])* $variant:ident => $name:literal,)*) => {
        /// What a pass does, the first part of its name.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum Stage {
            $($(#[$doc])* $variant,)*
        }

        impl Stage {
            /// Every stage, in the order of a frame.
            pub const ALL: &'static [Stage] = &[$(Stage::$variant,)*];

            /// The stage's part of the name.
            pub fn name(self) -> &'static str {
                match self {
                    $(Stage::$variant => $name,)*
                }
            }
        }
    };
}

stages! {
    /// Writing the frame's uniforms.
    Uniforms => "uniforms",
    /// Uploading the meshes' instance data.
    UploadMeshes => "upload.meshes",
    /// Clearing the caustic maps.
    CausticsClear => "caustics.clear",
    /// The diffuse surfaces from the light: where photons land (Shah step 1).
    ReceiverPositions => "receiver_positions",
    /// The refractors' back faces from the light (Wyman 2005's exit estimate).
    PhotonBackFaces => "photon_back_faces",
    /// The photon buffer (Wyman & Davis 2006 Sec. 3.1).
    PhotonBuffer => "photon_buffer",
    /// The photon buffer made 16-bit (Wyman 2008 Table 2's 16-bit sources).
    PhotonBufferTo16bit => "photon_buffer.to_16bit",
    /// The photon buffer copied into vertex arrays (Wyman 2008 Table 2).
    PhotonCopy => "photon_copy",
    /// Shah et al.'s photons per vertex, the buffer cleared first.
    VertexPhotonsClear => "vertex_photons.clear",
    VertexPhotons => "vertex_photons",
    /// `photon-trace`: its direct deposit into the receiver map cleared before the frame's first
    /// light, then photons traced through the scene's BVH into the photon buffer; with
    /// `progressive`, after every light's deposit, the running means of the caustic map (and of
    /// the receiver-map binning: `.flux`).
    PhotonTraceClear => "photon_trace.clear",
    PhotonTrace => "photon_trace",
    PhotonTraceAccumulate => "photon_trace.accumulate",
    /// Deferred caustic maps (Wyman & Nichols 2009 Fig. 10): the light-space geometry buffers,
    /// then the full-screen pass writing the photon buffer.
    DeferredPhotonsGeometry => "deferred_photons.geometry",
    DeferredPhotons => "deferred_photons",
    /// The photon hierarchy (Wyman 2008 Sec. 3.1): built, its counters reset, traversed level by
    /// level (finalized on the compute path), its list sizes counted.
    HierarchyBuild => "hierarchy.build",
    HierarchyReset => "hierarchy.reset",
    HierarchyTraverse => "hierarchy.traverse",
    HierarchyFinalize => "hierarchy.finalize",
    HierarchyCounts => "hierarchy.counts",
    /// Adaptive caustic maps (Wyman & Nichols 2009): the light-space geometry buffers and their
    /// coverage pyramid, then the traversal's counters, kernels and counts.
    AdaptiveGeometry => "adaptive.geometry",
    AdaptiveCoverage => "adaptive.coverage",
    AdaptiveReset => "adaptive.reset",
    AdaptiveSelect => "adaptive.select",
    AdaptiveTraverse => "adaptive.traverse",
    AdaptiveFinalize => "adaptive.finalize",
    AdaptiveSubdivide => "adaptive.subdivide",
    AdaptiveEmit => "adaptive.emit",
    AdaptiveHits => "adaptive.hits",
    AdaptiveConverged => "adaptive.converged",
    AdaptiveRefine => "adaptive.refine",
    AdaptiveFinalizePhotons => "adaptive.finalize.photons",
    AdaptiveCounts => "adaptive.counts",
    /// Each splat's footprint, for the `splats` dump (Wyman 2008 Sec. 3.3).
    SplatFootprints => "splat_footprints",
    /// The splat into the caustic map; the compute splat's clear, indirect arguments and resolve.
    Splat => "splat",
    SplatClear => "splat.clear",
    SplatArguments => "splat.arguments",
    SplatResolve => "splat.resolve",
    /// Wyman & Davis 2006's image-space caustics: photons as points, gathered, or quads, into a
    /// view (`eye`, `receiver`) or the light-space caustic map (`light_space`); the shading.
    WdPhotons => "wd.photons",
    WdGather => "wd.gather",
    WdQuads => "wd.quads",
    WdShade => "wd.shade",
    WdReceiverView => "wd.receiver_view",
    /// Screen-space photon mapping (Kim 2019) in the eye-space views: each pixel's photons
    /// divided by their kernel's edge-aware support, then the edge-aware gather.
    ScreenSpaceNormalize => "screen_space.normalize",
    ScreenSpaceFilter => "screen_space.filter",
    /// The eye render: shadow maps, background, refraction (forward or deferred, Wyman & Nichols
    /// 2009 Sec. 3.1), composite, the receiver map.
    ShadowMap => "shadow_map",
    Background => "background",
    RefractorBackFaces => "refractor_back_faces",
    RefractorFrontFaces => "refractor_front_faces",
    RefractorGeometry => "refractor_geometry",
    DeferredRefraction => "deferred_refraction",
    Composite => "composite",
    ReceiverMap => "receiver_map",
    /// Trendall & Stewart 2000: uploads, the height field, passes 1-6, the receiver, the view.
    PoolUpload => "pool.upload",
    PoolUniforms => "pool.uniforms",
    PoolHeightField => "pool.height_field",
    PoolPass1Normals => "pool.pass1_normals",
    PoolPass2GammaN => "pool.pass2_gamma_n",
    PoolPass3Transmitted => "pool.pass3_transmitted",
    PoolPass4Direction => "pool.pass4_direction",
    PoolPass5Integrand => "pool.pass5_integrand",
    PoolPass6Convolution => "pool.pass6_convolution",
    PoolReceiver => "pool.receiver",
    PoolView => "pool.view",
}

/// Where a pass sits in a traversal split into batches (Wyman & Nichols 2009 Sec. 4.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BatchPart {
    /// No batches: nothing in the name.
    Whole,
    /// The breadth-first part above the batches: `.breadth`.
    Breadth,
    /// Batch b: `.batch<b>`.
    Batch(u32),
}

/// A pass's name: its stage and the parts that follow (see the module's documentation).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PassName(String);

impl Stage {
    /// The stage a pass's name starts with, the longest (`splat.clear.light0` is
    /// `splat.clear`, not `splat`); None for a name built elsewhere.
    pub fn of_pass(pass: &str) -> Option<Stage> {
        Stage::ALL
            .iter()
            .copied()
            .filter(|s| pass == s.name() || pass.strip_prefix(s.name()).is_some_and(|rest| rest.starts_with('.')))
            .max_by_key(|s| s.name().len())
    }

    /// The stage alone, for a pass done once per frame.
    pub fn pass(self) -> PassName {
        PassName(self.name().to_string())
    }

    /// `<stage>.light<l>`.
    pub fn light(self, l: u32) -> PassName {
        self.pass().light(l)
    }
}

impl PassName {
    /// `.<view>`: the view an image-space pass renders (`eye`, `receiver`, `light_space`).
    pub fn view(self, view: &str) -> PassName {
        PassName(format!("{}.{view}", self.0))
    }

    /// `.level<k>`: a hierarchy's or a pyramid's level.
    pub fn level(self, k: u32) -> PassName {
        PassName(format!("{}.level{k}", self.0))
    }

    /// `.layer<k>`: a refractor layer of deferred refraction, back to front.
    pub fn layer(self, k: usize) -> PassName {
        PassName(format!("{}.layer{k}", self.0))
    }

    /// `.refractor<k>`: one specular object's own buffers.
    pub fn refractor(self, k: usize) -> PassName {
        PassName(format!("{}.refractor{k}", self.0))
    }

    /// `.batch<b>` or `.breadth` where the traversal is split into batches.
    pub fn batch(self, part: BatchPart) -> PassName {
        match part {
            BatchPart::Whole => self,
            BatchPart::Breadth => PassName(format!("{}.breadth", self.0)),
            BatchPart::Batch(b) => PassName(format!("{}.batch{b}", self.0)),
        }
    }

    /// `.light<l>`, last.
    pub fn light(self, l: u32) -> PassName {
        PassName(format!("{}.light{l}", self.0))
    }

    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl std::ops::Deref for PassName {
    type Target = str;
    fn deref(&self) -> &str {
        &self.0
    }
}

impl fmt::Display for PassName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_the_stage_then_its_parts_in_order() {
        let n = Stage::AdaptiveCounts.pass().level(2).batch(BatchPart::Batch(1)).light(0);
        assert_eq!(n.as_str(), "adaptive.counts.level2.batch1.light0");
        assert_eq!(Stage::Splat.pass().batch(BatchPart::Whole).light(3).as_str(), "splat.light3");
        assert_eq!(Stage::Splat.pass().batch(BatchPart::Breadth).light(0).as_str(), "splat.breadth.light0");
        assert_eq!(Stage::WdGather.pass().view("eye").light(1).as_str(), "wd.gather.eye.light1");
        assert_eq!(
            Stage::AdaptiveGeometry.pass().refractor(1).light(0).as_str(),
            "adaptive.geometry.refractor1.light0"
        );
        assert_eq!(Stage::DeferredRefraction.pass().layer(2).as_str(), "deferred_refraction.layer2");
    }

    #[test]
    fn a_pass_name_belongs_to_the_longest_stage_it_starts_with() {
        assert_eq!(Stage::of_pass("splat.clear.light0"), Some(Stage::SplatClear));
        assert_eq!(Stage::of_pass("splat.light0"), Some(Stage::Splat));
        assert_eq!(Stage::of_pass("background"), Some(Stage::Background));
        assert_eq!(Stage::of_pass("adaptive.finalize.photons.batch1.light0"), Some(Stage::AdaptiveFinalizePhotons));
        assert_eq!(Stage::of_pass("splats.light0"), None);
        assert_eq!(Stage::of_pass("backgrounds"), None);
    }

    #[test]
    fn every_stage_has_its_own_name() {
        let mut names: Vec<&str> = Stage::ALL.iter().map(|s| s.name()).collect();
        names.sort();
        let n = names.len();
        names.dedup();
        assert_eq!(names.len(), n, "two stages share a name");
    }
}
