//! GPU timing: a timestamp pair around every pass (both written at ALL_COMMANDS, i.e. when all
//! earlier work has finished: never TOP_OF_PIPE for the end), optional pipeline-statistics
//! queries, and a `Profiler` that keeps raw per-frame samples and reports median/min/max.

use crate::context::Context;
use crate::error::{Result, VkResultExt};
use crate::Feature;
use ash::vk;
use std::collections::BTreeMap;

/// Most passes one frame can profile (adaptive caustic maps' photon batches record a few per
/// level per batch).
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
    pub stats: Option<PipelineStats>,
}

#[derive(Debug, Clone, Default)]
pub struct FrameReport {
    pub passes: Vec<PassTiming>,
}

impl FrameReport {
    pub fn total_ms(&self) -> Option<f64> {
        self.passes.iter().map(|p| p.gpu_ms).sum()
    }
    pub fn pass(&self, name: &str) -> Option<&PassTiming> {
        self.passes.iter().find(|p| p.name == name)
    }
}

pub(crate) struct QueryPools {
    timestamps: Option<vk::QueryPool>,
    stats: Option<(vk::QueryPool, usize)>,
}

impl QueryPools {
    pub fn new(ctx: &Context, timestamps: bool, stats: bool) -> Result<QueryPools> {
        let d = ctx.shared.raw();
        let mut pools = QueryPools { timestamps: None, stats: None };
        if timestamps {
            let info =
                vk::QueryPoolCreateInfo::default().query_type(vk::QueryType::TIMESTAMP).query_count(2 * MAX_PASSES);
            let p = unsafe { d.create_query_pool(&info, None) }.call("vkCreateQueryPool")?;
            unsafe { d.reset_query_pool(p, 0, 2 * MAX_PASSES) };
            pools.timestamps = Some(p);
        }
        if stats {
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
            let info = vk::QueryPoolCreateInfo::default()
                .query_type(vk::QueryType::PIPELINE_STATISTICS)
                .query_count(MAX_PASSES)
                .pipeline_statistics(flags);
            match unsafe { d.create_query_pool(&info, None) } {
                Ok(p) => {
                    unsafe { d.reset_query_pool(p, 0, MAX_PASSES) };
                    pools.stats = Some((p, flags.as_raw().count_ones() as usize));
                }
                Err(e) => {
                    pools.destroy(ctx);
                    return Err(crate::VkError::Call { call: "vkCreateQueryPool", result: e });
                }
            }
        }
        Ok(pools)
    }

    pub fn begin(&self, ctx: &Context, cb: vk::CommandBuffer, pass: u32) -> Result<()> {
        if pass >= MAX_PASSES {
            return Err(crate::VkError::Invalid(format!("more than {MAX_PASSES} passes in one frame")));
        }
        let d = ctx.shared.raw();
        unsafe {
            if let Some(p) = self.timestamps {
                d.cmd_write_timestamp2(cb, vk::PipelineStageFlags2::ALL_COMMANDS, p, 2 * pass);
            }
            if let Some((p, _)) = self.stats {
                d.cmd_begin_query(cb, p, pass, vk::QueryControlFlags::empty());
            }
        }
        Ok(())
    }

    pub fn end(&self, ctx: &Context, cb: vk::CommandBuffer, pass: u32) {
        let d = ctx.shared.raw();
        unsafe {
            if let Some((p, _)) = self.stats {
                d.cmd_end_query(cb, p, pass);
            }
            if let Some(p) = self.timestamps {
                d.cmd_write_timestamp2(cb, vk::PipelineStageFlags2::ALL_COMMANDS, p, 2 * pass + 1);
            }
        }
    }

    /// Per-pass milliseconds and raw statistics for passes 0..n.
    #[allow(clippy::type_complexity)]
    pub fn read(&self, ctx: &Context, n: usize) -> Result<(Option<Vec<f64>>, Option<Vec<[u64; 9]>>)> {
        let d = ctx.shared.raw();
        let info = ctx.info();
        let mut times = None;
        if let (Some(p), true) = (self.timestamps, n > 0) {
            let mut raw = vec![0u64; 2 * n];
            unsafe {
                d.get_query_pool_results(p, 0, &mut raw, vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT)
            }
            .call("vkGetQueryPoolResults(timestamps)")?;
            let mask = if info.timestamp_valid_bits >= 64 { u64::MAX } else { (1u64 << info.timestamp_valid_bits) - 1 };
            let period = info.timestamp_period_ns as f64;
            times = Some(
                raw.chunks(2)
                    .map(|c| ((c[1] & mask).wrapping_sub(c[0] & mask) & mask) as f64 * period * 1e-6)
                    .collect(),
            );
        }
        let mut stats = None;
        if let (Some((p, count)), true) = (self.stats, n > 0) {
            let flags = vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT;
            // Results come as `count` consecutive u64s per query, in flag-bit order:
            // IA vertices, IA primitives, VS, [GS invocations, GS primitives], clip inv, clip prims, FS, CS.
            let rows: Vec<[u64; 9]> = if count == 9 {
                let mut raw = vec![[0u64; 9]; n];
                unsafe { d.get_query_pool_results(p, 0, &mut raw, flags) }
                    .call("vkGetQueryPoolResults(pipeline statistics)")?;
                raw
            } else {
                let mut raw = vec![[0u64; 7]; n];
                unsafe { d.get_query_pool_results(p, 0, &mut raw, flags) }
                    .call("vkGetQueryPoolResults(pipeline statistics)")?;
                raw.iter().map(|c| [c[0], c[1], c[2], 0, 0, c[3], c[4], c[5], c[6]]).collect()
            };
            stats = Some(rows);
        }
        Ok((times, stats))
    }

    pub fn destroy(&mut self, ctx: &Context) {
        let d = ctx.shared.raw();
        unsafe {
            if let Some(p) = self.timestamps.take() {
                d.destroy_query_pool(p, None);
            }
            if let Some((p, _)) = self.stats.take() {
                d.destroy_query_pool(p, None);
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
            passes: ms.iter().map(|(n, t)| PassTiming { name: n.to_string(), gpu_ms: Some(*t), stats: None }).collect(),
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
