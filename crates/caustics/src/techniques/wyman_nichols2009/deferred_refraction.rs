//! Deferred refraction (Wyman & Nichols 2009 Sec. 3.1) and multi-layer deferred refraction
//! (Sec. 3.1.1) for the eye view.
//!
//! After the background (step 1, the eye render's `background` pass), each refractor in turn,
//! farthest first, gets two passes:
//! - `refractor_geometry.layer<k>`: its front and back surfaces (normal, distance, window
//!   depth, Wyman 2005 thickness) written in one pass over its triangles; a geometry shader
//!   routes each face to the front (0) or back (1) layer (gl_Layer), which are depth-tested
//!   separately (steps 2 and 3 combined);
//! - `deferred_refraction.layer<k>`: one full-screen pass (a triangle covering the screen)
//!   that refracts where the refractor is visible and copies the previous result elsewhere
//!   (step 4), the previous result being the background for the farthest refractor and the
//!   last pass's output for the others (Sec. 3.1.1, steps 2-5). The last refractor's pass
//!   writes the final image.
//!
//! Each refractor keeps its own geometry buffers and result, so that every one is dumpable.
//! Reflective objects are layers too (a reflection lookup instead of the refraction). Photons
//! are followed through several refractors in light space, by deferred photons and adaptive
//! caustic maps (`deferred_photon_layers.glsl`), not by these eye-view passes.

use crate::dump::{self, layer, Dump, Space};
use crate::gpu::formats::{COLOR, DEPTH};
use crate::gpu::mesh_pipeline::mesh_layout;
use crate::gpu::target::read_image_layer;
use crate::gpu::{mesh_uses, GpuMesh, Stage, Target};
use crate::image_io::ImageF32;
use crate::scene::{MaterialKind, Scene};
use anyhow::Result;
use vkcore::{
    Access, Bind, Blend, Context, Cull, Format, Frame, GraphicsDesc, Image, ImageDesc, ImageView, Pipeline, Sampler,
    ShaderCompiler, Targets, Topology, Use, ViewKind,
};

/// Deferred refraction's geometry buffers, refractor by refractor (Sec. 3.1).
pub static REFRACTOR_GEOMETRY: Dump = Dump::new(
    "refractor_geometry",
    module_path!(),
    Space::Eye,
    dump::Format::Image,
    &[
        layer("layer<k>.front", &["NX", "NY", "NZ", "distance"]),
        layer("layer<k>.back", &["NX", "NY", "NZ", "distance"]),
        layer("layer<k>.front_depth", &["depth", "thickness"]),
        layer("layer<k>.back_depth", &["depth", "thickness"]),
    ],
);
/// The image after each refractor's full-screen pass (Sec. 3.1).
pub static REFRACTION_LAYERS: Dump = Dump::new(
    "refraction_layers",
    module_path!(),
    Space::Eye,
    dump::Format::Image,
    &[layer("layer<k>", &["R", "G", "B"])],
);
/// The eye render's buffers only deferred refraction has (`refraction = "deferred"`).
pub static DEFERRED_REFRACTION_DUMPS: &[&Dump] = &[&REFRACTOR_GEOMETRY, &REFRACTION_LAYERS];

/// The window depth and thickness layers: two floats.
pub const DEPTH_AND_THICKNESS: Format = Format::R32G32_SFLOAT;

/// One refractor's views: its two layers for rendering, and those its deferred pass samples.
pub struct LayerViews {
    surfaces: ImageView,
    depths: ImageView,
    depth_buffer: ImageView,
    front: ImageView,
    back: ImageView,
    front_depth: ImageView,
    /// Where its deferred pass writes (None for the last refractor: the final image).
    result: Option<ImageView>,
}

pub struct DeferredRefraction {
    geometry: Pipeline,
    refraction: Pipeline,
    /// Per refractor k: normal and distance, front in layer 2k, back in 2k + 1.
    pub surfaces: Image,
    /// Per refractor k: window depth and thickness, front in layer 2k, back in 2k + 1.
    pub depths: Image,
    _depth_buffer: Image,
    /// The results of all refractors but the last, one layer each.
    pub results: Option<Image>,
    pub layers: Vec<LayerViews>,
}

/// What the deferred passes read and write besides their own buffers.
pub struct Inputs<'a> {
    pub uniforms: &'a vkcore::Buffer,
    /// Every mesh of the scene (the specular ones' order is [`DeferredRefraction::record`]'s).
    pub meshes: &'a [GpuMesh],
    pub background: &'a ImageView,
    pub position: &'a ImageView,
    pub normal: &'a ImageView,
    pub final_image: &'a ImageView,
    pub nearest: &'a Sampler,
}

/// The specular (refractive and reflective) objects of `scene`, sorted coarsely back to front
/// (Sec. 3.1.1) by the distance from the eye to the centre of their bounds; ties keep the
/// scene's order.
pub fn back_to_front(scene: &Scene) -> Vec<usize> {
    let eye = scene.camera.eye;
    let mut specular: Vec<(usize, f32)> = (scene.objects.iter().enumerate())
        .filter(|(_, o)| !matches!(scene.material_of(o).kind, MaterialKind::Diffuse { .. }))
        .map(|(i, o)| {
            let (lo, hi) = o.mesh.bounds();
            (i, eye.distance(0.5 * (lo + hi)))
        })
        .collect();
    specular.sort_by(|a, b| b.1.total_cmp(&a.1));
    specular.into_iter().map(|(i, _)| i).collect()
}

impl DeferredRefraction {
    /// Pipelines and buffers for `refractors` layers (at least one: without a refractor one
    /// empty layer copies the background) at `width` x `height`.
    pub fn new(ctx: &Context, sh: &ShaderCompiler, refractors: usize, width: u32, height: u32) -> Result<Self> {
        let n = refractors.max(1) as u32;
        let mut d = GraphicsDesc::new(
            "refractor_geometry",
            sh.compile("eye/mesh.vert", &[])?,
            Some(sh.compile("wyman_nichols2009/refractor_geometry.frag", &[])?),
        );
        d.geometry = Some(sh.compile("wyman_nichols2009/refractor_geometry.geom", &[])?);
        d.vertex_layout = Some(mesh_layout());
        d.topology = Topology::Triangles;
        d.cull = Cull::None;
        d.color_formats = vec![COLOR, DEPTH_AND_THICKNESS];
        d.blend = Blend::Replace;
        d.depth_format = Some(DEPTH);
        d.depth_test = true;
        d.depth_write = true;
        let geometry = Pipeline::graphics(ctx, &d)?;
        // Step 4: "render a full screen quad" (one triangle over the screen).
        let mut r = GraphicsDesc::new(
            "deferred_refraction",
            sh.compile("wyman_nichols2009/full_screen.vert", &[])?,
            Some(sh.compile("wyman_nichols2009/deferred_refraction.frag", &[])?),
        );
        r.color_formats = vec![COLOR];
        let refraction = Pipeline::graphics(ctx, &r)?;
        let array =
            |name: &str, format, layers| Image::new(ctx, ImageDesc::new_2d(name, format, width, height).layers(layers));
        let surfaces = array("refractor geometry: normal, distance", COLOR, 2 * n)?;
        let depths = array("refractor geometry: depth, thickness", DEPTH_AND_THICKNESS, 2 * n)?;
        let depth_buffer = array("refractor geometry depth", DEPTH, 2 * n)?;
        let results = if n > 1 { Some(array("deferred refraction results", COLOR, n - 1)?) } else { None };
        let layers = (0..n)
            .map(|k| {
                let one = |i: &Image, l: u32| i.view(ViewKind::D2, 0..1, l..l + 1);
                let both = |i: &Image| i.view(ViewKind::D2Array, 0..1, 2 * k..2 * k + 2);
                Ok(LayerViews {
                    surfaces: both(&surfaces)?,
                    depths: both(&depths)?,
                    depth_buffer: both(&depth_buffer)?,
                    front: one(&surfaces, 2 * k)?,
                    back: one(&surfaces, 2 * k + 1)?,
                    front_depth: one(&depths, 2 * k)?,
                    result: match &results {
                        Some(r) if k + 1 < n => Some(one(r, k)?),
                        _ => None,
                    },
                })
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(DeferredRefraction { geometry, refraction, surfaces, depths, _depth_buffer: depth_buffer, results, layers })
    }

    /// Records both passes of every refractor, farthest first; the last writes `final_image`.
    pub fn record(&self, f: &mut Frame, inp: &Inputs, order: &[usize]) -> Result<()> {
        anyhow::ensure!(
            order.len().max(1) == self.layers.len(),
            "deferred refraction: {} refractors for {} layers",
            order.len(),
            self.layers.len()
        );
        for (k, views) in self.layers.iter().enumerate() {
            let mesh = order.get(k).map(|&i| &inp.meshes[i]);
            let attachments = [
                Use::view(&views.surfaces, Access::COLOR_ATTACHMENT),
                Use::view(&views.depths, Access::COLOR_ATTACHMENT),
                Use::view(&views.depth_buffer, Access::DEPTH_ATTACHMENT),
            ];
            f.pass(&Stage::RefractorGeometry.pass().layer(k))
                .bind(&self.geometry, [("frame", Bind::Uniform(inp.uniforms))])
                .uses(attachments)
                .uses(mesh_uses(mesh.map(std::slice::from_ref).unwrap_or_default()))
                .record(|cmd| {
                    let targets = Targets::colors(vec![
                        (&views.surfaces, Some([0.0; 4])),
                        (&views.depths, Some([1.0, 0.0, 0.0, 0.0])),
                    ]);
                    cmd.begin_rendering(&targets.with_depth(&views.depth_buffer, Some(1.0)).layered(2))?;
                    if let Some(m) = mesh {
                        m.draw(cmd, 1, 0)?;
                    }
                    cmd.end_rendering();
                    Ok(())
                })?;

            let previous = match k {
                0 => inp.background,
                _ => self.layers[k - 1].result.as_ref().unwrap_or(inp.final_image),
            };
            let output = views.result.as_ref().unwrap_or(inp.final_image);
            let binds = [
                ("frame", Bind::Uniform(inp.uniforms)),
                ("background_radiance", Bind::Sampled(previous, inp.nearest)),
                ("background_position", Bind::Sampled(inp.position, inp.nearest)),
                ("background_normal", Bind::Sampled(inp.normal, inp.nearest)),
                ("front_faces", Bind::Sampled(&views.front, inp.nearest)),
                ("back_faces", Bind::Sampled(&views.back, inp.nearest)),
                ("front_depth", Bind::Sampled(&views.front_depth, inp.nearest)),
            ];
            let uses = [Use::view(output, Access::COLOR_ATTACHMENT)];
            f.pass(&Stage::DeferredRefraction.pass().layer(k)).bind(&self.refraction, binds).uses(uses).record(
                |cmd| {
                    // Every pixel is written: the previous contents need not be loaded.
                    cmd.begin_rendering(&Targets::color(output, Some([0.0; 4])))?;
                    // Without a refractor the geometry buffers are empty: every pixel is copied.
                    cmd.push(&mesh.map(|m| m.constants).unwrap_or_default())?;
                    cmd.draw(3, 1, 0, 0);
                    cmd.end_rendering();
                    Ok(())
                },
            )?;
        }
        Ok(())
    }
}

impl DeferredRefraction {
    /// The buffer `d` of the last frame, refractor k (0: the farthest) in layers `layer<k>.*`:
    /// `refractor_geometry`, its front and back faces (normal and distance, window depth and
    /// thickness); `refraction_layers`, the image after its pass (the last one's is the eye's
    /// `final_image`). None for a buffer deferred refraction does not own.
    pub fn dump(&self, ctx: &Context, final_image: &Target, d: &'static Dump) -> Result<Option<ImageF32>> {
        if !DEFERRED_REFRACTION_DUMPS.contains(&d) {
            return Ok(None);
        }
        let mut layers = vec![];
        for k in 0..self.layers.len() as u32 {
            if d == &REFRACTOR_GEOMETRY {
                for (face, l) in [("front", 2 * k), ("back", 2 * k + 1)] {
                    let (surface, depth) = (format!("layer{k}.{face}"), format!("layer{k}.{face}_depth"));
                    let normal_distance = ["NX", "NY", "NZ", "distance"];
                    layers.push(read_image_layer(
                        ctx,
                        &self.surfaces,
                        l,
                        Some(&surface),
                        &normal_distance,
                        &[0, 1, 2, 3],
                    )?);
                    layers.push(read_image_layer(
                        ctx,
                        &self.depths,
                        l,
                        Some(&depth),
                        &["depth", "thickness"],
                        &[0, 1],
                    )?);
                }
            } else {
                let n = Some(format!("layer{k}"));
                layers.push(match &self.results {
                    Some(r) if k + 1 < self.layers.len() as u32 => {
                        read_image_layer(ctx, r, k, n.as_deref(), &["R", "G", "B"], &[0, 1, 2])?
                    }
                    _ => final_image.read_layer(ctx, 0, n.as_deref(), &["R", "G", "B"], &[0, 1, 2])?,
                });
            }
        }
        Ok(Some(final_image.as_image(layers)))
    }
}
