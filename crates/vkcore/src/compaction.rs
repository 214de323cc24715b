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
use crate::recorder::{Cmd, Targets};
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
/// Bytes of the compute path's counter ([`AppendCounter`]).
pub const COUNTER_BYTES: u64 = std::mem::size_of::<AppendCounter>() as u64;

/// The compute path's counter header, `CompactCounter` in
/// `shaders_glsl/vkcore/compact_counter.glsl`: the append step counts into `count`, then
/// `compact_finalize.comp` writes the arguments the next step is dispatched or drawn with.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct AppendCounter {
    /// Elements appended (may exceed `capacity`: overflow is visible).
    pub count: u32,
    /// Slots in the output buffer.
    pub capacity: u32,
    pub pad: [u32; 2],
    /// VkDispatchIndirectCommand (x, y, z) over 64-wide groups, w unused.
    pub dispatch: [u32; 4],
    /// VkDrawIndirectCommand (vertexCount, instanceCount, firstVertex, firstInstance).
    pub draw: [u32; 4],
}

impl AppendCounter {
    /// Byte offset of [`AppendCounter::dispatch`].
    pub const DISPATCH_OFFSET: u64 = std::mem::offset_of!(AppendCounter, dispatch) as u64;
    /// Byte offset of [`AppendCounter::draw`].
    pub const DRAW_OFFSET: u64 = std::mem::offset_of!(AppendCounter, draw) as u64;

    /// Bytes of the header the append step counts in (`count`, `capacity`, `pad`): what a reset
    /// writes (finalize writes the arguments after it).
    pub const HEADER_BYTES: usize = std::mem::offset_of!(AppendCounter, dispatch);

    /// An empty stream of `capacity` slots.
    pub fn empty(capacity: u32) -> AppendCounter {
        AppendCounter { count: 0, capacity, pad: [0; 2], dispatch: [0; 4], draw: [0; 4] }
    }

    /// A stream of `count` elements already in place (a seed, uploaded once), with the arguments
    /// finalize would have written.
    pub fn full(count: u32) -> AppendCounter {
        // As compact_finalize.comp: at least one group, in balanced rows (grid.rs).
        let (x, y) = crate::dispatch_grid(count.div_ceil(64));
        AppendCounter { count, capacity: count, pad: [0; 2], dispatch: [x, y, 1, 0], draw: [count, 1, 0, 0] }
    }
}

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
    path: CompactionPath,
    data: Buffer,
    /// xfb: the transform-feedback counter (bytes written, u32 at 0); compute: an append counter.
    counter: Buffer,
    capacity: u32,
    /// Bytes per element (the xfb counter counts bytes).
    element_bytes: u64,
}

impl CompactStream {
    /// The path that writes the stream.
    pub fn path(&self) -> CompactionPath {
        self.path
    }

    /// The elements (`capacity` of `element_bytes` each).
    pub fn data(&self) -> &Buffer {
        &self.data
    }

    /// xfb: the transform-feedback counter (bytes written, u32 at 0); compute: the append
    /// counter's header (see [`COUNTER_BYTES`]).
    pub fn counter(&self) -> &Buffer {
        &self.counter
    }

    /// The most elements it holds.
    pub fn capacity(&self) -> u32 {
        self.capacity
    }

    /// Bytes per element (the xfb counter counts bytes).
    pub fn element_bytes(&self) -> u64 {
        self.element_bytes
    }

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

    /// Uploads the counter of a stream whose first `count` elements are in place (a seed, its
    /// elements uploaded once): transform feedback's byte count, or the compute path's
    /// [`AppendCounter::full`].
    pub fn upload_seeded_counter(&self, ctx: &Context, count: u32) -> Result<()> {
        let bytes = count as u64 * self.element_bytes;
        if count > self.capacity || bytes > u32::MAX as u64 {
            return Err(crate::VkError::Invalid(format!(
                "a seed of {count} elements in a stream of {} (of {} bytes each)",
                self.capacity, self.element_bytes
            )));
        }
        let mut header = AppendCounter::full(count);
        header.capacity = self.capacity;
        if self.path == CompactionPath::TransformFeedback {
            header.count = bytes as u32;
        }
        ctx.upload_buffer(&self.counter, bytemuck::bytes_of(&header))
    }

    /// Records the zeroing of the count before a step appends (outside rendering; the pass
    /// declares [`CompactStream::reset_use`]): transform feedback's byte count, or the compute
    /// path's count with the capacity (the arguments are finalize's to write).
    pub fn reset(&self, cmd: &mut Cmd) -> Result<()> {
        match self.path {
            CompactionPath::TransformFeedback => {
                cmd.fill_buffer(&self.counter, 0);
                Ok(())
            }
            CompactionPath::Compute => {
                let empty = AppendCounter::empty(self.capacity);
                cmd.update_buffer(&self.counter, 0, &bytemuck::bytes_of(&empty)[..AppendCounter::HEADER_BYTES])
            }
        }
    }

    /// What [`CompactStream::reset`] writes.
    pub fn reset_use(&self) -> Use<'_> {
        Use::buffer(&self.counter, Access::TRANSFER_WRITE)
    }

    /// The counter read as indirect arguments (by [`CompactStream::draw`] and
    /// [`CompactStream::dispatch`]).
    pub fn arguments_use(&self) -> Use<'_> {
        Use::buffer(&self.counter, Access::INDIRECT)
    }

    /// Draws one vertex per element (instanced once): from the byte count on the xfb path, from
    /// [`AppendCounter::draw`] on the compute path (after finalize). The pass declares
    /// [`CompactStream::arguments_use`].
    pub fn draw(&self, cmd: &mut Cmd) -> Result<()> {
        match self.path {
            CompactionPath::TransformFeedback => {
                cmd.draw_indirect_byte_count(1, &self.counter, self.element_bytes as u32)
            }
            CompactionPath::Compute => cmd.draw_indirect(&self.counter, AppendCounter::DRAW_OFFSET),
        }
    }

    /// Dispatches 64-wide groups over the elements, from [`AppendCounter::dispatch`] (compute
    /// path, after finalize). The pass declares [`CompactStream::arguments_use`].
    pub fn dispatch(&self, cmd: &mut Cmd) -> Result<()> {
        cmd.dispatch_indirect(&self.counter, AppendCounter::DISPATCH_OFFSET)
    }

    /// The xfb path's step from `from` into this stream, inside rendering (the pass declares
    /// [`CompactStream::capture_uses`]): a point per element of `from`, whose elements are
    /// vertex buffer 0 with `from.as_vertices` (else the kernel reads them by index), all of
    /// them when `from.seeded` (drawn by number), else as many as its counter says; captured
    /// from the start, or with `append` after what earlier steps wrote. This stream's counter
    /// holds the bytes written afterwards.
    pub fn capture(&self, cmd: &mut Cmd, from: StepInput, append: bool) -> Result<()> {
        let vertices = from.as_vertices.then_some(&from.stream.data);
        self.capture_drawn(cmd, vertices, append, |cmd| {
            if from.seeded {
                cmd.draw(from.stream.capacity, 1, 0, 0);
                Ok(())
            } else {
                from.stream.draw(cmd)
            }
        })
    }

    /// The capture itself, for [`Self::capture`] and [`Compactor`]'s xfb step: `vertices` as
    /// vertex buffer 0, this stream's data captured from the start (or with `append` after what
    /// is there) while `draw` draws the points; the counter holds the bytes written afterwards.
    fn capture_drawn(
        &self,
        cmd: &mut Cmd,
        vertices: Option<&Buffer>,
        append: bool,
        draw: impl FnOnce(&mut Cmd) -> Result<()>,
    ) -> Result<()> {
        if let Some(v) = vertices {
            cmd.bind_vertex_buffer(v, 0)?;
        }
        cmd.bind_xfb_buffers(&[&self.data])?;
        if append {
            cmd.begin_xfb(&[&self.counter], true)?;
        } else {
            // No counter buffers at begin: capture starts at offset 0.
            cmd.begin_xfb(&[], false)?;
        }
        draw(cmd)?;
        cmd.end_xfb(&[&self.counter])
    }

    /// What [`CompactStream::capture`] reads of `from` (its elements as vertices, its counter as
    /// draw arguments) and writes; a kernel that reads `from`'s elements by index binds them.
    pub fn capture_uses<'a>(&'a self, from: StepInput<'a>) -> Vec<Use<'a>> {
        let mut uses = vec![];
        if from.as_vertices {
            uses.push(Use::buffer(&from.stream.data, Access::VERTEX_INPUT));
        }
        if !from.seeded {
            uses.push(from.stream.arguments_use());
        }
        uses.push(Use::buffer(&self.data, Access::XFB_WRITE));
        uses.push(Use::buffer(&self.counter, Access::XFB_COUNTER));
        uses
    }

    /// The elements a counter's first word stands for (the xfb path counts bytes; the compute
    /// path may count past the capacity).
    pub fn elements(&self, first_word: u32) -> u32 {
        match self.path {
            CompactionPath::TransformFeedback => (first_word as u64 / self.element_bytes) as u32,
            CompactionPath::Compute => first_word.min(self.capacity),
        }
    }

    /// Reads the element count back (for tests and statistics, never between steps).
    pub fn count(&self, ctx: &Context) -> Result<u32> {
        let c: Vec<u32> = ctx.read_buffer_as(&self.counter)?;
        Ok(self.elements(c[0]))
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

/// What one step of a compacted traversal reads (see [`CompactStream::capture`]).
#[derive(Clone, Copy)]
pub struct StepInput<'a> {
    pub stream: &'a CompactStream,
    /// Every element is in place (a seed): drawn by number, not from the counter.
    pub seeded: bool,
    /// The elements are vertex buffer 0 (else the kernel reads them by index).
    pub as_vertices: bool,
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
    finalize: Option<Finalize>,
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
                let finalize = Finalize::new(ctx, shaders, "compact.finalize")?;
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
                if let Some((pool, i)) = query {
                    cmd.begin_query(pool, i)?;
                }
                out.capture_drawn(cmd, Some(input), false, |cmd| match &src {
                    Source::Array(_, n) => {
                        cmd.draw(*n, 1, 0, 0);
                        Ok(())
                    }
                    Source::Stream(s) => s.draw(cmd),
                })?;
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
        frame.pass(&format!("{name}.reset")).uses([out.reset_use()]).record(|cmd| out.reset(cmd))?;
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
            if let Source::Stream(s) = &src {
                s.dispatch(cmd)?;
            } else {
                let (x, y) = crate::dispatch_grid(n.div_ceil(64));
                cmd.dispatch(x, y, 1);
            }
            Ok(())
        })?;
        finalize.record(frame, &format!("{name}.finalize"), out)
    }
}

/// The compute path's finalize kernel (`compact_finalize.comp`): after a step appended to a
/// stream, writes the [`AppendCounter`] arguments the next step is dispatched or drawn with.
pub struct Finalize(Pipeline);

impl Finalize {
    pub fn new(ctx: &Context, shaders: &ShaderCompiler, name: &str) -> Result<Finalize> {
        Ok(Finalize(Pipeline::compute(ctx, name, &shaders.compile("vkcore/compact_finalize.comp", &[])?)?))
    }

    /// One pass `name` over `stream`'s counter.
    pub fn record(&self, frame: &mut Frame, name: &str, stream: &CompactStream) -> Result<()> {
        frame.pass(name).bind(&self.0, [("Counter", Bind::Buffer(&stream.counter))]).record(|cmd| {
            cmd.dispatch(1, 1, 1);
            Ok(())
        })
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
