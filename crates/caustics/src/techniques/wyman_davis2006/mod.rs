//! Wyman & Davis, "Interactive image-space techniques for approximating caustics" (I3D 2006):
//! techniques `wd-points`, `wd-eye-points`, `wd-quads` and `wd-gather`.
//!
//! The photon buffer (Sec. 3.1) is rendered from the light: one photon per light-space texel of
//! the specular objects, refracted at both surfaces (Wyman 2005's two-sided estimate) or
//! reflected, finding the receivers by marching through the light's render of the first diffuse
//! surface and refining the crossing by bisection (`shaders_glsl/wyman_davis2006/depth_search.glsl`),
//! or for mirrors on one background plane (`reflection = plane`, Sec. 4: [`reflection`]). The
//! photon buffer is a stage other papers share (`techniques::shared`). The paper's four ways to
//! turn it into light (Sec. 3.2), each its own stage here:
//! - `wd-points`: splatted as points into a light-space caustic map (`shared::splat`);
//! - `wd-eye-points` (Fig. 4): drawn as points into the eye's view ([`points`]), each pixel
//!   lit by its own photons ([`gather`] with radius 0);
//! - `wd-quads` (Sec. 3.2.1, [`quads`]): polygons between adjacent photons with Eq. 1-4, in the
//!   eye's view or a light-space caustic map (`space`);
//! - `wd-gather` (Sec. 3.2.2, [`points`] then [`gather`]): the photons counted in an eye-space or
//!   a light-space buffer, then the 7x7 Gaussian gather with Eq. 6-11;
//!
//! and temporal filtering of the counts (Sec. 3.2.3, [`temporal`]). The eye-space variants
//! render their receiver map from an orthographic view of the receiver plane ([`views`]).
//! `photon-trace --deposit screen-space` draws its exact photons into the same views as
//! `wd-eye-points` and filters them there edge-aware (Kim 2019's screen-space photon mapping,
//! `techniques::shared::screen_space`).
//! Light-space quads and gathers are rendered again only when the lighting changes.

mod gather;
mod points;
pub mod push;
mod quads;
pub mod reflection;
pub mod settings;
pub mod temporal;
pub mod views;

pub use settings::PAPER;

use crate::gpu::{Stage, Target};
use crate::image_io::ImageF32;
use crate::scene::Scene;
use crate::techniques::settings::CausticSettings;
use crate::techniques::shared::screen_space::{self, FilterView, ScreenSpaceFilter};
use crate::techniques::shared::{CausticPasses, EyeView};
use crate::techniques::technique::Technique;
use anyhow::{Context as _, Result};
use glam::{Mat4, Vec3};
use push::ImageSpaceConstants;
use settings::{Space, TemporalFilter};
use temporal::History;
use views::ViewBuffers;
use vkcore::{Context, Frame, ImageView, Pipeline, ShaderCompiler};

/// Which of the paper's ways of turning photons into light a render uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    EyePoints,
    Quads(Space),
    Gather(Space),
    /// `photon-trace --deposit screen-space`: the exact photons as eye points, filtered
    /// edge-aware (Kim 2019).
    ScreenSpace,
}

/// The orthographic view of the receiver plane: its photons, and its geometry.
struct ReceiverView {
    buffers: ViewBuffers,
    position: Target,
    normal: Target,
    view_proj: Mat4,
    tolerance: [f32; 2],
}

/// How the photons become light (Sec. 3.2).
enum Draw {
    /// Drawn as points into a view's photon buffer, then gathered from it (radius 0 for
    /// `wd-eye-points`: each pixel lit by its own photons; Fig. 4, Sec. 3.2.2).
    PointsGathered { points: Pipeline, gather: Pipeline },
    /// Polygons between adjacent photons, drawn straight into the caustic (Sec. 3.2.1).
    Quads(quads::QuadPipelines),
    /// Drawn as points into a view's photon buffer, then filtered edge-aware on the view's
    /// geometry buffer (screen-space photon mapping, Kim 2019).
    PointsFiltered { points: Pipeline, filter: ScreenSpaceFilter },
}

/// Where they are drawn (one per renderer: boxing the eye's variant would save nothing).
#[allow(clippy::large_enum_variant)]
enum DrawnInto {
    /// The eye's view, then added to the eye's radiance by the shading pass; and, where the
    /// scene has a receiver map, the receiver view with the pipeline of its geometry.
    Eye { eye: ViewBuffers, shade: Pipeline, receiver: Option<(ReceiverView, Pipeline)> },
    /// The light's caustic map; the gathers first count the photons in their own buffers
    /// (history layers per light), which quads do not need.
    Light { counts: Option<ViewBuffers> },
}

/// The GPU resources of `wd-eye-points`, `wd-quads` and `wd-gather`.
pub struct ImageSpace {
    method: Method,
    /// The equation that lights the photons (Eq. 9-11 or 3-4).
    lighting: u32,
    draw: Draw,
    into: DrawnInto,
    history: History,
    tolerance: [f32; 2],
}

impl ImageSpace {
    /// The method of `settings`, if its technique is one of these.
    pub fn method(settings: &CausticSettings) -> Option<Method> {
        match settings.technique {
            Technique::WdEyePoints => Some(Method::EyePoints),
            Technique::WdQuads => Some(Method::Quads(settings.space)),
            Technique::WdGather => Some(Method::Gather(settings.space)),
            Technique::PhotonTrace if settings.eye_space() => Some(Method::ScreenSpace),
            _ => None,
        }
    }

    /// The resources for `scene`'s technique, None if it is not one of these.
    pub fn new(ctx: &Context, sh: &ShaderCompiler, scene: &Scene) -> Result<Option<ImageSpace>> {
        let s = &scene.caustics;
        let Some(method) = Self::method(s) else { return Ok(None) };
        let eye_space = s.eye_space();
        let light_space = !eye_space;
        let history = History::new(s.temporal_filter == TemporalFilter::On);
        let lights = scene.lights.len().clamp(1, crate::gpu::MAX_LIGHTS) as u32;
        let lighting = match method {
            Method::Quads(_) => s.quad_lighting.equation(),
            // Exact photons keep their flux on a Lambertian receiver: Eq. 11.
            Method::ScreenSpace => 11,
            Method::EyePoints | Method::Gather(_) => s.gather_lighting.equation(),
        };
        let camera = (scene.camera.width, scene.camera.height);
        let layers = history.layers();
        let draw = match method {
            Method::ScreenSpace => Draw::PointsFiltered {
                points: points::pipeline(ctx, sh, light_space)?,
                filter: ScreenSpaceFilter::new(ctx, sh)?,
            },
            Method::EyePoints | Method::Gather(_) => Draw::PointsGathered {
                points: points::pipeline(ctx, sh, light_space)?,
                gather: gather::pipeline(ctx, sh, light_space)?,
            },
            Method::Quads(_) => Draw::Quads(quads::pipeline(ctx, sh, light_space, s.quad_draw)?),
        };
        let into = match eye_space {
            true => {
                // A light's photons have their own history layers (light * layers + slot), so
                // each light is gathered from its own photons.
                let filtered = matches!(draw, Draw::PointsFiltered { .. });
                let eye =
                    ViewBuffers::new(ctx, "eye", camera, layers * lights, true)?.filtered(ctx, "eye", filtered)?;
                let receiver = match (&scene.receiver_map, views::receiver_view_proj(scene)) {
                    (Some(r), Some(view_proj)) => {
                        let size = (r.resolution, r.resolution);
                        let view =
                            ReceiverView {
                                buffers: ViewBuffers::new(ctx, "receiver view", size, layers * lights, true)?
                                    .filtered(ctx, "receiver view", filtered)?,
                                position: Target::color(ctx, "receiver view position", r.resolution, r.resolution)?,
                                normal: Target::color(ctx, "receiver view normal", r.resolution, r.resolution)?,
                                view_proj,
                                tolerance: views::tolerance(scene, true),
                            };
                        Some((view, gather::receiver_view_pipeline(ctx, sh)?))
                    }
                    _ => None,
                };
                DrawnInto::Eye { eye, shade: gather::shade_pipeline(ctx, sh)?, receiver }
            }
            false => {
                let m = s.caustic_map_resolution;
                let counts = match draw {
                    Draw::PointsGathered { .. } => {
                        Some(ViewBuffers::new(ctx, "light-space", (m, m), layers * lights, false)?)
                    }
                    Draw::Quads(_) | Draw::PointsFiltered { .. } => None,
                };
                DrawnInto::Light { counts }
            }
        };
        Ok(Some(ImageSpace { method, lighting, draw, into, history, tolerance: views::tolerance(scene, false) }))
    }

    /// Whether the caustics are rendered in the eye's view.
    pub fn eye_space(&self) -> bool {
        matches!(self.into, DrawnInto::Eye { .. })
    }

    /// The caustic irradiance of the receiver view, which the receiver map reads (eye space).
    pub fn receiver_caustic(&self) -> Option<&ImageView> {
        match &self.into {
            DrawnInto::Eye { receiver: Some((r, _)), .. } => r.buffers.caustic.as_ref().map(|t| &t.view),
            _ => None,
        }
    }

    /// Light `l`'s constants: its photons have their own history layers, from `l * layers`
    /// (eye and light space alike), so that each light is gathered from its own photons.
    fn constants(&self, base: ImageSpaceConstants, c: &CausticPasses, l: u32, radius: u32) -> ImageSpaceConstants {
        let history_base = l * self.history.layers();
        ImageSpaceConstants {
            light: l,
            lighting: self.lighting,
            slot: history_base + self.history.slot(),
            frames: self.history.frames(),
            radius,
            min_photons: if radius > 0 { gather::MIN_PHOTONS } else { 0 },
            photon_side: c.photons.width,
            history_base,
            ..base
        }
    }

    /// Light `l`'s part, once its photon buffer is rendered (or kept, `reuse`): its photons
    /// drawn into the eye's and the receiver's views and gathered there (or resolved per pixel,
    /// `wd-eye-points`), its quads drawn there (eye space), or its quads or gather into its
    /// caustic-map layer (light space, skipped when the photons were kept: the lighting did not
    /// change).
    pub fn record_light(
        &self,
        f: &mut Frame,
        c: &CausticPasses,
        l: u32,
        eye: Option<EyeView>,
        reuse: bool,
    ) -> Result<()> {
        let first = l == 0;
        let (eye_buffers, receiver) = match &self.into {
            DrawnInto::Eye { eye, receiver, .. } => (eye, receiver),
            DrawnInto::Light { counts } => return self.record_light_space(f, c, l, counts.as_ref(), reuse),
        };
        let eye = eye.context("eye-space caustics need the eye's view")?;
        if let (true, Some((r, p))) = (first, receiver) {
            record_receiver_geometry(f, c, p, r)?;
        }
        let eye_base = views::view_constants(eye.view_proj, eye.eye, self.tolerance, false);
        let mut targets = vec![("eye", eye_buffers, (eye.position, eye.normal), eye_base)];
        if let Some((r, _)) = receiver {
            let base = views::view_constants(r.view_proj, Vec3::ZERO, r.tolerance, true);
            targets.push(("receiver", &r.buffers, (&r.position.view, &r.normal.view), base));
        }
        for (view, buffers, geometry, base) in targets {
            let k = self.constants(base, c, l, 0);
            let out = &buffers.caustic.as_ref().context("no caustic image")?.view;
            if let Draw::PointsGathered { points: p, .. } | Draw::PointsFiltered { points: p, .. } = &self.draw {
                let into = points::PointsInto {
                    name: Stage::WdPhotons.pass().view(view).light(l),
                    buffers,
                    slot: k.slot,
                    geometry,
                    clear: true,
                };
                points::record(f, c, p, into, k)?;
            }
            match &self.draw {
                Draw::PointsGathered { gather: g, .. } => {
                    // Light l's photons, gathered at once into the view's caustic (lights
                    // after the first add to it: gather.comp).
                    let radius = if self.method == Method::EyePoints { 0 } else { gather::RADIUS };
                    let kg = self.constants(base, c, l, radius);
                    let name = Stage::WdGather.pass().view(view).light(l);
                    gather::record(f, &name, c, g, buffers, geometry, out, kg)?;
                }
                Draw::Quads(q) => {
                    quads::record(f, &Stage::WdQuads.pass().view(view).light(l), c, q, out, geometry, first, k)?;
                }
                Draw::PointsFiltered { filter, .. } => {
                    // Light l's photons, filtered edge-aware into the view's caustic.
                    // The receiver view's depth-edge tolerance is its points'; the eye's is the
                    // filter's own.
                    let ortho = base.eye[3] > 0.5;
                    let v = FilterView {
                        view,
                        photons: &buffers.photons.view,
                        position: geometry.0,
                        normal: geometry.1,
                        normalized: &buffers.normalized.as_ref().context("no normalized photons")?.view,
                        caustic: out,
                        size: (buffers.width, buffers.height),
                        eye: base.eye,
                        tolerance: if ortho {
                            [base.tolerance[0], base.tolerance[1]]
                        } else {
                            screen_space::EYE_TOLERANCE
                        },
                    };
                    filter.record(f, c.inputs.nearest, &v, l, k.slot)?;
                }
            }
        }
        Ok(())
    }

    /// Light `l`'s quads or gather into its caustic-map layer (light space), skipped when the
    /// photons were kept (`reuse`: the lighting did not change). `counts`: the gathers'.
    fn record_light_space(
        &self,
        f: &mut Frame,
        c: &CausticPasses,
        l: u32,
        counts: Option<&ViewBuffers>,
        reuse: bool,
    ) -> Result<()> {
        if reuse {
            return Ok(());
        }
        let cmap = &c.targets.per_light[l as usize].0;
        let rpos = &c.targets.per_light[l as usize].1;
        let base = ImageSpaceConstants::default();
        match &self.draw {
            Draw::PointsGathered { points: p, gather: g } => {
                let buffers = counts.context("no light-space photon counts")?;
                let k = self.constants(base, c, l, gather::RADIUS);
                let into = points::PointsInto {
                    name: Stage::WdPhotons.pass().view("light_space").light(l),
                    buffers,
                    slot: k.slot,
                    geometry: (rpos, rpos),
                    clear: true,
                };
                points::record(f, c, p, into, k)?;
                let name = Stage::WdGather.pass().view("light_space").light(l);
                gather::record(f, &name, c, g, buffers, (rpos, rpos), cmap, k)?;
            }
            Draw::Quads(q) => {
                let k = self.constants(base, c, l, 0);
                let name = Stage::WdQuads.pass().view("light_space").light(l);
                quads::record(f, &name, c, q, cmap, (rpos, rpos), true, k)?;
            }
            Draw::PointsFiltered { .. } => anyhow::bail!("screen-space photon mapping is in the eye's view"),
        }
        Ok(())
    }

    /// After every light (each gathered into the eye's and the receiver's views with its
    /// photons, [`Self::record_light`]): the caustics added to the eye's radiance. Advances the
    /// temporal filter's history when this frame wrote it.
    pub fn record_after_lights(
        &self,
        f: &mut Frame,
        c: &CausticPasses,
        eye: Option<EyeView>,
        reuse: bool,
    ) -> Result<()> {
        let DrawnInto::Eye { eye: eye_buffers, shade, .. } = &self.into else {
            if !reuse {
                self.history.advance();
            }
            return Ok(());
        };
        let eye = eye.context("eye-space caustics need the eye's view")?;
        let caustic = &eye_buffers.caustic.as_ref().context("no caustic image")?.view;
        let binds = [
            ("background", vkcore::Bind::Storage(eye.background)),
            ("albedo", vkcore::Bind::Sampled(eye.albedo, c.inputs.nearest)),
            ("caustic", vkcore::Bind::Sampled(caustic, c.inputs.nearest)),
        ];
        f.pass(&Stage::WdShade.pass()).bind(shade, binds).record(|cmd| {
            cmd.dispatch(eye_buffers.width.div_ceil(8), eye_buffers.height.div_ceil(8), 1);
            Ok(())
        })?;
        self.history.advance();
        Ok(())
    }

    /// The `eye_caustic` dump: the eye's caustic irradiance (main layer, W/m^2, and the photons
    /// of the neighbourhood), and where photons are drawn as points (eye points, gathers) this
    /// frame's eye-space photons and their directions. Quads are drawn straight into the
    /// caustic irradiance: their views' photon images are never written, and the main layer's
    /// fourth channel counts the quads' fragments over each pixel (`quads`: their depth
    /// complexity, Fig. 6).
    pub fn dump_eye(&self, ctx: &Context) -> Result<Option<ImageF32>> {
        const RGBA: [usize; 4] = [0, 1, 2, 3];
        let DrawnInto::Eye { eye: b, .. } = &self.into else { return Ok(None) };
        let mut layers = vec![];
        if let Some(c) = &b.caustic {
            let fourth = if matches!(self.draw, Draw::Quads(_)) { "quads" } else { "photons" };
            layers.push(c.read_layer(ctx, 0, None, &["R", "G", "B", fourth], &RGBA)?);
        }
        if let Draw::Quads(_) = self.draw {
            return Ok(Some(ImageF32 { width: b.width, height: b.height, layers }));
        }
        let slot = (self.history.slot() + self.history.layers() - 1) % self.history.layers();
        layers.push(b.photons.read_layer(ctx, slot, Some("photons"), &["R", "G", "B", "count"], &RGBA)?);
        layers.push(b.directions.read_layer(ctx, 0, Some("direction"), &["X", "Y", "Z", "cos_direct"], &RGBA)?);
        Ok(Some(ImageF32 { width: b.width, height: b.height, layers }))
    }
}

/// The receiver view's geometry: the receiver plane seen straight down.
fn record_receiver_geometry(f: &mut Frame, c: &CausticPasses, p: &Pipeline, r: &ReceiverView) -> Result<()> {
    let binds = [
        ("frame", vkcore::Bind::Uniform(c.inputs.frame_uniforms)),
        ("view_position", vkcore::Bind::Storage(&r.position.view)),
        ("view_normal", vkcore::Bind::Storage(&r.normal.view)),
    ];
    f.pass(&Stage::WdReceiverView.pass()).bind(p, binds).record(|cmd| {
        cmd.dispatch(r.buffers.width.div_ceil(8), r.buffers.height.div_ceil(8), 1);
        Ok(())
    })?;
    Ok(())
}
