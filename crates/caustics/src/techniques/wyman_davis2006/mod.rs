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
//! Light-space quads and gathers are rendered again only when the lighting changes.

mod gather;
mod points;
mod quads;
pub mod reflection;
pub mod settings;
pub mod temporal;
pub mod views;

pub use settings::PAPER;

use crate::gpu::{ImageSpaceConstants, Stage, Target};
use crate::image_io::{ImageF32, Layer};
use crate::scene::Scene;
use crate::techniques::settings::CausticSettings;
use crate::techniques::shared::{CausticPasses, EyeView};
use crate::techniques::technique::Technique;
use anyhow::{Context as _, Result};
use glam::{Mat4, Vec3};
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
}

/// The orthographic view of the receiver plane: its photons, and its geometry.
struct ReceiverView {
    buffers: ViewBuffers,
    position: Target,
    normal: Target,
    view_proj: Mat4,
    tolerance: [f32; 2],
}

/// The GPU resources of `wd-eye-points`, `wd-quads` and `wd-gather`.
pub struct ImageSpace {
    method: Method,
    /// The equation that lights the photons (Eq. 9-11 or 3-4).
    lighting: u32,
    /// Points into a view (eye space) or into a caustic map (light-space gather).
    points: Option<Pipeline>,
    quads: Option<quads::QuadPipelines>,
    gather: Option<Pipeline>,
    shade: Option<Pipeline>,
    receiver_geometry: Option<Pipeline>,
    /// The eye's view (eye space).
    eye: Option<ViewBuffers>,
    receiver: Option<ReceiverView>,
    /// The light-space gather's photon counts: history layers per light.
    light: Option<ViewBuffers>,
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
        let (gathers, lighting) = match method {
            Method::Quads(_) => (false, s.quad_lighting.equation()),
            _ => (true, s.gather_lighting.equation()),
        };
        let camera = (scene.camera.width, scene.camera.height);
        let layers = history.layers();
        let eye = match eye_space {
            // A light's photons have their own history layers (light * layers + slot), so
            // each light is gathered from its own photons.
            true => Some(ViewBuffers::new(ctx, "eye", camera, layers * lights, true)?),
            false => None,
        };
        let receiver = match (eye_space, &scene.receiver_map, views::receiver_view_proj(scene)) {
            (true, Some(r), Some(view_proj)) => {
                let size = (r.resolution, r.resolution);
                Some(ReceiverView {
                    buffers: ViewBuffers::new(ctx, "receiver view", size, layers * lights, true)?,
                    position: Target::color(ctx, "receiver view position", r.resolution, r.resolution)?,
                    normal: Target::color(ctx, "receiver view normal", r.resolution, r.resolution)?,
                    view_proj,
                    tolerance: views::tolerance(scene, true),
                })
            }
            _ => None,
        };
        let m = s.caustic_map_resolution;
        let light = match (light_space, gathers) {
            (true, true) => Some(ViewBuffers::new(ctx, "light-space", (m, m), layers * lights, false)?),
            _ => None,
        };
        Ok(Some(ImageSpace {
            method,
            lighting,
            points: if gathers { Some(points::pipeline(ctx, sh, light_space)?) } else { None },
            quads: if gathers { None } else { Some(quads::pipeline(ctx, sh, light_space)?) },
            gather: if gathers { Some(gather::pipeline(ctx, sh, light_space)?) } else { None },
            shade: if eye_space { Some(gather::shade_pipeline(ctx, sh)?) } else { None },
            receiver_geometry: if receiver.is_some() { Some(gather::receiver_view_pipeline(ctx, sh)?) } else { None },
            eye,
            receiver,
            light,
            history,
            tolerance: views::tolerance(scene, false),
        }))
    }

    /// Whether the caustics are rendered in the eye's view.
    pub fn eye_space(&self) -> bool {
        !matches!(self.method, Method::Quads(Space::Light) | Method::Gather(Space::Light))
    }

    /// The caustic irradiance of the receiver view, which the receiver map reads (eye space).
    pub fn receiver_caustic(&self) -> Option<&ImageView> {
        self.receiver.as_ref().and_then(|r| r.buffers.caustic.as_ref()).map(|t| &t.view)
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
        if self.eye_space() {
            let eye = eye.context("eye-space caustics need the eye's view")?;
            if let (true, Some(r), Some(p)) = (first, &self.receiver, &self.receiver_geometry) {
                record_receiver_geometry(f, c, p, r)?;
            }
            let eye_buffers = self.eye.as_ref().context("no eye-space buffers")?;
            let eye_base = views::view_constants(eye.view_proj, eye.eye, self.tolerance, false);
            let mut targets = vec![("eye", eye_buffers, (eye.position, eye.normal), eye_base)];
            if let Some(r) = &self.receiver {
                let base = views::view_constants(r.view_proj, Vec3::ZERO, r.tolerance, true);
                targets.push(("receiver", &r.buffers, (&r.position.view, &r.normal.view), base));
            }
            for (view, buffers, geometry, base) in targets {
                let k = self.constants(base, c, l, 0);
                match (&self.points, &self.quads) {
                    (Some(p), _) => {
                        // Light l's photons, gathered at once into the view's caustic (lights
                        // after the first add to it: gather.comp).
                        let into = points::PointsInto {
                            name: Stage::WdPhotons.pass().view(view).light(l),
                            buffers,
                            slot: k.slot,
                            geometry,
                            clear: true,
                        };
                        points::record(f, c, p, into, k)?;
                        let g = self.gather.as_ref().context("no gather pipeline")?;
                        let radius = if self.method == Method::EyePoints { 0 } else { gather::RADIUS };
                        let kg = self.constants(base, c, l, radius);
                        let out = &buffers.caustic.as_ref().context("no caustic image")?.view;
                        gather::record(
                            f,
                            &Stage::WdGather.pass().view(view).light(l),
                            c,
                            g,
                            buffers,
                            geometry,
                            out,
                            kg,
                        )?;
                    }
                    (None, Some(q)) => {
                        let out = &buffers.caustic.as_ref().context("no caustic image")?.view;
                        quads::record(f, &Stage::WdQuads.pass().view(view).light(l), c, q, out, geometry, first, k)?;
                    }
                    (None, None) => anyhow::bail!("image-space caustics without a pipeline"),
                }
            }
            return Ok(());
        }
        if reuse {
            return Ok(());
        }
        let cmap = &c.targets.per_light[l as usize].0;
        let rpos = &c.targets.per_light[l as usize].1;
        let base = ImageSpaceConstants::default();
        match (&self.points, &self.gather, &self.quads, &self.light) {
            (Some(p), Some(g), _, Some(buffers)) => {
                let k = self.constants(base, c, l, gather::RADIUS);
                let into = points::PointsInto {
                    name: Stage::WdPhotons.pass().view("light_space").light(l),
                    buffers,
                    slot: k.slot,
                    geometry: (rpos, rpos),
                    clear: true,
                };
                points::record(f, c, p, into, k)?;
                gather::record(
                    f,
                    &Stage::WdGather.pass().view("light_space").light(l),
                    c,
                    g,
                    buffers,
                    (rpos, rpos),
                    cmap,
                    k,
                )?;
            }
            (_, _, Some(q), _) => {
                let k = self.constants(base, c, l, 0);
                quads::record(
                    f,
                    &Stage::WdQuads.pass().view("light_space").light(l),
                    c,
                    q,
                    cmap,
                    (rpos, rpos),
                    true,
                    k,
                )?;
            }
            _ => anyhow::bail!("light-space caustics without a pipeline"),
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
        if !self.eye_space() {
            if !reuse {
                self.history.advance();
            }
            return Ok(());
        }
        let eye = eye.context("eye-space caustics need the eye's view")?;
        let eye_buffers = self.eye.as_ref().context("no eye-space buffers")?;
        let shade = self.shade.as_ref().context("no shading pipeline")?;
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
    /// caustic irradiance: their views' photon images are never written.
    pub fn dump_eye(&self, ctx: &Context) -> Result<Option<ImageF32>> {
        let Some(b) = &self.eye else { return Ok(None) };
        let mut layers = vec![];
        if let Some(c) = &b.caustic {
            layers.push(read(ctx, c, 0, None, &["R", "G", "B", "photons"])?);
        }
        if self.points.is_none() {
            return Ok(Some(ImageF32 { width: b.width, height: b.height, layers }));
        }
        let slot = (self.history.slot() + self.history.layers() - 1) % self.history.layers();
        layers.push(read(ctx, &b.photons, slot, Some("photons"), &["R", "G", "B", "count"])?);
        layers.push(read(ctx, &b.directions, 0, Some("direction"), &["X", "Y", "Z", "cos_direct"])?);
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

/// All four channels of `layer` of `t` as a dump layer.
fn read(ctx: &Context, t: &Target, layer: u32, name: Option<&str>, channels: &[&str]) -> Result<Layer> {
    Ok(Layer::new(name, channels, ctx.read_image_f32(&t.image, 0, layer)?))
}
