//! Wyman & Davis 2006's settings and dumps, as the scene's `[caustics]`, the bench configs and
//! the command line name them (a leaf module: the scene description reads it).

use super::super::shared::settings as shared;
use super::super::value_enum::value_enum;
use crate::dump::{self, layer_when, Dump, Format};

/// The paper, as tables and `--help` cite it.
pub const PAPER: &str = "Wyman & Davis 2006, image-space caustics";

/// The eye's caustic irradiance and the eye-space photon buffer it was gathered from.
pub static EYE_CAUSTIC: Dump = Dump::new(
    "eye_caustic",
    module_path!(),
    dump::Space::Eye,
    Format::Image,
    &[
        layer_when(
            "",
            &["R", "G", "B", "photons"],
            "with `wd-eye-points`, `wd-gather` and photon-trace's `screen-space` deposit",
        ),
        layer_when("", &["R", "G", "B", "quads"], "with `wd-quads`"),
        layer_when(
            "photons",
            &["R", "G", "B", "count"],
            "with `wd-eye-points`, `wd-gather` and photon-trace's `screen-space` deposit",
        ),
        layer_when(
            "direction",
            &["X", "Y", "Z", "cos_direct"],
            "with `wd-eye-points`, `wd-gather` and photon-trace's `screen-space` deposit",
        ),
    ],
);
/// The buffers only the eye-space variants have.
pub static DUMPS: &[&Dump] = &[&EYE_CAUSTIC];
/// What the eye-space variants dump: the shared light-space buffers but the caustic map, and
/// their own.
pub static EYE_DUMPS: &[&Dump] =
    &[&shared::RECEIVER_POSITIONS, &shared::PHOTON_BACK_FACES, &shared::PHOTON_BUFFER, &EYE_CAUSTIC];

value_enum! {
    /// Where caustic quads and gathers are rendered (`caustics.space`, `--space`; Sec. 3.2.1-3.2.2).
    pub enum Space {
        /// Into the eye's view, every frame (for the receiver map: an orthographic view straight
        /// down on the receiver plane).
        Eye = "eye",
        /// Into a light-space caustic map projected like a shadow map, rendered again only when
        /// the lighting changes.
        Light = "light",
    }
}

value_enum! {
    /// Temporal filtering of the photon counts (`caustics.temporal_filter`, `--temporal-filter`;
    /// Sec. 3.2.3).
    pub enum TemporalFilter {
        /// The counts of the current frame alone.
        Off = "off",
        /// The counts of the previous three frames averaged with the current frame's.
        On = "on",
    }
}

value_enum! {
    /// Where a photon reflected by a mirror lands (`caustics.reflection`, `--reflection`; Sec. 4).
    pub enum Reflection {
        /// The ray/receiver intersection in effect (`caustics.intersect`).
        DepthSearch = "depth-search",
        /// The paper's: the reflected ray intersected with one background plane (the receiver
        /// map's plane, else the lowest diffuse surface's).
        Plane = "plane",
    }
}

value_enum! {
    /// How the gathers and the eye-space points light a pixel's photons
    /// (`caustics.gather_lighting`, `--gather-lighting`; Sec. 3.2.2).
    pub enum GatherLighting {
        /// Eq. 9: each photon lit from its own stored incident direction.
        Eq9 = "eq9",
        /// Eq. 10: one lighting computation per pixel with its photons' average incident
        /// direction (the paper's choice).
        Eq10 = "eq10",
        /// Eq. 11: the photons lit from the light's direct direction (no stored directions).
        Eq11 = "eq11",
    }
}

value_enum! {
    /// How a caustic quad is lit (`caustics.quad_lighting`, `--quad-lighting`; Sec. 3.2.1).
    pub enum QuadLighting {
        /// Eq. 3: from the direction its photons arrive in (stored in the photon buffer).
        Eq3 = "eq3",
        /// Eq. 4: from the light's direct direction.
        Eq4 = "eq4",
    }
}

value_enum! {
    /// How a caustic quad is drawn (`caustics.quad_draw`, `--quad-draw`; Sec. 3.2.1).
    pub enum QuadDraw {
        /// Every quad as its polygon whatever its size, as the paper draws them: one under a
        /// pixel is hit or missed whole by the rasterizer, so its beam's power lands on the
        /// pixel centres it happens to cover (the paper's error, measured in the quality table).
        Polygons = "polygons",
        /// Polygons a pixel or more wide; one under a pixel as a point and a sliver as a line
        /// carrying its beam's whole power (quads.vert), so that every quad deposits its power.
        Exact = "exact",
    }
}

impl GatherLighting {
    /// The equation number the shaders switch on.
    pub fn equation(self) -> u32 {
        match self {
            GatherLighting::Eq9 => 9,
            GatherLighting::Eq10 => 10,
            GatherLighting::Eq11 => 11,
        }
    }
}

impl QuadLighting {
    /// The equation number the shaders switch on.
    pub fn equation(self) -> u32 {
        match self {
            QuadLighting::Eq3 => 3,
            QuadLighting::Eq4 => 4,
        }
    }
}
