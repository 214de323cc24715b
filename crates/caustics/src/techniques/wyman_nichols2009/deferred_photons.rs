//! Deferred caustic maps (Wyman & Nichols 2009 Sec. 3.2 and Fig. 10: "deferred caustic maps
//! (i.e., a dense photon buffer with a deferred renderpass)"; `photon_refraction = deferred`):
//! the dense photon buffer of every photon-buffer technique created by deferred shading instead
//! of by rasterizing the specular objects' front faces (`shared/photon_buffer.rs`):
//!
//! 1. the light-space geometry buffers of the specular objects at the photon buffer's
//!    resolution N (front and back faces in one pass, [`LightGeometryBuffers`], Sec. 3.1's
//!    single pass over the geometry, seen from the light as in Sec. 3.2);
//! 2. one full-screen pass (`wyman_nichols2009/deferred_photons.frag`) that traces the photon of
//!    every covered texel from the geometry buffers' texel and writes the same photon-buffer
//!    images as the forward pass (same format, same texel, same photon), so the splats, the
//!    hierarchy, the image-space techniques and the dumps read it unchanged.
//!
//! With several specular objects, Sec. 3.1.1's multi-layer refraction for photons (Sec. 5 and
//! Fig. 13: "caustics from more than two refractive interfaces, using multi-layered deferred
//! refraction when rendering photons"): each object also gets its own geometry buffers, and a
//! photon that leaves the object it met first is intersected with the others' buffers in image
//! space, refracted through the one it meets, and so on, before it lands
//! (`wyman_nichols2009/deferred_photon_layers.glsl`, with its approximations). The buffers of
//! all objects together give each photon its first surface, exactly as the forward pass sees
//! it, so every object is rasterized twice here where the paper rasterizes it once; with one
//! specular object there are only those.

use super::geometry_buffers::{LightGeometryBuffers, Uniforms};
use super::refractor_layers::{specular_objects, RefractorLayers, MAX_REFRACTORS};
use crate::gpu::formats::COLOR;
use crate::gpu::{GpuMesh, MeshConstants, Stage};
use crate::image_io::ImageF32;
use crate::techniques::shared::CausticPasses;
use anyhow::Result;
use vkcore::{Access, Bind, Context, GraphicsDesc, Pipeline, ShaderCompiler, Targets, Use};

pub struct DeferredPhotons {
    /// The indices of the specular meshes (the scene's objects), in the scene's order.
    specular: Vec<usize>,
    /// All specular objects' surfaces: the first one each photon meets.
    all: LightGeometryBuffers,
    /// With several specular objects, each one's own.
    refractors: RefractorLayers,
    photons: Pipeline,
}

impl DeferredPhotons {
    /// Buffers of `side`² texels (the photon buffer's) for the specular meshes of `meshes`.
    pub fn new(ctx: &Context, sh: &ShaderCompiler, side: u32, meshes: &[GpuMesh]) -> Result<DeferredPhotons> {
        let specular = specular_objects(meshes);
        anyhow::ensure!(
            specular.len() <= MAX_REFRACTORS,
            "photon_refraction `deferred`: the scene has {} specular objects; deferred photons follow photons \
             through at most {MAX_REFRACTORS} (use photon_refraction `forward`)",
            specular.len()
        );
        let refractors = RefractorLayers::new(ctx, sh, side, &specular)?;
        let mut d = GraphicsDesc::new(
            "deferred_photons",
            sh.compile("wyman_nichols2009/full_screen.vert", &[])?,
            Some(sh.compile(
                "wyman_nichols2009/deferred_photons.frag",
                &[("REFRACTORS", &refractors.refractors_define())],
            )?),
        );
        d.color_formats = vec![COLOR, COLOR, COLOR];
        Ok(DeferredPhotons {
            specular,
            all: LightGeometryBuffers::new(ctx, sh, side)?,
            refractors,
            photons: Pipeline::graphics(ctx, &d)?,
        })
    }

    /// `photon_back_faces` as the forward path's back-face pass renders it (NX, NY, NZ,
    /// distance): the back layer of all refractors' geometry buffers.
    pub fn dump_back_faces(&self, ctx: &Context) -> Result<ImageF32> {
        let img = self.all.dump_surfaces(ctx, self.all.side)?;
        let mut back = img.layers.into_iter().find(|l| l.name.as_deref() == Some("back.normal"));
        let back = back.take().ok_or_else(|| anyhow::anyhow!("geometry buffers without a back layer"))?;
        Ok(ImageF32 { layers: vec![crate::image_io::Layer { name: None, ..back }], ..img })
    }

    /// Records light `l`'s geometry buffers and the deferred pass that writes its photon buffer.
    pub fn record(&self, f: &mut vkcore::Frame, c: &CausticPasses, l: u32) -> Result<()> {
        let (inp, pt) = (c.inputs, c.photons);
        let u = Uniforms { frame: inp.frame_uniforms, caustics: inp.caustic_uniforms };
        self.all.record_surfaces(f, &u, inp.meshes, &self.specular, Stage::DeferredPhotonsGeometry.pass(), l)?;
        self.refractors.record(f, &u, inp.meshes, Stage::DeferredPhotonsGeometry, l)?;
        let mut binds = vec![
            ("frame", Bind::Uniform(inp.frame_uniforms)),
            ("caustics", Bind::Uniform(inp.caustic_uniforms)),
            ("light_back_faces", Bind::Sampled(&self.all.back_faces, inp.nearest)),
            ("receiver_positions", Bind::Sampled(&c.targets.receiver_positions.view, inp.nearest)),
            ("spot_textures", Bind::Sampled(inp.spot_textures, inp.linear)),
        ];
        binds.extend(
            ["surface_position", "surface_normal", "surface_material"]
                .into_iter()
                .zip(self.all.surface_binds(inp.nearest)),
        );
        binds.extend(self.refractors.binds(inp.nearest));
        let photons = [&pt.position, &pt.direction, &pt.power];
        f.pass(&Stage::DeferredPhotons.light(l))
            .bind(&self.photons, binds)
            .uses(photons.map(|t| Use::view(&t.view, Access::COLOR_ATTACHMENT)))
            .record(|cmd| {
                cmd.begin_rendering(&Targets::colors(photons.iter().map(|t| (&t.view, Some([0.0; 4]))).collect()))?;
                cmd.push(&MeshConstants { light: l, ..Default::default() })?;
                cmd.draw(3, 1, 0, 0);
                cmd.end_rendering();
                Ok(())
            })?;
        Ok(())
    }

    /// `photon_geometry_buffers.exr` for the light rendered last: the buffers of all specular
    /// objects (layers `front.position`, `front.normal`, `front.material`, `back.position`,
    /// `back.normal`, as `adaptive_geometry` names them), and with several objects each one's
    /// own, prefixed `refractor<k>.` (k in the scene's order of its specular objects).
    pub fn dump(&self, ctx: &Context) -> Result<ImageF32> {
        let mut img = self.all.dump_surfaces(ctx, self.all.side)?;
        self.refractors.dump_into(ctx, &mut img, self.all.side)?;
        Ok(img)
    }
}
