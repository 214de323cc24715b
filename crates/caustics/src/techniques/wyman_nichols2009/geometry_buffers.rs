//! The light-space geometry buffers of adaptive caustic maps (Wyman & Nichols 2009 Sec. 3.2,
//! step 1: "render geometry buffers for deferred photon creation"): the specular objects seen
//! from the light through the photon frustum (the `photon_view` the dense photon buffer is
//! rendered in), front and back surfaces in one pass (`light_geometry.geom` routes each face
//! to its layer, as the eye's deferred refraction does, Sec. 3.1), at `gbuffer_scale` times the
//! caustic map's resolution ("a quarter the final caustic map's resolution", the default).
//!
//! - layer 0, front: world position and Wyman 2005 thickness d_N; the interpolated normal and
//!   the object's index + 1 (0: no surface, the texel's coverage); the material (colour, mean
//!   index of refraction, 0 for a mirror);
//! - layer 1, back: the refractors' back faces as the photon trace reads them (unit normal and
//!   distance to the light, `shared/back_faces.frag`), and their positions.
//!
//! A coverage pyramid over the front layer's coverage (`coverage.comp`: any and all covered
//! texels below each node) lets the traversal discard a cluster only when no texel its photons
//! can sample is covered (see `adaptive.glsl`).
//!
//! How photons read them (`adaptive.glsl`, `surface_at`): a photon at light-space texture
//! coordinates uv is on the refractor when the texel uv lies in is covered (nearest-texel
//! coverage); its position, normal and thickness are interpolated bilinearly among the 2x2
//! texels around uv that the same object covers (weights renormalised), and its material is
//! that texel's. At a texel centre this reads that texel alone: with buffers as fine as the
//! photon grid, every photon is the dense photon buffer's photon of the same texel.

use super::push::CoverageConstants;
use crate::gpu::formats::{COLOR, DEPTH};
use crate::gpu::mesh_pipeline::mesh_layout;
use crate::gpu::{mesh_uses, GpuMesh, PassName, Stage};
use crate::image_io::{ImageF32, Layer};
use anyhow::Result;
use vkcore::{
    Access, Bind, Blend, Context, Cull, Format, Frame, GraphicsDesc, Image, ImageDesc, ImageView, Pipeline, Sampler,
    ShaderCompiler, Targets, Topology, Use, ViewKind,
};

/// The coverage pyramid's format: r any, g all covered (0 or 1, exact in 8 bits).
const COVERAGE: Format = Format::R8G8B8A8_UNORM;

/// What the geometry pass reads: the frame and caustic uniforms.
pub struct Uniforms<'a> {
    pub frame: &'a vkcore::Buffer,
    pub caustics: &'a vkcore::Buffer,
}

pub struct LightGeometryBuffers {
    /// The buffers' side G (texels).
    pub side: u32,
    /// The coverage pyramid's side P: G padded to a power of two.
    pub padded: u32,
    geometry: Pipeline,
    coverage: Pipeline,
    /// Layer 0 front, 1 back (see the module's documentation), each array of 2 layers.
    pub position: Image,
    pub normal: Image,
    pub material: Image,
    _depth: Image,
    coverage_pyramid: Image,
    /// Both layers of each (the geometry pass's targets, the traversal's sampled arrays).
    pub position_layers: ImageView,
    pub normal_layers: ImageView,
    pub material_layers: ImageView,
    depth_layers: ImageView,
    /// Layer 1 of `normal`: the back faces the photon trace samples (`light_back_faces`).
    pub back_faces: ImageView,
    /// Every level of the coverage pyramid (sampled), and each level alone (written).
    pub coverage_levels: ImageView,
    coverage_level: Vec<ImageView>,
}

impl LightGeometryBuffers {
    /// Buffers of `side`² texels and their pipelines.
    pub fn new(ctx: &Context, sh: &ShaderCompiler, side: u32) -> Result<LightGeometryBuffers> {
        let mut d = GraphicsDesc::new(
            "adaptive.geometry",
            sh.compile("shared/light_mesh.vert", &[("PHOTON_VIEW", "1")])?,
            Some(sh.compile("wyman_nichols2009/light_geometry.frag", &[])?),
        );
        d.geometry = Some(sh.compile("wyman_nichols2009/light_geometry.geom", &[])?);
        d.vertex_layout = Some(mesh_layout());
        d.topology = Topology::Triangles;
        d.cull = Cull::None;
        d.color_formats = vec![COLOR, COLOR, COLOR];
        d.blend = Blend::Replace;
        d.depth_format = Some(DEPTH);
        d.depth_test = true;
        d.depth_write = true;
        let geometry = Pipeline::graphics(ctx, &d)?;
        let coverage =
            Pipeline::compute(ctx, "adaptive.coverage", &sh.compile("wyman_nichols2009/coverage.comp", &[])?)?;
        let array = |name: &str, format| Image::new(ctx, ImageDesc::new_2d(name, format, side, side).layers(2));
        let position = array("light geometry: position", COLOR)?;
        let normal = array("light geometry: normal", COLOR)?;
        let material = array("light geometry: material", COLOR)?;
        let depth = array("light geometry depth", DEPTH)?;
        let both = |i: &Image| i.view(ViewKind::D2Array, 0..1, 0..2);
        let padded = side.next_power_of_two();
        let levels = padded.trailing_zeros() + 1;
        let coverage_pyramid =
            Image::new(ctx, ImageDesc::new_2d("light geometry coverage", COVERAGE, padded, padded).mips(levels))?;
        let coverage_level =
            (0..levels).map(|m| coverage_pyramid.view(ViewKind::D2, m..m + 1, 0..1)).collect::<vkcore::Result<_>>()?;
        Ok(LightGeometryBuffers {
            side,
            padded,
            geometry,
            coverage,
            position_layers: both(&position)?,
            normal_layers: both(&normal)?,
            material_layers: both(&material)?,
            depth_layers: both(&depth)?,
            back_faces: normal.view(ViewKind::D2, 0..1, 1..2)?,
            coverage_levels: coverage_pyramid.view(ViewKind::D2, 0..levels, 0..1)?,
            coverage_level,
            position,
            normal,
            material,
            _depth: depth,
            coverage_pyramid,
        })
    }

    /// Records light `l`'s geometry buffers (one pass over the specular meshes) and their
    /// coverage pyramid.
    pub fn record(&self, f: &mut Frame, u: &Uniforms, meshes: &[GpuMesh], nearest: &Sampler, l: u32) -> Result<()> {
        let specular = super::refractor_layers::specular_objects(meshes);
        self.record_surfaces(f, u, meshes, &specular, Stage::AdaptiveGeometry.pass(), l)?;
        self.record_coverage(f, nearest, l)
    }

    /// Records light `l`'s geometry buffers of the meshes `objects` (indices into `meshes`) in
    /// one pass named `<name>.light<l>`, without the coverage pyramid (deferred photons,
    /// `deferred_photons.rs`, read texels, not footprints).
    pub fn record_surfaces(
        &self,
        f: &mut Frame,
        u: &Uniforms,
        meshes: &[GpuMesh],
        objects: &[usize],
        name: PassName,
        l: u32,
    ) -> Result<()> {
        let attachments = [
            Use::view(&self.position_layers, Access::COLOR_ATTACHMENT),
            Use::view(&self.normal_layers, Access::COLOR_ATTACHMENT),
            Use::view(&self.material_layers, Access::COLOR_ATTACHMENT),
            Use::view(&self.depth_layers, Access::DEPTH_ATTACHMENT),
        ];
        f.pass(&name.light(l))
            .bind(&self.geometry, [("frame", Bind::Uniform(u.frame)), ("caustics", Bind::Uniform(u.caustics))])
            .uses(attachments)
            .uses(mesh_uses(meshes))
            .record(|cmd| {
                let targets = Targets::colors(vec![
                    (&self.position_layers, Some([0.0; 4])),
                    (&self.normal_layers, Some([0.0; 4])),
                    (&self.material_layers, Some([0.0; 4])),
                ]);
                cmd.begin_rendering(&targets.with_depth(&self.depth_layers, Some(1.0)).layered(2))?;
                for &i in objects {
                    meshes[i].draw(cmd, 1, l)?;
                }
                cmd.end_rendering();
                Ok(())
            })?;
        Ok(())
    }

    /// Both layers of the position, normal and material buffers, sampled as the photon-creating
    /// shaders declare them (position, normal, material).
    pub fn surface_binds<'a>(&'a self, nearest: &'a Sampler) -> [Bind<'a>; 3] {
        [
            Bind::Sampled(&self.position_layers, nearest),
            Bind::Sampled(&self.normal_layers, nearest),
            Bind::Sampled(&self.material_layers, nearest),
        ]
    }

    /// Records the coverage pyramid of light `l`'s front layer.
    fn record_coverage(&self, f: &mut Frame, nearest: &Sampler, l: u32) -> Result<()> {
        for (m, out) in self.coverage_level.iter().enumerate() {
            // Level 0 reads the geometry buffers; its `finer` binding is level 1, unused.
            let finer = &self.coverage_level[if m == 0 { 1 } else { m - 1 }];
            let binds = [
                ("geometry_normal", Bind::Sampled(&self.normal_layers, nearest)),
                ("finer", Bind::Sampled(finer, nearest)),
                ("level_out", Bind::Storage(out)),
            ];
            f.pass(&Stage::AdaptiveCoverage.pass().level(m as u32).light(l)).bind(&self.coverage, binds).record(
                |cmd| {
                    cmd.push(&CoverageConstants { level: m as u32 })?;
                    let s = (self.padded >> m).max(1);
                    cmd.dispatch(s.div_ceil(8), s.div_ceil(8), 1);
                    Ok(())
                },
            )?;
        }
        Ok(())
    }

    /// `adaptive_geometry.exr` for the light rendered last: layers `front.position` (X, Y, Z,
    /// thickness), `front.normal` (NX, NY, NZ, object: index + 1, 0 where no surface),
    /// `front.material` (R, G, B, ior: 0 for a mirror), `back.position` (X, Y, Z, distance),
    /// `back.normal` (NX, NY, NZ, distance) at G², and the coverage pyramid, level m in the
    /// top-left (P/2^m)² corner of layer `coverage.level<m>` (any, all), in an image of side P.
    pub fn dump(&self, ctx: &Context) -> Result<ImageF32> {
        let mut img = self.dump_surfaces(ctx, self.padded)?;
        let p = self.padded as usize;
        for m in 0..self.coverage_level.len() as u32 {
            let s = (self.padded >> m).max(1) as usize;
            let bytes = ctx.read_image(&self.coverage_pyramid, m, 0)?;
            let texels: Vec<f32> =
                bytes.chunks_exact(4).flat_map(|t| [t[0] as f32 / 255.0, t[1] as f32 / 255.0]).collect();
            img.layers.push(Layer::new(Some(&format!("coverage.level{m}")), &["any", "all"], place(&texels, s, 2, p)));
        }
        Ok(img)
    }

    /// The front and back layers alone (see [`Self::dump`]), each in the top-left G² corner of
    /// an image of side `p` (at least G).
    pub fn dump_surfaces(&self, ctx: &Context, p: u32) -> Result<ImageF32> {
        let (g, p) = (self.side as usize, p.max(self.side) as usize);
        let mut layers = vec![];
        let buffers: [(&Image, &str, [&str; 4]); 3] = [
            (&self.position, "position", ["X", "Y", "Z", "W"]),
            (&self.normal, "normal", ["NX", "NY", "NZ", "W"]),
            (&self.material, "material", ["R", "G", "B", "ior"]),
        ];
        for (layer, face) in [(0u32, "front"), (1, "back")] {
            for (image, what, mut channels) in buffers {
                if layer == 1 && what == "material" {
                    continue;
                }
                channels[3] = match (layer, what) {
                    (0, "position") => "thickness",
                    (0, "normal") => "object",
                    (1, _) => "distance",
                    _ => channels[3],
                };
                let texels = ctx.read_image_f32(image, 0, layer)?;
                layers.push(Layer::new(Some(&format!("{face}.{what}")), &channels, place(&texels, g, 4, p)));
            }
        }
        Ok(ImageF32 { width: p as u32, height: p as u32, layers })
    }
}

/// An `s`² image of `nc` channels in the top-left corner of a `p`² one.
fn place(src: &[f32], s: usize, nc: usize, p: usize) -> Vec<f32> {
    let mut out = vec![0.0f32; p * p * nc];
    for y in 0..s {
        out[y * p * nc..(y * p + s) * nc].copy_from_slice(&src[y * s * nc..(y + 1) * s * nc]);
    }
    out
}
