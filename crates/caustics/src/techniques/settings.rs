//! `[caustics]`: which technique renders caustics and with what parameters. Every setting is
//! declared once, in the `caustic_settings!` table below, which makes from it:
//! - [`CausticSettings`], the settings in effect (with their defaults);
//! - [`CausticOverrides`], the same fields as options: the scene's `[caustics]` table, a bench
//!   config's `[[technique]]` entry and the `render` command's flags (clap) are all this type;
//! - [`CausticSettings::validate_combination`]: a setting that belongs to some techniques only
//!   (`only Hcm`) is refused, with its key, for the others.

use super::photon_trace::settings::{Deposit as PhotonDeposit, MovingObjects, Trace};
use super::shah2007::settings::{Lookup, Refractions};
use super::shared::settings::{Intersect, PhotonView, SplatKernel, SplatPath, TraversalPath};
use super::technique::Technique;
use super::trendall_stewart2000::settings::{Precision, DEFAULT_KERNEL};
use super::wyman2008::settings::{Cluster, SplatMode, VaryingRadius};
use super::wyman_davis2006::settings::{GatherLighting, QuadDraw, QuadLighting, Reflection, Space, TemporalFilter};
use super::wyman_nichols2009::settings::{self as wn2009, Metric, PhotonRefraction, Refraction};
use super::{photon_trace, shared, trendall_stewart2000, wyman2008, wyman_davis2006};
use crate::dump::Dump;
use serde::{Deserialize, Serialize};

/// How a range check reports a bad key: its name (without the `caustics.` prefix) and why.
pub type Bad<'a> = &'a dyn Fn(&str, String) -> anyhow::Result<()>;

macro_rules! caustic_settings {
    ($(
        $(#[doc = $doc:literal])*
        $field:ident: $ty:ty = $default:expr $(, only $($owner:ident)|+)?;
    )+) => {
        /// `[caustics]`: the settings in effect (see each field; `scenes/README.md`).
        #[derive(Debug, Clone, PartialEq, Serialize)]
        pub struct CausticSettings {
            $( $(#[doc = $doc])* pub $field: $ty, )+
        }

        impl Default for CausticSettings {
            fn default() -> Self {
                CausticSettings { $( $field: $default, )+ }
            }
        }

        /// Each `Some` replaces the setting of the same name (see [`CausticSettings`]). The
        /// scene's `[caustics]`, a bench `[[technique]]` and the `render` flags.
        #[derive(Debug, Clone, Default, Deserialize, Serialize, clap::Args)]
        #[serde(deny_unknown_fields)]
        #[command(next_help_heading = "Technique (overrides the scene's [caustics])")]
        pub struct CausticOverrides {
            $( $(#[doc = $doc])* #[arg(long, allow_negative_numbers = true)]
                #[serde(default, skip_serializing_if = "Option::is_none")]
                pub $field: Option<$ty>, )+
        }

        impl CausticOverrides {
            /// Writes every set override over `s` (not checked: see [`CausticSettings::validate`]).
            pub fn apply(&self, s: &mut CausticSettings) {
                $( if let Some(v) = &self.$field { s.$field = v.clone(); } )+
                self.apply_derived(s);
            }

            /// The keys that are set, in declaration order.
            pub fn keys_set(&self) -> Vec<&'static str> {
                let mut keys = vec![];
                $( if self.$field.is_some() { keys.push(stringify!($field)); } )+
                keys
            }
        }

        impl CausticSettings {
            /// Every setting that belongs to some techniques only, with them.
            pub const OWNED: &'static [(&'static str, &'static [Technique])] = &[
                $( $( (stringify!($field), &[$(Technique::$owner),+]), )? )+
            ];

            /// The settings that differ from their defaults but do not belong to `technique`.
            fn foreign_settings(&self) -> Vec<(&'static str, String)> {
                let d = CausticSettings::default();
                let mut out = vec![];
                $( $(
                    if self.$field != d.$field && ![$(Technique::$owner),+].contains(&self.technique) {
                        out.push((stringify!($field), shown(&self.$field)));
                    }
                )? )+
                out
            }
        }
    };
}

caustic_settings! {
    /// The caustic technique (default `none`).
    technique: Technique = Technique::None;
    /// Photon buffer resolution N (N x N photons per light), 64..=4096; default 512. For
    /// pool-convolution: the height field's side (and the receiver map's).
    photons: u32 = 512;
    /// Splat radius in caustic-map texels, (0, 32]; default 1.5.
    splat_radius: f32 = 1.5;
    /// The splat kernel; default gaussian.
    splat_kernel: SplatKernel = SplatKernel::Gaussian;
    /// Caustic map (and receiver positions) resolution, 16..=8192; default 1024.
    caustic_map_resolution: u32 = 1024;
    /// rayGeo iterations (Shah) or bisection refinements (Wyman & Davis), 1..=64; default 4.
    iterations: u32 = 4;
    /// shah, shah-vertex: refract into and out of the object (two, default) or once where the
    /// light meets it, as the caustics mapping tutorial does (one).
    refractions: Refractions = Refractions::Two, only Shah | ShahVertex;
    /// shah, shah-vertex: how the caustic map becomes light, physical (irradiance, the default)
    /// or the tutorial's `diffuse * pow(caustic, 1.3)` (tutorial).
    lookup: Lookup = Lookup::Physical, only Shah | ShahVertex;
    /// shah, shah-vertex: the caustics mapping tutorial as written, true or false (default):
    /// sets refractions = one, iterations = 1 and lookup = tutorial wherever the same table or
    /// command line leaves them unset; a contrary value of any of them is refused.
    faithful: bool = false, only Shah | ShahVertex;
    /// Fresnel transmittance at both interfaces (true/false); default true.
    fresnel: bool = true;
    /// Refinements of the photon's exit point against the light-space back faces, 0..=16; 0 is
    /// Wyman 2005's estimate alone (the papers); default 4.
    back_face_iterations: u32 = 4;
    /// The light's view the photon buffer is rendered in: fitted to the specular objects
    /// (default), a fixed field of view about the light's direction (the papers'), or the
    /// shadow map's face.
    photon_view: PhotonView = PhotonView::Fitted;
    /// Full field of view in degrees of `photon_view = "fixed-fov"`, [1, 160]; default 90
    /// (Wyman & Davis 2006 Table 1).
    photon_fov: f32 = 90.0;
    /// Ray/receiver intersection; unset: the technique's own (wd-depth-search for wd-points and
    /// hcm, shah-iterative otherwise).
    intersect: Option<Intersect> = None;
    /// hcm, adaptive: the traversal path (Wyman 2008 Sec. 3.1; Wyman & Nichols 2009 Sec. 4):
    /// transform feedback (the papers') or compute; default xfb.
    path: TraversalPath = TraversalPath::Xfb, only Hcm | Adaptive;
    /// hcm: converging-photon clustering (Wyman 2008 Sec. 3.2); default none.
    cluster: Cluster = Cluster::None, only Hcm;
    /// Splat sizes (Wyman 2008 Sec. 3.3 and Fig. 7; for adaptive, its photons' divergence into
    /// the multi-resolution map, Wyman & Nichols 2009 Sec. 3.2.2): each size says whose splats
    /// it sizes, and is refused for the others; default fixed.
    splat: SplatMode = SplatMode::Fixed;
    /// hcm with varying splats: the radius estimator (Wyman 2008 Sec. 3.3); default max-distance.
    varying_radius: VaryingRadius = VaryingRadius::MaxDistance, only Hcm;
    /// How photons are splatted: points (raster, the papers') or a compute shader with float
    /// atomics (compute); both give the same map. Default raster.
    splat_path: SplatPath = SplatPath::Raster;
    /// Vertices per instance of the instanced photon fetch (Wyman 2008 Sec. 4: 1024, 2048, 4096);
    /// a power of two, 64..=65536; default 1024.
    instance_vertices: u32 = 1024;
    /// wd-quads, wd-gather: render into the eye's view or a light-space caustic map (Wyman &
    /// Davis 2006 Sec. 3.2.1-3.2.2); default eye.
    space: Space = Space::Eye, only WdQuads | WdGather;
    /// wd-eye-points, wd-gather: average the photon counts of the previous three frames with the
    /// current frame's (Wyman & Davis 2006 Sec. 3.2.3): on or off; default off.
    temporal_filter: TemporalFilter = TemporalFilter::Off, only WdEyePoints | WdGather;
    /// wd-eye-points, wd-gather: the lighting of a pixel's photons, eq9 (each photon's own
    /// direction), eq10 (their average direction, the paper's) or eq11 (the light's direction);
    /// default eq10.
    gather_lighting: GatherLighting = GatherLighting::Eq10, only WdEyePoints | WdGather;
    /// wd-quads: Eq. 3 (the photons' stored directions) or Eq. 4 (the light's); default eq3.
    quad_lighting: QuadLighting = QuadLighting::Eq3, only WdQuads;
    /// wd-quads: every quad as its polygon whatever its size (polygons, the paper's) or with the
    /// quads under a pixel as points and slivers as lines carrying their power (exact); default
    /// exact.
    quad_draw: QuadDraw = QuadDraw::Exact, only WdQuads;
    /// Where mirrored photons land: depth-search (the ray/receiver intersection in effect) or
    /// plane (Wyman & Davis 2006 Sec. 4: one background plane); default depth-search.
    reflection: Reflection = Reflection::DepthSearch;
    /// The eye render's refraction, whatever the technique: forward (Wyman 2005, the default)
    /// or deferred (Wyman & Nichols 2009 Sec. 3.1, several refractors back to front).
    refraction: Refraction = Refraction::Forward;
    /// Photon-buffer techniques: how the dense photon buffer is made, forward (the specular
    /// objects' front faces rasterized from the light, each fragment a photon: Wyman & Davis
    /// 2006, the default) or deferred (Wyman & Nichols 2009's "deferred caustic maps", Fig. 10:
    /// light-space geometry buffers, then one full-screen pass; with several specular objects,
    /// photons through each in turn, Sec. 3.1.1); independent of the eye's `refraction`.
    photon_refraction: PhotonRefraction = PhotonRefraction::Forward, only Shah | WdPoints | WdEyePoints | WdQuads | WdGather | Hcm;
    /// adaptive: when the traversal stops refining (Wyman & Nichols 2009 Sec. 3.2.1-3.2.2):
    /// max-traversal or max-error; default max-traversal.
    metric: Metric = Metric::MaxTraversal, only Adaptive;
    /// adaptive: the traversal's last level L, 0..=8 (7 and 8, 8192² and 16384², only with a
    /// photon_memory_limit): photons on a (64 × 2^L)² grid, the
    /// "maximal traversal level" of both metrics. Unset: from `photons` (which must then be
    /// 64 × 2^L); set without `photons` in the same table or command line, it sets `photons`.
    max_level: Option<u32> = None, only Adaptive;
    /// adaptive: the light-space geometry buffers' resolution as a fraction of the caustic map's
    /// (Wyman & Nichols 2009 Sec. 3.2: 0.25, the default), (0, 4], 16..=8192 texels.
    gbuffer_scale: f32 = wn2009::DEFAULT_GBUFFER_SCALE, only Adaptive;
    /// adaptive: the photon storage allowed, MiB (Wyman & Nichols 2009 Sec. 4.3): the traversal
    /// goes breadth-first as deep as it fits, then splits the pending clusters into batches, each
    /// refined and splatted before the next; 0 (the default) is no limit. With a limit, photons
    /// may go up to 16384 (max_level 8).
    photon_memory_limit: u32 = 0, only Adaptive;
    /// adaptive: the least number of batches the traversal is split into (Wyman & Nichols 2009
    /// Sec. 4.3, Fig. 8's overhead of batches), 1..=256; default 1 (batches only where the
    /// photon_memory_limit needs them). More are used where the limit needs more.
    photon_batches: u32 = 1, only Adaptive;
    /// photon-trace: the seed of its photons' jitter and Russian roulette (the same seed, the
    /// same photons); default 1.
    seed: u32 = 1, only PhotonTrace;
    /// photon-trace: the most specular interactions a photon may have before it is dropped,
    /// 1..=64; default 8 (the CPU reference's).
    max_bounces: u32 = 8, only PhotonTrace;
    /// photon-trace with Fresnel: trace the light a refractive object reflects off its outside
    /// (true, the physics, default) or drop it (false: what the image-space techniques draw).
    outside_reflection: bool = true, only PhotonTrace;
    /// photon-trace: where its photons' light reaches the receiver map, through the caustic map
    /// (caustic-map, default) or also binned straight into the receiver map's texels
    /// (receiver-map, as the CPU reference bins them; float atomics), or into the eye's view
    /// instead (screen-space: Kim 2019's screen-space photon mapping, an edge-aware filter).
    deposit: PhotonDeposit = PhotonDeposit::CausticMap, only PhotonTrace;
    /// photon-trace: how photons find the surface they meet next, compute (its own BVH
    /// traversal in a compute shader, default) or ray-query (rayQueryEXT against Vulkan
    /// acceleration structures: VK_KHR_acceleration_structure and VK_KHR_ray_query).
    trace: Trace = Trace::Compute, only PhotonTrace;
    /// photon-trace with trace ray-query: how the acceleration structures follow an object that
    /// moves, transform (a rigid motion moves its instance, any other rebuilds its bottom level;
    /// default), rebuild (every moved object's bottom level rebuilt) or refit (every moved
    /// object's bottom level refitted in place).
    moving_objects: MovingObjects = MovingObjects::Transform, only PhotonTrace;
    /// photon-trace: progressive accumulation (Knaus & Zwicker 2011): new photons every frame,
    /// each frame's splatted with a smaller radius, and the caustic map (and the receiver-map
    /// binning) the mean of every frame since the lights or objects last changed; default false.
    progressive: bool = false, only PhotonTrace;
    /// photon-trace with progressive: the radius rule's alpha in (0, 1], r_{i+1}^2 = r_i^2
    /// (i + alpha) / (i + 1) (Knaus & Zwicker 2011 Eq. 15); default 2/3 (their choice for
    /// surfaces; 1 keeps the radius).
    progressive_alpha: f32 = photon_trace::settings::DEFAULT_ALPHA, only PhotonTrace;
    /// photon-trace: photon differentials (Schjøth et al. 2007, after Igehy 1999): each photon
    /// carries its position's and direction's derivatives through every transfer, reflection and
    /// refraction, and is splatted as the ellipse its footprint spans (an anisotropic Gaussian,
    /// its power kept whole) instead of the fixed splat; default false.
    differentials: bool = false, only PhotonTrace;
    /// photon-trace: each photon jittered inside its stratum of the emission square (true, the
    /// default) or at the stratum's centre (false: a regular grid of photons).
    jitter: bool = true, only PhotonTrace;
    /// pool-convolution: the arithmetic of passes 1-6 (Trendall & Stewart 2000 Sec. 3.2, 5);
    /// default float.
    precision: Precision = Precision::Float, only PoolConvolution;
    /// pool-convolution: the side of the Pass 6 kernels, odd, 3..=63 (Sec. 4.1); default 7 (the
    /// paper's).
    kernel: u32 = DEFAULT_KERNEL, only PoolConvolution;
}

/// A setting's value as the scene file writes it (`last`, `4`, `0.5`), for messages.
fn shown<T: Serialize>(value: &T) -> String {
    match toml::Value::try_from(value) {
        Ok(toml::Value::String(s)) => s,
        Ok(v) => v.to_string(),
        Err(_) => "(unset)".into(),
    }
}

impl CausticOverrides {
    /// Settings that follow from others set in the same table or command line: `max_level`
    /// without `photons` sets `photons` to 64 × 2^max_level.
    fn apply_derived(&self, s: &mut CausticSettings) {
        if self.faithful == Some(true) {
            let (refractions, iterations, lookup) = CausticSettings::TUTORIAL;
            s.refractions = self.refractions.unwrap_or(refractions);
            s.iterations = self.iterations.unwrap_or(iterations);
            s.lookup = self.lookup.unwrap_or(lookup);
        }
        if let (Some(Some(level)), None) = (self.max_level, self.photons) {
            if level <= wn2009::MAX_LEVEL {
                s.photons = wn2009::TOP_PHOTONS << level;
            }
        }
    }
}

impl CausticSettings {
    /// What `faithful = true` means (the caustics mapping tutorial): one refraction, where the
    /// light meets the object (its `psIntersectPts`); rayGeo with 1 iteration (`num_iter`); and
    /// its `psDiffuse` lookup.
    pub const TUTORIAL: (Refractions, u32, Lookup) = (Refractions::One, 1, Lookup::Tutorial);

    /// The geometry buffers' side for technique `adaptive`: gbuffer_scale × the caustic map's
    /// resolution (Wyman & Nichols 2009 Sec. 3.2).
    pub fn gbuffer_side(&self) -> u32 {
        (self.gbuffer_scale as f64 * self.caustic_map_resolution as f64).round() as u32
    }

    /// Caustic-map layers per light: 4 for the multi-resolution map (levels 0-3, Wyman 2008
    /// Sec. 3.3) and for the interpolated splats' four radii (Fig. 7), else 1.
    pub fn caustic_levels(&self) -> u32 {
        use crate::techniques::wyman2008::settings::{INTERPOLATED_LEVELS, MULTIRES_LEVELS};
        match self.splat {
            SplatMode::VaryingMultires if matches!(self.technique, Technique::Hcm | Technique::Adaptive) => {
                MULTIRES_LEVELS
            }
            SplatMode::Interpolated if self.technique == Technique::Hcm => INTERPOLATED_LEVELS,
            _ => 1,
        }
    }

    /// Whether the technique renders its caustics in the eye's view (Wyman & Davis 2006's
    /// eye-space points, quads and gather; photon-trace's screen-space photon mapping): the eye render then has no caustic-map lookup, and
    /// the receiver map comes from an orthographic view of the receiver plane.
    pub fn eye_space(&self) -> bool {
        match self.technique {
            Technique::WdEyePoints => true,
            Technique::WdQuads | Technique::WdGather => self.space == Space::Eye,
            Technique::PhotonTrace => self.deposit == PhotonDeposit::ScreenSpace,
            _ => false,
        }
    }

    /// The intermediate buffers this render's technique adds to the eye render's (`--dump`),
    /// as their owners declare them.
    pub fn dumps(&self) -> Vec<&'static Dump> {
        use shared::settings::{CAUSTIC_MAP, PHOTON_BUFFER, RECEIVER_POSITIONS};
        let mut dumps = match self.technique {
            Technique::None => vec![],
            Technique::PoolConvolution => super::trendall_stewart2000::settings::DUMPS.to_vec(),
            // Screen-space photon mapping: the traced photons, then the eye's view.
            Technique::PhotonTrace if self.eye_space() => {
                vec![&RECEIVER_POSITIONS, &PHOTON_BUFFER, &wyman_davis2006::settings::EYE_CAUSTIC]
            }
            _ if self.eye_space() => wyman_davis2006::settings::EYE_DUMPS.to_vec(),
            Technique::Hcm => [shared::settings::DUMPS, wyman2008::settings::DUMPS].concat(),
            // No photon buffer: photons come from the geometry buffers (Wyman & Nichols 2009 Sec. 3.2).
            Technique::Adaptive => [&[&RECEIVER_POSITIONS, &CAUSTIC_MAP], wn2009::ADAPTIVE_DUMPS].concat(),
            Technique::PhotonTrace if self.differentials => {
                [super::photon_trace::settings::DUMPS, &[&shared::settings::PHOTON_FOOTPRINTS]].concat()
            }
            Technique::PhotonTrace => super::photon_trace::settings::DUMPS.to_vec(),
            _ => shared::settings::DUMPS.to_vec(),
        };
        if self.technique.has_photon_buffer() && self.photon_refraction == PhotonRefraction::Deferred {
            // After the photon buffer and its caustic map.
            let last = [&CAUSTIC_MAP, &PHOTON_BUFFER].iter().find_map(|n| dumps.iter().position(|d| d == n));
            dumps.insert(last.map_or(dumps.len(), |i| i + 1), &wn2009::PHOTON_GEOMETRY_BUFFERS);
        }
        dumps
    }

    /// Whether `photon-trace` bins its photons straight into the receiver map
    /// (`deposit = "receiver-map"`).
    pub fn receiver_deposit(&self) -> bool {
        self.technique == Technique::PhotonTrace && self.deposit == PhotonDeposit::ReceiverMap
    }

    /// What this technique's own settings need of the device, each with what needs it (the
    /// technique's own needs are `Technique::required_features`).
    pub fn settings_features(&self) -> Vec<(&'static str, &'static [vkcore::Feature])> {
        match self.technique {
            Technique::PhotonTrace => photon_trace::settings::required_features(self),
            _ => vec![],
        }
    }

    /// Everything these settings need of the device, each with what needs it: the technique's
    /// own features first, then those of its refraction, photon refraction, traversal path,
    /// own settings and splat path. `render::check_device` requires each (with the memory), and
    /// the registry's `Variant::needs` lists those beyond the technique's.
    pub fn device_needs(&self) -> Vec<(String, &'static [vkcore::Feature])> {
        let mut needs = vec![(format!("technique `{}`", self.technique), self.technique.required_features())];
        needs.push((
            format!("refraction `{}` (a geometry shader routes each face to the front or back layer)", self.refraction),
            self.refraction.required_features(),
        ));
        if self.technique.has_photon_buffer() {
            needs.push((
                format!(
                    "photon_refraction `{}` (a geometry shader routes each face to the front or back layer)",
                    self.photon_refraction
                ),
                self.photon_refraction.required_features(),
            ));
        }
        if matches!(self.technique, Technique::Hcm | Technique::Adaptive) {
            needs.push((format!("technique `{}` with --path {}", self.technique, self.path), self.path.features()));
        }
        needs.extend(self.settings_features().into_iter().map(|(who, f)| (who.to_string(), f)));
        if self.technique.has_caustics() && self.splat_path == SplatPath::Compute {
            needs.push((
                "splat_path `compute` (float atomics in shared/splat.comp)".to_string(),
                shared::settings::COMPUTE_SPLAT_FEATURES,
            ));
        }
        needs
    }

    /// The ray/receiver intersection in effect: the one asked for, else the technique's own.
    pub fn intersect(&self) -> Intersect {
        self.intersect.unwrap_or(self.technique.default_intersect())
    }

    /// Checks that the settings belong together, once they are final (a scene's `[caustics]`
    /// may set `hcm`'s keys and leave the technique to the command line): a setting of another
    /// technique means nothing here, so setting one is a mistake (and would be recorded in
    /// timings.json as if it had been applied). `origin` and `key` as for [`Self::validate`].
    pub fn validate_combination(&self, origin: &str, key: &str) -> anyhow::Result<()> {
        let bad = |k: &str, msg: String| -> anyhow::Result<()> {
            Err(crate::input_error!("{origin}: key `{key}{k}` (or flag --{}): {msg}", k.replace('_', "-")).into())
        };
        // `faithful` sets other keys, which would be foreign too: it is the one to name.
        let foreign = self.foreign_settings();
        if let Some((k, value)) = foreign.iter().find(|(k, _)| *k == "faithful").or(foreign.first()) {
            let owners: Vec<&str> = Self::OWNED
                .iter()
                .find(|(name, _)| name == k)
                .map(|(_, t)| t.iter().map(|t| t.name()).collect())
                .unwrap_or_default();
            bad(k, format!("`{value}` is a setting of technique {}, not of `{}`", owners.join(", "), self.technique))?;
        }
        if self.faithful {
            let (refractions, iterations, lookup) = Self::TUTORIAL;
            let contrary = [
                ("refractions", self.refractions != refractions, shown(&self.refractions)),
                ("iterations", self.iterations != iterations, shown(&self.iterations)),
                ("lookup", self.lookup != lookup, shown(&self.lookup)),
            ];
            if let Some((k, _, value)) = contrary.iter().find(|c| c.1) {
                let tutorial =
                    format!("refractions = \"{refractions}\", iterations = {iterations}, lookup = \"{lookup}\"");
                bad(k, format!("`{value}` contradicts faithful = true (the tutorial's {tutorial}): set faithful = false to mix"))?;
            }
        }
        if self.photon_fov != CausticSettings::default().photon_fov && self.photon_view != PhotonView::FixedFov {
            bad(
                "photon_fov",
                format!("sets the field of view of photon_view `fixed-fov`, not of `{}`", self.photon_view),
            )?;
        }
        let (splat, needs) = (self.splat, self.splat.needs());
        if !splat.sizes_splats_of(self.technique) {
            bad("splat", format!("`{splat}` {}, not those of `{}`", needs.sizes, self.technique))?;
        }
        if let (Some(why), SplatPath::Compute) = (needs.points, self.splat_path) {
            bad("splat", format!("`{splat}` {why} (splat_path = \"compute\")"))?;
        }
        if let Some(why) = needs.fitted_view.filter(|_| self.photon_view != PhotonView::Fitted) {
            bad("splat", format!("`{splat}` needs photon_view `fitted`, not `{}`: {why}", self.photon_view))?;
        }
        if let Some(why) = needs.forward_photons.filter(|_| self.photon_refraction != PhotonRefraction::Forward) {
            bad("splat", format!("`{splat}` needs photon_refraction `forward`: {why}"))?;
        }
        let varying = matches!(self.splat, SplatMode::VaryingSingle | SplatMode::VaryingMultires);
        if self.varying_radius != VaryingRadius::MaxDistance && !varying {
            let what = "sizes varying splats (technique hcm with splat varying-single or varying-multires)";
            bad("varying_radius", format!("`{}` {what}", self.varying_radius))?;
        }
        Ok(())
    }

    /// Checks ranges; `origin` says where the values came from (a file or the command line) and
    /// `key` prefixes key names, e.g. `caustics.`. (Names are checked when they are read.) The
    /// keys of one paper's technique only are checked in its `settings.rs` (`validate_ranges`).
    pub fn validate(&self, origin: &str, key: &str) -> anyhow::Result<()> {
        let bad = |k: &str, msg: String| -> anyhow::Result<()> {
            // On the command line the key is a flag: `--splat-radius`, not `--splat_radius`.
            let k = if key == "--" { k.replace('_', "-") } else { k.to_string() };
            Err(crate::input_error!("{origin}: key `{key}{k}`: {msg}").into())
        };
        let most = self.most_photons();
        if !(64..=most).contains(&self.photons) {
            let adaptive = self.technique == Technique::Adaptive;
            let hint = if adaptive && self.photon_memory_limit == 0 && self.photons > most {
                let name = |k: &str| if key == "--" { format!("--{}", k.replace('_', "-")) } else { k.to_string() };
                format!(
                    "; technique `adaptive` goes up to {}² ({} {}) with a {}, its photons then made in \
                     batches (Wyman & Nichols 2009 Sec. 4.3)",
                    wn2009::TOP_PHOTONS << wn2009::MAX_LEVEL,
                    name("max_level"),
                    wn2009::MAX_LEVEL,
                    name("photon_memory_limit")
                )
            } else {
                String::new()
            };
            // `max_level` alone sets the photons (`apply_derived`): name the key that was given.
            match self.max_level {
                Some(l) if adaptive && l <= wn2009::MAX_LEVEL && self.photons == wn2009::TOP_PHOTONS << l => bad(
                    "max_level",
                    format!("{l} means {}² photons, and photons must be 64 to {most} per side{hint}", self.photons),
                )?,
                _ => bad(
                    "photons",
                    format!("must be between 64 and {most} (photons per side), got {}{hint}", self.photons),
                )?,
            }
        }
        if !(self.splat_radius > 0.0 && self.splat_radius <= 32.0) {
            bad("splat_radius", format!("must be in (0, 32] caustic-map texels, got {}", self.splat_radius))?;
        }
        if !(16..=8192).contains(&self.caustic_map_resolution) {
            bad("caustic_map_resolution", format!("must be between 16 and 8192, got {}", self.caustic_map_resolution))?;
        }
        if self.back_face_iterations > 16 {
            bad("back_face_iterations", format!("must be between 0 and 16, got {}", self.back_face_iterations))?;
        }
        if !(64..=65536).contains(&self.instance_vertices) || !self.instance_vertices.is_power_of_two() {
            bad(
                "instance_vertices",
                format!("must be a power of two between 64 and 65536, got {}", self.instance_vertices),
            )?;
        }
        if !(self.photon_fov >= 1.0 && self.photon_fov <= 160.0) {
            bad("photon_fov", format!("must be between 1 and 160 degrees, got {}", self.photon_fov))?;
        }
        // Each paper's own keys (`only ...` in the table), checked by their paper.
        trendall_stewart2000::settings::validate_ranges(self, &bad)?;
        wn2009::validate_ranges(self, &bad)?;
        photon_trace::settings::validate_ranges(self, &bad)?;
        if !(1..=64).contains(&self.iterations) {
            bad("iterations", format!("must be between 1 and 64, got {}", self.iterations))?;
        }
        Ok(())
    }
}

impl CausticSettings {
    /// The most photons per side: 16384 for `adaptive` under a memory limit (its batches need no
    /// buffer of them all), else 4096.
    pub fn most_photons(&self) -> u32 {
        if self.technique == Technique::Adaptive && self.photon_memory_limit > 0 {
            wn2009::TOP_PHOTONS << wn2009::MAX_LEVEL
        } else {
            4096
        }
    }

    /// Technique `adaptive`'s last traversal level L (64 × 2^L = photons); None when photons is
    /// no such size (`validate` refuses it).
    pub fn adaptive_level(&self) -> Option<u32> {
        wn2009::finest_level(self.photons)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_adaptive_caustic_maps_check_their_geometry_buffers_side() {
        // 0.25 × 32 = 8 texels: too small for adaptive's geometry buffers, which the other
        // techniques do not make, so a 32² caustic map is theirs to ask for.
        let mut s = CausticSettings { caustic_map_resolution: 32, technique: Technique::Shah, ..Default::default() };
        s.validate("test", "--").expect("shah at a 32² caustic map");
        s.technique = Technique::Adaptive;
        s.photons = 64;
        let err = s.validate("test", "--").expect_err("adaptive at a 32² caustic map").to_string();
        assert!(err.contains("--gbuffer-scale") && err.contains("8 texels wide"), "{err}");
    }

    /// The keys of one paper's technique are range-checked by that paper (`validate_ranges` in
    /// its `settings.rs`), and `validate` reaches each, naming the key and the value.
    #[test]
    fn each_papers_own_keys_are_range_checked_through_validate() {
        let cases: [(CausticSettings, &str, &str); 6] = [
            (
                CausticSettings { technique: Technique::PhotonTrace, max_bounces: 0, ..Default::default() },
                "max_bounces",
                "got 0",
            ),
            (
                CausticSettings { technique: Technique::PhotonTrace, max_bounces: 65, ..Default::default() },
                "max_bounces",
                "got 65",
            ),
            (
                CausticSettings { technique: Technique::PoolConvolution, kernel: 8, ..Default::default() },
                "kernel",
                "got 8",
            ),
            (
                CausticSettings { technique: Technique::Adaptive, photon_batches: 0, ..Default::default() },
                "photon_batches",
                "got 0",
            ),
            (
                CausticSettings { technique: Technique::Adaptive, photon_batches: 257, ..Default::default() },
                "photon_batches",
                "got 257",
            ),
            (
                CausticSettings {
                    technique: Technique::Adaptive,
                    photon_memory_limit: (1 << 20) + 1,
                    ..Default::default()
                },
                "photon_memory_limit",
                "got 1048577",
            ),
        ];
        for (s, key, says) in cases {
            let err = s.validate("test.toml", "caustics.").expect_err(key).to_string();
            assert!(err.contains(&format!("caustics.{key}")) && err.contains(says), "{key}: {err}");
        }
        let ok = CausticSettings { technique: Technique::PhotonTrace, max_bounces: 64, ..Default::default() };
        ok.validate("test.toml", "caustics.").expect("64 bounces");
    }

    /// scenes/README.md's `[caustics]` table has a row for every key, with its default as a scene
    /// file writes it (a fraction such as `2/3` is read as one).
    #[test]
    fn the_scene_files_readme_has_a_row_for_every_key_with_its_default() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/README.md");
        let readme = std::fs::read_to_string(path).expect("scenes/README.md");
        let section = readme.split("## `[caustics]`").nth(1).expect("its [caustics] section");
        let section = section.split("\n## ").next().unwrap_or_default();
        let rows: std::collections::HashMap<&str, &str> = section
            .lines()
            .filter_map(|l| {
                let cells: Vec<&str> = l.split('|').map(str::trim).collect();
                (cells.len() > 4 && cells[1].starts_with('`')).then(|| (cells[1].trim_matches('`'), cells[3]))
            })
            .collect();
        let number = |w: &str| match w.split_once('/') {
            Some((a, b)) => Some(a.parse::<f64>().ok()? / b.parse::<f64>().ok()?),
            None => w.parse::<f64>().ok(),
        };
        let defaults = toml::Value::try_from(CausticSettings::default()).expect("the defaults as TOML");
        for (key, value) in defaults.as_table().expect("a table") {
            let cell = rows.get(key.as_str()).unwrap_or_else(|| panic!("scenes/README.md has no row for `{key}`"));
            let written = cell.trim_matches('`');
            let same = match value {
                toml::Value::String(v) => written == format!("\"{v}\""),
                toml::Value::Boolean(v) => written == v.to_string(),
                toml::Value::Integer(v) => number(written) == Some(*v as f64),
                toml::Value::Float(v) => number(written).is_some_and(|w| (w - v).abs() < 1e-6),
                other => panic!("`{key}`: a default of another kind, {other}"),
            };
            assert!(same, "scenes/README.md gives `{key}` the default {cell}; it is {value}");
        }
        // The keys unset by default (no value to serialize) have their rows too.
        for key in ["intersect", "max_level"] {
            assert!(rows.contains_key(key), "scenes/README.md has no row for `{key}`");
        }
    }

    /// Past 4096² photons `adaptive` needs a memory limit: the refusal says so, under the key the
    /// user gave (`max_level` alone sets the photons), and the other techniques get no such hint.
    #[test]
    fn too_many_photons_for_adaptive_names_the_memory_limit_and_the_key_given() {
        let deep =
            CausticSettings { technique: Technique::Adaptive, max_level: Some(7), photons: 8192, ..Default::default() };
        let err = deep.validate("test", "--").expect_err("level 7 without a limit").to_string();
        assert!(err.contains("--max-level") && err.contains("8192²") && err.contains("--photon-memory-limit"), "{err}");
        let photons = CausticSettings { max_level: None, ..deep.clone() };
        let err = photons.validate("test", "--").expect_err("8192 without a limit").to_string();
        assert!(
            err.contains("--photons") && err.contains("got 8192") && err.contains("--photon-memory-limit"),
            "{err}"
        );
        // A max_level that does not give these photons (both set, disagreeing) is about photons.
        let both = CausticSettings { max_level: Some(6), ..deep.clone() };
        let err = both.validate("test", "--").expect_err("8192 and level 6").to_string();
        assert!(err.contains("--photons") && err.contains("got 8192"), "{err}");
        CausticSettings { photon_memory_limit: 64, ..deep }.validate("test", "--").expect("level 7 under a limit");
        let shah = CausticSettings { technique: Technique::Shah, photons: 8192, ..Default::default() };
        let err = shah.validate("test", "--").expect_err("shah at 8192").to_string();
        assert!(err.contains("--photons") && !err.contains("memory"), "{err}");
        let file = CausticSettings { max_level: None, ..deep.clone() };
        let err = file.validate("scene.toml", "caustics.").expect_err("8192 in a file").to_string();
        assert!(err.contains("caustics.photons") && err.contains("a photon_memory_limit"), "{err}");
    }

    /// Screen-space photon mapping deposits into the eye's view: the caustic map's progressive
    /// means and differential splats are refused beside it, naming the key.
    #[test]
    fn the_screen_space_deposit_refuses_what_only_a_caustic_map_has() {
        let screen = CausticSettings {
            technique: Technique::PhotonTrace,
            deposit: PhotonDeposit::ScreenSpace,
            ..Default::default()
        };
        assert!(screen.eye_space(), "screen-space photon mapping is in the eye's view");
        screen.validate("test.toml", "caustics.").expect("screen-space alone");
        for (s, key) in [
            (CausticSettings { progressive: true, ..screen.clone() }, "progressive"),
            (CausticSettings { differentials: true, ..screen.clone() }, "differentials"),
            (CausticSettings { splat_radius: 3.0, ..screen.clone() }, "splat_radius"),
            (CausticSettings { splat_path: SplatPath::Compute, ..screen.clone() }, "splat_path"),
        ] {
            let err = s.validate("test.toml", "caustics.").expect_err(key).to_string();
            assert!(err.contains(&format!("caustics.{key}")) && err.contains("screen-space"), "{key}: {err}");
        }
    }
}
