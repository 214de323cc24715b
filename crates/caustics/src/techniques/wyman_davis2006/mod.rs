//! Wyman & Davis, "Interactive image-space techniques for approximating caustics" (I3D 2006):
//! technique `wd-points`.
//!
//! The photon buffer (Sec. 3.1) is rendered from the light: one photon per light-space texel of
//! the specular objects, refracted at both surfaces (Wyman 2005's two-sided estimate), finding
//! the receivers by marching through the light's render of the first diffuse surface and
//! refining the crossing by bisection (`shaders_glsl/wyman_davis2006/depth_search.glsl`). Its
//! photons are then splatted as points (Sec. 3.2) into a light-space caustic map whose texels
//! hold power, turned into irradiance with the texel's area on the receiver (Eq. 5-8). The
//! photon buffer and the splat are stages other papers share (`techniques::shared`).
//!
//! Not yet implemented: caustic quads (Sec. 3.2.1), the eye-space and light-space gathers
//! (Sec. 3.2.2-3.2.3) and the temporal filter.

/// The paper, as tables and `--help` cite it.
pub const PAPER: &str = "Wyman & Davis 2006, image-space caustics";
