//! Stream compaction, both ways: (a) the papers' way, a geometry shader that emits only the
//! kept points into transform-feedback buffers, the next step drawn with
//! vkCmdDrawIndirectByteCountEXT from the xfb counter buffer; (b) the modern way, a compute
//! append buffer with an atomic counter and indirect dispatch/draw arguments. Neither reads
//! anything back on the CPU between steps. The [`Compactor`]'s elements are 16-byte `uvec4`s; a
//! [`CompactStream`] of other users may hold elements of any size.

use crate::bind::Bind;
use crate::buffer::{Buffer, Memory};
use crate::context::Context;
use crate::error::Result;
use crate::frame::{Frame, Use};
use crate::pipeline::{GraphicsDesc, Pipeline, Topology, VertexAttribute, VertexLayout};
use crate::query::QueryPool;
use crate::recorder::Targets;
use crate::shader::ShaderCompiler;
use crate::tracker::Access;
use crate::Feature;
use ash::vk;

crate::push_constants! {
    /// The compute path's push constants (`shaders_glsl/vkcore/compact_append.comp`).
    pub struct CompactConstants {
        /// Elements in the input when `use_in_count` is 0.
        pub n: u32,
        /// 1: the input's count is the previous step's counter, on the GPU.
        pub use_in_count: u32,
        /// Elements the output holds.
        pub capacity: u32,
    }
}

/// Bytes per element of the [`Compactor`]'s streams.
pub const ELEMENT_BYTES: u64 = 16;
/// Bytes of the compute path's counter (see `shaders_glsl/vkcore/compact_counter.glsl`).
pub const COUNTER_BYTES: u64 = 48;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompactionPath {
    /// Geometry shader + VK_EXT_transform_feedback.
    TransformFeedback,
    /// Compute shader + atomic append counter.
    Compute,
}

impl CompactionPath {
    pub fn name(self) -> &'static str {
        match self {
            CompactionPath::TransformFeedback => "xfb",
            CompactionPath::Compute => "compute",
        }
    }
}

/// A compacted stream on the GPU: the elements and their GPU-side count.
pub struct CompactStream {
    pub path: CompactionPath,
    pub data: Buffer,
    /// xfb: the transform-feedback counter (bytes written, u32 at 0); compute: an append counter.
    pub counter: Buffer,
    pub capacity: u32,
    /// Bytes per element (the xfb counter counts bytes).
    pub element_bytes: u64,
}

impl CompactStream {
    /// A stream of `capacity` elements of [`ELEMENT_BYTES`] (the [`Compactor`]'s).
    pub fn new(ctx: &Context, name: &str, path: CompactionPath, capacity: u32) -> Result<CompactStream> {
        Self::with_element_bytes(ctx, name, path, capacity, ELEMENT_BYTES)
    }

    /// A stream of `capacity` elements of `element_bytes` each (a multiple of 4).
    pub fn with_element_bytes(
        ctx: &Context,
        name: &str,
        path: CompactionPath,
        capacity: u32,
        element_bytes: u64,
    ) -> Result<CompactStream> {
        if element_bytes == 0 || !element_bytes.is_multiple_of(4) {
            return Err(crate::VkError::Invalid(format!("{name}: elements of {element_bytes} bytes")));
        }
        let bytes = capacity.max(1) as u64 * element_bytes;
        let data = Buffer::new(ctx, &format!("{name} elements"), bytes, Memory::Gpu)?;
        let counter = Buffer::new(ctx, &format!("{name} counter"), COUNTER_BYTES, Memory::Gpu)?;
        Ok(CompactStream { path, data, counter, capacity, element_bytes })
    }

    /// Reads the element count back (for tests and statistics, never between steps).
    pub fn count(&self, ctx: &Context) -> Result<u32> {
        let c: Vec<u32> = ctx.read_buffer_as(&self.counter)?;
        Ok(match self.path {
            CompactionPath::TransformFeedback => (c[0] as u64 / self.element_bytes) as u32,
            CompactionPath::Compute => c[0].min(self.capacity),
        })
    }

    /// Reads the kept elements back as `T`s (`T` of `element_bytes` bytes).
    pub fn read_as<T: bytemuck::Pod>(&self, ctx: &Context) -> Result<Vec<T>> {
        if std::mem::size_of::<T>() as u64 != self.element_bytes {
            return Err(crate::VkError::Invalid(format!(
                "reading elements of {} bytes as {} bytes",
                self.element_bytes,
                std::mem::size_of::<T>()
            )));
        }
        let n = self.count(ctx)? as usize;
        let mut all: Vec<T> = ctx.read_buffer_as(&self.data)?;
        all.truncate(n);
        Ok(all)
    }

    /// Reads the kept elements of a [`Compactor`] stream back.
    pub fn read(&self, ctx: &Context) -> Result<Vec<[u32; 4]>> {
        self.read_as(ctx)
    }
}

/// Where a compaction step's input comes from.
pub enum Source<'a> {
    /// The first `n` elements of a buffer.
    Array(&'a Buffer, u32),
    /// The output of an earlier step: its count stays on the GPU.
    Stream(&'a CompactStream),
}

pub struct Compactor {
    pub path: CompactionPath,
    xfb: Option<Pipeline>,
    append: Option<Pipeline>,
    finalize: Option<Pipeline>,
    dummy_counter: Option<Buffer>,
}

impl Compactor {
    /// A compactor keeping elements where `keep_expr` (GLSL over `uvec4 v`) is true.
    pub fn new(ctx: &Context, shaders: &ShaderCompiler, path: CompactionPath, keep_expr: &str) -> Result<Compactor> {
        let defines = [("KEEP_EXPR", keep_expr)];
        match path {
            CompactionPath::TransformFeedback => {
                ctx.require(
                    "stream compaction (xfb path)",
                    &[Feature::GeometryShader, Feature::TransformFeedback, Feature::TransformFeedbackDraw],
                )?;
                let mut desc = GraphicsDesc::new("compact.xfb", shaders.compile("vkcore/compact.vert", &[])?, None);
                desc.geometry = Some(shaders.compile("vkcore/compact.geom", &defines)?);
                desc.topology = Topology::Points;
                desc.rasterizer_discard = true;
                desc.vertex_layout = Some(VertexLayout {
                    stride: ELEMENT_BYTES as u32,
                    attributes: vec![VertexAttribute { location: 0, format: vk::Format::R32G32B32A32_UINT, offset: 0 }],
                });
                Ok(Compactor {
                    path,
                    xfb: Some(Pipeline::graphics(ctx, &desc)?),
                    append: None,
                    finalize: None,
                    dummy_counter: None,
                })
            }
            CompactionPath::Compute => {
                let append = Pipeline::compute(
                    ctx,
                    "compact.append",
                    &shaders.compile("vkcore/compact_append.comp", &defines)?,
                )?;
                let finalize =
                    Pipeline::compute(ctx, "compact.finalize", &shaders.compile("vkcore/compact_finalize.comp", &[])?)?;
                let dummy = ctx.buffer_with_data("compact dummy counter", &[0u8; COUNTER_BYTES as usize])?;
                Ok(Compactor {
                    path,
                    xfb: None,
                    append: Some(append),
                    finalize: Some(finalize),
                    dummy_counter: Some(dummy),
                })
            }
        }
    }

    /// Records the compaction of `src` into `out` as passes of `frame`. With `query`, the xfb
    /// path also records primitives written/needed into query `query.1` of the pool.
    pub fn record(
        &self,
        frame: &mut Frame,
        name: &str,
        src: Source,
        out: &CompactStream,
        query: Option<(&QueryPool, u32)>,
    ) -> Result<()> {
        if let Some(p) = &self.xfb {
            let (input, input_counter) = match &src {
                Source::Array(b, _) => (*b, None),
                Source::Stream(s) => (&s.data, Some(&s.counter)),
            };
            let mut uses = vec![
                Use::buffer(input, Access::VERTEX_INPUT),
                Use::buffer(&out.data, Access::XFB_WRITE),
                Use::buffer(&out.counter, Access::XFB_COUNTER),
            ];
            if let Some(c) = input_counter {
                uses.push(Use::buffer(c, Access::INDIRECT));
            }
            return frame.pass(name).bind(p, []).uses(uses).record(|cmd| {
                cmd.begin_rendering(&Targets::none())?;
                cmd.bind_vertex_buffer(input, 0)?;
                cmd.bind_xfb_buffers(&[&out.data])?;
                if let Some((pool, i)) = query {
                    cmd.begin_query(pool, i)?;
                }
                // No counter buffers at begin: capture starts at offset 0.
                cmd.begin_xfb(&[], false)?;
                match &src {
                    Source::Array(_, n) => cmd.draw(*n, 1, 0, 0),
                    Source::Stream(s) => cmd.draw_indirect_byte_count(1, &s.counter, ELEMENT_BYTES as u32)?,
                }
                cmd.end_xfb(&[&out.counter])?;
                if let Some((pool, i)) = query {
                    cmd.end_query(pool, i)?;
                }
                cmd.end_rendering();
                Ok(())
            });
        }
        let (Some(append), Some(finalize), Some(dummy)) = (&self.append, &self.finalize, &self.dummy_counter) else {
            return Err(crate::VkError::Invalid("compactor has no pipelines".into()));
        };
        let header: Vec<u8> = [0u32, out.capacity, 0, 0].iter().flat_map(|x| x.to_le_bytes()).collect();
        frame
            .pass(&format!("{name}.reset"))
            .uses([Use::buffer(&out.counter, Access::TRANSFER_WRITE)])
            .record(|cmd| cmd.update_buffer(&out.counter, 0, &header))?;
        let (input, in_counter, n, indirect) = match &src {
            Source::Array(b, n) => (*b, dummy, *n, false),
            Source::Stream(s) => (&s.data, &s.counter, 0, true),
        };
        let binds = [
            ("Input", Bind::BufferRead(input)),
            ("InputCounter", Bind::BufferRead(in_counter)),
            ("Output", Bind::Buffer(&out.data)),
            ("OutputCounter", Bind::Buffer(&out.counter)),
        ];
        // The step's count is read as dispatch arguments too.
        let arguments = indirect.then(|| Use::buffer(in_counter, Access::INDIRECT));
        frame.pass(name).bind(append, binds).uses(arguments).record(|cmd| {
            cmd.push(&CompactConstants { n, use_in_count: indirect as u32, capacity: out.capacity })?;
            if indirect {
                cmd.dispatch_indirect(in_counter, 16)?;
            } else {
                let groups = n.div_ceil(64);
                let x = groups.clamp(1, 65535);
                cmd.dispatch(x, groups.div_ceil(x).max(1), 1);
            }
            Ok(())
        })?;
        frame.pass(&format!("{name}.finalize")).bind(finalize, [("Counter", Bind::Buffer(&out.counter))]).record(
            |cmd| {
                cmd.dispatch(1, 1, 1);
                Ok(())
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::CompactConstants;
    use crate::shader::ShaderCompiler;

    #[test]
    fn compact_constants_match_their_glsl_twin() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaders_glsl");
        let spirv = ShaderCompiler::new(&root)
            .unwrap()
            .compile("vkcore/compact_append.comp", &[("KEEP_EXPR", "true")])
            .unwrap();
        crate::check_push_constants::<CompactConstants>(&spirv).unwrap();
    }
}
