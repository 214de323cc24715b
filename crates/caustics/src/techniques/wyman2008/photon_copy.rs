//! The faithful Wyman & Davis 2006 route from photon buffer to splats: copy the photon image
//! into a vertex array (OpenGL's render-to-vertex-array via a pixel buffer object), then draw
//! one point per vertex. Wyman 2008 Sec. 4 and Tables 1-2 measure what this copy costs and how
//! the data types on both sides change it; our default path (instanced fetch from the photon
//! texture) needs no copy at all.
//!
//! The photon buffer is rendered in 32-bit float. For the 16-bit sources of Table 2 a pass
//! `photon_buffer.to_16bit` first converts it into 16-bit images (standing in for a 16-bit
//! FBO; it is timed as its own pass, not as part of the copy). The copy pass `photon_copy` then does what the
//! driver would: a plain copy when both sides have the same type, and for 16-bit to 32-bit a
//! converting blit into a 32-bit image followed by the copy.

use crate::gpu::{SplatConstants, Stage, Target};
use crate::techniques::shared::pipelines::point_splat_desc;
use crate::techniques::shared::targets::PhotonTargets;
use crate::techniques::shared::FrameInputs;
use anyhow::Result;
use vkcore::{
    Access, Bind, Buffer, Context, Format, Frame, ImageDesc, ImageView, Memory, Pipeline, ShaderCompiler, Targets, Use,
    VertexAttribute, VertexLayout,
};

/// Data types on both sides of the copy (Wyman 2008 Table 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CopyType {
    /// 16-bit float framebuffer into a 32-bit float vertex array (the naive combination).
    Half16ToFloat32,
    /// 32-bit float on both sides.
    Float32ToFloat32,
    /// 16-bit float on both sides.
    Half16ToHalf16,
}

/// Names accepted by `photon_copy` in bench configs.
pub const COPY_TYPES: &[&str] = &["none", "16-to-32", "32-to-32", "16-to-16"];

impl CopyType {
    /// `none` is None (instanced fetch, no copy).
    pub fn parse(name: &str) -> Option<Option<CopyType>> {
        match name {
            "none" => Some(None),
            "16-to-32" => Some(Some(CopyType::Half16ToFloat32)),
            "32-to-32" => Some(Some(CopyType::Float32ToFloat32)),
            "16-to-16" => Some(Some(CopyType::Half16ToHalf16)),
            _ => None,
        }
    }
    /// The vertex array holds 16-bit floats.
    pub fn vertices_are_half(self) -> bool {
        self == CopyType::Half16ToHalf16
    }
}

/// What the copy reads (photon position and power), by the source's data type.
// One per renderer: boxing the larger variants would save nothing.
#[allow(clippy::large_enum_variant)]
enum CopySource {
    /// The 32-bit photon buffer itself.
    Float32,
    /// 16-bit images the photon buffer is converted into first, copied as they are.
    Half16([Target; 2]),
    /// 16-bit images, blitted into 32-bit ones (`wide`) before the copy (16-to-32: the
    /// conversion the driver makes).
    Half16Widened { half: [Target; 2], wide: [Target; 2] },
}

impl CopySource {
    /// The 16-bit images `photon_buffer.to_16bit` writes, for 16-bit sources.
    fn half(&self) -> Option<&[Target; 2]> {
        match self {
            CopySource::Float32 => None,
            CopySource::Half16(half) | CopySource::Half16Widened { half, .. } => Some(half),
        }
    }
}

/// The images and buffers of the copy path for one photon buffer size.
pub struct PhotonCopy {
    pub ty: CopyType,
    source: CopySource,
    /// The vertex array of photon positions.
    pub positions: Buffer,
    /// Photon powers, one texel per vertex.
    pub powers: Buffer,
    width: u32,
    /// Splats from the vertex array: one point per vertex.
    splat: Pipeline,
}

impl PhotonCopy {
    pub fn new(ctx: &Context, sh: &ShaderCompiler, ty: CopyType, width: u32) -> Result<PhotonCopy> {
        let img = |name: &str, f: Format| Target::new(ctx, ImageDesc::new_2d(name, f, width, width));
        let half = || -> Result<[Target; 2]> {
            Ok([
                img("photon position (16-bit)", Format::R16G16B16A16_SFLOAT)?,
                img("photon power (16-bit)", Format::R16G16B16A16_SFLOAT)?,
            ])
        };
        let source = match ty {
            CopyType::Float32ToFloat32 => CopySource::Float32,
            CopyType::Half16ToHalf16 => CopySource::Half16(half()?),
            CopyType::Half16ToFloat32 => CopySource::Half16Widened {
                half: half()?,
                wide: [
                    img("photon position (converted)", Format::R32G32B32A32_SFLOAT)?,
                    img("photon power (converted)", Format::R32G32B32A32_SFLOAT)?,
                ],
            },
        };
        let texel = if ty.vertices_are_half() { 8 } else { 16 };
        let bytes = width as u64 * width as u64 * texel;
        Ok(PhotonCopy {
            ty,
            source,
            positions: Buffer::new(ctx, "photon vertex array", bytes, Memory::Gpu)?,
            powers: Buffer::new(ctx, "photon power array", bytes, Memory::Gpu)?,
            width,
            splat: Self::splat_pipeline(ctx, sh, ty)?,
        })
    }

    /// The point splat reading the vertex array instead of the photon texture.
    fn splat_pipeline(ctx: &Context, sh: &ShaderCompiler, ty: CopyType) -> Result<Pipeline> {
        let half = ty.vertices_are_half();
        let mut defines = vec![("PHOTON_VERTEX_ARRAY", "1")];
        if half {
            defines.push(("PHOTON_HALF", "1"));
        }
        let mut d = point_splat_desc(sh)?;
        d.name = "splat_vertex_array".into();
        d.vertex = sh.compile("shared/splat.vert", &defines)?;
        let (format, stride) = if half { (Format::R16G16B16A16_SFLOAT, 8) } else { (Format::R32G32B32A32_SFLOAT, 16) };
        d.vertex_layout =
            Some(VertexLayout { stride, attributes: vec![VertexAttribute { location: 0, format, offset: 0 }] });
        Ok(Pipeline::graphics(ctx, &d)?)
    }

    /// Splats light `l`'s copied photons into `cmap`, one point per vertex of the array.
    pub fn record_splat(&self, f: &mut Frame, inp: &FrameInputs, cmap: &ImageView, l: u32) -> Result<()> {
        let binds = [
            ("frame", Bind::Uniform(inp.frame_uniforms)),
            ("caustics", Bind::Uniform(inp.caustic_uniforms)),
            ("PhotonPower", Bind::BufferRead(&self.powers)),
        ];
        f.pass(&Stage::Splat.light(l))
            .bind(&self.splat, binds)
            .uses([Use::view(cmap, Access::COLOR_ATTACHMENT), Use::buffer(&self.positions, Access::VERTEX_INPUT)])
            .record(|cmd| {
                cmd.begin_rendering(&Targets::color(cmap, Some([0.0; 4])))?;
                cmd.push(&SplatConstants { light: l, vertices_per_instance: 0 })?;
                cmd.bind_vertex_buffer(&self.positions, 0)?;
                cmd.draw(self.vertices(), 1, 0, 0);
                cmd.end_rendering();
                Ok(())
            })?;
        Ok(())
    }

    /// Photons (vertices) in the array.
    pub fn vertices(&self) -> u32 {
        self.width * self.width
    }

    /// Records `photon_buffer.to_16bit.light<l>` (16-bit sources) and `photon_copy.light<l>`.
    pub fn record(&self, f: &mut Frame, pt: &PhotonTargets, l: u32) -> Result<()> {
        let src32 = [&pt.position, &pt.power];
        if let Some(half) = self.source.half() {
            let mut uses: Vec<Use> = src32.iter().map(|t| Use::view(&t.view, Access::TRANSFER_READ)).collect();
            uses.extend(half.iter().map(|t| Use::view(&t.view, Access::TRANSFER_WRITE)));
            f.pass(&Stage::PhotonBufferTo16bit.light(l)).uses(uses).record(|cmd| {
                for (s, d) in src32.iter().zip(half) {
                    cmd.blit_converting(&s.image, &d.image);
                }
                Ok(())
            })?;
        }
        let dst = [&self.positions, &self.powers];
        let mut uses: Vec<Use> = dst.iter().map(|b| Use::buffer(b, Access::TRANSFER_WRITE)).collect();
        match &self.source {
            CopySource::Half16Widened { half, wide } => {
                uses.extend(half.iter().map(|t| Use::view(&t.view, Access::TRANSFER_READ)));
                uses.extend(wide.iter().map(|t| Use::view(&t.view, Access::TRANSFER_WRITE)));
                f.pass(&Stage::PhotonCopy.light(l)).uses(uses).record(|cmd| {
                    for (s, w) in half.iter().zip(wide) {
                        cmd.blit_converting(&s.image, &w.image);
                    }
                    let converted: Vec<Use> = wide.iter().map(|t| Use::view(&t.view, Access::TRANSFER_READ)).collect();
                    cmd.sync(&converted)?;
                    for (w, b) in wide.iter().zip(dst) {
                        cmd.copy_image_to_buffer(&w.image, 0, 0, b);
                    }
                    Ok(())
                })?;
            }
            CopySource::Float32 | CopySource::Half16(_) => {
                let src = self.source.half().map_or(src32, |[position, power]| [position, power]);
                uses.extend(src.iter().map(|t| Use::view(&t.view, Access::TRANSFER_READ)));
                f.pass(&Stage::PhotonCopy.light(l)).uses(uses).record(|cmd| {
                    for (s, b) in src.iter().zip(dst) {
                        cmd.copy_image_to_buffer(&s.image, 0, 0, b);
                    }
                    Ok(())
                })?;
            }
        }
        Ok(())
    }
}
