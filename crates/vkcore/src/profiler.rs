//! GPU timing: a timestamp pair around every pass (both written at ALL_COMMANDS, i.e. when all
//! earlier work has finished: never TOP_OF_PIPE for the end), optional pipeline-statistics
//! queries, and a `Profiler` that keeps raw per-frame samples and reports median/min/max.

use crate::context::Context;
use crate::error::{Result, VkResultExt};
use crate::Feature;
use ash::vk;
use std::collections::BTreeMap;

/// Most passes one frame may record (adaptive caustic maps' photon batches record a few per level
/// per batch; their plan keeps a frame under this, and a frame beyond it is an error). The query
/// pools do not hold this many: they grow with the frame's passes (see `QueryPools`).
pub const MAX_PASSES: u32 = 4096;

/// Counters from a pipeline-statistics query (None where the device has no such counter).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PipelineStats {
    pub input_vertices: u64,
    pub input_primitives: u64,
    pub vertex_invocations: u64,
    pub geometry_invocations: u64,
    pub geometry_primitives: u64,
    pub clipping_invocations: u64,
    pub clipping_primitives: u64,
    pub fragment_invocations: u64,
    pub compute_invocations: u64,
}

impl PipelineStats {
    pub(crate) fn from_raw(r: [u64; 9]) -> PipelineStats {
        PipelineStats {
            input_vertices: r[0],
            input_primitives: r[1],
            vertex_invocations: r[2],
            geometry_invocations: r[3],
            geometry_primitives: r[4],
            clipping_invocations: r[5],
            clipping_primitives: r[6],
            fragment_invocations: r[7],
            compute_invocations: r[8],
        }
    }
}

/// One pass of one frame.
#[derive(Debug, Clone)]
pub struct PassTiming {
    pub name: String,
    /// GPU milliseconds between the pass's two timestamps (None without timestamps).
    pub gpu_ms: Option<f64>,
    /// Host milliseconds from the pass's own submit to its fence, in a frame recorded with
    /// [`crate::FrameOptions::host_pass_times`] (None otherwise).
    pub host_ms: Option<f64>,
    pub stats: Option<PipelineStats>,
}

#[derive(Debug, Clone, Default)]
pub struct FrameReport {
    pub passes: Vec<PassTiming>,
    /// GPU milliseconds of the whole frame, from a timestamp pair around it (ring frames timed
    /// per frame, see [`crate::Timing`]).
    pub frame_gpu_ms: Option<f64>,
    /// The frame's number in its ring (0 for a one-shot frame) and its slot.
    pub index: u64,
    pub slot: Option<usize>,
    /// What recording and submitting the frame asked of the driver (objects created, submits,
    /// barriers, timestamps).
    pub counters: crate::Counters,
    /// Every pass in recording order with the resources it read and wrote, where the context
    /// records frame graphs (`Context::record_frame_graphs`); empty otherwise.
    pub graph: Vec<crate::frame::PassNode>,
}

impl FrameReport {
    pub fn total_ms(&self) -> Option<f64> {
        self.passes.iter().map(|p| p.gpu_ms).sum()
    }
    pub fn pass(&self, name: &str) -> Option<&PassTiming> {
        self.passes.iter().find(|p| p.name == name)
    }
}

/// Passes per chunk of query pools: a frame's pools grow a chunk at a time, so they are sized
/// to the passes it records (rounded up to a chunk), up to [`MAX_PASSES`].
const CHUNK: u32 = 32;

/// One chunk: timestamps for `CHUNK` passes (two each) and, optionally, their statistics.
struct Chunk {
    timestamps: Option<vk::QueryPool>,
    stats: Option<vk::QueryPool>,
}

/// A frame's timestamp and pipeline-statistics queries, in chunks made as passes need them. A
/// ring slot keeps its chunks from frame to frame (reset from the host once the slot's fence
/// has signalled), so a warm slot creates none.
pub(crate) struct QueryPools {
    timestamps: bool,
    stats_flags: Option<vk::QueryPipelineStatisticFlags>,
    chunks: Vec<Chunk>,
}

impl QueryPools {
    pub fn new(ctx: &Context, timestamps: bool, stats: bool) -> Result<QueryPools> {
        let stats_flags = stats.then(|| {
            let mut flags = vk::QueryPipelineStatisticFlags::INPUT_ASSEMBLY_VERTICES
                | vk::QueryPipelineStatisticFlags::INPUT_ASSEMBLY_PRIMITIVES
                | vk::QueryPipelineStatisticFlags::VERTEX_SHADER_INVOCATIONS
                | vk::QueryPipelineStatisticFlags::CLIPPING_INVOCATIONS
                | vk::QueryPipelineStatisticFlags::CLIPPING_PRIMITIVES
                | vk::QueryPipelineStatisticFlags::FRAGMENT_SHADER_INVOCATIONS
                | vk::QueryPipelineStatisticFlags::COMPUTE_SHADER_INVOCATIONS;
            if ctx.info().has(Feature::GeometryShader) {
                flags |= vk::QueryPipelineStatisticFlags::GEOMETRY_SHADER_INVOCATIONS
                    | vk::QueryPipelineStatisticFlags::GEOMETRY_SHADER_PRIMITIVES;
            }
            flags
        });
        Ok(QueryPools { timestamps, stats_flags, chunks: vec![] })
    }

    pub fn timestamps(&self) -> bool {
        self.timestamps
    }

    /// Makes sure the chunk holding pass `pass` exists (created and reset from the host).
    fn ensure(&mut self, ctx: &Context, pass: u32) -> Result<()> {
        if pass >= MAX_PASSES {
            return Err(crate::VkError::Invalid(format!("more than {MAX_PASSES} passes in one frame")));
        }
        let d = ctx.shared.raw();
        while self.chunks.len() as u32 <= pass / CHUNK {
            let mut chunk = Chunk { timestamps: None, stats: None };
            if self.timestamps {
                let info =
                    vk::QueryPoolCreateInfo::default().query_type(vk::QueryType::TIMESTAMP).query_count(2 * CHUNK);
                let p = unsafe { d.create_query_pool(&info, None) }.call("vkCreateQueryPool")?;
                ctx.shared.counters.object(1);
                unsafe { d.reset_query_pool(p, 0, 2 * CHUNK) };
                chunk.timestamps = Some(p);
            }
            if let Some(flags) = self.stats_flags {
                let info = vk::QueryPoolCreateInfo::default()
                    .query_type(vk::QueryType::PIPELINE_STATISTICS)
                    .query_count(CHUNK)
                    .pipeline_statistics(flags);
                match unsafe { d.create_query_pool(&info, None) } {
                    Ok(p) => {
                        ctx.shared.counters.object(1);
                        unsafe { d.reset_query_pool(p, 0, CHUNK) };
                        chunk.stats = Some(p);
                    }
                    Err(e) => {
                        if let Some(t) = chunk.timestamps {
                            unsafe { d.destroy_query_pool(t, None) };
                        }
                        return Err(crate::VkError::Call { call: "vkCreateQueryPool", result: e });
                    }
                }
            }
            self.chunks.push(chunk);
        }
        Ok(())
    }

    /// Resets the queries of the first `passes` passes from the host, for the slot's next frame
    /// (the GPU is done with them: the slot's fence has signalled).
    pub fn reset(&self, ctx: &Context, passes: u32) {
        let d = ctx.shared.raw();
        for chunk in self.chunks.iter().take(passes.div_ceil(CHUNK) as usize) {
            unsafe {
                if let Some(p) = chunk.timestamps {
                    d.reset_query_pool(p, 0, 2 * CHUNK);
                }
                if let Some(p) = chunk.stats {
                    d.reset_query_pool(p, 0, CHUNK);
                }
            }
        }
    }

    fn timestamp(&self, ctx: &Context, cb: vk::CommandBuffer, query: u32) {
        if let Some(p) = self.chunks[(query / 2 / CHUNK) as usize].timestamps {
            unsafe {
                ctx.shared.raw().cmd_write_timestamp2(cb, vk::PipelineStageFlags2::ALL_COMMANDS, p, query % (2 * CHUNK))
            };
            ctx.shared.counters.timestamp();
        }
    }

    /// Opens pass `pass`'s queries: its first timestamp (when every earlier command has
    /// finished) and its statistics.
    pub fn begin(&mut self, ctx: &Context, cb: vk::CommandBuffer, pass: u32) -> Result<()> {
        self.ensure(ctx, pass)?;
        self.timestamp(ctx, cb, 2 * pass);
        if let Some(p) = self.chunks[(pass / CHUNK) as usize].stats {
            unsafe { ctx.shared.raw().cmd_begin_query(cb, p, pass % CHUNK, vk::QueryControlFlags::empty()) };
        }
        Ok(())
    }

    pub fn end(&self, ctx: &Context, cb: vk::CommandBuffer, pass: u32) {
        if let Some(p) = self.chunks[(pass / CHUNK) as usize].stats {
            unsafe { ctx.shared.raw().cmd_end_query(cb, p, pass % CHUNK) };
        }
        self.timestamp(ctx, cb, 2 * pass + 1);
    }

    /// Per-pass milliseconds and raw statistics for passes 0..n (a frame timed as a whole has
    /// one "pass": the frame).
    #[allow(clippy::type_complexity)]
    pub fn read(&self, ctx: &Context, n: usize) -> Result<(Option<Vec<f64>>, Option<Vec<[u64; 9]>>)> {
        let d = ctx.shared.raw();
        let info = ctx.info();
        let flags = vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT;
        let mut times = None;
        if self.timestamps && n > 0 {
            let mut raw = vec![0u64; 2 * n];
            for (c, chunk) in raw.chunks_mut(2 * CHUNK as usize).zip(&self.chunks) {
                if let Some(p) = chunk.timestamps {
                    unsafe { d.get_query_pool_results(p, 0, c, flags) }.call("vkGetQueryPoolResults(timestamps)")?;
                }
            }
            let mask = if info.timestamp_valid_bits >= 64 { u64::MAX } else { (1u64 << info.timestamp_valid_bits) - 1 };
            let period = info.timestamp_period_ns as f64;
            times = Some(
                raw.chunks(2)
                    .map(|c| ((c[1] & mask).wrapping_sub(c[0] & mask) & mask) as f64 * period * 1e-6)
                    .collect(),
            );
        }
        let mut stats = None;
        if let (Some(stat_flags), true) = (self.stats_flags, n > 0) {
            let count = stat_flags.as_raw().count_ones() as usize;
            let mut rows: Vec<[u64; 9]> = Vec::with_capacity(n);
            for (k, chunk) in self.chunks.iter().enumerate() {
                let here = (n - k * CHUNK as usize).min(CHUNK as usize);
                if here == 0 || k * CHUNK as usize >= n {
                    break;
                }
                let Some(p) = chunk.stats else { continue };
                // Results come as `count` consecutive u64s per query, in flag-bit order:
                // IA vertices, IA primitives, VS, [GS invocations, GS primitives], clip inv,
                // clip prims, FS, CS.
                if count == 9 {
                    let mut raw = vec![[0u64; 9]; here];
                    unsafe { d.get_query_pool_results(p, 0, &mut raw, flags) }
                        .call("vkGetQueryPoolResults(pipeline statistics)")?;
                    rows.extend(raw);
                } else {
                    let mut raw = vec![[0u64; 7]; here];
                    unsafe { d.get_query_pool_results(p, 0, &mut raw, flags) }
                        .call("vkGetQueryPoolResults(pipeline statistics)")?;
                    rows.extend(raw.iter().map(|c| [c[0], c[1], c[2], 0, 0, c[3], c[4], c[5], c[6]]));
                }
            }
            stats = Some(rows);
        }
        Ok((times, stats))
    }

    pub fn destroy(&mut self, ctx: &Context) {
        let d = ctx.shared.raw();
        for chunk in self.chunks.drain(..) {
            unsafe {
                if let Some(p) = chunk.timestamps {
                    d.destroy_query_pool(p, None);
                }
                if let Some(p) = chunk.stats {
                    d.destroy_query_pool(p, None);
                }
            }
        }
    }
}

/// Summary of one pass over many frames.
#[derive(Debug, Clone)]
pub struct PassSummary {
    pub name: String,
    pub samples_ms: Vec<f64>,
    pub median_ms: f64,
    pub min_ms: f64,
    pub max_ms: f64,
}

/// Collects raw per-pass samples across frames (Falcor-style capture).
#[derive(Debug, Default, Clone)]
pub struct Profiler {
    order: Vec<String>,
    samples: BTreeMap<String, Vec<f64>>,
    frames: usize,
}

impl Profiler {
    pub fn record(&mut self, report: &FrameReport) {
        self.frames += 1;
        for p in &report.passes {
            if let Some(ms) = p.gpu_ms {
                if !self.samples.contains_key(&p.name) {
                    self.order.push(p.name.clone());
                }
                self.samples.entry(p.name.clone()).or_default().push(ms);
            }
        }
    }

    pub fn frames(&self) -> usize {
        self.frames
    }

    /// Per-pass median/min/max in first-seen order.
    pub fn summary(&self) -> Vec<PassSummary> {
        self.order
            .iter()
            .filter_map(|name| {
                let s = self.samples.get(name)?;
                let mut sorted = s.clone();
                sorted.sort_by(|a, b| a.total_cmp(b));
                let n = sorted.len();
                let median = if n % 2 == 1 { sorted[n / 2] } else { 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]) };
                Some(PassSummary {
                    name: name.clone(),
                    samples_ms: s.clone(),
                    median_ms: median,
                    min_ms: sorted[0],
                    max_ms: sorted[n - 1],
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(ms: &[(&str, f64)]) -> FrameReport {
        FrameReport {
            passes: ms
                .iter()
                .map(|(n, t)| PassTiming { name: n.to_string(), gpu_ms: Some(*t), host_ms: None, stats: None })
                .collect(),
            ..Default::default()
        }
    }

    #[test]
    fn median_min_max_over_frames() {
        let mut p = Profiler::default();
        p.record(&frame(&[("b", 3.0), ("a", 1.0)]));
        p.record(&frame(&[("b", 1.0), ("a", 2.0)]));
        p.record(&frame(&[("b", 2.0), ("a", 10.0)]));
        p.record(&frame(&[("a", 4.0)]));
        let s = p.summary();
        assert_eq!(s[0].name, "b", "first-seen order");
        assert_eq!((s[0].median_ms, s[0].min_ms, s[0].max_ms), (2.0, 1.0, 3.0));
        assert_eq!(s[1].samples_ms, vec![1.0, 2.0, 10.0, 4.0]);
        assert_eq!(s[1].median_ms, 3.0, "even count: mean of the middle two");
        assert_eq!(p.frames(), 4);
    }
}
